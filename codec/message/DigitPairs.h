// time_UTC hhmmss and date_UTC yymmdd (ValueKind::Time and Date): three
// two-digit numbers packed as one decimal number. Whoever writes or reads
// those items packs and unpacks them here.
#pragma once

#include <chrono>
#include <cstdint>
#include <optional>

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

// time_UTC and date_UTC (years 2000-2099) as seconds since 1970, or nothing
// when they name no real time.
inline std::optional<std::int64_t> utcSeconds(std::int64_t timeUtc, std::int64_t dateUtc)
{
    using namespace std::chrono;
    const auto [hh, mm, ss] = DigitPairs::unpack(timeUtc);
    const auto [yy, mo, dd] = DigitPairs::unpack(dateUtc);
    if (timeUtc < 0 || dateUtc < 0 || hh > 23 || mm > 59 || ss > 59 || dateUtc > 991231)
        return std::nullopt;
    const year_month_day ymd{year(2000 + static_cast<int>(yy)), month(unsigned(mo)), day(unsigned(dd))};
    if (!ymd.ok())
        return std::nullopt;
    return sys_days(ymd).time_since_epoch().count() * 86400LL + hh * 3600LL + mm * 60LL + ss;
}

}  // namespace rcm
