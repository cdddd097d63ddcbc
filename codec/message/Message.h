// The typed model of one Remote Control Message. Every item is optional: an
// item not set is not sent. Values are held in the units of the text format
// (degrees x scale, kHz, hhmmss ...) and checked against the item table when
// encoded, so an operator's out-of-range entry is refused with a reason, never
// wrapped into a wrong byte.
#pragma once

#include "codec/message/ItemTable.h"

#include <cstdint>
#include <string>
#include <vector>

namespace rcm {

// A station: the international dialling code of its country and a unit number.
struct StationId {
    std::uint16_t country = 0;
    std::uint16_t unit = 0;
    friend bool operator==(const StationId&, const StationId&) = default;
};

// One item's value. Which members are used depends on the item's ValueKind:
//   Unsigned, Signed, Time, Date, Fields, Raw: number
//   Station: number = country, second = unit
//   BytePair: number, second
//   Text: text
//   CameraId: text = three-letter maker, number = camera number
struct Value {
    std::int64_t number = 0;
    std::int64_t second = 0;
    std::string text;

    static Value of(std::int64_t n) { return Value{n, 0, {}}; }
    static Value pair(std::int64_t a, std::int64_t b) { return Value{a, b, {}}; }
    static Value station(StationId s) { return Value{s.country, s.unit, {}}; }
    static Value string(std::string s, std::int64_t n = 0) { return Value{n, 0, std::move(s)}; }
    friend bool operator==(const Value&, const Value&) = default;
};

struct ItemValue {
    ItemId id;
    Value value;
    friend bool operator==(const ItemValue&, const ItemValue&) = default;
};

// One unit (the header, one engine, the flaps, one radio ...): its items in
// canonical order, the key item first.
class Unit {
public:
    explicit Unit(UnitKind kind = UnitKind::Header) : m_kind(kind) {}

    UnitKind kind() const { return m_kind; }
    const std::vector<ItemValue>& items() const { return m_items; }
    bool empty() const { return m_items.empty(); }

    const Value* find(ItemId id) const;
    bool has(ItemId id) const { return find(id) != nullptr; }
    // Sets or replaces (returning true when it replaced); the item must belong
    // to this unit's kind.
    bool set(ItemId id, Value value);
    bool set(ItemId id, std::int64_t number) { return set(id, Value::of(number)); }
    bool erase(ItemId id);

    // The number of a numeric item, or `fallback` when absent.
    std::int64_t number(ItemId id, std::int64_t fallback = 0) const;
    // Two-bit field `field` of a Fields item, 0 (corrupt) when absent.
    unsigned fieldCode(ItemId id, int field) const;
    // Sets one field, starting from all-valid defaults (code 01) when absent.
    void setFieldCode(ItemId id, int field, unsigned code);

    friend bool operator==(const Unit&, const Unit&) = default;

private:
    UnitKind m_kind;
    std::vector<ItemValue> m_items;
};

// BLOCK 2: one section of a flight plan update.
struct FlightPlanSection {
    static constexpr std::size_t kMaxData = 215;
    std::uint32_t planId = 0;
    std::uint16_t sectionId = 0;
    std::vector<std::uint8_t> data;

    bool empty() const { return planId == 0 && sectionId == 0 && data.empty(); }
    friend bool operator==(const FlightPlanSection&, const FlightPlanSection&) = default;
};

struct Message {
    Unit header{UnitKind::Header};
    std::vector<Unit> engines;
    Unit flaps{UnitKind::Flaps};
    Unit fuelDump{UnitKind::FcuGeneral};
    Unit settings{UnitKind::Settings};
    std::vector<Unit> radios;
    Unit sense{UnitKind::Sense};
    std::vector<Unit> cameras;
    FlightPlanSection flightPlan;

    // Adds a repeated unit with its key item set; returns it.
    Unit& addEngine(std::uint8_t id);
    Unit& addRadio(const std::string& systemId);
    Unit& addCamera(const std::string& maker, std::uint8_t number);

    // The unit for a kind: the single one, or the vector of repeated ones.
    Unit* single(UnitKind kind);
    const Unit* single(UnitKind kind) const;
    std::vector<Unit>* repeated(UnitKind kind);
    const std::vector<Unit>* repeated(UnitKind kind) const;

    // Calls f(const Unit&) for every unit in canonical order, empty ones too.
    template <typename F>
    void forEachUnit(F&& f) const
    {
        f(header);
        for (const Unit& u : engines) f(u);
        f(flaps);
        f(fuelDump);
        f(settings);
        for (const Unit& u : radios) f(u);
        f(sense);
        for (const Unit& u : cameras) f(u);
    }

    friend bool operator==(const Message&, const Message&) = default;
};

// "engine 2", "radio VHF1", "camera NIK 1", "flaps": names a unit in messages.
std::string describeUnit(const Unit& unit);

}  // namespace rcm
