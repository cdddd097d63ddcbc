#include "codec/message/MessagePrediction.h"

#include "codec/message/DigitPairs.h"

#include <chrono>
#include <vector>

namespace rcm {

bool advanceTimeAndDate(std::uint32_t& timeUtc, std::uint32_t& dateUtc, std::uint32_t seconds)
{
    const std::optional<std::int64_t> now = utcSeconds(timeUtc, dateUtc);
    if (!now)
        return false;
    const std::chrono::sys_seconds next{std::chrono::seconds(*now + seconds)};
    timeUtc = static_cast<std::uint32_t>(DigitPairs::timeOf(next).packed());
    dateUtc = static_cast<std::uint32_t>(DigitPairs::dateOf(next).packed());
    return true;
}

Message advanceMessage(const Message& last, std::uint32_t seconds)
{
    Message next = last;
    if (const Value* id = last.header.find(ItemId::ID_msg))
        next.header.set(ItemId::ID_msg, static_cast<std::int64_t>((id->number + seconds) % kMessageIdModulus));
    const Value* time = last.header.find(ItemId::time_UTC);
    const Value* date = last.header.find(ItemId::date_UTC);
    if (time && date) {
        auto t = static_cast<std::uint32_t>(time->number);
        auto d = static_cast<std::uint32_t>(date->number);
        if (advanceTimeAndDate(t, d, seconds)) {
            next.header.set(ItemId::time_UTC, t);
            next.header.set(ItemId::date_UTC, d);
        }
    }
    return next;
}

namespace {

bool aircraftKeeps(ItemId id)
{
    return id == ItemId::ID_msg || id == ItemId::ID_UA_source || id == ItemId::time_UTC || id == ItemId::date_UTC;
}

// The unit of `status` that `commanded` (a unit of a command) speaks of.
Unit* counterpart(Message& status, const Unit& commanded)
{
    if (Unit* single = status.single(commanded.kind()))
        return single->empty() && commanded.kind() != UnitKind::Header ? nullptr : single;  // a part it lacks
    std::vector<Unit>* units = status.repeated(commanded.kind());
    if (!units || commanded.empty())
        return nullptr;
    const ItemValue& key = commanded.items().front();
    for (Unit& u : *units)
        if (const Value* v = u.find(key.id); v && *v == key.value)
            return &u;
    return nullptr;
}

// Applies the command's changes to `status`, the i-th when bit i of `mask`
// is set (changes past the 64th always); returns how many there are.
int apply(Message& status, const Message& command, std::uint64_t mask)
{
    int changes = 0;
    command.forEachUnit([&](const Unit& commanded) {
        if (commanded.empty())
            return;
        Unit* target = counterpart(status, commanded);
        if (!target)
            return;
        for (const ItemValue& item : commanded.items()) {
            if (commanded.kind() == UnitKind::Header && aircraftKeeps(item.id))
                continue;
            const Value* now = target->find(item.id);
            if (now && *now == item.value)
                continue;
            const int i = changes++;
            if (i < 64 && !(mask >> i & 1))
                continue;
            target->set(item.id, item.value);
        }
    });
    return changes;
}

}  // namespace

Message withCommanded(const Message& status, const Message& command, std::uint64_t changeMask)
{
    Message out = status;
    apply(out, command, changeMask);
    return out;
}

int commandedChanges(const Message& status, const Message& command)
{
    Message scratch = status;
    return apply(scratch, command, 0);
}

}  // namespace rcm
