// Random valid messages for round-trip tests: every kind of item, random
// numbers of units, random subsets of items, sometimes a flight plan section.
// Values are drawn from each item's range in the item table, so a change to the
// table changes what is generated.
#pragma once

#include "codec/message/ItemTable.h"
#include "codec/message/Message.h"
#include "codec/message/MessageEncoder.h"

#include <random>
#include <string>

namespace rcm::test {

inline std::int64_t randomIn(std::mt19937_64& rng, std::int64_t lo, std::int64_t hi)
{
    return std::uniform_int_distribution<std::int64_t>(lo, hi)(rng);
}

inline std::string randomAscii(std::mt19937_64& rng, std::size_t n)
{
    std::string s;
    for (std::size_t i = 0; i < n; ++i)
        s += static_cast<char>(randomIn(rng, 0x20, 0x7E));
    return s;
}

inline Value randomValue(std::mt19937_64& rng, const ItemInfo& item)
{
    switch (item.kind) {
    case ValueKind::Unsigned:
    case ValueKind::Signed:
        return Value::of(randomIn(rng, item.min, item.max));
    case ValueKind::Raw:
        return Value::of(randomIn(rng, 0, 255));
    case ValueKind::Station:
        return Value::pair(randomIn(rng, item.min, item.max), randomIn(rng, 0, 65535));
    case ValueKind::BytePair:
        return Value::pair(randomIn(rng, 0, 255), randomIn(rng, 0, 255));
    case ValueKind::Time:
        return Value::of(randomIn(rng, 0, 23) * 10000 + randomIn(rng, 0, 59) * 100 + randomIn(rng, 0, 59));
    case ValueKind::Date:
        return Value::of(randomIn(rng, 0, 99) * 10000 + randomIn(rng, 1, 12) * 100 + randomIn(rng, 1, 28));
    case ValueKind::Fields: {
        std::uint8_t byte = 0;
        for (int f = 0; f < static_cast<int>(item.fields.size()); ++f) {
            unsigned code;
            do
                code = static_cast<unsigned>(randomIn(rng, 0, 3));
            while (!fieldCodeValid(item.fields[f], code));
            byte = withFieldCode(byte, f, code);
        }
        return Value::of(byte);
    }
    case ValueKind::Text: {
        // Trailing spaces are padding on the wire, so a value never ends in one.
        std::string s = randomAscii(rng, static_cast<std::size_t>(randomIn(rng, 1, item.size)));
        if (s.back() == ' ')
            s.back() = 'X';
        return Value::string(s);
    }
    case ValueKind::CameraId:
        return Value::string(randomAscii(rng, 3), randomIn(rng, 0, 255));
    }
    return {};
}

inline void fillUnit(std::mt19937_64& rng, Unit& unit, double presence)
{
    for (const ItemInfo& item : itemTable()) {
        if (item.owner != unit.kind() || item.key)
            continue;
        if (std::bernoulli_distribution(presence)(rng))
            unit.set(item.id, randomValue(rng, item));
    }
}

// A random message that encodes: items are dropped until it fits.
inline Message randomMessage(std::mt19937_64& rng)
{
    Message m;
    const double presence = std::uniform_real_distribution<double>(0.2, 1.0)(rng);
    for (const ItemInfo& item : itemTable()) {
        if (item.owner != UnitKind::Header)
            continue;
        if (std::bernoulli_distribution(presence)(rng))
            m.header.set(item.id, randomValue(rng, item));
    }
    for (UnitKind kind : {UnitKind::Flaps, UnitKind::FcuGeneral, UnitKind::Settings, UnitKind::Sense})
        fillUnit(rng, *m.single(kind), presence);
    for (UnitKind kind : {UnitKind::Engine, UnitKind::Radio, UnitKind::Camera}) {
        const int count = static_cast<int>(randomIn(rng, 0, 3));
        for (int i = 0; i < count; ++i) {
            Unit& u = m.repeated(kind)->emplace_back(kind);
            const ItemInfo& key = itemInfo(*unitKey(kind));
            u.set(key.id, randomValue(rng, key));
            fillUnit(rng, u, presence);
        }
    }
    // Drop items from the end until BLOCK 1 fits.
    while (block1ItemBytes(m) > 223) {
        for (UnitKind kind : {UnitKind::Camera, UnitKind::Radio, UnitKind::Engine}) {
            auto& units = *m.repeated(kind);
            if (!units.empty() && block1ItemBytes(m) > 223)
                units.pop_back();
        }
    }
    if (std::bernoulli_distribution(0.5)(rng)) {
        m.flightPlan.planId = static_cast<std::uint32_t>(randomIn(rng, 0, 0xFFFFFFFF));
        m.flightPlan.sectionId = static_cast<std::uint16_t>(randomIn(rng, 0, 0xFFFF));
        const auto n = static_cast<std::size_t>(randomIn(rng, 0, FlightPlanSection::kMaxData));
        for (std::size_t i = 0; i < n; ++i)
            m.flightPlan.data.push_back(static_cast<std::uint8_t>(randomIn(rng, 0, 255)));
        if (m.flightPlan.empty())
            m.flightPlan.sectionId = 1;
    }
    return m;
}

}  // namespace rcm::test
