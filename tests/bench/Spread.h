// A benchmark's timings in one line: how many, min, median, a high
// percentile, max and mean, in milliseconds.
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <vector>

namespace rcm::bench {

// `high`: the percentile to show, 0.95 or 0.99; `decimals` of a millisecond.
inline void printSpread(const char* what, std::vector<std::int64_t> micros, double high, int decimals)
{
    if (micros.empty())
        return;
    std::sort(micros.begin(), micros.end());
    double total = 0;
    for (std::int64_t m : micros)
        total += double(m);
    const auto at = [&](double q) { return double(micros[std::size_t(q * double(micros.size() - 1))]) / 1000.0; };
    std::printf("%-8s n=%zu  min %.*f ms  median %.*f ms  p%d %.*f ms  max %.*f ms  mean %.*f ms\n", what,
                micros.size(), decimals, double(micros.front()) / 1000.0, decimals, at(0.5), int(high * 100 + 0.5),
                decimals, at(high), decimals, double(micros.back()) / 1000.0, decimals,
                total / double(micros.size()) / 1000.0);
}

}  // namespace rcm::bench
