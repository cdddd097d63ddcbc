#pragma once

// The voice a keyed link receives (codec/voice/SecureVoice.h): secure frames
// opened, and the plain frames of those that authenticate handed on to the
// inner VoiceSink (a decoder) as if they had come over a plain link. A forged
// or replayed frame is never handed on; each is counted, and said through
// the handler (in the link's thread, at most once a second, with the counts
// so far).

#include "link/voice/VoiceSink.h"

#include "codec/voice/SecureVoice.h"

#include <atomic>
#include <functional>
#include <memory>
#include <vector>

class Clock;

class SecureVoiceSink : public VoiceSink {
public:
    // forged, replayed: the totals so far.
    using RefusedHandler = std::function<void(std::uint64_t forged, std::uint64_t replayed)>;

    SecureVoiceSink(std::shared_ptr<VoiceSink> inner, const rcm::secure::VoiceKeys& keys, std::shared_ptr<Clock> clock,
                    RefusedHandler refused = {});

    void writeVoice(std::span<const std::uint8_t> bytes) override;

    // The link's thread.
    const rcm::voice::SecureVoiceOpener::Stats& stats() const { return m_opener.stats(); }
    // Any thread.
    std::uint64_t forged() const { return m_forged.load(); }
    std::uint64_t replayed() const { return m_replayed.load(); }
    std::uint64_t accepted() const { return m_accepted.load(); }

private:
    std::shared_ptr<VoiceSink> m_inner;
    std::shared_ptr<Clock> m_clock;
    rcm::voice::SecureVoiceOpener m_opener;
    RefusedHandler m_refused;
    std::vector<std::uint8_t> m_plain;
    std::int64_t m_lastSaid = 0;  // steady microseconds
    std::uint64_t m_saidRefusals = 0;
    std::atomic<std::uint64_t> m_forged{0};
    std::atomic<std::uint64_t> m_replayed{0};
    std::atomic<std::uint64_t> m_accepted{0};
};
