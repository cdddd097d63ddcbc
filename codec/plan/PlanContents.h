#pragma once

// What the flight plan bytes hold (codec/message/FlightPlanTransfer.h carries
// them as an opaque run of bytes): the mission, and in format 2 also the
// geofence and the rally points. Plain C++ over byte buffers, so that an
// aircraft decodes the same bytes the console encodes.
//
// Every number is big-endian like every number in the profile. Positions are
// fixed-point integers (as in MAVLink's MISSION_ITEM_INT) so that the bytes,
// and so the plan's CRC-32, do not depend on how a machine rounds floating
// point; altitudes and radii are in millimetres for the same reason.
//
// ## Format 1: the mission
//
//     Header, 16 bytes
//     bytes  field
//     1      format: 1 or 2
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
// "not given", distinct from 0, which is a place. So a format 1 plan of N
// items is 16 + 34 N bytes.
//
// ## Format 2: the mission, the geofence and the rally points
//
// The header and the items as in format 1 (format byte 2), then:
//
//     2      P: fence polygons, uint16; then P times:
//              1   flags: bit 0 inclusion (1: stay inside; 0: stay outside)
//              1   reserved: 0
//              2   V: vertices, uint16, 3 or more
//              8V  V times latitude, longitude: int32 1e-7 degree each
//     2      C: fence circles, uint16; then C times, 14 bytes each:
//              1   flags: bit 0 inclusion
//              1   reserved: 0
//              4   centre latitude, int32 1e-7 degree
//              4   centre longitude, int32 1e-7 degree
//              4   radius, uint32 millimetres, more than 0
//     2      R: rally points, uint16; then R times, 12 bytes each:
//              4   latitude, int32 1e-7 degree
//              4   longitude, int32 1e-7 degree
//              4   altitude, int32 millimetres above home
//
// Nothing follows. A sender writes format 1 when the plan has no fence and
// no rally point, so a plan that has neither has the same bytes (and CRC) as
// before format 2 existed, and an aircraft that reads only format 1 still
// takes it.
//
// ## The aircraft's report
//
// An aircraft that decodes a format 2 plan says what it holds in its
// acknowledgement (FlightPlanAcknowledgement::report), so the operator sees
// that the fence and rally points arrived, not only that the bytes did:
//
//     1      format of the plan held
//     2      mission items, uint16
//     2      fence polygons, uint16
//     2      fence vertices in all polygons, uint16 (saturating)
//     2      fence circles, uint16
//     2      rally points, uint16
//
// 11 bytes. An acknowledgement of a format 1 plan carries no report, as
// before.

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace rcm::plan {

inline constexpr std::int32_t kNotGiven = INT32_MIN;
inline constexpr std::size_t kHeaderBytes = 16;
inline constexpr std::size_t kItemBytes = 34;

struct Item {
    std::uint16_t seq = 0;
    std::uint16_t command = 0;
    std::uint8_t frame = 0;
    bool autoContinue = true;
    std::array<std::uint32_t, 4> params{};  // binary32 bit patterns
    std::int32_t x = kNotGiven;             // 1e-7 degree
    std::int32_t y = kNotGiven;             // 1e-7 degree
    std::int32_t z = kNotGiven;             // millimetres
    friend bool operator==(const Item&, const Item&) = default;
};

struct Position {
    std::int32_t latitude = 0;   // 1e-7 degree
    std::int32_t longitude = 0;  // 1e-7 degree
    friend bool operator==(const Position&, const Position&) = default;
};

struct FencePolygon {
    bool inclusion = true;
    std::vector<Position> vertices;
    friend bool operator==(const FencePolygon&, const FencePolygon&) = default;
};

struct FenceCircle {
    bool inclusion = true;
    Position centre;
    std::uint32_t radius = 0;  // millimetres
    friend bool operator==(const FenceCircle&, const FenceCircle&) = default;
};

struct RallyPoint {
    Position position;
    std::int32_t altitude = 0;  // millimetres above home
    friend bool operator==(const RallyPoint&, const RallyPoint&) = default;
};

struct Contents {
    std::int32_t homeLatitude = kNotGiven;
    std::int32_t homeLongitude = kNotGiven;
    std::int32_t homeAltitude = kNotGiven;
    std::vector<Item> items;
    std::vector<FencePolygon> polygons;
    std::vector<FenceCircle> circles;
    std::vector<RallyPoint> rallyPoints;

    // 1 without fence and rally points, else 2.
    std::uint8_t format() const;
    friend bool operator==(const Contents&, const Contents&) = default;
};

// The plan bytes. Throws std::invalid_argument for what the layout cannot
// hold (more than 65535 items, polygons, vertices ..., a polygon with fewer
// than 3 vertices, a circle without a radius), naming it.
std::vector<std::uint8_t> encode(const Contents& contents);

// Nothing, with the reason and the byte offset in `error`, for bytes that are
// not a format 1 or 2 plan.
std::optional<Contents> decode(std::span<const std::uint8_t> bytes, std::string* error = nullptr);

// What an aircraft reports of the plan it holds.
struct Report {
    static constexpr std::size_t kSize = 11;
    std::uint8_t format = 0;
    std::uint16_t items = 0;
    std::uint16_t polygons = 0;
    std::uint16_t vertices = 0;
    std::uint16_t circles = 0;
    std::uint16_t rallyPoints = 0;

    static Report of(const Contents& contents);
    std::vector<std::uint8_t> toBytes() const;
    // Nothing unless `bytes` is exactly kSize long.
    static std::optional<Report> read(std::span<const std::uint8_t> bytes);
    // "9 mission items, fence 2 polygons (11 vertices) and 1 circle, 3 rally points"
    std::string describe() const;
    friend bool operator==(const Report&, const Report&) = default;
};

}  // namespace rcm::plan
