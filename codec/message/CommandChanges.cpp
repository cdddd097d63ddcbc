#include "codec/message/CommandChanges.h"

#include <algorithm>

namespace rcm {

namespace {

bool isOneShot(ItemId id)
{
    return std::find(kOneShotItems.begin(), kOneShotItems.end(), id) != kOneShotItems.end();
}

// The unit of `units` with the same key item value as `like`.
const Unit* matching(const std::vector<Unit>& units, const Unit& like)
{
    const auto key = unitKey(like.kind());
    const Value* wanted = key ? like.find(*key) : nullptr;
    if (!wanted)
        return nullptr;
    const auto it =
        std::find_if(units.begin(), units.end(), [&](const Unit& u) { return u.find(*key) && *u.find(*key) == *wanted; });
    return it == units.end() ? nullptr : &*it;
}

// The unit of `message` that matches `like`: the single unit of its kind, or
// the repeated one with the same key.
const Unit* matching(const Message& message, const Unit& like)
{
    if (const std::vector<Unit>* units = message.repeated(like.kind()))
        return matching(*units, like);
    const Unit* single = message.single(like.kind());
    return single && !single->empty() ? single : nullptr;
}

void compareUnits(const Unit* from, const Unit* to, std::vector<ItemChange>& out)
{
    const Unit& either = to ? *to : *from;
    const auto key = unitKey(either.kind());
    ItemChange base;
    base.kind = either.kind();
    base.unit = describeUnit(either);
    if (key && either.find(*key))
        base.key = *either.find(*key);
    for (const ItemInfo& info : itemTable()) {
        if (info.owner != either.kind() || (key && info.id == *key))
            continue;
        const Value* a = from ? from->find(info.id) : nullptr;
        const Value* b = to ? to->find(info.id) : nullptr;
        if ((!a && !b) || (a && b && *a == *b))
            continue;
        ItemChange change = base;
        change.id = info.id;
        if (a)
            change.from = *a;
        if (b)
            change.to = *b;
        if (info.kind == ValueKind::Fields && a && b) {
            for (int f = 0; f < static_cast<int>(info.fields.size()); ++f) {
                if (from->fieldCode(info.id, f) == to->fieldCode(info.id, f))
                    continue;
                change.field = f;
                out.push_back(change);
            }
            continue;
        }
        out.push_back(std::move(change));
    }
}

}  // namespace

std::vector<ItemChange> commandChanges(const Message& from, const Message& to)
{
    std::vector<ItemChange> out;
    for (int k = 0; k < kUnitKindCount; ++k) {
        const auto kind = static_cast<UnitKind>(k);
        if (kind == UnitKind::Header)
            continue;
        if (const std::vector<Unit>* units = to.repeated(kind)) {
            for (const Unit& unit : *units)
                compareUnits(matching(*from.repeated(kind), unit), &unit, out);
            for (const Unit& unit : *from.repeated(kind))
                if (!matching(*units, unit))
                    compareUnits(&unit, nullptr, out);
        } else {
            compareUnits(from.single(kind), to.single(kind), out);
        }
    }
    return out;
}

const Value* valueAt(const Message& message, const ItemChange& change)
{
    Unit like(change.kind);
    if (const auto key = unitKey(change.kind)) {
        if (!change.key)
            return nullptr;
        like.set(*key, *change.key);
    }
    const Unit* unit = matching(message, like);
    if (!unit && !unitKey(change.kind))
        unit = message.single(change.kind);
    return unit ? unit->find(change.id) : nullptr;
}

bool holdsChange(const Message& message, const ItemChange& change)
{
    const Value* v = valueAt(message, change);
    if (!v || !change.to)
        return !v && !change.to;
    if (change.field < 0)
        return *v == *change.to;
    return fieldCode(static_cast<std::uint8_t>(v->number), change.field) ==
           fieldCode(static_cast<std::uint8_t>(change.to->number), change.field);
}

Message withValuesOf(const Message& target, const Message& source)
{
    Message out = target;
    auto adopt = [&](Unit& unit) {
        const Unit* theirs = matching(source, unit);
        if (!theirs)
            return;
        const auto key = unitKey(unit.kind());
        for (const ItemValue& item : std::vector<ItemValue>(unit.items())) {
            if ((key && item.id == *key) || isOneShot(item.id))
                continue;
            if (const Value* v = theirs->find(item.id))
                unit.set(item.id, *v);
        }
    };
    for (int k = 0; k < kUnitKindCount; ++k) {
        const auto kind = static_cast<UnitKind>(k);
        if (kind == UnitKind::Header)
            continue;
        if (std::vector<Unit>* units = out.repeated(kind))
            std::for_each(units->begin(), units->end(), adopt);
        else
            adopt(*out.single(kind));
    }
    return out;
}

std::vector<Unit> unitsMissingFrom(const Message& source, const Message& target)
{
    std::vector<Unit> missing;
    source.forEachUnit([&](const Unit& unit) {
        if (unit.kind() != UnitKind::Header && !unit.empty() && !matching(target, unit))
            missing.push_back(unit);
    });
    return missing;
}

Message heldCommand(const Message& command)
{
    Message held;
    held.header = command.header;
    return held;
}

}  // namespace rcm
