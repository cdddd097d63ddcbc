#include "codec/voice/Resample.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace rcm {

std::vector<std::int16_t> resample(std::span<const std::int16_t> in, int fromRate, int toRate)
{
    if (fromRate <= 0 || toRate <= 0 || in.empty())
        return {};
    if (fromRate == toRate)
        return {in.begin(), in.end()};
    const double ratio = static_cast<double>(toRate) / fromRate;
    const double scale = std::min(1.0, ratio);
    const double cutoff = 0.5 * 0.95 * scale;  // cycles per input sample
    const double halfWidth = 16.0 / scale;     // input samples each side
    const auto outSize = static_cast<std::size_t>(std::llround(static_cast<double>(in.size()) * ratio));
    const auto last = static_cast<std::ptrdiff_t>(in.size()) - 1;

    std::vector<std::int16_t> out(outSize);
    for (std::size_t n = 0; n < outSize; ++n) {
        const double t = static_cast<double>(n) / ratio;  // where output n falls, in input samples
        const auto first = std::max<std::ptrdiff_t>(0, static_cast<std::ptrdiff_t>(std::ceil(t - halfWidth)));
        const auto stop = std::min<std::ptrdiff_t>(last, static_cast<std::ptrdiff_t>(std::floor(t + halfWidth)));
        double sum = 0;
        for (std::ptrdiff_t k = first; k <= stop; ++k) {
            const double u = t - static_cast<double>(k);
            const double x = 2 * cutoff * u;
            const double sinc = x == 0 ? 1.0 : std::sin(std::numbers::pi * x) / (std::numbers::pi * x);
            const double w = 0.42 + 0.5 * std::cos(std::numbers::pi * u / halfWidth) +
                             0.08 * std::cos(2 * std::numbers::pi * u / halfWidth);
            sum += in[static_cast<std::size_t>(k)] * 2 * cutoff * sinc * w;
        }
        out[n] = static_cast<std::int16_t>(std::clamp(std::lround(sum), -32768L, 32767L));
    }
    return out;
}

}  // namespace rcm
