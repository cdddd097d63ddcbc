#pragma once

// QGroundControl's complex items in a .plan ("type": "ComplexItem"), read
// into the mission items QGroundControl uploads for them, in its order and
// with its parameters:
//
// - "fwLandingPattern" (fixed-wing landing pattern, versions 1 and 2) and
//   "vtolLandingPattern" (version 1): DO_LAND_START; the stop-photos pair
//   (DO_SET_CAM_TRIGG_DIST 0, IMAGE_STOP_CAPTURE) and VIDEO_STOP_CAPTURE when
//   asked for; the final approach (LOITER_TO_ALT with the loiter radius,
//   negative anticlockwise, or a WAYPOINT); LAND (VTOL_LAND). The positions
//   are the file's: QGroundControl flies the approach and landing
//   coordinates it saved, whatever its heading and distance fields say.
// - "survey" and "CorridorScan": the items QGroundControl saved with them
//   ("TransectStyleComplexItem" / "Items"), which are what it uploads until
//   the operator edits the pattern. A version 3 survey (QGroundControl 3.3
//   and before) holds none and is refused.
// - "StructureScan" (version 3): built as QGroundControl builds it, since
//   the file holds only the pattern: the structure's polygon moved out by
//   the camera's distance to the surface (QGroundControl's own edge offset,
//   in its plane about the first vertex), entered and left at the first
//   vertex at the entrance altitude, one loop of the polygon per layer with
//   the camera triggered every side footprint, the gimbal pointed at the
//   structure with DO_SET_ROI_WPNEXT_OFFSET and released with
//   DO_SET_ROI_NONE.
//
// Approximations, all within centimetres: the structure scan's offset uses
// QGroundControl 4's plane (azimuthal equidistant on a sphere of the WGS 84
// equatorial radius); QGroundControl 5 uses an ellipsoidal tangent plane,
// which moves a vertex 30 m out by a few centimetres. The footprints
// (CameraCalc "AdjustedFootprintFrontal"/"Side") are the ones QGroundControl
// saved; for a known camera it computes them again when it loads the file,
// which gives the same values unless its camera list changed since. The
// number of layers is QGroundControl's: the structure's height over the
// frontal footprint, rounded up, at least 1.
//
// Refused, each saying which item and what: a landing pattern with
// QGroundControl 5's "useDoChangeSpeed" on (where QGroundControl puts that
// speed change is not known here), any other complex item type, and
// anything QGroundControl itself would not load.

#include "link/plan/MissionPlan.h"

#include <QJsonObject>
#include <QStringList>

#include <functional>

class QgcComplexItemReader {
public:
    // Sets the error for the element at `path` (keys and indices from the
    // top of the file) to `what`; returns false.
    using Fail = std::function<bool(const QStringList& path, const QString& what)>;
    // Reads one item in QGroundControl's simple item layout, at `path`,
    // named `where` in errors.
    using ReadSimpleItem =
        std::function<bool(const QJsonValue& value, const QString& where, const QStringList& path, MissionItem& item)>;

    QgcComplexItemReader(Fail fail, ReadSimpleItem readSimpleItem);

    // "fixed-wing landing pattern", "survey"; for a type not read, the type as written.
    static QString kindName(const QString& complexItemType);

    // Appends the mission items the complex item `item` (at `path`, named
    // `where` in errors: "mission item 4") stands for to `out`; their seq is
    // left for the caller to number.
    bool read(const QJsonObject& item, const QString& where, const QStringList& path, QList<MissionItem>& out);

private:
    bool readLanding(const QJsonObject& item, bool vtol, const QString& where, const QStringList& path,
                     QList<MissionItem>& out);
    bool readTransectStyle(const QJsonObject& item, const QString& where, const QStringList& path,
                           QList<MissionItem>& out);
    bool readStructureScan(const QJsonObject& item, const QString& where, const QStringList& path,
                           QList<MissionItem>& out);
    // A [latitude, longitude, altitude] (altitude required) or [latitude, longitude].
    bool readCoordinate(const QJsonObject& item, const QString& key, bool withAltitude, const QString& where,
                        const QStringList& path, GeoPoint& point, double* altitude);
    bool readNumber(const QJsonObject& object, const QString& key, const QString& where, const QStringList& path,
                    double& value);
    bool readBool(const QJsonObject& object, const QString& key, const QString& where, const QStringList& path,
                  bool& value, std::optional<bool> byDefault = std::nullopt);

    Fail m_fail;
    ReadSimpleItem m_readSimpleItem;
};
