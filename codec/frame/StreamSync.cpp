#include "codec/frame/StreamSync.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cstring>
#include <utility>

namespace rcm {
namespace {

// Big enough that a large feed() is copied in few slices, small enough to
// stay in L1; what must be carried between calls is under 800 bytes.
constexpr std::size_t kBufferSize = 8192;
// What a codeword beyond correction adds to a reading's score: it has at
// least 17 byte errors, so at least 17 bit errors. Without it, a reading one
// byte off that scrapes through with 16 corrections would beat the true one
// whose same codeword fails by one byte.
constexpr int kFailedCodewordBits = rs::kMaxCorrectable + 1;
constexpr int kMaxPartialWindowBitErrors = 3;
constexpr int kMaxSlippedMarkBitErrors = 2;
// Bytes a frame due may be found early or late by (StreamSync::trySlipped):
// a slip of up to 8 bytes in the frame before (read where it was due, not
// exact or beyond correction) and one in this frame's preamble, which may
// have taken its mark, add up (soak_receive --attacks 10^6, byte slips:
// 8 lost in codeword 1, then 3 of the next preamble's last bytes, 11 early).
constexpr std::uint64_t kMaxSlip = 16;
// ... and the frame after a reading that decoded but was not exact, off the
// start due: that reading may itself be up to 16 bytes off the frame it was
// read from (a rotation RS corrected), so the lock is taken from it with that
// margin too. Otherwise slips in frames in a row (the first read at its
// place beyond correction, the second read a byte off into a rotation) leave
// the next 10 or more bytes from where anything expects it, and its own slip
// may have taken its mark: lost although libfec reads it there.
constexpr std::uint64_t kMaxSlipAfterInexact = kMaxSlip + static_cast<std::uint64_t>(rs::kMaxCorrectable);
constexpr int kMinSlippedFill = 6;
// A reading that decodes but is not exact may be a rotation of a real frame
// whose start no window shows (its mark lost to a slip, bytes inserted
// between the mark and codeword 1, an alias inside padding): RS codes are
// cyclic, so the real codewords are the decoded ones rotated back. Every
// start within a codeword's length either side is compared with them,
// without decoding; one is taken only when both codewords are there with
// no byte to correct and the frame is exact. A rotation of a real frame
// always needs a correction in each codeword (the bytes wrapped around are
// another codeword's or the next preamble's), so none can pass for it.
constexpr std::int64_t kRotationSearch = static_cast<std::int64_t>(kCodewordSize) - 1;

constexpr std::array<std::uint8_t, 16> kWindow = {0x55, 0x55, 0x55, 0x55, 0x55, 0x55, 0x55, 0x55,
                                                  0x55, 0x55, 0x55, 0x55, 0x55, 0x55, 0x0F, 0x0F};
static_assert(StreamSync::kWindowSize == kWindow.size());

std::uint64_t load64(const std::uint8_t* p)
{
    std::uint64_t v;
    std::memcpy(&v, p, sizeof v);
    return v;
}

// In native byte order, like load64's result: only bit counts matter.
const std::uint64_t kWindowLo = load64(kWindow.data());
const std::uint64_t kWindowHi = load64(kWindow.data() + 8);
constexpr std::uint64_t kFillWord = 0x5555555555555555ULL;

std::uint64_t preambleStart(std::uint64_t c)
{
    return c >= kPreambleSize ? c - kPreambleSize : 0;
}

int decodedCount(const DecodedBlocks& b)
{
    return (b.corrected.block1 >= 0 ? 1 : 0) + (b.corrected.block2 >= 0 ? 1 : 0);
}

int corrections(const DecodedBlocks& b)
{
    return std::max(b.corrected.block1, 0) + std::max(b.corrected.block2, 0);
}

struct Candidate {
    std::uint64_t c;
    int distance;
};

// One start's RS result. score: window bit errors plus the bits RS changed,
// i.e. how many bit errors this reading of the stream has to assume.
struct Trial {
    DecodedBlocks blocks;
    std::uint64_t c = 0;
    int distance = 0;
    int score = 0;
};

// Both codewords at one start, RS-decoded: each corrected, or as received
// with -1 when beyond correction.
struct Decoded {
    std::uint8_t cw[2][kCodewordSize];
    int corrected[2];
};

// Bytes lost inside BLOCK 1's leading padding (or inserted after it) can
// leave codeword 1, read a few bytes off, within 16 bytes of its own
// rotation by k: the padding lines up with itself. RS "corrects" it into
// that rotation, which wraps the padding's first k bytes round to the end,
// and BLOCK 1 comes out shifted by k, its last item k parity bytes: a
// command never sent, which can pass as exact. So a codeword 1 that needed
// a correction and decodes into one beginning with padding and ending with
// 55 55 is not trusted (k = 1 leaves a last item of one byte, which no item
// is). A genuine frame is refused so only when its last two parity bytes
// are 55, 1 in 65,536, and codeword 1 took errors.
bool rotatedPadding(const std::uint8_t* cw, int corrected)
{
    constexpr std::size_t last = kCodewordSize - 1;
    return corrected > 0 && cw[0] == kPreambleFillByte && cw[last] == kPreambleFillByte &&
           cw[last - 1] == kPreambleFillByte;
}

// RS codes are cyclic, so read j bytes from where `near` decoded, a codeword
// that RS would decode is, within 16 bytes, near's rotated by j: whenever
// that rotation is within 16 bytes of what is read there, it is what the
// decoder would return (decoding within 16 errors is unique), and the
// decoder, the costly part of trying the starts around a noisy frame, need
// not run.
void rsDecode(const std::uint8_t* codewords, const Decoded* near, std::int64_t j, Decoded& d)
{
    constexpr std::int64_t n = kCodewordSize;
    for (int b = 0; b < 2; ++b) {
        const std::uint8_t* received = codewords + b * kCodewordSize;
        std::uint8_t* cw = d.cw[b];
        if (near && near->corrected[b] >= 0 && j != 0 && j >= -rs::kMaxCorrectable && j <= rs::kMaxCorrectable) {
            const std::size_t from = static_cast<std::size_t>((j + n) % n);
            std::memcpy(cw, near->cw[b] + from, kCodewordSize - from);
            std::memcpy(cw + (kCodewordSize - from), near->cw[b], from);
            int changed = 0;
            for (std::size_t i = 0; i < kCodewordSize; ++i)
                changed += cw[i] != received[i];
            if (changed <= rs::kMaxCorrectable) {
                d.corrected[b] = changed;
                continue;
            }
        }
        std::memcpy(cw, received, kCodewordSize);
        d.corrected[b] = rs::decode(cw);
    }
    if (rotatedPadding(d.cw[0], d.corrected[0])) {
        std::memcpy(d.cw[0], codewords, kCodewordSize);
        d.corrected[0] = -1;
    }
}

// The codewords read j bytes from where `near` decoded both, when both are
// near's rotated by j within `maxChanged` bytes: what the decoder would
// return there, had without decoding. False otherwise.
bool rotated(const std::uint8_t* codewords, const Decoded& near, std::int64_t j, Decoded& d, int maxChanged)
{
    constexpr std::int64_t n = kCodewordSize;
    const std::size_t from = static_cast<std::size_t>((j % n + n) % n);
    // Compared in place first: most starts differ within a few bytes.
    for (int b = 0; b < 2; ++b) {
        if (near.corrected[b] < 0)
            return false;
        const std::uint8_t* received = codewords + b * kCodewordSize;
        const std::uint8_t* cw = near.cw[b];
        const std::size_t split = kCodewordSize - from;
        int changed = 0;
        for (std::size_t i = 0; i < split && changed <= maxChanged; ++i)
            changed += cw[from + i] != received[i];
        for (std::size_t i = split; i < kCodewordSize && changed <= maxChanged; ++i)
            changed += cw[i - split] != received[i];
        if (changed > maxChanged)
            return false;
        d.corrected[b] = changed;
    }
    for (int b = 0; b < 2; ++b) {
        std::memcpy(d.cw[b], near.cw[b] + from, kCodewordSize - from);
        std::memcpy(d.cw[b] + (kCodewordSize - from), near.cw[b], from);
    }
    return true;
}

// The trial's score: the bit errors this reading of the stream has to
// assume. Bits, not bytes: a reading one byte off "corrects" a whole byte
// per codeword (about 4 bits each) where a true reading at a low bit error
// rate corrects about 1 bit a byte, and the preamble window weighs its
// errors in bits too.
void score(const std::uint8_t* codewords, const Decoded& rs, Trial& t)
{
    t.score = 0;
    for (int b = 0; b < 2; ++b) {
        const std::uint8_t* received = codewords + b * kCodewordSize;
        if (rs.corrected[b] < 0)
            t.score += kFailedCodewordBits;
        if (rs.corrected[b] > 0) {
            for (std::size_t i = 0; i < kCodewordSize; ++i)
                t.score += std::popcount(static_cast<unsigned>(rs.cw[b][i] ^ received[i]));
        }
    }
    std::memcpy(t.blocks.block1.data(), rs.corrected[0] >= 0 ? rs.cw[0] : codewords, kBlockSize);
    std::memcpy(t.blocks.block2.data(), rs.corrected[1] >= 0 ? rs.cw[1] : codewords + kCodewordSize, kBlockSize);
    t.blocks.corrected.block1 = rs.corrected[0];
    t.blocks.corrected.block2 = rs.corrected[1];
}

// One codeword alone confirms a start only under a preamble window close to
// perfect, and not inside the codewords of a frame that failed. Padding in
// both blocks lines up with other padding and with the next preamble, so
// inside a failed frame there are windows (55 x14 then two bytes near 0F 0F,
// or 55 x14, 00, parity) from which one codeword reads as a rotation of real
// data and decodes; taking it would also skip the real next frame.
bool confirms(const Trial& t, bool insideFailed)
{
    const int n = decodedCount(t.blocks);
    return n == 2 || (n == 1 && !insideFailed && t.distance <= kMaxPartialWindowBitErrors);
}

// RS codes are cyclic, so a reading a few bytes off decodes too, into
// shifted garbage; what gives it away is the extra errors it must assume.
bool better(const Trial& a, const Trial& b)
{
    if (a.score != b.score)
        return a.score < b.score;
    return corrections(a.blocks) < corrections(b.blocks);
}

// The failure report of the closest candidate: a codeword that decoded
// without confirming the start is not trusted either.
DecodedBlocks uncorrectedBlocks(const std::uint8_t* codewords, const DecodedBlocks& decoded)
{
    DecodedBlocks blocks = decoded;
    if (blocks.corrected.block1 >= 0)
        std::memcpy(blocks.block1.data(), codewords, kBlockSize);
    if (blocks.corrected.block2 >= 0)
        std::memcpy(blocks.block2.data(), codewords + kCodewordSize, kBlockSize);
    blocks.corrected.block1 = blocks.corrected.block2 = -1;
    return blocks;
}

}  // namespace

StreamSync::StreamSync(Handler onFrame, Acceptor exact)
    : handler_(std::move(onFrame)), exact_(std::move(exact)), buf_(kBufferSize)
{
}

void StreamSync::reset()
{
    base_ = 0;
    len_ = 0;
    scan_ = kWindowSize;
    expect_ = 0;
    due_ = 0;
    failEnd_ = 0;
    covered_ = 0;
    hasPending_ = false;
    emitted_ = false;
    lastEmitted_ = 0;
    expectTried_ = false;
    lastClean2_.fill(0);
    paddingCount_ = 0;
    stats_ = Stats{};
}

void StreamSync::feed(std::span<const std::uint8_t> bytes)
{
    stats_.bytesIn += bytes.size();
    while (!bytes.empty()) {
        if (len_ == buf_.size())
            compact();
        const std::size_t n = std::min(bytes.size(), buf_.size() - len_);
        std::memcpy(buf_.data() + len_, bytes.data(), n);
        len_ += n;
        bytes = bytes.subspan(n);
        process(false);
    }
    accountSkippedUpTo(keepFrom());
}

void StreamSync::flush()
{
    process(true);
    if (hasPending_)
        reportPending();
    const std::uint64_t end = base_ + len_;
    accountSkippedUpTo(end);
    base_ = end;
    len_ = 0;
    scan_ = end + kWindowSize;
    expect_ = 0;
    expectTried_ = false;
    due_ = 0;
    failEnd_ = 0;
}

std::size_t StreamSync::bufferedBytes() const
{
    return static_cast<std::size_t>(base_ + len_ - keepFrom());
}

bool StreamSync::qualifies(std::uint64_t c, int distance) const
{
    if (distance <= kMaxWindowBitErrors)
        return true;
    // A preamble whose last bytes took a slip (bytes inserted into the fill)
    // or a burst: the mark itself within 2 bits of 0F 0F, and at least 6 of
    // the 14 fill bytes before it exactly 55. By chance in random bytes
    // about once in 10^13 places.
    const std::uint8_t* w = at(c - kWindowSize);
    if (std::popcount(static_cast<unsigned>(w[14] ^ kPreambleMark)) +
            std::popcount(static_cast<unsigned>(w[15] ^ kPreambleMark)) <=
        kMaxSlippedMarkBitErrors) {
        int fill = 0;
        for (std::size_t i = 0; i < kWindowSize - 2; ++i)
            fill += w[i] == kPreambleFillByte;
        if (fill >= kMinSlippedFill)
            return true;
    }
    if (c != due_ || distance > kMaxDueWindowBitErrors)
        return false;
    // Inside the preamble fill every window is 8 bits from the tail (its
    // 0F 0F read 55 55), and one byte early 4 bits: so the due start must
    // show the mark itself, its two bytes within 3 bits of 0F 0F (8 from 55 55).
    const std::uint8_t* mark = at(c - 2);
    return std::popcount(static_cast<unsigned>(mark[0] ^ kPreambleMark)) +
               std::popcount(static_cast<unsigned>(mark[1] ^ kPreambleMark)) <=
           3;
}

int StreamSync::distance(std::uint64_t c) const
{
    const std::uint8_t* w = at(c - kWindowSize);
    return std::popcount(load64(w) ^ kWindowLo) + std::popcount(load64(w + 8) ^ kWindowHi);
}

std::uint64_t StreamSync::keepFrom() const
{
    // Every later frame starts at or after a candidate not yet examined (or
    // up to kRotationSearch bytes before one), or is the failed frame still
    // waiting to be reported.
    std::uint64_t keep = preambleStart(scan_ > kRotationSearch ? scan_ - kRotationSearch : 0);
    if (hasPending_)
        keep = std::min(keep, preambleStart(pendingC_));
    return std::clamp(keep, base_, base_ + len_);
}

void StreamSync::compact()
{
    const std::uint64_t keep = keepFrom();
    const std::size_t drop = static_cast<std::size_t>(keep - base_);
    if (drop == 0)
        return;
    std::memmove(buf_.data(), buf_.data() + drop, len_ - drop);
    len_ -= drop;
    base_ = keep;
}

void StreamSync::accountSkippedUpTo(std::uint64_t offset)
{
    if (offset > covered_) {
        stats_.bytesSkipped += offset - covered_;
        covered_ = offset;
    }
}

void StreamSync::process(bool final)
{
    for (;;) {
        const std::uint64_t end = base_ + len_;
        // What lies before the frame due is scanned first where a whole frame
        // fits before it: a frame there (the true one a byte after a rotation
        // just refused) comes before it, and taking the frame due first would
        // skip it. Right after a frame taken, none fits, and on a clean
        // stream the frame due is taken without a scan.
        const std::uint64_t dueRegion = expect_ - std::min(expect_, expectSlip_);
        const std::uint64_t scanFirst = dueRegion - std::min(dueRegion, kDatagramSize - 1);
        if (expect_ != 0 && scan_ >= scanFirst) {
            if (expect_ + kDatagramSize > end) {
                if (!final)
                    return;
                expect_ = 0;
                expectTried_ = false;
            } else {
                if (!expectTried_) {
                    const std::uint64_t c = std::exchange(expect_, 0);
                    if (tryExpected(c))
                        continue;  // which expects the next one
                    expect_ = c;
                    expectTried_ = true;
                }
                // Not where it was due: a few bytes either side, once they are here.
                if (expect_ + expectSlip_ + kDatagramSize > end && !final)
                    return;
                const std::uint64_t c = std::exchange(expect_, 0);
                expectTried_ = false;
                if (trySlipped(c, end))
                    continue;
            }
        }

        std::uint64_t q = scan_;
        const std::uint64_t stop = expect_ != 0 ? std::min(end + 1, scanFirst) : end + 1;
        const Scan found = scanFor(q, stop, end, final);
        if (found == Scan::Taken)
            continue;
        scan_ = q;
        // Only a good frame whose preamble covers the failed start can show
        // that start was false; once scanning is past that, report it.
        if (hasPending_ && scan_ >= pendingC_ + kPreambleSize)
            reportPending();
        if (found == Scan::Waiting || q > end)
            return;
        if (expect_ != 0 && q >= scanFirst)
            continue;  // the frame due is looked for first

        const std::uint64_t last = q + kNeighbourhood - 1;
        if (last + kDatagramSize <= end)
            decideNeighbourhood(q, last, end);
        else if (!final || !decideNeighbourhood(q, std::min(last, end), end))
            return;
    }
}

StreamSync::Scan StreamSync::scanFor(std::uint64_t& q, std::uint64_t stop, std::uint64_t end, bool final)
{
    for (; q < stop; ++q) {
        if (qualifies(q, distance(q)))
            return Scan::Candidate;
        if (!fillBefore(q))
            continue;
        if (q == end)  // whether the fill ends here is not known yet
            return final ? Scan::Reached : Scan::Waiting;
        if (*at(q) == kPreambleFillByte)
            continue;
        if (q + kDatagramSize > end && !final)
            return Scan::Waiting;
        if (tryWithoutMark(q, end))
            return Scan::Taken;
    }
    return Scan::Reached;
}

bool StreamSync::fillBefore(std::uint64_t q) const
{
    const std::uint8_t* w = at(q - kWindowSize);
    return load64(w) == kFillWord && load64(w + 8) == kFillWord;
}

bool StreamSync::tryWithoutMark(std::uint64_t q, std::uint64_t end)
{
    // The fill ends at q, with no mark: a slip took it. On a keyed link
    // codeword 1 starts there; on the plain link BLOCK 1 begins with its
    // padding, so it starts that many bytes of 55 before, as many as in a
    // frame lately taken. Taken only where it cannot be a rotation, like a
    // slipped frame due (takeIfWhole).
    if (!exact_)
        return false;
    for (std::size_t i = 0; i <= paddingCount_; ++i) {
        const std::uint64_t padding = i == 0 ? 0 : paddings_[i - 1];
        if (padding > q)
            continue;
        const std::uint64_t c = q - padding;
        if (c < base_ + kPreambleSize || c + kDatagramSize > end || (emitted_ && c <= lastEmitted_) ||
            !fillBefore(c))
            continue;
        if (takeIfWhole(c))
            return true;
    }
    return false;
}

bool StreamSync::takeIfWhole(std::uint64_t c)
{
    // A start whatever its window shows, taken only where it cannot be a
    // rotation of a real frame, which needs a correction in each codeword
    // (the bytes wrapped around are another codeword's or a preamble's): one
    // codeword clean, the other within RS's reach (and not a padding
    // rotation), and the frame exact.
    const std::uint8_t* received = at(c);
    bool clean[2] = {false, false};
    rs::checkCodewords(received, received + kCodewordSize, &clean[0], &clean[1]);
    if (!clean[0] && !clean[1])
        return false;
    Decoded d;
    for (int b = 0; b < 2; ++b) {
        std::memcpy(d.cw[b], received + b * kCodewordSize, kCodewordSize);
        d.corrected[b] = clean[b] ? 0 : rs::decode(d.cw[b]);
        if (d.corrected[b] < 0)
            return false;
    }
    if (rotatedPadding(d.cw[0], d.corrected[0]))
        return false;
    DecodedBlocks blocks;
    std::memcpy(blocks.block1.data(), d.cw[0], kBlockSize);
    std::memcpy(blocks.block2.data(), d.cw[1], kBlockSize);
    blocks.corrected.block1 = d.corrected[0];
    blocks.corrected.block2 = d.corrected[1];
    if (!exact_(blocks))
        return false;
    confirm(c, distance(c), blocks, true);
    return true;
}

bool StreamSync::tryExpected(std::uint64_t c)
{
    // A perfect window with two clean codewords cannot be beaten by any
    // other start in its neighbourhood, so the full scan would pick it too.
    if (distance(c) != 0)
        return false;
    const std::uint8_t* cw = at(c);
    // Codeword 2 is often the last frame's again (no flight plan section):
    // then it is known clean without computing its parity.
    const bool repeated = std::memcmp(cw + kCodewordSize, lastClean2_.data(), kCodewordSize) == 0;
    bool clean1 = false, clean2 = repeated;
    if (repeated)
        clean1 = rs::isCodeword(cw);
    else
        rs::checkCodewords(cw, cw + kCodewordSize, &clean1, &clean2);
    if (!clean1 || !clean2)
        return false;
    if (!repeated)
        std::memcpy(lastClean2_.data(), cw + kCodewordSize, kCodewordSize);
    DecodedBlocks blocks;
    std::memcpy(blocks.block1.data(), cw, kBlockSize);
    std::memcpy(blocks.block2.data(), cw + kCodewordSize, kBlockSize);
    // A constant or foreign frame where one was due may hide the real one a
    // few bytes on: only an exact frame ends the search.
    if (exact_ && !exact_(blocks))
        return false;
    confirm(c, 0, blocks, true);
    return true;
}

bool StreamSync::trySlipped(std::uint64_t c, std::uint64_t end)
{
    // The frame due, a few bytes early or late (bytes lost or inserted in it
    // or the frame before), whatever its window shows: its mark may be what
    // was lost. Taken only where it cannot be a rotation (takeIfWhole).
    if (!exact_)
        return false;
    // j = 0: the start due itself, when tryExpected passed it over for its
    // window (a slip took this frame's mark, and one in the frame before put
    // its codewords back where they were due).
    for (std::uint64_t j = 0; j <= expectSlip_; ++j) {
        const std::array<std::uint64_t, 2> starts = {c - j, c + j};
        for (std::size_t k = 0; k < (j == 0 ? 1U : 2U); ++k) {
            const std::uint64_t at = starts[k];
            if (at < base_ + kPreambleSize || at + kDatagramSize > end || (emitted_ && at <= lastEmitted_))
                continue;
            if (j == 0 && distance(at) == 0)
                continue;  // tryExpected's
            if (takeIfWhole(at))
                return true;
        }
    }
    return false;
}

// The qualifying starts of one neighbourhood, closest window first, and the
// readings tried there.
struct StreamSync::Neighbourhood {
    std::array<Candidate, kNeighbourhood> cands;
    std::size_t n = 0;
    // At the end of the stream, candidates whose codewords are cut off
    // cannot be tried; none near one of them (a rotation RS would correct:
    // up to 16 bytes off) whose window is no closer may be accepted instead
    // (one byte early, a cut-off frame still "decodes"). Further off, a
    // cut-off window is no reason to refuse a whole frame: it may lie inside
    // that frame's own BLOCK 1 (padding, then 0F 0F).
    std::array<Candidate, kNeighbourhood> cutOff;
    std::size_t nCutOff = 0;
    bool barred(std::uint64_t c, int distance) const
    {
        for (std::size_t i = 0; i < nCutOff; ++i) {
            const std::uint64_t apart = cutOff[i].c > c ? cutOff[i].c - c : c - cutOff[i].c;
            if (cutOff[i].distance <= distance && apart <= static_cast<std::uint64_t>(rs::kMaxCorrectable))
                return true;
        }
        return false;
    }
    // The reading taken is the best the acceptance decision finds exact, or,
    // when none is, the best of all (which it will then refuse); without an
    // acceptor every reading counts as exact.
    Trial trials[3];
    Decoded decoded[2];  // [0]: the closest window's, to predict the others near it
    Decoded bestDecoded;
    int best = -1;
    int exact = -1;
    DecodedBlocks firstBlocks;  // the failure report, should nothing confirm
};

bool StreamSync::decideNeighbourhood(std::uint64_t q, std::uint64_t last, std::uint64_t end)
{
    Neighbourhood hood;
    gatherCandidates(hood, q, last, end);
    if (std::all_of(hood.cands.begin(), hood.cands.begin() + hood.n,
                    [&](const Candidate& k) { return hood.barred(k.c, k.distance); }))
        return false;
    tryCandidates(hood);
    if (hood.best >= 0 && hood.exact < 0 && exact_ && hood.trials[hood.best].blocks.ok())
        searchRotations(hood, end);
    if (hood.best >= 0) {
        const Trial& taken = hood.trials[hood.exact >= 0 ? hood.exact : hood.best];
        if (hood.barred(taken.c, taken.distance))
            return false;
        // A reading that is not exact, inside a frame already found not to
        // be, is no news: it is dropped like a failure there.
        if (hood.exact >= 0 || taken.c >= failEnd_) {
            confirm(taken.c, taken.distance, taken.blocks, hood.exact >= 0);
            return true;
        }
    }
    holdFailure(hood);
    scan_ = q + kNeighbourhood;
    return true;
}

void StreamSync::gatherCandidates(Neighbourhood& hood, std::uint64_t q, std::uint64_t last, std::uint64_t end) const
{
    for (std::uint64_t c = q; c <= last; ++c) {
        const int d = distance(c);
        if (!qualifies(c, d))
            continue;
        if (c + kDatagramSize > end) {
            hood.cutOff[hood.nCutOff++] = {c, d};
            continue;
        }
        // Insertion keeps equal distances in stream order.
        std::size_t i = hood.n++;
        while (i > 0 && hood.cands[i - 1].distance > d) {
            hood.cands[i] = hood.cands[i - 1];
            --i;
        }
        hood.cands[i] = {c, d};
    }
}

void StreamSync::tryCandidates(Neighbourhood& hood) const
{
    Trial* trials = hood.trials;
    for (std::size_t i = 0; i < hood.n; ++i) {
        const Candidate& candidate = hood.cands[i];
        // score >= distance: once the distance alone exceeds the score of the
        // reading to be taken, no later candidate can win, nor tie with fewer
        // corrections.
        if (hood.exact >= 0) {
            const Trial& b = trials[hood.exact];
            if (candidate.distance > b.score || (candidate.distance == b.score && corrections(b.blocks) == 0))
                break;
        }
        int slot = 0;
        while (slot == hood.best || slot == hood.exact)
            ++slot;
        Trial& t = trials[slot];
        Decoded& d = hood.decoded[i == 0 ? 0 : 1];
        rsDecode(at(candidate.c), i == 0 ? nullptr : &hood.decoded[0],
                 static_cast<std::int64_t>(candidate.c - hood.cands[0].c), d);
        score(at(candidate.c), d, t);
        t.c = candidate.c;
        t.distance = candidate.distance;
        t.score += t.distance;
        if (i == 0)
            hood.firstBlocks = uncorrectedBlocks(at(t.c), t.blocks);
        if (!confirms(t, t.c < failEnd_))
            continue;
        if (hood.best < 0 || better(t, trials[hood.best])) {
            hood.best = slot;
            hood.bestDecoded = d;
        }
        if ((hood.exact < 0 || better(t, trials[hood.exact])) && (!exact_ || exact_(t.blocks)))
            hood.exact = slot;
    }
}

// The best reading decodes into what is not a frame: perhaps a rotation of
// the real one.
void StreamSync::searchRotations(Neighbourhood& hood, std::uint64_t end) const
{
    const std::uint64_t from = hood.trials[hood.best].c;
    const int spare = hood.best == 0 ? 1 : 0;
    for (std::int64_t j = 1; j <= kRotationSearch; ++j) {
        for (const std::int64_t signedJ : {-j, j}) {
            if (signedJ < 0 && static_cast<std::uint64_t>(-signedJ) > from)
                continue;
            const std::uint64_t c = from + static_cast<std::uint64_t>(signedJ);
            if (c < base_ + kPreambleSize || c + kDatagramSize > end || (emitted_ && c <= lastEmitted_))
                continue;
            Decoded d;
            if (!rotated(at(c), hood.bestDecoded, signedJ, d, 0))
                continue;
            Trial& t = hood.trials[spare];
            score(at(c), d, t);
            t.c = c;
            t.distance = distance(c);
            t.score += t.distance;
            if (exact_(t.blocks)) {
                hood.exact = spare;
                return;
            }
        }
    }
}

// Nothing confirmed: the failure is held, to be reported where the next
// frame was due if that was a candidate (at a high bit error rate the true
// window may be further from the preamble than one a byte early is).
void StreamSync::holdFailure(Neighbourhood& hood)
{
    std::uint64_t p = hood.cands[0].c;
    for (std::size_t i = 0; i < hood.n; ++i)
        if (hood.cands[i].c == due_)
            p = due_;
    const int pDistance = distance(p);
    if (p != hood.cands[0].c) {
        const std::uint8_t* cw = at(p);
        std::memcpy(hood.firstBlocks.block1.data(), cw, kBlockSize);
        std::memcpy(hood.firstBlocks.block2.data(), cw + kCodewordSize, kBlockSize);
    }
    if (p < failEnd_) {
        // Inside a failure still held. When that one started in this frame's
        // preamble (a window there that two or three bit errors brought
        // within 6 bits, tried in a neighbourhood the start due lay beyond)
        // and this is the start due, that was the false start: the lock
        // keeps the frame due, and the frames after it are looked for from
        // there, not from a start 40 bytes early that every later failure
        // would be measured from.
        if (p != due_ || !hasPending_ || pendingC_ >= p || pendingC_ + kPreambleSize <= p)
            return;
        hasPending_ = false;
    }
    if (hasPending_)
        reportPending();
    hasPending_ = true;
    pendingC_ = p;
    pendingDistance_ = pDistance;
    pendingBlocks_ = hood.firstBlocks;
    failEnd_ = p + kDatagramSize;
    if (p == due_) {
        due_ = p + kFrameSize;  // lock kept through a frame beyond correction
        expect(due_, kMaxSlip);
    } else if (due_ < p) {
        // Past the start due with no frame found there (its window lost to
        // errors): the next frame is due after this failure, so a lock lost
        // is regained where frames are read only with predictions.
        due_ = p + kFrameSize;
    }
}

void StreamSync::confirm(std::uint64_t c, int distance, const DecodedBlocks& blocks, bool exact)
{
    if (hasPending_) {
        if (c >= pendingC_ + kPreambleSize)
            reportPending();
        else
            hasPending_ = false;  // a false start inside this frame's preamble
    }
    emitFrame(c, distance, blocks);
    if (!exact) {
        // Refused (a frame cut short, one read a few bytes off, a fake): a
        // real frame may start anywhere after it, so scanning goes on from
        // the next byte; inside it only an exact reading is taken. The lock
        // is kept only where this frame was due.
        if (c == due_) {
            due_ = c + kFrameSize;
            expect(due_, kMaxSlip);  // looked for there, and a few bytes either side
        } else {
            // Off the start due: the lock stays where it was, but the next
            // frame is also looked for 600 bytes after this reading, with
            // the margin of a reading that may be a rotation.
            expect(c + kFrameSize, kMaxSlipAfterInexact);
        }
        scan_ = c + 1;
        failEnd_ = std::max(failEnd_, c + kDatagramSize);
        return;
    }
    rememberPadding(blocks);
    due_ = c + kFrameSize;
    if (blocks.corrected.block2 >= 0 || blocks.corrected.block1 < 0) {
        scan_ = c + kDatagramSize;
        expect(c + kFrameSize, kMaxSlip);
    } else {
        // Codeword 2 may have failed because bytes were lost inside it, so
        // the next frame may begin there.
        scan_ = c + kCodewordSize;
        failEnd_ = std::max(failEnd_, c + kDatagramSize);
    }
}

void StreamSync::rememberPadding(const DecodedBlocks& blocks)
{
    if (blocks.corrected.block1 < 0)
        return;
    const auto padding = static_cast<std::uint8_t>(
        std::find_if(blocks.block1.begin(), blocks.block1.end(), [](std::uint8_t b) { return b != kPreambleFillByte; }) -
        blocks.block1.begin());
    if (padding == 0 || std::find(paddings_.begin(), paddings_.begin() + paddingCount_, padding) !=
                            paddings_.begin() + paddingCount_)
        return;
    // The newest first; the oldest forgotten.
    std::move_backward(paddings_.begin(), paddings_.end() - 1, paddings_.end());
    paddings_[0] = padding;
    paddingCount_ = std::min(paddingCount_ + 1, paddings_.size());
}

void StreamSync::expect(std::uint64_t c, std::uint64_t slip)
{
    expect_ = c;
    expectTried_ = false;
    expectSlip_ = slip;
}

void StreamSync::reportPending()
{
    hasPending_ = false;
    emitFrame(pendingC_, pendingDistance_, pendingBlocks_);
}

void StreamSync::emitFrame(std::uint64_t c, int distance, const DecodedBlocks& blocks)
{
    emitted_ = true;
    lastEmitted_ = c;
    const std::uint64_t start = preambleStart(c);
    const std::uint64_t end = c + kDatagramSize;
    accountSkippedUpTo(start);
    covered_ = std::max(covered_, end);

    if (blocks.ok())
        ++stats_.framesDecoded;
    else
        ++stats_.framesUncorrectable;
    stats_.correctedBytes1 += static_cast<std::uint64_t>(std::max(blocks.corrected.block1, 0));
    stats_.correctedBytes2 += static_cast<std::uint64_t>(std::max(blocks.corrected.block2, 0));

    if (!handler_)
        return;
    SyncedFrame frame;
    frame.offset = static_cast<std::int64_t>(c) - static_cast<std::int64_t>(kPreambleSize);
    frame.raw = std::span<const std::uint8_t>(at(start), static_cast<std::size_t>(end - start));
    frame.blocks = blocks;
    frame.preambleBitErrors = distance;
    handler_(frame);
}

}  // namespace rcm
