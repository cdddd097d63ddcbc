#pragma once

// Mission Planner's .waypoints (also ArduPilot's and MAVProxy's mission
// .txt): the text format "QGC WPL 110". The first line is "QGC WPL 110";
// every other line is one item of 12 fields separated by tabs or spaces:
//
//   INDEX CURRENT_WP FRAME COMMAND PARAM1 PARAM2 PARAM3 PARAM4 LATITUDE
//   LONGITUDE ALTITUDE AUTOCONTINUE
//
// The line with index 0, when it comes first, is the home position, as in
// every mission file Mission Planner writes: its latitude, longitude and
// altitude become the plan's home and it is not a mission item. A home at
// 0 degrees north, 0 east (what Mission Planner writes before it knows one)
// is no home.
//
// The fence and rally items of MAVLink's fence and rally missions, as
// Mission Planner and MAVProxy save them (no home line: index 0 is the
// first vertex), go to the plan's geofence and rally points, wherever they
// are in the file: FENCE_POLYGON_VERTEX_INCLUSION / _EXCLUSION (5001, 5002;
// param1 the polygon's vertex count, its vertices on consecutive lines),
// FENCE_CIRCLE_INCLUSION / _EXCLUSION (5003, 5004; param1 the radius in
// metres), RALLY_POINT (5100; the altitude above home). FENCE_RETURN_POINT
// (5000) has no place in a MissionPlan and is passed over. Blank lines, CRLF
// line ends and lines starting with '#' (ArduPilot's test missions carry such
// comments) are passed over. "QGC WPL 120", QGroundControl's format before
// 2016 with no home line, is refused: a .plan carries the same and more.

#include "link/plan/MissionPlan.h"

#include <optional>

namespace WaypointsFile {

std::optional<MissionPlan> read(const QByteArray& text, const QString& source, QString* error = nullptr);
// QGC WPL 110 with the home on line 2 (zeros when the plan has none).
// Positions not given are written as 0, NaN parameters as "nan". The
// geofence and the rally points have no place in this format and are left
// out.
QByteArray write(const MissionPlan& plan);

}  // namespace WaypointsFile
