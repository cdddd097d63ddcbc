// Sample-rate conversion of 16-bit mono PCM by windowed-sinc interpolation,
// for speech taken from files at other rates (espeak-ng writes 22,050 Hz,
// sound cards 44,100 or 48,000) into the voice codec's 8,000 Hz.
//
// Plain C++20, no Qt.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace rcm {

// `in` at fromRate as round(in.size() * toRate / fromRate) samples at
// toRate. Going down, what lies above 95% of the new Nyquist frequency is
// filtered out first; the filter spans 16 zero crossings each side, a
// Blackman window tapering it.
std::vector<std::int16_t> resample(std::span<const std::int16_t> in, int fromRate, int toRate);

}  // namespace rcm
