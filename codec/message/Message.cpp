#include "codec/message/Message.h"

#include <algorithm>
#include <stdexcept>
#include <utility>

namespace rcm {

const Value* Unit::find(ItemId id) const
{
    for (const ItemValue& item : m_items)
        if (item.id == id)
            return &item.value;
    return nullptr;
}

bool Unit::set(ItemId id, Value value)
{
    const int rank = canonicalRank(id);
    if (rank < 0 || itemTable()[static_cast<std::size_t>(rank)].owner != m_kind)
        throw std::logic_error("Unit::set: item does not belong to this unit");
    // Decoders and builders add items in canonical order: append without a search.
    if (m_items.empty() || canonicalRank(m_items.back().id) < rank) {
        if (m_items.empty())
            m_items.reserve(8);
        m_items.push_back(ItemValue{id, std::move(value)});
        return false;
    }
    auto it = std::find_if(m_items.begin(), m_items.end(),
                           [rank](const ItemValue& v) { return canonicalRank(v.id) >= rank; });
    if (it != m_items.end() && it->id == id) {
        it->value = std::move(value);
        return true;
    }
    m_items.insert(it, ItemValue{id, std::move(value)});
    return false;
}

bool Unit::erase(ItemId id)
{
    auto it = std::find_if(m_items.begin(), m_items.end(), [id](const ItemValue& v) { return v.id == id; });
    if (it == m_items.end())
        return false;
    m_items.erase(it);
    return true;
}

std::int64_t Unit::number(ItemId id, std::int64_t fallback) const
{
    const Value* v = find(id);
    return v ? v->number : fallback;
}

unsigned Unit::fieldCode(ItemId id, int field) const
{
    const Value* v = find(id);
    return v ? rcm::fieldCode(static_cast<std::uint8_t>(v->number), field) : 0u;
}

void Unit::setFieldCode(ItemId id, int field, unsigned code)
{
    const ItemInfo& info = itemInfo(id);
    const Value* v = find(id);
    const std::uint8_t byte = v ? static_cast<std::uint8_t>(v->number)
                                : withEveryFieldCode(1, static_cast<int>(info.fields.size()));
    set(id, Value::of(withFieldCode(byte, field, code)));
}

Unit& Message::addEngine(std::uint8_t id)
{
    Unit& u = engines.emplace_back(UnitKind::Engine);
    u.set(ItemId::eng_ID, id);
    return u;
}

Unit& Message::addRadio(const std::string& systemId)
{
    Unit& u = radios.emplace_back(UnitKind::Radio);
    u.set(ItemId::system_ID, Value::string(systemId));
    return u;
}

Unit& Message::addCamera(const std::string& maker, std::uint8_t number)
{
    Unit& u = cameras.emplace_back(UnitKind::Camera);
    u.set(ItemId::cam_ID, Value::string(maker, number));
    return u;
}

Unit* Message::single(UnitKind kind)
{
    return const_cast<Unit*>(std::as_const(*this).single(kind));
}

const Unit* Message::single(UnitKind kind) const
{
    switch (kind) {
    case UnitKind::Header: return &header;
    case UnitKind::Flaps: return &flaps;
    case UnitKind::FcuGeneral: return &fuelDump;
    case UnitKind::Settings: return &settings;
    case UnitKind::Sense: return &sense;
    default: return nullptr;
    }
}

std::vector<Unit>* Message::repeated(UnitKind kind)
{
    return const_cast<std::vector<Unit>*>(std::as_const(*this).repeated(kind));
}

const std::vector<Unit>* Message::repeated(UnitKind kind) const
{
    switch (kind) {
    case UnitKind::Engine: return &engines;
    case UnitKind::Radio: return &radios;
    case UnitKind::Camera: return &cameras;
    default: return nullptr;
    }
}

std::string describeUnit(const Unit& unit)
{
    std::string name(sectionName(unit.kind()));
    const auto key = unitKey(unit.kind());
    if (!key)
        return name;
    const Value* v = unit.find(*key);
    if (!v)
        return name + " (no " + std::string(itemInfo(*key).name) + ")";
    switch (unit.kind()) {
    case UnitKind::Engine: return "engine " + std::to_string(v->number);
    case UnitKind::Radio: return "radio " + v->text;
    default: return "camera " + v->text + " " + std::to_string(v->number);
    }
}

}  // namespace rcm
