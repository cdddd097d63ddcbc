// Finds 600-byte frames in a byte stream that arrives in pieces of any size,
// with garbage between frames, lost or inserted bytes and bit errors.
//
// Candidates. Start c (the first byte of codeword 1) is scored by the
// Hamming distance between the 16 bytes before c and the preamble tail
// 55 x14, 0F 0F. It qualifies at <= 6 bits; where the next frame is due
// (600 bytes after the last one reported, good or not) at <= 16 bits, if
// its last two bytes are within 3 bits of 0F 0F. RS decoding confirms it.
//
// Readings. RS confirmation alone cannot tell a true start from one a few
// bytes off: RS codes are cyclic, so codewords read k bytes early or late
// are cyclic shifts with k bytes changed, and for k <= 16 they "decode"
// into shifted garbage. So from the first qualifying candidate q, all
// qualifying candidates in q .. q+89 compete (89: any all-55 window is 8
// bits away and qualifies with two bit errors, so a shorter neighbourhood
// could hold only such a false start inside a preamble). Each is a reading
// of the stream, scored by the bit errors it must assume: window distance
// plus the bits RS corrected, plus 17 for a codeword beyond correction.
// A reading confirms when both codewords decode, or one does under a window
// within 3 bits outside the codewords of a frame that failed. Of the
// readings that confirm, the one taken is the lowest-scored that the
// acceptor (the acceptance decision's exactness rules, FrameReceiver)
// finds exact, or, when none is, the lowest-scored of all, which the
// acceptance decision will then refuse. So a frame within RS's reach is
// found even when a reading a byte off scores as well, and a slip that
// leaves a codeword decoding into its rotation costs that frame only. One
// rotation could pass as exact: bytes lost inside BLOCK 1's leading padding
// make codeword 1 decode into BLOCK 1 shifted, its last item parity bytes;
// a codeword 1 that begins with padding and ends with two corrected 55s is
// therefore taken as beyond correction.
//
// Failures. When nothing in a neighbourhood confirms, one "uncorrectable"
// frame is reported where the next frame was due if that was a candidate,
// else at the lowest-distance candidate (and, once past the start due, the
// next frame is due 600 bytes after it); later failing candidates that
// start inside its codewords are dropped silently, and one there that
// confirms is still emitted, which is how the frame after lost bytes is
// found. The report waits until scanning is 90 bytes past it: if a good
// frame's preamble covers it, or the frame due fails there too, it was a
// false start and is dropped (the frame due is reported instead).
//
// On a clean continuous stream the frame due is checked first: a perfect
// window with two clean codewords cannot be beaten, so no search is made.
// Otherwise it is looked for at the start due and up to 16 bytes either
// side (slips of up to 8 in the frame before and in its own preamble),
// clean and exact, whatever its window shows (a slip may have taken its
// mark); and after a reading refused as not exact off the start due, also
// 600 bytes on from that reading, up to 32 bytes either side (16, plus the
// 16 a rotation RS corrected may be off by), so slips in frames in a row do
// not leave the next frame where nothing looks for it. What lies before the
// frame due is scanned first where a whole frame fits before it: the true
// frame a byte after a refused rotation comes before it.
//
// A mark lost far from any frame due (after frames cut short): where 16 or
// more bytes of fill end with no mark, codeword 1 starts there (keyed link)
// or, on the plain link, whose BLOCK 1 begins with padding, as many bytes
// before as BLOCK 1's padding in the last frames taken; clean and exact only.
//
// Plain C++20, no Qt. Not thread-safe; the handler and the acceptor must
// not call back into the synchroniser. Memory is fixed: an 8 KiB buffer
// allocated once.
#pragma once

#include "codec/frame/Frame.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

namespace rcm {

struct SyncedFrame {
    // Stream offset of the frame's first preamble byte, i.e. codeword 1's
    // offset - 90. Negative when the stream began inside this frame's
    // preamble (at least its last 16 bytes must have been received).
    std::int64_t offset = 0;
    // The frame as received: 600 bytes, or fewer when offset < 0 (then it
    // starts at stream offset 0). The last 510 bytes are always the two
    // codewords. Valid only during the callback.
    std::span<const std::uint8_t> raw;
    DecodedBlocks blocks;       // corrected: -1 where a codeword is beyond correction
    int preambleBitErrors = 0;  // bits the 16 bytes before codeword 1 differ from 55 x14, 0F, 0F
    bool ok() const { return blocks.ok(); }
};

class StreamSync {
public:
    using Handler = std::function<void(const SyncedFrame&)>;
    // True when blocks whose codewords both decoded pass the acceptance
    // decision's exactness rules (FrameReceiver's); no side effects.
    using Acceptor = std::function<bool(const DecodedBlocks&)>;

