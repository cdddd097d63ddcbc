#pragma once

// A mission from QGroundControl (a `.plan` file) and the bytes the console
// uploads for it in BLOCK 2 sections (codec/message/FlightPlanTransfer.h carries them
// as an opaque plan; this is what they hold).
//
// ## Flight plan contents: the waypoint list (plan format 1)
//
// The plan bytes are a header and one record per mission item, big-endian
// like every number in the profile. The records are MAVLink's MISSION_ITEM_INT
// without its routing fields: an autopilot that speaks MAVLink, which is what
// flies the mission, takes them over one to one, and QGroundControl, which
// plans it, writes exactly these fields. Positions are fixed-point integers
// (as in MISSION_ITEM_INT) so that the bytes, and so the plan's CRC-32, do not
// depend on how a machine rounds floating point; altitude is in millimetres
// for the same reason.
//
//     Header, 16 bytes
//     bytes  field
//     1      format: 1, this layout
//     1      reserved: 0
//     2      N: number of mission items, uint16
//     4      home latitude, int32, 1e-7 degree (QGC plannedHomePosition)
//     4      home longitude, int32, 1e-7 degree
//     4      home altitude, int32, millimetres above mean sea level
//
//     Mission item, 34 bytes, N times in mission order
//     bytes  field
//     2      seq: the item's position in the mission, 0 .. N-1, uint16
//     2      command: MAVLink MAV_CMD, uint16 (16 NAV_WAYPOINT, 21 NAV_LAND,
//            22 NAV_TAKEOFF, 20 NAV_RETURN_TO_LAUNCH, 178 DO_CHANGE_SPEED ...)
//     1      frame: MAVLink MAV_FRAME, uint8 (0 GLOBAL: altitude above mean
//            sea level; 2 MISSION: no position; 3 GLOBAL_RELATIVE_ALT:
//            altitude above home; 10 GLOBAL_TERRAIN_ALT: above terrain)
//     1      flags: bit 0 (least significant) autocontinue; other bits 0
//     16     param1 .. param4: IEEE 754 binary32 each; NaN where the plan
//            says null ("keep the current value")
//     4      x: latitude, int32, 1e-7 degree (MAVLink param5)
//     4      y: longitude, int32, 1e-7 degree (param6)
//     4      z: altitude, int32, millimetres in the item's frame (param7)
//
// A position the plan leaves null is 0x80000000 (INT32_MIN) in x, y or z:
// "not given", distinct from 0, which is a place. For frame 2 (MISSION) x, y
// and z carry whatever params 5-7 say, scaled the same way. So a plan of N
// items is 16 + 34 N bytes: the sample's 9 items are 322 bytes, two BLOCK 2
// sections with the 10-byte transfer descriptor.

#include <QByteArray>
#include <QList>
#include <QString>

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

    // "NAV_WAYPOINT" for the commands a console shows often, else "MAV_CMD 1234".
    QString commandName() const;
    QString frameName() const;
};

class MissionPlan {
public:
    static constexpr quint8 kFormat = 1;
    static constexpr int kHeaderBytes = 16;
    static constexpr int kItemBytes = 34;
    static constexpr std::int32_t kNotGiven = INT32_MIN;

    // Reads a QGroundControl plan. Only SimpleItems can be sent: a plan with a
    // survey, a corridor scan or another ComplexItem is refused, naming it
    // (QGroundControl can convert those to simple items).
    static std::optional<MissionPlan> load(const QString& path, QString* error = nullptr);
    static std::optional<MissionPlan> fromQgcJson(const QByteArray& json, const QString& source,
                                                  QString* error = nullptr);

    // The plan bytes in the layout above, and their inverse. Values are
    // rounded to the nearest step of their field (1e-7 degree, 1 mm).
    QByteArray toBytes() const;
    static std::optional<MissionPlan> fromBytes(const QByteArray& bytes, QString* error = nullptr);

    QList<MissionItem> items;
    std::optional<double> homeLatitude;
    std::optional<double> homeLongitude;
    std::optional<double> homeAltitude;  // metres above mean sea level
};
