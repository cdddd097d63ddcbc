// time_UTC hhmmss and date_UTC yymmdd (ValueKind::Time and Date): three
// two-digit numbers packed as one decimal number. Whoever writes or reads
// those items packs and unpacks them here.
#pragma once

#include <chrono>
#include <cstdint>

namespace rcm {

struct DigitPairs {
    std::int64_t high = 0;    // hours, or the year of the century
    std::int64_t middle = 0;  // minutes, or the month
    std::int64_t low = 0;     // seconds, or the day

    static constexpr DigitPairs unpack(std::int64_t packed)
    {
        return {packed / 10000, packed / 100 % 100, packed % 100};
    }
    constexpr std::int64_t packed() const { return high * 10000 + middle * 100 + low; }

    // time_UTC and date_UTC of an instant, to the second.
    static DigitPairs timeOf(std::chrono::system_clock::time_point utc)
    {
        using namespace std::chrono;
        const auto day = floor<days>(utc);
        const hh_mm_ss time{floor<seconds>(utc - day)};
        return {time.hours().count(), time.minutes().count(), time.seconds().count()};
    }
    static DigitPairs dateOf(std::chrono::system_clock::time_point utc)
    {
        using namespace std::chrono;
        const year_month_day date{floor<days>(utc)};
        return {int(date.year()) % 100, unsigned(date.month()), unsigned(date.day())};
    }
};

}  // namespace rcm
