// Rehearsal faults on the frames one end of the link sends: bit errors,
// error bursts, lost frames, added delay, an outage, and silence. Driven by a
// seeded generator and by the caller's clock, so a run with the same seed and
// the same frame times damages the same bits: tests and rehearsals repeat
// exactly.
//
// What each fault does:
//   bit error rate   every bit of a sent frame flips independently with this
//                    probability.
//   burst            the number of bursts in a frame is Poisson with mean
//                    `burstRate` (bursts per frame, so per second at the
//                    link's cadence); each burst covers `burstLength`
//                    consecutive bits at a uniform position inside the frame,
//                    its first and last bits flipped and each bit between
//                    flipped with probability 1/2 (the usual burst model: a
//                    burst of length L starts and ends with an error).
//   drop             each frame is lost with this probability.
//   delay            each frame leaves this much later; the caller holds it.
//   outage           from `outageStart` for `outageDuration` after the
//                    injector's start nothing is sent and nothing received.
//   silent           nothing is sent; what arrives is still received.
// A frame lost to an outage or silence draws no random numbers, so switching
// those on does not move the errors in the frames that do go out.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <random>
#include <span>

struct FaultSettings {
    double bitErrorRate = 0.0;
    std::size_t burstLength = 0;  // bits; 0: no bursts
    double burstRate = 0.0;       // mean bursts per frame
    double dropProbability = 0.0;
    std::chrono::milliseconds delay{0};
    std::chrono::milliseconds outageStart{0};
    std::chrono::milliseconds outageDuration{0};  // 0: no outage
    bool silent = false;
    std::uint64_t seed = 1;

    // True when any fault is switched on.
    bool any() const;
};

class FaultInjector {
public:
    using Clock = std::chrono::steady_clock;

    enum class Fate { Sent, Dropped, Outage, Silenced };

    struct Outcome {
        Fate fate = Fate::Sent;
        std::chrono::milliseconds delay{0};  // Sent only: hold the frame this long
        std::size_t flippedBits = 0;         // bits that differ from what was given
        std::size_t bursts = 0;
        bool sent() const { return fate == Fate::Sent; }
    };

    struct Counters {
        std::uint64_t framesOffered = 0;
        std::uint64_t framesSent = 0;
        std::uint64_t framesDropped = 0;
        std::uint64_t framesLostToOutage = 0;
        std::uint64_t framesSilenced = 0;
        std::uint64_t framesNotReceived = 0;  // arrivals blanked by the outage
        std::uint64_t bitsFlipped = 0;
        std::uint64_t bursts = 0;
        std::uint64_t framesDamaged = 0;  // sent with at least one bit flipped
    };

    explicit FaultInjector(const FaultSettings& settings = {});

    const FaultSettings& settings() const { return m_settings; }
    const Counters& counters() const { return m_counters; }

    // `elapsed` is the time since the injector's start, by the caller's
    // clock. Decides the frame's fate and, when it is sent, damages `frame`
    // in place.
    Outcome outgoing(std::span<std::uint8_t> frame, std::chrono::milliseconds elapsed);
    // False when bytes arriving at `elapsed` are lost to the outage.
    bool incoming(std::chrono::milliseconds elapsed);
    bool inOutage(std::chrono::milliseconds elapsed) const;

    // The building blocks, for tests and for damaging bytes outside a frame
    // cadence. Each returns the number of bits it flipped (bits flipped twice
    // by overlapping bursts count twice here; Outcome::flippedBits does not).
    std::size_t flipRandomBits(std::span<std::uint8_t> bytes);
    std::size_t injectBursts(std::span<std::uint8_t> bytes, std::size_t* bursts = nullptr);

private:
    FaultSettings m_settings;
    std::mt19937_64 m_rng;
    Counters m_counters;
};
