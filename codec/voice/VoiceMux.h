// Byte multiplexing of the command frames with voice on one 9,600 bps link
// (PROFILE.md section 4, docs/protocol.md section 7): control and voice bytes
// alternate, control first, C V C V ..., so each second carries one 600-byte
// frame in the control phase and 600 voice bytes in the other.
//
// The receiver does not know which phase is which: it joins the stream at
// any byte, and a lost byte swaps the phases. The preamble tells: the phase
// in which its last 16 bytes (55 x14, 0F 0F) turn up is the control phase.
// Voice frames are built so that they never come near that pattern (see
// VoiceCodec.h), so the voice phase cannot be taken for control.
//
// Plain C++20, no Qt. Neither class is thread-safe.
#pragma once

#include "codec/frame/Frame.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

namespace rcm {

// One frame and its second of voice: 9,600 bits.
inline constexpr std::size_t kMuxedFrameSize = 2 * kFrameSize;  // 1,200
// Sent in the control phase when no frame is waiting, so that voice still
// flows; far from the preamble's 55 and 0F, and no Item_ID.
inline constexpr std::uint8_t kControlFillByte = 0x00;

// out[2i] = control[i], out[2i + 1] = voice[i]. control and voice have the
// same size, out twice that.
void interleave(std::span<const std::uint8_t> control, std::span<const std::uint8_t> voice,
                std::span<std::uint8_t> out);
std::array<std::uint8_t, kMuxedFrameSize> multiplexFrame(std::span<const std::uint8_t, kFrameSize> frame,
                                                         std::span<const std::uint8_t, kFrameSize> voice);

// The streaming form, fed as the serial link sends: each call produces the
// next byte pairs of the line. A frame once started is sent whole, and a
// queued frame starts right after the one before, so frames sent back to
// back stand exactly 1,200 bytes apart; with no frame to send the control
// phase carries kControlFillByte and the voice goes on.
class VoiceMultiplexer {
public:
    // Enough to ride out a sender that is late and then catches up; more
    // would only age the commands.
    static constexpr std::size_t kMaxQueuedFrames = 4;

    struct Stats {
        std::uint64_t pairs = 0;  // byte pairs produced
        std::uint64_t framesStarted = 0;
        std::uint64_t framesDropped = 0;  // queued while kMaxQueuedFrames already waited: the oldest goes
        std::uint64_t fillBytes = 0;      // control bytes that were fill
    };

    // To follow the frame being sent (or to start at the next pair when
    // none is). False when the queue was full and its oldest frame was
    // dropped to make room.
    bool queueFrame(std::span<const std::uint8_t, kFrameSize> frame);
    // The next voice.size() byte pairs into out (2 x voice.size() bytes).
    void multiplex(std::span<const std::uint8_t> voice, std::span<std::uint8_t> out);
    // While set, a queued frame does not end fill: the serial link holds the
    // first frame after a pause a little, so that the frame after it, due a
    // second later from a sender whose ticks wobble, is there in time to
    // follow it with no gap. A frame that follows another is never held.
    void setHoldFill(bool hold) { m_holdFill = hold; }

    // A frame is part sent: the next pair continues it.
    bool sendingFrame() const { return m_position < kFrameSize; }
    std::size_t queuedFrames() const { return m_queued; }
    // Control bytes of the current frame still to go (0 when none is being sent).
    std::size_t frameBytesLeft() const { return sendingFrame() ? kFrameSize - m_position : 0; }
    const Stats& stats() const { return m_stats; }

private:
    bool startNext();

    FrameBytes m_current{};
    std::size_t m_position = kFrameSize;  // next byte of m_current; kFrameSize: none
    bool m_frameJustEnded = false;        // the last pair ended a frame: the next may follow it
    bool m_holdFill = false;
    std::array<FrameBytes, kMaxQueuedFrames> m_queue{};
    std::size_t m_head = 0;
    std::size_t m_queued = 0;
    Stats m_stats;
};

// Splits the received line into the control stream, for a StreamSync, and
// the voice stream, for a VoiceDecoder. Bytes arrive in pieces of any size.
//
// Until a preamble shows which phase is which, the first byte is taken as
// control (the sender starts with control). When the preamble's last 16
// bytes turn up in the voice phase within StreamSync's tolerance
// (kMaxWindowBitErrors), the phases are swapped at once: the new control
// phase's last 90 bytes (the preamble) go to the control handler first, so
// the synchroniser sees the frame whole, and everything after follows the
// new phases. Bytes already handed on before the swap stay where they went:
// the synchroniser and the voice decoder each find their way again.
//
// Memory is fixed: 90 bytes of history per phase and two small output buffers.
class VoiceDemultiplexer {
public:
    using BytesHandler = std::function<void(std::span<const std::uint8_t>)>;

    static constexpr int kMaxWindowBitErrors = 6;  // as StreamSync's

    struct Stats {
        std::uint64_t bytesIn = 0;
        std::uint64_t controlBytes = 0;  // handed to the control handler, the replayed preambles included
        std::uint64_t voiceBytes = 0;
        std::uint64_t phaseChanges = 0;
    };

    // Handlers are called during feed(), control and voice each in stream
    // order; spans are valid only during the call. They must not call back
    // into the demultiplexer.
    VoiceDemultiplexer(BytesHandler onControl, BytesHandler onVoice);

    void feed(std::span<const std::uint8_t> bytes);
    // Forgets the phase and the history, statistics included: the next byte
    // is taken as control, as at the start.
    void reset();

    // 0: bytes at even offsets of the stream fed since construction or
    // reset() carry control; 1: odd ones.
    int controlPhase() const { return m_controlPhase; }
    const Stats& stats() const { return m_stats; }

private:
    struct Phase {
        std::uint64_t windowLo = 0;  // last 16 bytes, oldest in the top byte of windowHi
        std::uint64_t windowHi = 0;
        std::array<std::uint8_t, kPreambleSize> history{};  // ring of the last 90 bytes
        std::size_t next = 0;                               // where the next byte goes in history
        std::size_t count = 0;                              // bytes in history
    };

    void swapPhases(int control);
    void flushOutput();

    BytesHandler m_onControl;
    BytesHandler m_onVoice;
    std::array<Phase, 2> m_phases;
    int m_controlPhase = 0;
    std::uint64_t m_offset = 0;  // bytes fed since construction or reset()
    std::vector<std::uint8_t> m_control;
    std::vector<std::uint8_t> m_voice;
    Stats m_stats;
};

}  // namespace rcm
