#pragma once

// The voice a keyed link sends (codec/voice/SecureVoice.h): a VoiceSource of
// plain 20 ms frames, read two at a time and sealed into one 24-byte secure
// frame per 40 ms: the same 600 bytes a second, enciphered and authenticated.

#include "link/voice/VoiceSource.h"

#include "codec/voice/SecureVoice.h"

#include <array>
#include <memory>

class Clock;

class SecureVoiceSource : public VoiceSource {
public:
    // `inner` is told to give its frames in pairs. `clock` starts the counter.
    SecureVoiceSource(std::shared_ptr<VoiceSource> inner, const rcm::secure::VoiceKeys& keys,
                      std::shared_ptr<Clock> clock);

    void readVoice(std::span<std::uint8_t> out) override;
    std::uint64_t framesSealed() const { return m_sealed; }

private:
    void nextFrame();

    std::shared_ptr<VoiceSource> m_inner;
    std::shared_ptr<Clock> m_clock;
    rcm::voice::SecureVoiceSealer m_sealer;
    std::array<std::uint8_t, rcm::voice::kSecureFrameBytes> m_frame{};
    std::size_t m_position = rcm::voice::kSecureFrameBytes;
    std::uint64_t m_sealed = 0;
};
