#include "link/voice/SecureVoiceSource.h"

#include "link/clock/Clock.h"

#include <algorithm>

using namespace rcm::voice;

SecureVoiceSource::SecureVoiceSource(std::shared_ptr<VoiceSource> inner, const rcm::secure::VoiceKeys& keys,
                                     std::shared_ptr<Clock> clock)
    : m_inner(std::move(inner)),
      m_clock(std::move(clock)),
      m_sealer(keys, [clock = m_clock] { return clock->utcMicros(); })
{
    m_inner->setFramesPerPacket(int(kSecureFrameHalves));
}

void SecureVoiceSource::readVoice(std::span<std::uint8_t> out)
{
    while (!out.empty()) {
        if (m_position == m_frame.size())
            nextFrame();
        const std::size_t n = std::min(out.size(), m_frame.size() - m_position);
        std::copy_n(m_frame.begin() + static_cast<std::ptrdiff_t>(m_position), n, out.begin());
        m_position += n;
        out = out.subspan(n);
    }
}

void SecureVoiceSource::nextFrame()
{
    std::array<std::uint8_t, kSecureFrameHalves * kFrameBytes> plain;
    m_inner->readVoice(plain);
    std::array<VoiceFrame, kSecureFrameHalves> frames;
    for (std::size_t h = 0; h < kSecureFrameHalves; ++h) {
        // The inner source writes whole, correct frames; one that is not (no
        // source at all) goes as idle.
        if (!parseFrame(std::span<const std::uint8_t, kFrameBytes>(plain.data() + h * kFrameBytes, kFrameBytes),
                        frames[h]))
            frames[h] = VoiceFrame{};
    }
    m_sealer.seal(frames[0], frames[1], m_frame);
    m_position = 0;
    ++m_sealed;
}
