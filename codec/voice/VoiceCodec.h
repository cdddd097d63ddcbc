// The voice channel's speech codec and framing (docs/protocol.md section 7):
// Codec 2 at 3,200 bit/s in frames of 12 bytes per 20 ms, so the voice phase
// of the multiplexed link (600 bytes a second) carries exactly 50 frames a
// second, speech or idle.
//
//   byte 0     sync A2
//   byte 1     kind (bits 7-6: 01 speech, 10 idle) and sequence (bits 5-0, mod 64)
//   bytes 2-9  one Codec 2 3200 frame (8 bytes, 160 samples); 00 x8 when idle
//   bytes 10-11  Reed-Solomon parity over bytes 0-9: RS(12,10) over GF(256),
//              corrects one wrong byte anywhere in the frame
//
// A receiver that is in step expects a frame every 12 bytes and takes what RS
// accepts there; after two failures in a row it hunts: an A2 byte, a frame
// that RS accepts, a valid kind, and a sequence that agrees with the bytes
// since the last frame (or, lacking one, the next frame's). Every frame slot
// becomes 160 samples of output: speech decoded, idle and lost frames as
// silence. The number of frames lost is read from the sequence, to the
// nearest count the bytes in between allow, so the output keeps the
// stream's timing through errors and lost bytes.
//
// The sync byte, 7 bits from 55 and 5 from 0F, comes every 12 bytes, so any
// 16 bytes of voice frames are at least 7 bits from the preamble's last 16
// (55 x14, 0F 0F), beyond the 6 within which VoiceDemultiplexer takes a
// phase for control; Codec 2's bits and the parity put them far further.
//
// Plain C++20 over libcodec2. Neither class is thread-safe; each holds its own
// Codec 2 state, but Codec 2 draws the phases of unvoiced sound from one
// random generator for the whole process: decoded samples depend on what was
// decoded before, and decoders in two threads would race on it, so a program
// decodes voice in one thread.
#pragma once

#include "codec/voice/FrameStream.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

struct CODEC2;

namespace rcm::voice {

inline constexpr int kSampleRate = 8000;           // 16-bit mono PCM in and out
inline constexpr std::size_t kFrameSamples = 160;  // 20 ms
inline constexpr std::size_t kFrameBytes = 12;     // on the link
inline constexpr std::size_t kCodec2Bytes = 8;     // Codec 2 3200: 64 bits per 20 ms
inline constexpr std::size_t kFramesPerSecond = 50;
inline constexpr std::size_t kBytesPerSecond = kFrameBytes * kFramesPerSecond;  // 600
inline constexpr std::uint8_t kSyncByte = 0xA2;
inline constexpr std::uint8_t kSequenceModulus = 64;

enum class FrameKind : std::uint8_t { Speech = 0x40, Idle = 0x80 };

using FrameSpan = std::span<std::uint8_t, kFrameBytes>;
using PcmFrame = std::span<const std::int16_t, kFrameSamples>;

// A voice frame checked and corrected: what its bytes say.
struct VoiceFrame {
    FrameKind kind = FrameKind::Idle;
    std::uint8_t sequence = 0;
    std::array<std::uint8_t, kCodec2Bytes> payload{};
    int corrected = 0;  // bytes RS corrected: 0 or 1
};

// The frame at `bytes` (12 of them) after RS correction, if it is one.
bool parseFrame(std::span<const std::uint8_t, kFrameBytes> bytes, VoiceFrame& frame);
// A frame's 12 bytes, parity included: what VoiceEncoder writes.
void buildFrame(FrameKind kind, std::uint8_t sequence, std::span<const std::uint8_t, kCodec2Bytes> payload,
                FrameSpan out);

// The voice frames' Reed-Solomon code, for any frame length up to 255: the
// generator (x + a)(x + a^2) over GF(256) (0x11D), systematic, parity in
// the last two bytes, byte 0 the highest power. addParity() writes them;
// correctOneByte() corrects one wrong byte in place and says 0 (none
// wrong), 1 (one corrected) or -1 (more than one: beyond correction).
void addParity(std::span<std::uint8_t> frame);
int correctOneByte(std::span<std::uint8_t> frame);

class VoiceEncoder {
public:
    VoiceEncoder();
    ~VoiceEncoder();
    VoiceEncoder(const VoiceEncoder&) = delete;
    VoiceEncoder& operator=(const VoiceEncoder&) = delete;

    // One frame of speech; the sequence counts on, over speech and idle alike.
    void speechFrame(PcmFrame pcm, FrameSpan out);
    // When nobody speaks: a frame that decodes as 20 ms of silence.
    void idleFrame(FrameSpan out);

    // PCM in pieces of any size: a frame is appended to `out` for every 160
    // samples, the rest waits for the next call.
    void encode(std::span<const std::int16_t> pcm, std::vector<std::uint8_t>& out);
    // End of talk: what waits, padded with silence to a frame (nothing when
    // nothing waits).
    void finish(std::vector<std::uint8_t>& out);
    std::size_t pendingSamples() const { return m_pending; }

    std::uint8_t nextSequence() const { return m_sequence; }

private:
    void frame(FrameKind kind, const std::uint8_t* payload, FrameSpan out);

    std::unique_ptr<CODEC2, void (*)(CODEC2*)> m_codec2;
    std::array<std::int16_t, kFrameSamples> m_buffer{};
    std::size_t m_pending = 0;
    std::uint8_t m_sequence = 0;
};

class VoiceDecoder {
public:
    // Two frame slots in a row that fail put the decoder out of step.
    static constexpr int kMaxMisses = 2;

    VoiceDecoder();
    ~VoiceDecoder();
    VoiceDecoder(const VoiceDecoder&) = delete;
    VoiceDecoder& operator=(const VoiceDecoder&) = delete;

    // Bytes in pieces of any size; 160 samples appended to `pcm` per frame
    // slot, as soon as a frame is taken (a slot found lost is played with
    // the next frame taken).
    void decode(std::span<const std::uint8_t> bytes, std::vector<std::int16_t>& pcm);
    // Forgets the stream and the statistics; the Codec 2 state starts afresh.
    void reset();

    // In step: the next frame is expected at a known place.
    bool inStep() const { return m_stream.tracking; }
    // What the decoder counts; its corrected frames had a byte corrected by RS.
    struct Stats : FrameStreamStats {
        std::uint64_t speechFrames = 0;
        std::uint64_t idleFrames = 0;
        std::uint64_t bytesSkipped = 0;  // between frames taken (garbage, frames lost, lost alignment)
    };
    const Stats& stats() const { return m_stats; }
    // Bytes held for a later decision (at most two frames' worth between calls).
    std::size_t bufferedBytes() const { return m_stream.buffer.size(); }

private:
    void process(std::vector<std::int16_t>& pcm);
    bool frameAt(std::uint64_t offset, VoiceFrame& frame) const;
    std::uint64_t framesLostBefore(std::uint64_t offset, std::uint8_t sequence) const;
    void take(std::uint64_t offset, const VoiceFrame& frame, std::uint64_t lost, std::vector<std::int16_t>& pcm);

    std::unique_ptr<CODEC2, void (*)(CODEC2*)> m_codec2;
    FrameStream m_stream{kFrameBytes, kMaxMisses};
    bool m_hasLast = false;  // a frame has been taken
    std::uint8_t m_lastSequence = 0;
    Stats m_stats;
};

}  // namespace rcm::voice
