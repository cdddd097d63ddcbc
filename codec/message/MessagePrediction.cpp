#include "codec/message/MessagePrediction.h"

#include <chrono>

namespace rcm {

namespace {
constexpr std::uint32_t kMessageIdModulus = 1u << 24;
}

bool advanceTimeAndDate(std::uint32_t& timeUtc, std::uint32_t& dateUtc, std::uint32_t seconds)
{
    using namespace std::chrono;
    const unsigned hh = timeUtc / 10000, mm = timeUtc / 100 % 100, ss = timeUtc % 100;
    const year_month_day ymd{year(2000 + static_cast<int>(dateUtc / 10000)), month(dateUtc / 100 % 100),
                             day(dateUtc % 100)};
    if (hh > 23 || mm > 59 || ss > 59 || dateUtc > 991231 || !ymd.ok())
        return false;
    const std::int64_t of = hh * 3600LL + mm * 60LL + ss + seconds;
    const year_month_day next{sys_days(ymd) + days(of / 86400)};
    const std::int64_t s = of % 86400;
    timeUtc = static_cast<std::uint32_t>(s / 3600 * 10000 + s / 60 % 60 * 100 + s % 60);
    dateUtc = static_cast<std::uint32_t>((static_cast<int>(next.year()) - 2000) * 10000 +
                                         static_cast<unsigned>(next.month()) * 100 +
                                         static_cast<unsigned>(next.day()));
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
