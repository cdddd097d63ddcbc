#include "link/aircraft/FaultInjector.h"

#include <algorithm>
#include <bit>
#include <vector>

namespace {

// Bits are numbered from the most significant bit of the first byte: the
// order a UART sends them in does not matter for independent errors, and a
// burst then stays inside neighbouring bits of neighbouring bytes.
void flipBit(std::span<std::uint8_t> bytes, std::uint64_t bit)
{
    bytes[bit / 8] ^= static_cast<std::uint8_t>(0x80u >> (bit % 8));
}

}  // namespace

bool FaultSettings::any() const
{
    return bitErrorRate > 0 || (burstLength > 0 && burstRate > 0) || dropProbability > 0 || delay.count() > 0 ||
           outageDuration.count() > 0 || silent;
}

FaultInjector::FaultInjector(const FaultSettings& settings) : m_settings(settings), m_rng(settings.seed) {}

bool FaultInjector::inOutage(std::chrono::milliseconds elapsed) const
{
    return m_settings.outageDuration.count() > 0 && elapsed >= m_settings.outageStart &&
           elapsed < m_settings.outageStart + m_settings.outageDuration;
}

bool FaultInjector::incoming(std::chrono::milliseconds elapsed)
{
    if (!inOutage(elapsed))
        return true;
    ++m_counters.framesNotReceived;
    return false;
}

std::size_t FaultInjector::flipRandomBits(std::span<std::uint8_t> bytes)
{
    const double p = m_settings.bitErrorRate;
    const std::uint64_t bits = std::uint64_t{bytes.size()} * 8;
    if (p <= 0 || bits == 0)
        return 0;
    if (p >= 1) {
        for (std::uint8_t& b : bytes)
            b = static_cast<std::uint8_t>(~b);
        return bits;
    }
    // The gaps between independent errors are geometric: one draw per error,
    // not one per bit.
    std::geometric_distribution<std::uint64_t> gap(p);
    std::size_t flipped = 0;
    for (std::uint64_t bit = gap(m_rng); bit < bits; bit += 1 + gap(m_rng)) {
        flipBit(bytes, bit);
        ++flipped;
    }
    return flipped;
}

std::size_t FaultInjector::injectBursts(std::span<std::uint8_t> bytes, std::size_t* bursts)
{
    if (bursts)
        *bursts = 0;
    const std::uint64_t bits = std::uint64_t{bytes.size()} * 8;
    if (m_settings.burstLength == 0 || m_settings.burstRate <= 0 || bits == 0)
        return 0;
    const std::uint64_t length = std::min<std::uint64_t>(m_settings.burstLength, bits);
    const auto count = std::poisson_distribution<std::size_t>(m_settings.burstRate)(m_rng);
    std::uniform_int_distribution<std::uint64_t> where(0, bits - length);
    std::size_t flipped = 0;
    for (std::size_t i = 0; i < count; ++i) {
        const std::uint64_t start = where(m_rng);
        flipBit(bytes, start);
        ++flipped;
        if (length > 1) {
            flipBit(bytes, start + length - 1);
            ++flipped;
        }
        std::uint64_t coin = 0;
        for (std::uint64_t k = 1; k + 1 < length; ++k) {
            if ((k - 1) % 64 == 0)
                coin = m_rng();
            if (coin & 1) {
                flipBit(bytes, start + k);
                ++flipped;
            }
            coin >>= 1;
        }
    }
    if (bursts)
        *bursts = count;
    return flipped;
}

FaultInjector::Outcome FaultInjector::outgoing(std::span<std::uint8_t> frame, std::chrono::milliseconds elapsed)
{
    Outcome out;
    ++m_counters.framesOffered;
    if (inOutage(elapsed)) {
        out.fate = Fate::Outage;
        ++m_counters.framesLostToOutage;
        return out;
    }
    if (m_settings.silent) {
        out.fate = Fate::Silenced;
        ++m_counters.framesSilenced;
        return out;
    }
    if (m_settings.dropProbability > 0 && std::bernoulli_distribution(m_settings.dropProbability)(m_rng)) {
        out.fate = Fate::Dropped;
        ++m_counters.framesDropped;
        return out;
    }

    const std::vector<std::uint8_t> original(frame.begin(), frame.end());
    flipRandomBits(frame);
    injectBursts(frame, &out.bursts);
    for (std::size_t i = 0; i < frame.size(); ++i)
        out.flippedBits += static_cast<std::size_t>(std::popcount(static_cast<unsigned>(frame[i] ^ original[i])));

    out.delay = m_settings.delay;
    ++m_counters.framesSent;
    m_counters.bitsFlipped += out.flippedBits;
    m_counters.bursts += out.bursts;
    if (out.flippedBits)
        ++m_counters.framesDamaged;
    return out;
}
