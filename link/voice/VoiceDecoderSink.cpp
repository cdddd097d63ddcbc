#include "link/voice/VoiceDecoderSink.h"

#include <utility>

VoiceDecoderSink::VoiceDecoderSink(PcmHandler handler) : m_handler(std::move(handler)) {}

void VoiceDecoderSink::writeVoice(std::span<const std::uint8_t> bytes)
{
    m_pcm.clear();
    m_decoder.decode(bytes, m_pcm);
    m_speechFrames = m_decoder.stats().speechFrames;
    m_samplesOut += m_pcm.size();
    if (!m_pcm.empty() && m_handler)
        m_handler(m_pcm);
}
