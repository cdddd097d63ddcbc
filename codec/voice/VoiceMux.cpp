#include "codec/voice/VoiceMux.h"

#include <algorithm>
#include <bit>
#include <cassert>
#include <cstring>
#include <utility>

namespace rcm {
namespace {

// The preamble's last 16 bytes, 55 x14, 0F 0F, as a shift register holds
// them: the 8 older bytes in the high word, the newest byte lowest.
constexpr std::uint64_t kWindowHi = 0x5555555555555555ULL;
constexpr std::uint64_t kWindowLo = 0x5555555555550F0FULL;
constexpr std::size_t kWindowSize = 16;

// Handed on in pieces of at most this many bytes, so memory stays fixed
// however large a feed() is.
constexpr std::size_t kOutputChunk = 4096;

}  // namespace

void interleave(std::span<const std::uint8_t> control, std::span<const std::uint8_t> voice, std::span<std::uint8_t> out)
{
    assert(control.size() == voice.size() && out.size() == 2 * control.size());
    for (std::size_t i = 0; i < control.size(); ++i) {
        out[2 * i] = control[i];
        out[2 * i + 1] = voice[i];
    }
}

std::array<std::uint8_t, kMuxedFrameSize> multiplexFrame(std::span<const std::uint8_t, kFrameSize> frame,
                                                         std::span<const std::uint8_t, kFrameSize> voice)
{
    std::array<std::uint8_t, kMuxedFrameSize> out;
    interleave(frame, voice, out);
    return out;
}

bool VoiceMultiplexer::queueFrame(std::span<const std::uint8_t, kFrameSize> frame)
{
    bool kept = true;
    if (m_queued == kMaxQueuedFrames) {
        m_head = (m_head + 1) % kMaxQueuedFrames;
        --m_queued;
        ++m_stats.framesDropped;
        kept = false;
    }
    std::memcpy(m_queue[(m_head + m_queued) % kMaxQueuedFrames].data(), frame.data(), kFrameSize);
    ++m_queued;
    return kept;
}

bool VoiceMultiplexer::startNext()
{
    if (m_queued == 0)
        return false;
    m_current = m_queue[m_head];
    m_head = (m_head + 1) % kMaxQueuedFrames;
    --m_queued;
    m_position = 0;
    ++m_stats.framesStarted;
    return true;
}

void VoiceMultiplexer::multiplex(std::span<const std::uint8_t> voice, std::span<std::uint8_t> out)
{
    assert(out.size() == 2 * voice.size());
    for (std::size_t i = 0; i < voice.size(); ++i) {
        if (m_position == kFrameSize && (m_frameJustEnded || !m_holdFill))
            startNext();
        m_frameJustEnded = false;
        if (m_position < kFrameSize) {
            out[2 * i] = m_current[m_position++];
            m_frameJustEnded = m_position == kFrameSize;
        } else {
            out[2 * i] = kControlFillByte;
            ++m_stats.fillBytes;
        }
        out[2 * i + 1] = voice[i];
    }
    m_stats.pairs += voice.size();
}

VoiceDemultiplexer::VoiceDemultiplexer(BytesHandler onControl, BytesHandler onVoice)
    : m_onControl(std::move(onControl)), m_onVoice(std::move(onVoice))
{
    m_control.reserve(kOutputChunk);
    m_voice.reserve(kOutputChunk);
}

void VoiceDemultiplexer::reset()
{
    m_phases = {};
    m_controlPhase = 0;
    m_offset = 0;
    m_control.clear();
    m_voice.clear();
    m_stats = Stats{};
}

void VoiceDemultiplexer::feed(std::span<const std::uint8_t> bytes)
{
    m_stats.bytesIn += bytes.size();
    for (const std::uint8_t b : bytes) {
        const int p = static_cast<int>(m_offset++ & 1);
        Phase& phase = m_phases[static_cast<std::size_t>(p)];
        phase.windowHi = (phase.windowHi << 8) | (phase.windowLo >> 56);
        phase.windowLo = (phase.windowLo << 8) | b;
        phase.history[phase.next] = b;
        phase.next = (phase.next + 1) % kPreambleSize;
        phase.count = std::min(phase.count + 1, kPreambleSize);

        std::vector<std::uint8_t>& out = p == m_controlPhase ? m_control : m_voice;
        out.push_back(b);
        if (out.size() == kOutputChunk)
            flushOutput();

        if (p != m_controlPhase && phase.count >= kWindowSize &&
            std::popcount(phase.windowHi ^ kWindowHi) + std::popcount(phase.windowLo ^ kWindowLo) <=
                kMaxWindowBitErrors)
            swapPhases(p);
    }
    flushOutput();
}

void VoiceDemultiplexer::swapPhases(int control)
{
    // What went before, in order, so that the replayed preamble follows it.
    flushOutput();
    const Phase& phase = m_phases[static_cast<std::size_t>(control)];
    std::array<std::uint8_t, kPreambleSize> preamble;
    const std::size_t first = (phase.next + kPreambleSize - phase.count) % kPreambleSize;
    for (std::size_t i = 0; i < phase.count; ++i)
        preamble[i] = phase.history[(first + i) % kPreambleSize];
    m_stats.controlBytes += phase.count;
    if (m_onControl)
        m_onControl(std::span<const std::uint8_t>(preamble.data(), phase.count));
    m_controlPhase = control;
    ++m_stats.phaseChanges;
}

void VoiceDemultiplexer::flushOutput()
{
    if (!m_control.empty()) {
        m_stats.controlBytes += m_control.size();
        if (m_onControl)
            m_onControl(m_control);
        m_control.clear();
    }
    if (!m_voice.empty()) {
        m_stats.voiceBytes += m_voice.size();
        if (m_onVoice)
            m_onVoice(m_voice);
        m_voice.clear();
    }
}

}  // namespace rcm
