// The one table of BLOCK 1 items. Encoder, decoder, text format, panels and
// the Wireshark dissector all read it; nothing else restates an item.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <string_view>

namespace rcm {

enum class ItemId : std::uint8_t {
    ID_msg = 0x03,
    ID_UA_source = 0x04,
    time_UTC = 0x05,
    date_UTC = 0x06,
    ID_BLK12_format = 0x07,
    ID_GCS_destination = 0x08,
    ID_GCS_backup = 0x09,
    eng_status = 0x30,
    eng_ID = 0x31,
    eng_prop_pitch = 0x32,
    eng_carb_SET = 0x33,
    FLAP_status = 0x40,
    F_aileron_LHS_set = 0x41,
    F_aileron_RHS_set = 0x42,
    F_lift_set = 0x43,
    F_rudder_set = 0x44,
    F_elev_set = 0x45,
    F_airbrake_set = 0x46,
    ENABLE_fuel_dump = 0x60,
    land_wheels = 0x70,
    lights = 0x71,
    setting_72 = 0x72,
    receiver_control = 0x80,
    system_ID = 0x81,
    Rx_freq = 0x82,
    Tx_freq = 0x83,
    Tx_OP_power = 0x84,
    SA_zoom_LHS_cam = 0xB0,
    SA_zoom_FWD_cam = 0xB1,
    SA_zoom_RHS_cam = 0xB2,
    cam_ID = 0xC0,
    cam_mag_compass = 0xC1,
    cam_elev = 0xC2,
    cam_zoom_set = 0xC3,
    take_one_photo = 0xC4,
    cam_GCS_destination = 0xC5,
    cam_GCS_backup = 0xC6,
};

// ID_msg counts up by one a frame and wraps here (3 value bytes).
inline constexpr std::uint32_t kMessageIdModulus = 1u << 24;

// The flaps unit's control surfaces, each a commanded angle, in canonical
// order; and the sense-and-avoid cameras' zooms, left, forward, right.
// ItemTable.cpp checks both against the table.
inline constexpr std::array<ItemId, 6> kFlapSurfaces{ItemId::F_aileron_LHS_set, ItemId::F_aileron_RHS_set,
                                                     ItemId::F_lift_set,        ItemId::F_rudder_set,
                                                     ItemId::F_elev_set,        ItemId::F_airbrake_set};
inline constexpr std::array<ItemId, 3> kSenseAndAvoidZooms{ItemId::SA_zoom_LHS_cam, ItemId::SA_zoom_FWD_cam,
                                                           ItemId::SA_zoom_RHS_cam};

// Items that command something once (a photograph): sent in one frame, then
// back to the resting value; never taken from a report, which says what
// happened, not what to do again.
inline constexpr std::array<ItemId, 1> kOneShotItems{ItemId::take_one_photo};

// Two-bit field codes by meaning (PROFILE.md section 2); the table names
// each field's codes by these. A code no field names means data corruption.
namespace code {
inline constexpr unsigned kAuto = 1, kGcs = 2, kRc = 3;  // control source
inline constexpr unsigned kNoSlave = 1, kMasterSlave = 2;
inline constexpr unsigned kOff = 1, kOn = 2;
inline constexpr unsigned kOut = 1, kRetracted = 2;  // a wheel
inline constexpr unsigned kNoDump = 1, kDump = 2;
inline constexpr unsigned kDisabled = 1, kEnabled = 2;
inline constexpr unsigned kNone = 1, kTake = 2;  // take one photo
}  // namespace code

// Bytes inside BLOCK 1 that are not items.
inline constexpr std::uint8_t kPad55 = 0x55;    // NULL_0101
inline constexpr std::uint8_t kPadAA = 0xAA;    // NULL_1010
inline constexpr std::uint8_t kBegin = 0x01;    // BEGIN + section byte, never emitted
inline constexpr std::uint8_t kEnd = 0x02;      // END, never emitted

// The units an item belongs to, in canonical order. Engine, Radio and Camera
// repeat; each instance starts with its key item.
enum class UnitKind : std::uint8_t { Header, Engine, Flaps, FcuGeneral, Settings, Radio, Sense, Camera };
inline constexpr int kUnitKindCount = 8;

enum class ValueKind : std::uint8_t {
    Unsigned,   // big-endian unsigned integer of `size` bytes
    Signed,     // big-endian two's complement
    Station,    // country dialling code (uint16) + unit number (uint16)
    Time,       // hhmmss as a decimal number in a uint24
    Date,       // yymmdd likewise
    BytePair,   // two independent bytes
    Fields,     // four two-bit fields, 01 and 10 valid, reserved fields 00
    Text,       // ASCII, space padded
    CameraId,   // three ASCII characters + camera number
    Raw,        // an opaque byte kept as it was
};

// One two-bit field: its name and the names of its four codes, indexed by the
// code (00, 01, 10, 11). An empty name marks a code meaning "data corruption".
struct FieldInfo {
    std::string_view name;
    std::array<std::string_view, 4> codes;
    std::string_view label;  // for people: "Control source"
    // For people, indexed like `codes`: "Independent" for NO_SLAVE; empty: the code name.
    std::array<std::string_view, 4> words{};
};

// How the console shows a number to people where that is not the text
// format's unit and scale: `wire` units of the value are `shown` units of
// `unit` (kHz as MHz: 1000 -> 1; a 0..255 setting as percent: 255 -> 100),
// with `decimals`. The console offers `min`..`max` (wire units) when they
// are narrower than the item's range; the encoder and the text format keep
// the item's range.
struct Presentation {
    std::string_view unit;
    std::int64_t wire = 1;
    std::int64_t shown = 1;
    int decimals = 0;
    std::int64_t min = 0;
    std::int64_t max = -1;  // below min: the item's own range
};

// What one action of the operator may change of an item before the console
// asks first (docs/protocol.md section 2): a change from the value in force
// by more than `step` (wire units), to either end of the item's range when
// `extremes`, or of a field to the code named for it. A change in the other
// direction (gear out, fuel kept, a transmitter off) never asks.
inline constexpr std::int64_t kAnyStep = std::numeric_limits<std::int64_t>::max();
struct FieldConfirmation {
    std::uint8_t code = 0;    // the code that asks; 0 (corrupt in every field): none
    std::string_view action;  // the button that confirms it: "Retract nose wheel"
};
struct LargeChange {
    std::int64_t step = kAnyStep;               // numbers: the largest change made without asking
    bool extremes = false;                      // numbers: a change to min or max asks
    std::string_view action;                    // numbers: the button that confirms it: "Move left aileron"
    std::array<FieldConfirmation, 4> fields{};  // Fields: per field, most significant first
    std::string_view note;                      // why it asks, for people; may be empty
};

struct ItemInfo {
    ItemId id;
    std::string_view name;   // the name in the text format, unique within its unit
    std::uint8_t size;       // value bytes after the Item_ID byte
    ValueKind kind;
    std::int64_t min;        // range of the value in its text units x scale
    std::int64_t max;        //   (Station: of the country code; Text: of the length)
    int scale;               // 100 for hundredths of a degree, else 1
    std::string_view unit;   // "deg", "kHz", "dBm", "" ...
    UnitKind owner;
    std::string_view label;  // for people: "Propeller pitch"
    std::span<const FieldInfo> fields;  // Fields kind only, most significant first
    bool key = false;        // starts a repeated unit
    std::optional<Presentation> presentation{};  // nothing: unit and scale as above
    LargeChange largeChange{};                   // by default no change asks
};

// All items in canonical order: the order an encoder emits them in.
std::span<const ItemInfo> itemTable();

// nullptr when the ID is not an item (padding, BEGIN/END and unused IDs too).
const ItemInfo* findItem(std::uint8_t id);
inline const ItemInfo* findItem(ItemId id) { return findItem(static_cast<std::uint8_t>(id)); }
const ItemInfo& itemInfo(ItemId id);  // for IDs known to be items
const ItemInfo* findItem(UnitKind owner, std::string_view name);

// How the console shows the item: its presentation, or else its own unit
// and scale with the range of the table ("deg" written as the degree sign).
Presentation presentation(const ItemInfo& item);

// Position of an item in canonical order; used to keep units sorted.
int canonicalRank(ItemId id);

// The key item of a repeated unit, or nothing for the single units.
std::optional<ItemId> unitKey(UnitKind kind);
bool isRepeated(UnitKind kind);

// Text-format section names: "HEADER", "engine", ...; and the enclosing
// section ("FCU" for engine, flaps, FCU_general; "" for top-level ones).
std::string_view sectionName(UnitKind kind);
std::string_view parentSectionName(UnitKind kind);
std::optional<UnitKind> unitKindFromSection(std::string_view name);
std::string_view unitLabel(UnitKind kind);  // "Engine", "Radio" ... for people

// Two-bit field access, B1_0B1_1 being field 0 (the most significant bits).
constexpr unsigned fieldCode(std::uint8_t value, int field)
{
    return (value >> (6 - 2 * field)) & 0x3u;
}
constexpr std::uint8_t withFieldCode(std::uint8_t value, int field, unsigned code)
{
    const int shift = 6 - 2 * field;
    return static_cast<std::uint8_t>((value & ~(0x3u << shift)) | ((code & 0x3u) << shift));
}
// A Fields item's byte with `code` in each of its first `fields` fields and
// the rest reserved (00).
constexpr std::uint8_t withEveryFieldCode(unsigned code, int fields = 4)
{
    std::uint8_t value = 0;
    for (int f = 0; f < fields; ++f)
        value = withFieldCode(value, f, code);
    return value;
}
// True when the code has a meaning for this field (not corruption).
inline bool fieldCodeValid(const FieldInfo& field, unsigned code) { return !field.codes[code & 3].empty(); }

}  // namespace rcm
