#pragma once

// Where a voice link takes the bytes of its voice stream from: 600 a
// second, whole voice frames back to back (codec/voice/VoiceCodec.h), idle frames
// when nobody speaks. The link asks for exactly what the line is about to
// carry, in the link's thread.

#include <cstdint>
#include <span>

class VoiceSource {
public:
    virtual ~VoiceSource() = default;
    // Fills all of `out`, at once: never blocks, never leaves a gap.
    virtual void readVoice(std::span<std::uint8_t> out) = 0;
    // From the next frame on, frames are read `frames` at a time, whole (a
    // secure link seals two 20 ms frames in one): a source that decides
    // speech or idle per frame decides it per packet, so that a talk is never
    // split by an idle half. A new link calls it before its first read.
    virtual void setFramesPerPacket(int frames) { (void)frames; }
};
