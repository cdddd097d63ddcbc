#include "link/voice/SecureVoiceSink.h"

#include "link/clock/Clock.h"

SecureVoiceSink::SecureVoiceSink(std::shared_ptr<VoiceSink> inner, const rcm::secure::VoiceKeys& keys,
                                 std::shared_ptr<Clock> clock, RefusedHandler refused)
    : m_inner(std::move(inner)),
      m_clock(std::move(clock)),
      m_opener(keys, [clock = m_clock] { return clock->utcMicros(); }),
      m_refused(std::move(refused))
{
}

void SecureVoiceSink::writeVoice(std::span<const std::uint8_t> bytes)
{
    m_plain.clear();
    m_opener.open(bytes, m_plain);
    const auto& stats = m_opener.stats();
    m_forged = stats.forged;
    m_replayed = stats.replayed;
    m_accepted = stats.accepted;
    if (!m_plain.empty() && m_inner)
        m_inner->writeVoice(m_plain);
    // Refusals are said when there are new ones, at most once a second: a
    // forger sending fifty a second makes one line a second, not fifty.
    const std::uint64_t refusals = stats.forged + stats.replayed;
    const std::int64_t now = m_clock->steadyMicros();
    if (m_refused && refusals != m_saidRefusals && now - m_lastSaid >= 1000000) {
        m_saidRefusals = refusals;
        m_lastSaid = now;
        m_refused(stats.forged, stats.replayed);
    }
}
