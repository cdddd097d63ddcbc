#include "codec/frame/StreamSync.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cstring>
#include <limits>
#include <utility>

namespace rcm {
namespace {

// Big enough that a large feed() is copied in few slices, small enough to
// stay in L1; what must be carried between calls is under 800 bytes.
constexpr std::size_t kBufferSize = 8192;
constexpr std::size_t kSlipCheck = rs::kMaxCorrectable;
// What a codeword beyond correction adds to a reading's score: it has at
// least 17 byte errors, so at least 17 bit errors. Without it, a reading one
// byte off that scrapes through with 16 corrections would beat the true one
// whose same codeword fails by one byte.
constexpr int kFailedCodewordBits = rs::kMaxCorrectable + 1;
constexpr int kMaxPartialWindowBitErrors = 3;

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

std::uint64_t preambleStart(std::uint64_t c)
{
    return c >= kPreambleSize ? c - kPreambleSize : 0;
}

int decodedCount(const DecodedBlocks& b)
{
    return (b.corrected1 >= 0 ? 1 : 0) + (b.corrected2 >= 0 ? 1 : 0);
}

int corrections(const DecodedBlocks& b)
{
    return std::max(b.corrected1, 0) + std::max(b.corrected2, 0);
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
}

// A byte slip displaces a codeword, and read at its nominal place it is
// then a cyclic shift of itself with k bytes changed: for k <= 16 it
// "decodes", into shifted garbage. Slips inside codeword 1 displace codeword
// 2; slips in its first 16 bytes displace codeword 1 as well (which still
// "decodes": the preamble window cannot see such a slip).
//
// Evidence that decoded codeword D sits k bytes from where it was read: laid
// at the displaced place, D rotated back differs from the stream only in the
// |k| bytes at one end, where the bytes read were foreign and the bytes just
// beyond the other end are D's. So for each k: were all |k| end bytes
// corrected, and by how many bits do they differ from D more than the bytes
// beyond do. A slip makes whole foreign bytes (about 4 bits each); bit errors
// in a true reading rarely correct every end byte, and then by a bit or so,
// and the bytes beyond rarely match D (when the data repeats, as 55 padding
// next to a preamble does, they may: hence a margin of k + 1 bits, or k when
// a slip is already likely).
class Shifts {
public:
    // `received` has 16 readable bytes before it and `after` after its 255.
    // A shift of k needs k + slack bits of evidence.
    Shifts(const std::uint8_t* received, const std::uint8_t* decoded, std::size_t after, int slack)
    {
        constexpr std::size_t kLast = kCodewordSize - 1;
        int early = 0;
        int late = 0;
        bool earlyAll = true;
        bool lateAll = true;
        for (std::size_t i = 0; i < kMax; ++i) {
            const int inside = std::popcount(static_cast<unsigned>(received[i] ^ decoded[i]));
            const int beyond = i < after ? std::popcount(static_cast<unsigned>(received[kCodewordSize + i] ^ decoded[i])) : 8;
            early += inside - beyond;
            earlyAll = earlyAll && inside > 0;
            early_[i] = earlyAll && early >= static_cast<int>(i) + 1 + slack ? early : 0;

            const std::uint8_t d = decoded[kLast - i];
            const int insideL = std::popcount(static_cast<unsigned>(received[kLast - i] ^ d));
            const int beyondL = std::popcount(static_cast<unsigned>(*(received - 1 - i) ^ d));
            late += insideL - beyondL;
            lateAll = lateAll && insideL > 0;
            late_[i] = lateAll && late >= static_cast<int>(i) + 1 + slack ? late : 0;
        }
    }
    // The most likely displacement: +k really begins k bytes later (bytes
    // inserted before it), -k really begins k bytes earlier (bytes lost), 0 none.
    int best() const
    {
        int k = 0;
        int most = 0;
        for (std::size_t i = 0; i < kMax; ++i) {
            if (early_[i] > most) {
                most = early_[i];
                k = static_cast<int>(i) + 1;
            }
            if (late_[i] > most) {
                most = late_[i];
                k = -static_cast<int>(i) - 1;
            }
        }
        return k;
    }

private:
    static constexpr std::size_t kMax = rs::kMaxCorrectable;
    int early_[kMax];
    int late_[kMax];
};

// After a slip of `shift` bytes inside codeword 1 (as codeword 2 showed),
// is its decoding D the codeword sent? A slip past D's first 16 bytes leaves
// D right, the bytes after the slip read shifted (received[i] ==
// D[i - shift]); a slip among the first 16 makes D a rotation of the codeword
// sent, the bytes before the slip read where that codeword has them
// (received[i] == D[i + shift]). Only the corrected bytes tell, and when they
// tell neither (a slip right at either end), D may be either.
bool slipLeavesCodeword(const std::uint8_t* received, const std::uint8_t* decoded, int shift)
{
    constexpr int n = static_cast<int>(kCodewordSize);
    int after = 0;
    int before = 0;
    for (int i = 0; i < n; ++i) {
        if (received[i] == decoded[i])
            continue;
        after += received[i] == decoded[((i - shift) % n + n) % n];
        before += received[i] == decoded[((i + shift) % n + n) % n];
    }
    return after > before;
}

// Is D the codeword sent, rotated by a slip of k bytes after its first o
// bytes? Such a slip leaves those o bytes where the codeword sent has them,
// which in D's terms is `shift` places on (received[i] == D[i + shift]), and
// k foreign bytes: D's last k for bytes lost, the k after the first o for
// bytes inserted. RS decodes when the o bytes hold few changes, as when the
// slip was early, or inside repeated data such as padding: then only the
// bytes where a run of 00 meets the 55s move. Over the first o bytes, each
// change that the shift explains counts for the slip and each byte it
// breaks against it; bit errors count against both. The changed bytes are
// whole foreign bytes, about 4 bits from D each, where the bit errors of a
// true reading differ by about 1; hence the margin of 2 bits a byte.
bool headSlip(const std::uint8_t* received, const std::uint8_t* decoded, bool lostOnly)
{
    constexpr int n = static_cast<int>(kCodewordSize);
    constexpr int kMax = rs::kMaxCorrectable;
    int changes[kMax];
    int count = 0;
    for (int i = 0; i < n && count < kMax; ++i) {
        if (received[i] != decoded[i])
            changes[count++] = i;
    }
    for (int shift = -kMax; shift <= (lostOnly ? -1 : kMax); ++shift) {
        if (shift == 0)
            continue;
        auto shifted = [&](int i) { return decoded[(i + shift + n) % n]; };
        bool any = false;  // the slip must explain some change
        for (int c = 0; c < count && !any; ++c)
            any = received[changes[c]] == shifted(changes[c]);
        if (!any)
            continue;
        const int k = shift < 0 ? -shift : shift;
        int evidence = 0;
        int best = 0;
        int o = 0;
        for (int i = 0; i < n - k; ++i) {
            evidence += (received[i] != decoded[i]) - (received[i] != shifted(i));
            if (evidence > best) {
                best = evidence;
                o = i + 1;
            }
        }
        if (best == 0)
            continue;
        const int foreign = shift < 0 ? n - k : o;
        if (foreign + k > n)
            continue;
        int bits = 0;
        for (int i = 0; i < o; ++i) {
            if (received[i] != decoded[i] && received[i] == shifted(i))
                bits += std::popcount(static_cast<unsigned>(received[i] ^ decoded[i]));
        }
        bool all = true;
        for (int i = foreign; i < foreign + k && all; ++i) {
            all = received[i] != decoded[i];
            bits += std::popcount(static_cast<unsigned>(received[i] ^ decoded[i]));
        }
        if (all && bits >= 2 * (best + k))
            return true;
    }
    return false;
}

// headSlip, and its mirror image: D rotated, with the slip among its last
// bytes (seen when the reading itself starts a byte or so early). Only the
// mirror of a loss: the mirror of an insertion, the bytes before the slip
// read k places early, is also what a slip near the end of a codeword read
// in the right place leaves, and RS then rightly corrects it.
bool slipNearEnd(const std::uint8_t* received, const std::uint8_t* decoded)
{
    if (headSlip(received, decoded, false))
        return true;
    if (received[kCodewordSize - 1] == decoded[kCodewordSize - 1])
        return false;
    std::uint8_t r[kCodewordSize];
    std::uint8_t d[kCodewordSize];
    std::reverse_copy(received, received + kCodewordSize, r);
    std::reverse_copy(decoded, decoded + kCodewordSize, d);
    return headSlip(r, d, true);
}

// Did RS "correct" preamble or padding fill into data? The padding both
// blocks carry lines up with the next frame's preamble and with each other,
// so a reading that runs k bytes past a block's end into 55s can be a
// rotation of that block with only the bytes opposite the fill changed, and
// decode. Bit errors in a true reading almost never leave a byte that RS
// changes reading exactly 55 (padding, hit, no longer reads 55).
bool filledFromPadding(const std::uint8_t* received, const std::uint8_t* decoded)
{
    // Bytes lost in a run at the head of a block (the zeros of a BLOCK 2
    // without update, say) shift the next preamble's first 55s into the
    // codeword's end and nothing else: RS then changes only those. A bit
    // error rarely turns a byte into exactly 55, and by one bit, not two.
    int run = 0;
    for (int i = static_cast<int>(kCodewordSize) - 1; i >= 0 && received[i] != decoded[i]; --i) {
        if (received[i] != kPreambleFillByte || std::popcount(static_cast<unsigned>(received[i] ^ decoded[i])) < 2) {
            run = 0;
            break;
        }
        ++run;
    }
    if (run > 0)
        return true;

    int changed = 0;
    int fill = 0;
    for (std::size_t i = 0; i < kCodewordSize; ++i) {
        if (received[i] != decoded[i]) {
            ++changed;
            fill += received[i] == kPreambleFillByte;
        }
    }
    return fill >= 3 && 2 * fill >= changed;
}

// Like decodeCodewords, but also counts the bits corrected and refuses
// codewords a byte slip has displaced: a codeword whose ends show it sits
// elsewhere, or whose corrections show it rotated by a slip near one end.
// A slip inside codeword 1 displaces codeword 2 and leaves codeword 1 beyond
// correction or corrected: when codeword 2 is displaced, codeword 1 goes too
// unless its corrections show the slip left it whole.
// Bits, not bytes: a reading one byte off "corrects" a whole byte per
// codeword (about 4 bits each) where a true reading at a low bit error rate
// corrects about 1 bit a byte, and the preamble window weighs its errors in
// bits too.
void decodeAt(const std::uint8_t* codewords, std::size_t after, const Decoded& rs, Trial& t)
{
    const std::uint8_t* received[2] = {codewords, codewords + kCodewordSize};
    std::uint8_t cw[2][kCodewordSize];
    int corrected[2];
    std::memcpy(cw, rs.cw, sizeof cw);
    std::memcpy(corrected, rs.corrected, sizeof corrected);
    int shift[2] = {0, 0};
    bool moved[2] = {false, false};
    for (int b = 0; b < 2; ++b) {
        if (corrected[b] <= 0)
            continue;
        // Codeword 2 after a codeword 1 beyond correction: a slip is likely.
        const int slack = b == 1 && corrected[0] < 0 ? 0 : 1;
        shift[b] = Shifts(received[b], cw[b], b == 0 ? kCodewordSize + after : after, slack).best();
        moved[b] = shift[b] != 0 || slipNearEnd(received[b], cw[b]) || filledFromPadding(received[b], cw[b]);
    }
    if (shift[1] != 0 && corrected[0] > 0 && !slipLeavesCodeword(received[0], cw[0], shift[1]))
        moved[0] = true;
    for (int b = 0; b < 2; ++b) {
        if (moved[b]) {
            corrected[b] = -1;
            std::memcpy(cw[b], received[b], kCodewordSize);
        }
    }
    t.score = 0;
    for (int b = 0; b < 2; ++b) {
        if (corrected[b] < 0)
            t.score += kFailedCodewordBits;
        if (corrected[b] > 0) {
            for (std::size_t i = 0; i < kCodewordSize; ++i)
                t.score += std::popcount(static_cast<unsigned>(cw[b][i] ^ received[b][i]));
        }
    }
    std::memcpy(t.blocks.block1.data(), cw[0], kBlockSize);
    std::memcpy(t.blocks.block2.data(), cw[1], kBlockSize);
    t.blocks.corrected1 = corrected[0];
    t.blocks.corrected2 = corrected[1];
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

}  // namespace

StreamSync::StreamSync(Handler onFrame) : handler_(std::move(onFrame)), buf_(kBufferSize) {}

void StreamSync::reset()
{
    base_ = 0;
    len_ = 0;
    scan_ = kWindowSize;
    expect_ = 0;
    failEnd_ = 0;
    covered_ = 0;
    hasPending_ = false;
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
    failEnd_ = 0;
}

std::size_t StreamSync::bufferedBytes() const
{
    return static_cast<std::size_t>(base_ + len_ - keepFrom());
}

int StreamSync::distance(std::uint64_t c) const
{
    const std::uint8_t* w = at(c - kWindowSize);
    return std::popcount(load64(w) ^ kWindowLo) + std::popcount(load64(w + 8) ^ kWindowHi);
}

std::uint64_t StreamSync::keepFrom() const
{
    // Every later frame starts at or after a candidate not yet examined, or
    // is the failed frame still waiting to be reported.
    std::uint64_t keep = preambleStart(scan_);
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
        if (expect_ != 0) {
            if (expect_ + kDatagramSize > end) {
                if (!final)
                    return;
                expect_ = 0;
            } else {
                const std::uint64_t c = std::exchange(expect_, 0);
                if (tryExpected(c))
                    continue;
            }
        }

        std::uint64_t q = scan_;
        while (q <= end && distance(q) > kMaxWindowBitErrors)
            ++q;
        scan_ = q;
        // Only a good frame whose preamble covers the failed start can show
        // that start was false; once scanning is past that, report it.
        if (hasPending_ && scan_ >= pendingC_ + kPreambleSize)
            reportPending();
        if (q > end)
            return;

        // kSlipCheck: room to look past codeword 2 for a displaced one.
        const std::uint64_t last = q + kNeighbourhood - 1;
        if (last + kDatagramSize + kSlipCheck <= end)
            decideNeighbourhood(q, last, end);
        else if (!final || !decideNeighbourhood(q, std::min(last, end), end))
            return;
    }
}

bool StreamSync::tryExpected(std::uint64_t c)
{
    // A perfect window with two clean codewords cannot be beaten by any
    // other start in its neighbourhood, so the full scan would pick it too.
    if (distance(c) != 0)
        return false;
    const std::uint8_t* cw = at(c);
    bool clean1 = false, clean2 = false;
    rs::checkCodewords(cw, cw + kCodewordSize, &clean1, &clean2);
    if (!clean1 || !clean2)
        return false;
    DecodedBlocks blocks;
    std::memcpy(blocks.block1.data(), cw, kBlockSize);
    std::memcpy(blocks.block2.data(), cw + kCodewordSize, kBlockSize);
    confirm(c, 0, blocks);
    return true;
}

bool StreamSync::decideNeighbourhood(std::uint64_t q, std::uint64_t last, std::uint64_t end)
{
    std::array<Candidate, kNeighbourhood> cands;
    std::size_t n = 0;
    // At the end of the stream, candidates whose codewords are cut off
    // cannot be tried; none whose window is no closer than theirs may be
    // accepted instead (one byte early, a cut-off frame still "decodes").
    int bar = std::numeric_limits<int>::max();
    for (std::uint64_t c = q; c <= last; ++c) {
        const int d = distance(c);
        if (d > kMaxWindowBitErrors)
            continue;
        if (c + kDatagramSize > end) {
            bar = std::min(bar, d);
            continue;
        }
        // Insertion keeps equal distances in stream order.
        std::size_t i = n++;
        while (i > 0 && cands[i - 1].distance > d) {
            cands[i] = cands[i - 1];
            --i;
        }
        cands[i] = {c, d};
    }
    if (n == 0 || cands[0].distance >= bar)
        return false;

    Trial trials[2];
    Decoded decoded[2];  // [0]: the closest window's, to predict the others near it
    int best = -1;
    DecodedBlocks firstBlocks;
    for (std::size_t i = 0; i < n; ++i) {
        // score >= distance: once the distance alone exceeds the best score,
        // no later candidate can win, nor tie with fewer corrections.
        if (best >= 0) {
            const Trial& b = trials[best];
            if (cands[i].distance > b.score || (cands[i].distance == b.score && corrections(b.blocks) == 0))
                break;
        }
        const int slot = best == 0 ? 1 : 0;
        Trial& t = trials[slot];
        const std::uint64_t after = end - (cands[i].c + kDatagramSize);
        Decoded& d = decoded[i == 0 ? 0 : 1];
        rsDecode(at(cands[i].c), i == 0 ? nullptr : &decoded[0],
                 static_cast<std::int64_t>(cands[i].c - cands[0].c), d);
        decodeAt(at(cands[i].c), static_cast<std::size_t>(std::min<std::uint64_t>(after, kSlipCheck)), d, t);
        t.c = cands[i].c;
        t.distance = cands[i].distance;
        t.score += t.distance;
        if (i == 0) {
            // The failure report, should nothing confirm, is this
            // candidate's; a codeword that decoded without confirming the
            // start is not trusted either.
            firstBlocks = t.blocks;
            const std::uint8_t* cw = at(t.c);
            if (firstBlocks.corrected1 >= 0)
                std::memcpy(firstBlocks.block1.data(), cw, kBlockSize);
            if (firstBlocks.corrected2 >= 0)
                std::memcpy(firstBlocks.block2.data(), cw + kCodewordSize, kBlockSize);
            firstBlocks.corrected1 = firstBlocks.corrected2 = -1;
        }
        if (confirms(t, t.c < failEnd_) && (best < 0 || better(t, trials[best])))
            best = slot;
    }
    if (best >= 0) {
        if (trials[best].distance >= bar)
            return false;
        confirm(trials[best].c, trials[best].distance, trials[best].blocks);
        return true;
    }

    const std::uint64_t p = cands[0].c;
    if (p >= failEnd_) {
        if (hasPending_)
            reportPending();
        hasPending_ = true;
        pendingC_ = p;
        pendingDistance_ = cands[0].distance;
        pendingBlocks_ = firstBlocks;
        failEnd_ = p + kDatagramSize;
    }
    scan_ = q + kNeighbourhood;
    return true;
}

void StreamSync::confirm(std::uint64_t c, int distance, const DecodedBlocks& blocks)
{
    if (hasPending_) {
        if (c >= pendingC_ + kPreambleSize)
            reportPending();
        else
            hasPending_ = false;  // a false start inside this frame's preamble
    }
    emitFrame(c, distance, blocks);
    if (blocks.corrected2 >= 0 || blocks.corrected1 < 0) {
        scan_ = c + kDatagramSize;
        expect_ = c + kFrameSize;
    } else {
        // Codeword 2 may have failed because bytes were lost inside it, so
        // the next frame may begin there.
        scan_ = c + kCodewordSize;
        failEnd_ = std::max(failEnd_, c + kDatagramSize);
    }
}

void StreamSync::reportPending()
{
    hasPending_ = false;
    emitFrame(pendingC_, pendingDistance_, pendingBlocks_);
}

void StreamSync::emitFrame(std::uint64_t c, int distance, const DecodedBlocks& blocks)
{
    const std::uint64_t start = preambleStart(c);
    const std::uint64_t end = c + kDatagramSize;
    accountSkippedUpTo(start);
    covered_ = std::max(covered_, end);

    if (blocks.ok())
        ++stats_.framesDecoded;
    else
        ++stats_.framesUncorrectable;
    stats_.corrected1 += static_cast<std::uint64_t>(std::max(blocks.corrected1, 0));
    stats_.corrected2 += static_cast<std::uint64_t>(std::max(blocks.corrected2, 0));

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
