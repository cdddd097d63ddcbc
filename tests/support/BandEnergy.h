// Energy per frequency band of 8 kHz speech, to compare what went into the
// voice channel with what came out without listening: Codec 2 keeps the
// spectral envelope, not the waveform, so samples cannot be compared, but
// where the energy lies can.
#pragma once

#include <array>
#include <cmath>
#include <complex>
#include <cstdint>
#include <numbers>
#include <span>
#include <vector>

namespace rcm::test {

inline constexpr std::size_t kBands = 8;  // 500 Hz each, 0-4 kHz at 8 kHz

// In place, radix 2; a.size() a power of two.
inline void fft(std::vector<std::complex<double>>& a)
{
    const std::size_t n = a.size();
    for (std::size_t i = 1, j = 0; i < n; ++i) {
        std::size_t bit = n >> 1;
        for (; j & bit; bit >>= 1)
            j ^= bit;
        j ^= bit;
        if (i < j)
            std::swap(a[i], a[j]);
    }
    for (std::size_t len = 2; len <= n; len <<= 1) {
        const std::complex<double> w = std::polar(1.0, -2 * std::numbers::pi / static_cast<double>(len));
        for (std::size_t i = 0; i < n; i += len) {
            std::complex<double> wk = 1;
            for (std::size_t k = 0; k < len / 2; ++k) {
                const std::complex<double> u = a[i + k];
                const std::complex<double> v = a[i + k + len / 2] * wk;
                a[i + k] = u + v;
                a[i + k + len / 2] = u - v;
                wk *= w;
            }
        }
    }
}

// Mean power per band over the whole signal (Hann-windowed 256-point
// spectra, half overlapping), in dB re a full-scale sine's.
inline std::array<double, kBands> bandEnergyDb(std::span<const std::int16_t> pcm)
{
    constexpr std::size_t n = 256;
    std::array<double, kBands> power{};
    std::size_t spectra = 0;
    std::vector<std::complex<double>> a(n);
    for (std::size_t at = 0; at + n <= pcm.size(); at += n / 2) {
        for (std::size_t i = 0; i < n; ++i) {
            const double w = 0.5 - 0.5 * std::cos(2 * std::numbers::pi * static_cast<double>(i) / n);
            a[i] = w * pcm[at + i] / 32768.0;
        }
        fft(a);
        for (std::size_t bin = 1; bin < n / 2; ++bin)
            power[bin * kBands / (n / 2)] += std::norm(a[bin]);
        ++spectra;
    }
    std::array<double, kBands> db{};
    for (std::size_t b = 0; b < kBands; ++b)
        db[b] = 10 * std::log10(power[b] / static_cast<double>(spectra ? spectra : 1) / (n * n / 16.0) + 1e-12);
    return db;
}

}  // namespace rcm::test
