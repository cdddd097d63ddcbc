// AES-256-HCTR2 timing for the telemetry block size: a 223-byte message
// (one RS(255,223) payload) with a 40-byte tweak. Plain C++, no Qt.
//
//   bench_hctr2 [iterations]        (default 200000)
//
// Prints ns per encrypt and per decrypt, once with the POLYVAL this CPU
// selects and once with the portable constant-time POLYVAL forced.

#include "codec/Hctr2.h"

#include <array>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <vector>

namespace {

double nsPer(long iterations, std::chrono::steady_clock::duration d)
{
    return static_cast<double>(std::chrono::duration_cast<std::chrono::nanoseconds>(d).count())
           / static_cast<double>(iterations);
}

int run(const char* label, long iterations)
{
    std::array<std::uint8_t, 32> key{};
    std::array<std::uint8_t, 40> tweak{};
    std::vector<std::uint8_t> msg(223), buf(223);
    for (std::size_t i = 0; i < key.size(); ++i)
        key[i] = static_cast<std::uint8_t>(i * 7 + 1);
    for (std::size_t i = 0; i < tweak.size(); ++i)
        tweak[i] = static_cast<std::uint8_t>(i * 13 + 5);
    for (std::size_t i = 0; i < msg.size(); ++i)
        msg[i] = static_cast<std::uint8_t>(i * 31 + 3);

    const rcm::Hctr2 cipher(key);
    for (int i = 0; i < 1000; ++i) // warm-up
        cipher.encrypt(tweak, msg, buf);

    using clock = std::chrono::steady_clock;
    buf = msg;
    auto t0 = clock::now();
    for (long i = 0; i < iterations; ++i) {
        tweak[0] = static_cast<std::uint8_t>(i); // a fresh tweak each time
        cipher.encrypt(tweak, buf, buf);
    }
    auto t1 = clock::now();
    for (long i = iterations - 1; i >= 0; --i) {
        tweak[0] = static_cast<std::uint8_t>(i);
        cipher.decrypt(tweak, buf, buf);
    }
    auto t2 = clock::now();
    if (buf != msg) {
        std::fprintf(stderr, "bench_hctr2: round trip failed\n");
        return 1;
    }
    const double enc = nsPer(iterations, t1 - t0), dec = nsPer(iterations, t2 - t1);
    std::printf("AES-256-HCTR2, 223-byte message, 40-byte tweak, POLYVAL %-8s: "
                "encrypt %7.0f ns (%6.1f MB/s), decrypt %7.0f ns (%6.1f MB/s)\n",
                label, enc, 223e3 / enc, dec, 223e3 / dec);
    return 0;
}

} // namespace

int main(int argc, char** argv)
{
    const long iterations = argc > 1 ? std::atol(argv[1]) : 200000;
    if (iterations <= 0) {
        std::fprintf(stderr, "usage: bench_hctr2 [iterations]\n");
        return 2;
    }
    int rc = run(rcm::detail::polyvalPclmulAvailable() ? "pclmul" : "portable", iterations);
    rcm::detail::setForcePortablePolyval(true);
    rc |= run("portable", iterations);
    rcm::detail::setForcePortablePolyval(false);
    return rc;
}
