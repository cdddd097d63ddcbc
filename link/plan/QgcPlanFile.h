#pragma once

// QGroundControl's .plan (JSON): the mission, the geofence and the rally
// points. Also reads QGroundControl's older .mission files (the mission
// object alone, at the top of the file).
//
// Mission items come in three styles, all still loaded by QGroundControl:
// "params" with 7 values; "params" with 4 values and "coordinate":
// [latitude, longitude, altitude]; and "param1".."param4" with "coordinate".
// Complex items (landing patterns, surveys, corridor and structure scans)
// are read into the simple items QGroundControl uploads for them
// (link/plan/QgcComplexItemReader.h).
//
// The geofence is read from version 2 ("polygons" and "circles"), the rally
// points from version 2 ("points"), and from those keys without a "version"
// as other programs write them. Version 1 of either, which QGroundControl
// itself skips, is accepted only when empty, so that nothing in a file is
// lost without a word. The geofence's breach return point has no place in a
// MissionPlan and is not read.
//
// Errors name the file, the line where the offending element starts (left
// out when that is line 1: the item number says as much in a plan written
// on one line), the element and what is wrong with it.

#include "link/plan/MissionPlan.h"

#include <optional>

namespace QgcPlanFile {

std::optional<MissionPlan> read(const QByteArray& json, const QString& source, QString* error = nullptr);
// A .plan QGroundControl loads: file version 1, mission version 2 with
// simple items in the "params" style, geofence and rally points version 2.
// NaN parameters and positions not given are written as null.
QByteArray write(const MissionPlan& plan);

}  // namespace QgcPlanFile
