#pragma once

// A VoiceSink that decodes: PCM (8 kHz, 16-bit mono) out through a handler,
// in the link's thread, 160 samples per 20 ms frame slot received, silence
// for idle and lost frames (codec/voice/VoiceCodec.h). The handler hands it on,
// to a WAV file or a sound card's buffer, without blocking.

#include "link/voice/VoiceSink.h"

#include "codec/voice/VoiceCodec.h"

#include <atomic>
#include <functional>
#include <span>
#include <vector>

class VoiceDecoderSink : public VoiceSink {
public:
    using PcmHandler = std::function<void(std::span<const std::int16_t>)>;

    explicit VoiceDecoderSink(PcmHandler handler);

    void writeVoice(std::span<const std::uint8_t> bytes) override;

    // The link's thread.
    const rcm::voice::VoiceDecoder::Stats& stats() const { return m_decoder.stats(); }
    // Any thread: for status views and tests.
    std::uint64_t speechFrames() const { return m_speechFrames.load(); }
    std::uint64_t samplesOut() const { return m_samplesOut.load(); }

private:
    PcmHandler m_handler;
    rcm::voice::VoiceDecoder m_decoder;
    std::vector<std::int16_t> m_pcm;
    std::atomic<std::uint64_t> m_speechFrames{0};
    std::atomic<std::uint64_t> m_samplesOut{0};
};
