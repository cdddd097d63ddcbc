#pragma once

// Where a voice link delivers the voice stream it received: the bytes of the
// voice phase as they arrive, in the link's thread, with whatever errors and
// losses the line made. Finding the frames in them is the sink's business.

#include <cstdint>
#include <span>

class VoiceSink {
public:
    virtual ~VoiceSink() = default;
    // Must not block: the link's receiving waits on it.
    virtual void writeVoice(std::span<const std::uint8_t> bytes) = 0;
};