    static constexpr std::size_t kWindowSize = 16;
    static constexpr int kMaxWindowBitErrors = 6;
    // Where the next frame is due (600 bytes after the last one reported),
    // a window this far from the preamble still qualifies.
    static constexpr int kMaxDueWindowBitErrors = 16;
    static constexpr std::size_t kNeighbourhood = kPreambleSize;  // candidates q .. q+89
    // Upper bound of bufferedBytes() between feed() calls: the frame due
    // after a failed neighbourhood (up to a frame on) with the 32 bytes after
    // it that its search a few bytes either side needs, the frame before
    // it, and the codeword and preamble before the scan that a rotation back
    // may find a frame in.
    static constexpr std::size_t kMaxCarried = 2 * kFrameSize + kCodewordSize + kPreambleSize;

    struct Stats {
        std::uint64_t bytesIn = 0;
        std::uint64_t bytesSkipped = 0;  // in no emitted frame (good or uncorrectable)
        std::uint64_t framesDecoded = 0;        // both codewords decoded
        std::uint64_t framesUncorrectable = 0;  // emitted with at least one codeword beyond correction
        std::uint64_t correctedBytes1 = 0;      // bytes RS corrected in codeword 1, summed over frames
        std::uint64_t correctedBytes2 = 0;
    };

    explicit StreamSync(Handler onFrame, Acceptor exact = {});

    // Frames are reported in stream order, each as soon as the bytes that
    // decide it have arrived (up to 599 bytes after its codewords begin, 510
    // on a clean continuous stream).
    void feed(std::span<const std::uint8_t> bytes);
    // End of stream: decides what the bytes received allow (a last frame
    // whose 510 codeword bytes are all there is reported) and counts the rest
    // as skipped. A later feed() starts a new segment: offsets keep counting,
    // but no frame spans the break.
    void flush();
    // Forgets everything, statistics included; offsets restart at 0.
    void reset();

    const Stats& stats() const { return stats_; }
    // Received bytes a later decision may still need (<= kMaxCarried after
    // feed() returns). The buffer itself is a fixed 8 KiB.
    std::size_t bufferedBytes() const;

private:
    void process(bool final);
    enum class Scan { Candidate, Reached, Waiting, Taken };
    Scan scanFor(std::uint64_t& q, std::uint64_t stop, std::uint64_t end, bool final);
    bool fillBefore(std::uint64_t q) const;
    bool tryWithoutMark(std::uint64_t q, std::uint64_t end);
    bool takeIfWhole(std::uint64_t c);
    void rememberPadding(const DecodedBlocks& blocks);
    bool tryExpected(std::uint64_t c);
    bool trySlipped(std::uint64_t c, std::uint64_t end);
    struct Neighbourhood;
    bool decideNeighbourhood(std::uint64_t q, std::uint64_t last, std::uint64_t end);
    void gatherCandidates(Neighbourhood& hood, std::uint64_t q, std::uint64_t last, std::uint64_t end) const;
    void tryCandidates(Neighbourhood& hood) const;
    void searchRotations(Neighbourhood& hood, std::uint64_t end) const;
    void holdFailure(Neighbourhood& hood);
    void confirm(std::uint64_t c, int distance, const DecodedBlocks& blocks, bool exact);
    void emitFrame(std::uint64_t c, int distance, const DecodedBlocks& blocks);
    void expect(std::uint64_t c, std::uint64_t slip);
    void reportPending();
    void accountSkippedUpTo(std::uint64_t offset);
    void compact();
    std::uint64_t keepFrom() const;
    int distance(std::uint64_t c) const;
    bool qualifies(std::uint64_t c, int distance) const;
    const std::uint8_t* at(std::uint64_t offset) const { return buf_.data() + (offset - base_); }

    Handler handler_;
    Acceptor exact_;
    std::vector<std::uint8_t> buf_;
    std::uint64_t base_ = 0;     // stream offset of buf_[0]
    std::size_t len_ = 0;
    std::uint64_t scan_ = kWindowSize;  // next candidate not yet examined
    std::uint64_t expect_ = 0;   // where the next frame is likely to start (0: no guess)
    bool expectTried_ = false;   // ... and it was not there exactly
    std::uint64_t expectSlip_ = 16;  // ... and how many bytes either side it is looked for
    std::uint64_t due_ = 0;      // where the next frame is due after the last reported, good or not
    std::uint64_t failEnd_ = 0;  // failing candidates before this are dropped silently
    std::uint64_t covered_ = 0;  // bytes before this are in an emitted frame or counted as skipped
    bool emitted_ = false;       // a frame was reported since the last reset
    std::uint64_t lastEmitted_ = 0;  // its codeword 1's offset
    bool hasPending_ = false;    // a failed frame waiting to be reported
    std::uint64_t pendingC_ = 0;
    int pendingDistance_ = 0;
    DecodedBlocks pendingBlocks_;
    Stats stats_;
    std::array<std::uint8_t, kCodewordSize> lastClean2_{};  // codeword 2 of the last clean frame due
    // BLOCK 1's leading padding in the frames lately taken, newest first:
    // where a frame whose mark was lost starts, before the fill's end.
    std::array<std::uint8_t, 4> paddings_{};
    std::size_t paddingCount_ = 0;
};

}  // namespace rcm
