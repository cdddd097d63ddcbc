#pragma once

// A flight plan as the console edits it: the mission items, home, the
// geofence and the rally points, in degrees and metres. Its bytes for BLOCK 2
// are laid out by codec/plan/PlanContents.h (format 1 without fence and rally
// points, format 2 with them); toBytes() and fromBytes() convert, rounding
// to the nearest step of each field (1e-7 degree, 1 mm).
//
// Reading and writing plan files of other programs is link/plan/PlanFile.h.

#include <QByteArray>
#include <QList>
#include <QString>
#include <QStringList>

#include <array>
#include <cstdint>
#include <optional>

struct MissionItem {
    quint16 seq = 0;
    quint16 command = 0;
    quint8 frame = 0;
    bool autoContinue = true;
    std::array<double, 4> params{};   // NaN: null in the plan
    std::optional<double> latitude;   // degrees
    std::optional<double> longitude;  // degrees
    std::optional<double> altitude;   // metres, in the item's frame

    // Mission Planner's name: "WAYPOINT", "DO_MOUNT_CONTROL"; "MAV_CMD 1234"
    // for a command link/plan/MavCommand.h does not know.
    QString commandName() const;
    QString frameName() const;
    // MAV_FRAMEs whose x and y are a latitude and a longitude.
    static bool isGlobalFrame(int frame);
    // A global frame with both latitude and longitude, in a command that
    // takes a position (link/plan/MavCommand.h; any command it does not
    // know): a place on the map. 0 degrees north, 0 east is not: MAVLink
    // planners write it for "no position" in items such as DO_LAND_START
    // and a TAKEOFF that climbs where it is.
    bool hasPosition() const;
    // The altitude, when the command uses one (any command MavCommand does
    // not know, in a global frame): a TAKEOFF's yes, a RETURN_TO_LAUNCH's no.
    bool hasAltitude() const;
    friend bool operator==(const MissionItem&, const MissionItem&) = default;
};

struct GeoPoint {
    double latitude = 0;   // degrees
    double longitude = 0;  // degrees
    friend bool operator==(const GeoPoint&, const GeoPoint&) = default;
};

struct FencePolygon {
    bool inclusion = true;  // true: the aircraft stays inside; false: outside
    QList<GeoPoint> vertices;
    friend bool operator==(const FencePolygon&, const FencePolygon&) = default;
};

struct FenceCircle {
    bool inclusion = true;
    GeoPoint centre;
    double radius = 0;  // metres
    friend bool operator==(const FenceCircle&, const FenceCircle&) = default;
};

struct RallyPoint {
    GeoPoint position;
    double altitude = 0;  // metres above home
    friend bool operator==(const RallyPoint&, const RallyPoint&) = default;
};

class MissionPlan {
public:
    static constexpr int kHeaderBytes = 16;
    static constexpr int kItemBytes = 34;
    static constexpr std::int32_t kNotGiven = INT32_MIN;
    static constexpr double kDegreeSteps = 1e7;  // steps of a degree in the plan bytes
    static constexpr double kMillimetres = 1e3;  // steps of a metre

    // True when `value`, scaled by `steps` and rounded, fits the plan bytes'
    // int32 fields (and is not INT32_MIN, which means "not given").
    static bool fitsField(double value, double steps);

    // Plan bytes (codec/plan/PlanContents.h). Nothing, with the reason, for a
    // plan the layout cannot hold (a value out of its field's range, more
    // than 65535 of something).
    std::optional<QByteArray> encode(QString* error = nullptr) const;
    // encode() for a plan known to fit (one that came from fromBytes() or a
    // plan file reader, which check ranges); empty when it does not.
    QByteArray toBytes() const;
    static std::optional<MissionPlan> fromBytes(const QByteArray& bytes, QString* error = nullptr);

    // 1 without fence and rally points, else 2.
    int format() const;
    // Home as a place on the map: nothing without one, or at 0 degrees north,
    // 0 east, which Mission Planner writes for a home it does not know.
    std::optional<GeoPoint> home() const;
    bool hasFence() const { return !fencePolygons.isEmpty() || !fenceCircles.isEmpty(); }
    // Renumbers seq 0 .. N-1 after an edit. People count the items from 1,
    // as QGroundControl and Mission Planner do: item seq is "mission item
    // seq + 1" in every message.
    void renumber();
    // Each mission item with a position, and each rally point, that the
    // fence forbids, for people: "mission item 4 is inside exclusion circle
    // 1", "rally point 2 is outside every inclusion area". Distances on a
    // sphere of the Earth's mean radius; polygon edges as straight lines in
    // latitude and longitude, which is what a fence a few kilometres across
    // is drawn as.
    QStringList fenceViolations() const;

    QList<MissionItem> items;
    std::optional<double> homeLatitude;
    std::optional<double> homeLongitude;
    std::optional<double> homeAltitude;  // metres above mean sea level
    QList<FencePolygon> fencePolygons;
    QList<FenceCircle> fenceCircles;
    QList<RallyPoint> rallyPoints;

    friend bool operator==(const MissionPlan&, const MissionPlan&) = default;
};
