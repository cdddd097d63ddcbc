#include "codec/message/ItemTable.h"

#include <initializer_list>
#include <stdexcept>
#include <utility>

namespace rcm {
namespace {

// Code names, indexed by the two-bit code 00, 01, 10, 11; "" where unnamed.
constexpr std::array<std::string_view, 4> codeNames(std::initializer_list<std::pair<unsigned, std::string_view>> named)
{
    std::array<std::string_view, 4> names{};
    for (const auto& [c, name] : named)
        names[c] = name;
    return names;
}

constexpr auto kControl = codeNames({{code::kAuto, "AUTO"}, {code::kGcs, "GCS"}, {code::kRc, "RC"}});
constexpr auto kSlave = codeNames({{code::kNoSlave, "NO_SLAVE"}, {code::kMasterSlave, "MASTER_SLAVE"}});
constexpr auto kOnOff = codeNames({{code::kOff, "OFF"}, {code::kOn, "ON"}});
constexpr auto kWheel = codeNames({{code::kOut, "OUT"}, {code::kRetracted, "RETRACTED"}});
constexpr auto kDump = codeNames({{code::kNoDump, "NO_DUMP"}, {code::kDump, "DUMP"}});
constexpr auto kFacility = codeNames({{code::kDisabled, "DISABLED"}, {code::kEnabled, "ENABLED"}});
constexpr auto kPhoto = codeNames({{code::kNone, "NONE"}, {code::kTake, "TAKE"}});

// The same codes for people.
constexpr std::array<std::string_view, 4> kControlWords{"", "Automatic", "Ground station", "RC transmitter"};
constexpr std::array<std::string_view, 4> kSlaveWords{"", "Independent", "Master and slave", ""};
// Every engine's status carries the mode that pairs engine 1 (master) with
// engine 3 (slave); the panels say on each engine's card what it means there.
constexpr std::array<std::string_view, 4> kEngineSlaveWords{"", "Independent", "Engine 1 master, engine 3 slave", ""};
constexpr std::array<std::string_view, 4> kOnOffWords{"", "Off", "On", ""};
constexpr std::array<std::string_view, 4> kWheelWords{"", "Out (down)", "Retracted", ""};
constexpr std::array<std::string_view, 4> kDumpWords{"", "Keep fuel", "Dump", ""};
constexpr std::array<std::string_view, 4> kFacilityWords{"", "Disabled", "Enabled", ""};
constexpr std::array<std::string_view, 4> kPhotoWords{"", "None", "Take", ""};

// A 0..255 setting "between the two extremes" (propeller pitch, carburettor,
// zoom): people read it as percent of the way from one extreme to the other.
constexpr Presentation kPercent{"%", 255, 100, 1};
// The radios tune in kHz on the wire; airband frequencies are read in MHz.
constexpr Presentation kMegahertz{"MHz", 1000, 1, 3};
// uint8 dBm allows 255 dBm (10^22 W). The console offers 0..50 dBm, 1 mW to
// 100 W: airborne VHF sets transmit 8..25 W (39..44 dBm), and 100 W is the
// most any ground or airborne airband set gives. The text format and the
// encoder still take 0..255, as the profile does.
constexpr Presentation kTransmitPower{"dBm", 1, 1, 0, 0, 50};

// Changes one action makes only once the operator confirms (ItemTable.h,
// LargeChange; docs/protocol.md section 2 lists them).
// A control surface: more than 5 degrees at once. Single steps of a degree
// (a slider's arrow key) and small trims go as they are.
constexpr LargeChange surfaceChange(std::string_view action)
{
    return {5, false, action, {}, "A surface moved far in one step can upset the aircraft."};
}
// An engine setting: more than 20 % of its range (51 of 255) at once, or to
// either extreme (0 or 255), however small the step there.
constexpr LargeChange engineChange(std::string_view action)
{
    return {51, true, action, {}, "A large or full change of an engine setting changes thrust at once."};
}
constexpr LargeChange kGearRetraction{kAnyStep, false, "",
                                      {{{code::kRetracted, "Retract left wheel"},
                                        {code::kRetracted, "Retract right wheel"},
                                        {code::kRetracted, "Retract nose wheel"},
                                        {code::kRetracted, "Retract tail wheel"}}},
                                      "A retracted wheel cannot carry the aircraft on the ground."};
constexpr LargeChange kFuelDumping{kAnyStep, false, "",
                                   {{{code::kEnabled, "Enable fuel dump"},
                                     {code::kDump, "Dump tank 1"},
                                     {code::kDump, "Dump tank 2"},
                                     {code::kDump, "Dump tank 3"}}},
                                   "Dumped fuel cannot be recovered."};
constexpr LargeChange kTransmitterOn{kAnyStep, false, "",
                                     {{{}, {code::kOn, "Switch transmitter on"}}},
                                     "The transmitter radiates at its frequency and power as soon as it is on."};

constexpr FieldInfo kEngStatus[] = {
    {"control", kControl, "Control source", kControlWords},
    {"slave", kSlave, "Master/slave mode", kEngineSlaveWords},
};
constexpr FieldInfo kFlapStatus[] = {
    {"control", kControl, "Control source", kControlWords},
    {"slave_aileron", kSlave, "Master LH + slave RH aileron", kSlaveWords},
};
constexpr FieldInfo kFuelDump[] = {
    {"facility", kFacility, "Fuel dump facility", kFacilityWords},
    {"tank1", kDump, "Dump tank 1", kDumpWords},
    {"tank2", kDump, "Dump tank 2", kDumpWords},
    {"tank3", kDump, "Dump tank 3", kDumpWords},
};
constexpr FieldInfo kWheels[] = {
    {"LHS", kWheel, "Left wheel", kWheelWords},
    {"RHS", kWheel, "Right wheel", kWheelWords},
    {"NOSE", kWheel, "Nose wheel", kWheelWords},
    {"TAIL", kWheel, "Tail wheel", kWheelWords},
};
constexpr FieldInfo kLights[] = {
    {"wing_RHS", kOnOff, "Right wing light", kOnOffWords},
    {"wing_LHS", kOnOff, "Left wing light", kOnOffWords},
    {"tail", kOnOff, "Tail light", kOnOffWords},
    {"wheel_brake", kOnOff, "Wheel brake", kOnOffWords},
};
constexpr FieldInfo kRadioControl[] = {
    {"receiver", kOnOff, "Receiver", kOnOffWords},
    {"transmitter", kOnOff, "Transmitter", kOnOffWords},
};
constexpr FieldInfo kPhotoField[] = {
    {"photo", kPhoto, "Take one photograph", kPhotoWords},
};

using enum ItemId;
using enum ValueKind;
using enum UnitKind;

constexpr std::int64_t kCountryMax = 1929;  // the seed's largest dialling code

// Canonical order: sections as PROFILE.md lists them, key item first in each
// repeated unit, the unit's other items in ascending Item_ID order.
constexpr ItemInfo kItems[] = {
    {ID_msg, "ID_msg", 3, Unsigned, 0, 0xFFFFFF, 1, "", Header, "Message ID", {}},
    {ID_UA_source, "ID_UA_source", 4, Station, 1, kCountryMax, 1, "", Header, "Aircraft ID", {}},
    {time_UTC, "time_UTC", 3, Time, 0, 235959, 1, "hh:mm:ss", Header, "Time (UTC)", {}},
    {date_UTC, "date_UTC", 3, Date, 0, 991231, 1, "yymmdd", Header, "Date (UTC)", {}},
    {ID_BLK12_format, "ID_BLK12_format", 2, BytePair, 0, 255, 1, "", Header, "Block 1 and 2 format IDs", {}},
    {ID_GCS_destination, "ID_GCS_destination", 4, Station, 1, kCountryMax, 1, "", Header, "GCS destination", {}},
    {ID_GCS_backup, "ID_GCS_backup", 4, Station, 1, kCountryMax, 1, "", Header, "GCS backup", {}},

    {eng_ID, "eng_ID", 1, Unsigned, 0, 255, 1, "", Engine, "Engine ID", {}, true},
    {eng_status, "eng_status", 1, Fields, 0, 255, 1, "", Engine, "Engine status", kEngStatus},
    {eng_prop_pitch, "eng_prop_pitch", 1, Unsigned, 0, 255, 1, "", Engine, "Propeller pitch", {}, false, kPercent,
     engineChange("Set propeller pitch")},
    {eng_carb_SET, "eng_carb_SET", 1, Unsigned, 0, 255, 1, "", Engine, "Carburettor setting", {}, false, kPercent,
     engineChange("Set carburettor")},

    {FLAP_status, "FLAP_status", 1, Fields, 0, 255, 1, "", Flaps, "Flaps status", kFlapStatus},
    {F_aileron_LHS_set, "F_aileron_LHS_set", 1, Signed, -127, 127, 1, "deg", Flaps, "Left aileron", {}, false, std::nullopt,
     surfaceChange("Move left aileron")},
    {F_aileron_RHS_set, "F_aileron_RHS_set", 1, Signed, -127, 127, 1, "deg", Flaps, "Right aileron", {}, false, std::nullopt,
     surfaceChange("Move right aileron")},
    {F_lift_set, "F_lift_set", 1, Signed, -127, 127, 1, "deg", Flaps, "Lift flaps", {}, false, std::nullopt,
     surfaceChange("Move lift flaps")},
    {F_rudder_set, "F_rudder_set", 1, Signed, -127, 127, 1, "deg", Flaps, "Rudder", {}, false, std::nullopt,
     surfaceChange("Move rudder")},
    {F_elev_set, "F_elev_set", 1, Signed, -127, 127, 1, "deg", Flaps, "Elevator", {}, false, std::nullopt,
     surfaceChange("Move elevator")},
    {F_airbrake_set, "F_airbrake_set", 1, Signed, -127, 127, 1, "deg", Flaps, "Airbrake", {}, false, std::nullopt,
     surfaceChange("Move airbrake")},

    {ENABLE_fuel_dump, "ENABLE_fuel_dump", 1, Fields, 0, 255, 1, "", FcuGeneral, "Fuel dump", kFuelDump, false,
     std::nullopt, kFuelDumping},

    {land_wheels, "land_wheels", 1, Fields, 0, 255, 1, "", Settings, "Landing gear", kWheels, false, std::nullopt,
     kGearRetraction},
    {lights, "lights", 1, Fields, 0, 255, 1, "", Settings, "Lights and wheel brake", kLights},
    {setting_72, "setting_72", 1, Raw, 0, 255, 1, "", Settings, "Reserved setting 72", {}},

    {system_ID, "system_ID", 8, Text, 0, 8, 1, "", Radio, "System ID", {}, true},
    {receiver_control, "receiver_control", 1, Fields, 0, 255, 1, "", Radio, "Receiver and transmitter", kRadioControl,
     false, std::nullopt, kTransmitterOn},
    {Rx_freq, "Rx_freq", 4, Unsigned, 0, 0xFFFFFFFF, 1, "kHz", Radio, "Receive frequency", {}, false, kMegahertz},
    {Tx_freq, "Tx_freq", 4, Unsigned, 0, 0xFFFFFFFF, 1, "kHz", Radio, "Transmit frequency", {}, false, kMegahertz},
    {Tx_OP_power, "Tx_OP_power", 1, Unsigned, 0, 255, 1, "dBm", Radio, "Transmit power", {}, false, kTransmitPower},

    {SA_zoom_LHS_cam, "SA_zoom_LHS_cam", 1, Unsigned, 0, 255, 1, "", Sense, "Left camera zoom", {}, false, kPercent},
    {SA_zoom_FWD_cam, "SA_zoom_FWD_cam", 1, Unsigned, 0, 255, 1, "", Sense, "Forward camera zoom", {}, false, kPercent},
    {SA_zoom_RHS_cam, "SA_zoom_RHS_cam", 1, Unsigned, 0, 255, 1, "", Sense, "Right camera zoom", {}, false, kPercent},

    {cam_ID, "cam_ID", 4, CameraId, 0, 255, 1, "", Camera, "Camera ID", {}, true},
    {cam_mag_compass, "cam_mag_compass", 2, Unsigned, 0, 35999, 100, "deg", Camera, "Compass bearing", {}},
    {cam_elev, "cam_elev", 2, Signed, -32767, 32767, 100, "deg", Camera, "Elevation", {}},
    {cam_zoom_set, "cam_zoom_set", 1, Unsigned, 0, 255, 1, "", Camera, "Zoom", {}, false, kPercent},
    {take_one_photo, "take_one_photo", 1, Fields, 0, 255, 1, "", Camera, "Take one photo", kPhotoField},
    {cam_GCS_destination, "ID_GCS_destination", 4, Station, 1, kCountryMax, 1, "", Camera, "Imagery destination GCS", {}},
    {cam_GCS_backup, "ID_GCS_backup", 4, Station, 1, kCountryMax, 1, "", Camera, "Imagery backup GCS", {}},
};

constexpr int kItemCount = static_cast<int>(std::size(kItems));

// The items of `owner` of `kind` are exactly `ids`, in order.
template <std::size_t N>
constexpr bool itemsAre(UnitKind owner, ValueKind kind, const std::array<ItemId, N>& ids)
{
    std::size_t n = 0;
    for (const ItemInfo& info : kItems)
        if (info.owner == owner && info.kind == kind && (n == N || info.id != ids[n++]))
            return false;
    return n == N;
}
static_assert(itemsAre(Flaps, Signed, kFlapSurfaces));
static_assert(itemsAre(Sense, Unsigned, kSenseAndAvoidZooms));

// Every large-change rule names its button, and a field's code that asks is
// one the field has.
constexpr bool largeChangesNamed()
{
    for (const ItemInfo& info : kItems) {
        const LargeChange& large = info.largeChange;
        if ((large.step != kAnyStep || large.extremes) && large.action.empty())
            return false;
        for (std::size_t f = 0; f < large.fields.size(); ++f) {
            const FieldConfirmation& field = large.fields[f];
            if (field.code == 0)
                continue;
            if (f >= info.fields.size() || info.fields[f].codes[field.code & 3u].empty() || field.action.empty())
                return false;
        }
    }
    return true;
}
static_assert(largeChangesNamed());

// Item_ID -> index in kItems, -1 for bytes that are not items; built at
// compile time because the decoder consults it for every byte it reads.
constexpr std::array<std::int16_t, 256> kIndexById = [] {
    std::array<std::int16_t, 256> byId{};
    byId.fill(-1);
    for (int i = 0; i < kItemCount; ++i)
        byId[static_cast<std::uint8_t>(kItems[i].id)] = static_cast<std::int16_t>(i);
    return byId;
}();

struct UnitNames {
    std::string_view section;
    std::string_view parent;
    std::string_view label;
};
constexpr UnitNames kUnitNames[kUnitKindCount] = {
    {"HEADER", "", "Header"},
    {"engine", "FCU", "Engine"},
    {"flaps", "FCU", "Flaps"},
    {"FCU_general", "FCU", "Fuel dump"},
    {"SETTINGS", "", "Settings"},
    {"comms_system", "COMMS", "Radio"},
    {"SENSE", "", "Sense and avoid"},
    {"camera", "PAYLOAD", "Camera"},
};

}  // namespace

std::span<const ItemInfo> itemTable() { return kItems; }

const ItemInfo* findItem(std::uint8_t id)
{
    const int index = kIndexById[id];
    return index < 0 ? nullptr : &kItems[index];
}

const ItemInfo& itemInfo(ItemId id)
{
    const ItemInfo* info = findItem(id);
    if (!info)
        throw std::logic_error("itemInfo: not an item ID");
    return *info;
}

const ItemInfo* findItem(UnitKind owner, std::string_view name)
{
    for (const ItemInfo& item : kItems)
        if (item.owner == owner && item.name == name)
            return &item;
    return nullptr;
}

Presentation presentation(const ItemInfo& item)
{
    Presentation shown = item.presentation.value_or(Presentation{item.unit, item.scale, 1, 0});
    if (!item.presentation)
        for (int scale = item.scale; scale > 1; scale /= 10)
            ++shown.decimals;
    if (shown.unit == "deg")
        shown.unit = "\u00b0";
    if (shown.max < shown.min) {
        shown.min = item.min;
        shown.max = item.max;
    }
    return shown;
}

int canonicalRank(ItemId id) { return kIndexById[static_cast<std::uint8_t>(id)]; }

std::optional<ItemId> unitKey(UnitKind kind)
{
    switch (kind) {
    case Engine: return eng_ID;
    case Radio: return system_ID;
    case Camera: return cam_ID;
    default: return std::nullopt;
    }
}

bool isRepeated(UnitKind kind) { return unitKey(kind).has_value(); }

std::string_view sectionName(UnitKind kind) { return kUnitNames[static_cast<int>(kind)].section; }
std::string_view parentSectionName(UnitKind kind) { return kUnitNames[static_cast<int>(kind)].parent; }
std::string_view unitLabel(UnitKind kind) { return kUnitNames[static_cast<int>(kind)].label; }

std::optional<UnitKind> unitKindFromSection(std::string_view name)
{
    for (int i = 0; i < kUnitKindCount; ++i)
        if (kUnitNames[i].section == name)
            return static_cast<UnitKind>(i);
    return std::nullopt;
}

}  // namespace rcm
