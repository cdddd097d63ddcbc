// AES-256-HCTR2 timing for the telemetry block size: a 223-byte message
// (one RS(255,223) payload), with the 6-byte tweak of the secure link's
// BLOCK 1 and with a 40-byte tweak that changes on every call. Plain C++, no
// Qt.
//
//   bench_hctr2 [rounds]        (default 300 rounds of 1,000 calls)
//
// Prints ns per encrypt and per decrypt, once with the POLYVAL this CPU
// selects and once with the portable constant-time POLYVAL forced. Each
// figure is the fastest round: the machine is shared with builds, and other
// processes only ever add time. The four measurements of one cipher are
// interleaved round by round, so none is favoured by when it ran.

#include "codec/secure/Hctr2.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <vector>

namespace {

using Clock = std::chrono::steady_clock;
constexpr long kCalls = 1000;

struct Best {
    double ns = 1e300;
    void add(Clock::duration d)
    {
        ns = std::min(ns, std::chrono::duration<double, std::nano>(d).count() / kCalls);
    }
};

int run(const char* label, long rounds)
{
    std::array<std::uint8_t, 32> key{};
    std::array<std::uint8_t, 40> longTweak{};
    const std::array<std::uint8_t, 6> block1Tweak{0x52, 0x43, 0x4D, 0x01, 0x01, 0x01};
    std::vector<std::uint8_t> msg(223), buf(223);
    for (std::size_t i = 0; i < key.size(); ++i)
        key[i] = static_cast<std::uint8_t>(i * 7 + 1);
    for (std::size_t i = 0; i < longTweak.size(); ++i)
        longTweak[i] = static_cast<std::uint8_t>(i * 13 + 5);
    for (std::size_t i = 0; i < msg.size(); ++i)
        msg[i] = static_cast<std::uint8_t>(i * 31 + 3);

    const rcm::Hctr2 cipher(key);
    for (int i = 0; i < 1000; ++i) // warm-up
        cipher.encrypt(longTweak, msg, buf);

    Best enc6, dec6, enc40, dec40;
    buf = msg;
    for (long r = 0; r < rounds; ++r) {
        auto t0 = Clock::now();
        for (long i = 0; i < kCalls; ++i)
            cipher.encrypt(block1Tweak, buf, buf);
        auto t1 = Clock::now();
        for (long i = 0; i < kCalls; ++i)
            cipher.decrypt(block1Tweak, buf, buf);
        auto t2 = Clock::now();
        enc6.add(t1 - t0);
        dec6.add(t2 - t1);

        t0 = Clock::now();
        for (long i = 0; i < kCalls; ++i) {
            longTweak[0] = static_cast<std::uint8_t>(i); // a fresh tweak each time
            cipher.encrypt(longTweak, buf, buf);
        }
        t1 = Clock::now();
        for (long i = kCalls - 1; i >= 0; --i) {
            longTweak[0] = static_cast<std::uint8_t>(i);
            cipher.decrypt(longTweak, buf, buf);
        }
        t2 = Clock::now();
        enc40.add(t1 - t0);
        dec40.add(t2 - t1);
    }
    if (buf != msg) {
        std::fprintf(stderr, "bench_hctr2: round trip failed\n");
        return 1;
    }
    std::printf("AES-256-HCTR2, 223-byte message, POLYVAL %-8s:  6-byte tweak: encrypt %5.0f ns, decrypt %5.0f ns;"
                "  40-byte tweak: encrypt %5.0f ns, decrypt %5.0f ns\n",
                label, enc6.ns, dec6.ns, enc40.ns, dec40.ns);
    return 0;
}

} // namespace

int main(int argc, char** argv)
{
    const long rounds = argc > 1 ? std::atol(argv[1]) : 300;
    if (rounds <= 0) {
        std::fprintf(stderr, "usage: bench_hctr2 [rounds]\n");
        return 2;
    }
    std::printf("fastest of %ld rounds of %ld calls\n", rounds, kCalls);
    int rc = run(rcm::detail::polyvalPclmulAvailable() ? "pclmul" : "portable", rounds);
    rcm::detail::setForcePortablePolyval(true);
    rc |= run("portable", rounds);
    rcm::detail::setForcePortablePolyval(false);
    return rc;
}
