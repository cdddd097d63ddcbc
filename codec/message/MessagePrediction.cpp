#include "codec/message/MessagePrediction.h"

#include "codec/message/DigitPairs.h"

#include <chrono>

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

}  // namespace rcm
