#pragma once

// A VoiceSource that speaks the PCM it is given: a microphone's, a file's.
// PCM (8 kHz, 16-bit mono) is pushed from any thread; the link's thread
// pulls bytes, and at each frame boundary the next 160 samples waiting are
// encoded, or an idle frame goes when fewer wait. endTalk() lets a last
// partial frame go, padded with silence.
//
// Latency: samples wait for the next frame boundary of the voice stream (at
// most 20 ms) and for any backlog before them. A microphone whose clock runs
// ahead of the line's would grow the backlog for ever, so live input keeps
// at most maxBacklog, dropping the oldest samples beyond it; a file, pushed
// all at once, is given no limit and is paced by the line.

#include "link/voice/VoiceSource.h"

#include "codec/voice/VoiceCodec.h"

#include <array>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <deque>
#include <mutex>
#include <span>
#include <string>

class VoiceEncoderSource : public VoiceSource {
public:
    static constexpr std::chrono::milliseconds kDefaultMaxBacklog{100};

    // maxBacklog 0: no limit.
    explicit VoiceEncoderSource(std::chrono::milliseconds maxBacklog = kDefaultMaxBacklog);

    // Any thread.
    void pushPcm(std::span<const std::int16_t> pcm);
    // A 16-bit PCM WAV file at any rate, resampled to 8 kHz, pushed whole
    // and ended: it goes out at the line's pace, whatever the backlog limit.
    bool speakFile(const std::string& path, std::string& error);
    void endTalk();
    // Drops what waits, at once: a new talk starts afresh.
    void clear();
    std::size_t backlogSamples() const;
    std::uint64_t samplesDropped() const;
    std::uint64_t speechFramesSent() const;
    // Peak magnitude of the last frame sent, 0..1 (0 for idle): what the
    // operator's level meter shows. Any thread.
    float sentLevel() const { return m_sentLevel.load(); }

    // The link's thread.
    void readVoice(std::span<std::uint8_t> out) override;
    void setFramesPerPacket(int frames) override;

private:
    void nextFrame();

    const std::size_t m_maxBacklog;  // samples; 0: no limit
    mutable std::mutex m_mutex;      // guards the members below it up to m_encoder
    std::deque<std::int16_t> m_pcm;
    bool m_talkEnded = false;
    std::uint64_t m_dropped = 0;
    std::uint64_t m_speechFrames = 0;

    rcm::voice::VoiceEncoder m_encoder;  // the link's thread only
    std::array<std::uint8_t, rcm::voice::kFrameBytes> m_frame{};
    std::size_t m_framePosition = rcm::voice::kFrameBytes;
    int m_packetFrames = 1;
    int m_frameInPacket = 0;    // of the packet being read
    bool m_packetSpeech = false;  // the packet being read is speech
    std::atomic<float> m_sentLevel{0};
};
