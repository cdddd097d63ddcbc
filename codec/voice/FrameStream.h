#pragma once

// What the two voice receivers (VoiceDecoder, SecureVoiceOpener) share: the
// byte stream they find fixed-size frames in, held from where they may still
// look, and where they stand in it. In step, the next frame is expected at
// `expect`, right after the last; hunting, each offset from `scan` on is
// tried, from the sync byte.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace rcm::voice {

// The counts both receivers keep, among their others.
struct FrameStreamStats {
    std::uint64_t bytesIn = 0;
    std::uint64_t lostFrames = 0;       // slots played as silence: beyond correction, or bytes lost
    std::uint64_t correctedFrames = 0;  // a byte corrected
    std::uint64_t resyncs = 0;          // lost step and hunted
};

struct FrameStream {
    FrameStream(std::size_t frameSize, int missesToHunt) : frameBytes(frameSize), maxMisses(missesToHunt) {}

    std::uint64_t end() const { return base + buffer.size(); }
    const std::uint8_t* at(std::uint64_t offset) const { return buffer.data() + (offset - base); }

    // A frame taken at `offset`: in step, the next expected right after it.
    void took(std::uint64_t offset)
    {
        lastEnd = offset + frameBytes;
        tracking = true;
        expect = lastEnd;
        misses = 0;
    }

    // A frame where one was expected, refused whole: still in step after it.
    void passed()
    {
        expect += frameBytes;
        lastEnd = expect;
    }

    // No frame taken where one was expected: its slot is passed over, and
    // after maxMisses in a row (bytes lost or inserted, most likely) hunting
    // starts again from the last frame taken. True when it did.
    bool missed()
    {
        expect += frameBytes;
        if (++misses < maxMisses)
            return false;
        tracking = false;
        scan = lastEnd;
        return true;
    }

    // Bytes in, in slices, so that a large piece costs no more memory than a
    // small one: process() looks for frames after each slice, then the bytes
    // no longer needed go. Kept: in step, from the last frame taken, where
    // hunting would start again; hunting, from the next offset to try.
    template <typename Process>
    void feed(std::span<const std::uint8_t> bytes, const Process& process)
    {
        constexpr std::size_t kSlice = 1024;
        while (!bytes.empty()) {
            const std::size_t n = std::min(bytes.size(), kSlice);
            buffer.insert(buffer.end(), bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(n));
            bytes = bytes.subspan(n);
            process();
            const std::uint64_t keep = std::max(base, tracking ? std::min(lastEnd, expect) : scan);
            const std::size_t drop = static_cast<std::size_t>(std::min<std::uint64_t>(keep - base, buffer.size()));
            buffer.erase(buffer.begin(), buffer.begin() + static_cast<std::ptrdiff_t>(drop));
            base += drop;
        }
    }

    // Looks for frames until the bytes held run out. In step, inStep(offset)
    // judges the frame expected at offset: took(), passed() or missed().
    // Hunting, hunt(end) tries the offsets from scan up to the end of the
    // bytes held and says whether it took a frame.
    template <typename InStep, typename Hunt>
    void search(const InStep& inStep, const Hunt& hunt)
    {
        for (;;) {
            if (tracking) {
                if (expect + frameBytes > end())
                    return;
                inStep(expect);
            } else if (!hunt(end())) {
                return;
            }
        }
    }

    std::size_t frameBytes;
    int maxMisses;
    std::vector<std::uint8_t> buffer;
    std::uint64_t base = 0;  // stream offset of buffer[0]
    bool tracking = false;
    std::uint64_t lastEnd = 0;  // stream offset just after the last frame taken
    std::uint64_t expect = 0;   // in step: where the next frame should start
    int misses = 0;
    std::uint64_t scan = 0;  // hunting: the next offset to try
};

}  // namespace rcm::voice
