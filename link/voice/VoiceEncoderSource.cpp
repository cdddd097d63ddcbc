#include "link/voice/VoiceEncoderSource.h"

#include "codec/voice/Resample.h"
#include "codec/voice/WavFile.h"

#include <algorithm>
#include <cstdlib>

using namespace rcm::voice;

VoiceEncoderSource::VoiceEncoderSource(std::chrono::milliseconds maxBacklog)
    : m_maxBacklog(static_cast<std::size_t>(maxBacklog.count()) * kSampleRate / 1000)
{
}

void VoiceEncoderSource::pushPcm(std::span<const std::int16_t> pcm)
{
    const std::lock_guard lock(m_mutex);
    m_talkEnded = false;
    m_pcm.insert(m_pcm.end(), pcm.begin(), pcm.end());
    if (m_maxBacklog != 0 && m_pcm.size() > m_maxBacklog) {
        const std::size_t drop = m_pcm.size() - m_maxBacklog;
        m_pcm.erase(m_pcm.begin(), m_pcm.begin() + static_cast<std::ptrdiff_t>(drop));
        m_dropped += drop;
    }
}

bool VoiceEncoderSource::speakFile(const std::string& path, std::string& error)
{
    const std::optional<rcm::PcmAudio> audio = rcm::WavFile::read(path, error);
    if (!audio)
        return false;
    const std::vector<std::int16_t> pcm = rcm::resample(audio->samples, audio->sampleRate, kSampleRate);
    const std::lock_guard lock(m_mutex);
    m_pcm.insert(m_pcm.end(), pcm.begin(), pcm.end());
    m_talkEnded = true;
    return true;
}

void VoiceEncoderSource::endTalk()
{
    const std::lock_guard lock(m_mutex);
    m_talkEnded = true;
}

void VoiceEncoderSource::clear()
{
    const std::lock_guard lock(m_mutex);
    m_pcm.clear();
    m_talkEnded = false;
}

std::size_t VoiceEncoderSource::backlogSamples() const
{
    const std::lock_guard lock(m_mutex);
    return m_pcm.size();
}

std::uint64_t VoiceEncoderSource::samplesDropped() const
{
    const std::lock_guard lock(m_mutex);
    return m_dropped;
}

std::uint64_t VoiceEncoderSource::speechFramesSent() const
{
    const std::lock_guard lock(m_mutex);
    return m_speechFrames;
}

void VoiceEncoderSource::readVoice(std::span<std::uint8_t> out)
{
    while (!out.empty()) {
        if (m_framePosition == kFrameBytes)
            nextFrame();
        const std::size_t n = std::min(out.size(), kFrameBytes - m_framePosition);
        std::copy_n(m_frame.begin() + static_cast<std::ptrdiff_t>(m_framePosition), n, out.begin());
        m_framePosition += n;
        out = out.subspan(n);
    }
}

void VoiceEncoderSource::setFramesPerPacket(int frames)
{
    m_packetFrames = std::max(1, frames);
    m_frameInPacket = 0;
    m_framePosition = kFrameBytes;  // the next read starts a frame, and a packet
}

void VoiceEncoderSource::nextFrame()
{
    std::array<std::int16_t, kFrameSamples> pcm{};
    bool speech = false;
    {
        const std::lock_guard lock(m_mutex);
        const std::size_t n = std::min(m_pcm.size(), kFrameSamples);
        // A packet's first frame decides for the packet: speech only when
        // the whole packet's samples wait (or the talk has ended), so that
        // live speech is never cut into speech and idle halves.
        if (m_frameInPacket == 0)
            m_packetSpeech = m_pcm.size() >= kFrameSamples * std::size_t(m_packetFrames) || (n > 0 && m_talkEnded);
        m_frameInPacket = (m_frameInPacket + 1) % m_packetFrames;
        if (m_packetSpeech && (n == kFrameSamples || (n > 0 && m_talkEnded))) {
            std::copy_n(m_pcm.begin(), n, pcm.begin());
            m_pcm.erase(m_pcm.begin(), m_pcm.begin() + static_cast<std::ptrdiff_t>(n));
            speech = true;
            ++m_speechFrames;
        }
        if (m_pcm.empty())
            m_talkEnded = false;
    }
    // Encoded outside the lock: pushPcm() from the audio thread never waits on Codec 2.
    if (speech)
        m_encoder.speechFrame(pcm, m_frame);
    else
        m_encoder.idleFrame(m_frame);
    int peak = 0;
    for (const std::int16_t s : pcm)
        peak = std::max(peak, std::abs(int(s)));
    m_sentLevel = float(peak) / 32768.0f;
    m_framePosition = 0;
}
