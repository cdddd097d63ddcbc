#pragma once

// A plan drawn in Google Earth or any other program that writes KML:
//
// - every LineString's points become mission waypoints (NAV_WAYPOINT, 16),
//   in the order of the document;
// - every Polygon becomes a geofence polygon: its outer boundary an
//   inclusion polygon (the aircraft stays inside), each inner boundary an
//   exclusion polygon (a hole the aircraft stays out of). KML closes a ring
//   by repeating its first vertex; the repeat is dropped;
// - a Point placemark whose name starts with "Rally" (any case) becomes a
//   rally point; any other Point placemark a waypoint, in document order with
//   the LineStrings' points.
//
// Altitudes follow the geometry's <altitudeMode>: "relativeToGround" takes
// the KML altitude as metres above home (frame 3, GLOBAL_RELATIVE_ALT),
// "absolute" as metres above mean sea level (frame 0, GLOBAL; refused for a
// rally point, whose altitude is above home). Otherwise, and for a point
// with no altitude, KML puts the point on the ground (clampToGround is KML's
// default, and the altitude Google Earth writes then is 0), so the point
// takes kDefaultAltitude above home instead: a waypoint at 0 m above home
// would fly into the ground.
//
// The plan has no home: KML has no such thing. Errors name the file, the
// line and column, and the element.

#include "link/plan/MissionPlan.h"

#include <optional>

namespace KmlFile {

// Metres above home for points KML puts on the ground.
inline constexpr double kDefaultAltitude = 100;

std::optional<MissionPlan> read(const QByteArray& kml, const QString& source, QString* error = nullptr);

}  // namespace KmlFile
