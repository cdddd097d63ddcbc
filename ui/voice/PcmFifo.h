#pragma once

// Received voice on its way to the sound card: 8 kHz 16-bit mono samples
// pushed by the link's thread, pulled by the audio thread. Bounded: when
// the card falls behind, the oldest samples go, so playback never lags by
// more than the capacity.

#include <cstdint>
#include <deque>
#include <mutex>
#include <span>

class PcmFifo {
public:
    explicit PcmFifo(std::size_t capacity) : m_capacity(capacity) {}

    // Any thread.
    void push(std::span<const std::int16_t> pcm);
    // Fills `out` with what waits and silence after it; returns how many
    // samples were real.
    std::size_t pull(std::span<std::int16_t> out);
    std::size_t size() const;
    void clear();
    std::uint64_t samplesDropped() const;

private:
    const std::size_t m_capacity;
    mutable std::mutex m_mutex;
    std::deque<std::int16_t> m_samples;
    std::uint64_t m_dropped = 0;
};
