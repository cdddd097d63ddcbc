// Random and mutated byte streams through StreamSync, fed whole and in random
// pieces, and what it emits through decodeFrame/decodeBlocks, under
// ASan/UBSan: nothing may crash or read out of bounds, and the synchroniser's
// promises must hold (the same frames however the stream is cut, bounded
// memory, statistics that add up, clean frames always found). Fixed seed,
// bounded work: a CTest target, not an open-ended fuzzer. An optional
// argument sets the number of rounds.
#include "tests/support/RandomMessage.h"

#include "codec/frame/Frame.h"
#include "codec/message/MessageDecoder.h"
#include "codec/message/MessageEncoder.h"
#include "codec/frame/StreamSync.h"

#include <algorithm>
#include <bit>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>

using namespace rcm;

namespace {

using Bytes = std::vector<std::uint8_t>;

int round_ = 0;

[[noreturn]] void fail(const char* what)
{
    std::fprintf(stderr, "fuzz_streamsync: round %d: %s\n", round_, what);
    std::abort();
}

void check(bool ok, const char* what)
{
    if (!ok)
        fail(what);
}

// FNV-1a over everything a handler sees, to compare two runs.
struct Digest {
    std::uint64_t h = 1469598103934665603ull;
    void add(const void* p, std::size_t n)
    {
        const auto* b = static_cast<const std::uint8_t*>(p);
        for (std::size_t i = 0; i < n; ++i)
            h = (h ^ b[i]) * 1099511628211ull;
    }
    template <typename T>
    void add(const T& v)
    {
        add(&v, sizeof v);
    }
};

Block randomBlock(std::mt19937_64& rng)
{
    Block b;
    for (auto& x : b)
        x = static_cast<std::uint8_t>(rng());
    return b;
}

FrameBytes randomFrame(std::mt19937_64& rng)
{
    switch (rng() % 3) {
    case 0: {
        Diagnostics errors;
        if (auto f = encodeFrame(test::randomMessage(rng), errors))
            return *f;
        [[fallthrough]];
    }
    case 1: {
        // Padding-heavy blocks: the shape that aliases most readily.
        Block b1 = randomBlock(rng);
        Block b2{};
        std::fill_n(b1.begin(), rng() % 223, std::uint8_t{0x55});
        std::fill(b2.begin() + 7, b2.end() - 1, std::uint8_t{0x55});
        return makeFrame(b1, b2);
    }
    default:
        return makeFrame(randomBlock(rng), randomBlock(rng));
    }
}

struct Built {
    Bytes bytes;
    std::vector<std::int64_t> cleanFrames;  // offsets, when nothing was mutated
    bool mutated = false;
};

Built buildStream(std::mt19937_64& rng)
{
    Built s;
    // Mostly one or two parts, now and then many: rounds stay cheap enough
    // for 10^5 of them in CTest, and long streams are still made.
    const bool longStream = rng() % 128 == 0;
    const int parts = longStream ? 1 + static_cast<int>(rng() % 40) : 1 + static_cast<int>(rng() % 2);
    for (int p = 0; p < parts; ++p) {
        switch (rng() % 6) {
        case 0: {  // garbage
            const std::size_t n = rng() % (longStream ? 1500 : 300);
            for (std::size_t i = 0; i < n; ++i)
                s.bytes.push_back(static_cast<std::uint8_t>(rng()));
            break;
        }
        case 1: {  // preamble-like runs, with and without the mark
            s.bytes.insert(s.bytes.end(), rng() % 120, std::uint8_t{0x55});
            if (rng() % 2)
                s.bytes.insert(s.bytes.end(), 2, std::uint8_t{0x0F});
            // Followed by garbage, or by bytes near 0F 0F even without the
            // mark, it is a frame whose codewords are lost: reported.
            s.mutated = true;
            break;
        }
        case 2: {  // a frame cut short
            const FrameBytes f = randomFrame(rng);
            s.bytes.insert(s.bytes.end(), f.begin(), f.begin() + static_cast<std::ptrdiff_t>(rng() % kFrameSize));
            s.mutated = true;  // its remains may be reported
            break;
        }
        default: {
            s.cleanFrames.push_back(static_cast<std::int64_t>(s.bytes.size()));
            const FrameBytes f = randomFrame(rng);
            s.bytes.insert(s.bytes.end(), f.begin(), f.end());
            break;
        }
        }
    }
    if (s.bytes.empty() || rng() % 3 == 0)
        return s;

    s.mutated = true;
    // Bit errors at a random rate up to 1e-2, then a few slips and smears.
    const double ber = static_cast<double>(rng() % 1000) * 1e-5;
    if (ber > 0) {
        std::geometric_distribution<std::uint64_t> gap(ber);
        for (std::uint64_t bit = gap(rng); bit < s.bytes.size() * 8; bit += 1 + gap(rng))
            s.bytes[bit / 8] ^= static_cast<std::uint8_t>(0x80u >> (bit % 8));
    }
    const int edits = static_cast<int>(rng() % 6);
    for (int e = 0; e < edits && !s.bytes.empty(); ++e) {
        const std::size_t at = rng() % s.bytes.size();
        switch (rng() % 3) {
        case 0:
            s.bytes.erase(s.bytes.begin() + static_cast<std::ptrdiff_t>(at),
                          s.bytes.begin() + static_cast<std::ptrdiff_t>(std::min(s.bytes.size(), at + 1 + rng() % 600)));
            break;
        case 1:
            s.bytes.insert(s.bytes.begin() + static_cast<std::ptrdiff_t>(at), 1 + rng() % 20,
                           static_cast<std::uint8_t>(rng()));
            break;
        default:
            for (std::size_t i = at; i < std::min(s.bytes.size(), at + rng() % 64); ++i)
                s.bytes[i] = static_cast<std::uint8_t>(rng());
            break;
        }
    }
    return s;
}

struct Run {
    Digest digest;
    std::vector<std::int64_t> offsets;
    std::vector<bool> ok;
    StreamSync::Stats stats;
    std::uint64_t covered = 0;  // bytes inside emitted frames, overlaps counted once
};

Run runOnce(const Bytes& bytes, std::mt19937_64* cut)
{
    Run run;
    std::int64_t coveredTo = 0;
    StreamSync sync([&](const SyncedFrame& f) {
        check(f.raw.size() >= kDatagramSize + StreamSync::kWindowSize && f.raw.size() <= kFrameSize, "raw size");
        check(f.offset >= 0 ? f.raw.size() == kFrameSize
                            : static_cast<std::int64_t>(f.raw.size()) == static_cast<std::int64_t>(kFrameSize) + f.offset,
              "raw size against offset");
        check(run.offsets.empty() || f.offset > run.offsets.back(), "frames out of order");
        // A window within 6 bits of the preamble's tail anywhere; up to 16
        // where a frame was due, 600 bytes after one reported before; or a
        // mark within 2 bits of 0F 0F after at least 6 fill bytes 55.
        const std::uint8_t* window = f.raw.data() + f.raw.size() - kDatagramSize - StreamSync::kWindowSize;
        int fill = 0;
        for (std::size_t i = 0; i < StreamSync::kWindowSize - 2; ++i)
            fill += window[i] == kPreambleFillByte;
        const int markBits = std::popcount(static_cast<unsigned>(window[14] ^ kPreambleMark)) +
                             std::popcount(static_cast<unsigned>(window[15] ^ kPreambleMark));
        const bool due = f.preambleBitErrors <= StreamSync::kMaxDueWindowBitErrors &&
                         std::binary_search(run.offsets.begin(), run.offsets.end(),
                                            f.offset - static_cast<std::int64_t>(kFrameSize));
        check(f.preambleBitErrors >= 0, "window distance");
        check(f.preambleBitErrors <= StreamSync::kMaxWindowBitErrors || due || (markBits <= 2 && fill >= 6),
              "a window neither near the preamble's tail, nor where a frame was due, nor a slipped mark");
        const std::int64_t start = std::max<std::int64_t>(f.offset, 0);
        const std::int64_t end = f.offset + static_cast<std::int64_t>(kFrameSize);
        check(end <= static_cast<std::int64_t>(bytes.size()), "frame past the end of the stream");
        check(std::equal(f.raw.begin(), f.raw.end(), bytes.begin() + start), "raw differs from the stream");
        run.covered += static_cast<std::uint64_t>(end - std::max(start, coveredTo));
        coveredTo = end;
        run.offsets.push_back(f.offset);
        run.ok.push_back(f.ok());

        run.digest.add(f.offset);
        run.digest.add(f.raw.data(), f.raw.size());
        run.digest.add(f.blocks.block1);
        run.digest.add(f.blocks.block2);
        run.digest.add(f.blocks.corrected.block1);
        run.digest.add(f.blocks.corrected.block2);
        run.digest.add(f.preambleBitErrors);

        // What a consumer does next must not trip either.
        (void)decodeBlocks(f.blocks);
        (void)decodeFrame(f.raw.last(kDatagramSize));
        if (f.raw.size() == kFrameSize)
            (void)decodeFrame(f.raw);
    });
    if (!cut) {
        sync.feed(bytes);
        check(sync.bufferedBytes() <= StreamSync::kMaxCarried, "carried too much");
    } else {
        std::size_t i = 0;
        while (i < bytes.size()) {
            const std::size_t n = std::min<std::size_t>(bytes.size() - i, (*cut)() % 8 ? 1 + (*cut)() % 700 : 1 + (*cut)() % 20000);
            sync.feed(std::span<const std::uint8_t>(bytes.data() + i, n));
            check(sync.bufferedBytes() <= StreamSync::kMaxCarried, "carried too much");
            i += n;
        }
    }
    sync.flush();
    check(sync.bufferedBytes() == 0, "bytes left after flush");
    run.stats = sync.stats();
    return run;
}

}  // namespace

int main(int argc, char** argv)
{
    const int rounds = argc > 1 ? std::atoi(argv[1]) : 100000;
    std::mt19937_64 rng(0x5EC5);
    std::size_t frames = 0, good = 0, bytesTotal = 0;
    for (round_ = 0; round_ < rounds; ++round_) {
        const Built s = buildStream(rng);
        const Run whole = runOnce(s.bytes, nullptr);
        std::mt19937_64 cut(rng());
        const Run split = runOnce(s.bytes, &cut);

        check(whole.digest.h == split.digest.h, "cutting the stream changed what was found");
        const StreamSync::Stats& st = whole.stats;
        check(st.bytesIn == s.bytes.size(), "bytesIn");
        check(st.framesDecoded + st.framesUncorrectable == whole.offsets.size(), "frame counts");
        check(st.bytesSkipped + whole.covered == st.bytesIn, "skipped + covered != received");
        check(split.stats.bytesSkipped == st.bytesSkipped && split.stats.correctedBytes1 == st.correctedBytes1 &&
                  split.stats.correctedBytes2 == st.correctedBytes2,
              "statistics depend on the cut");
        if (!s.mutated) {
            check(whole.offsets == s.cleanFrames, "a clean frame was missed or misplaced");
            check(std::all_of(whole.ok.begin(), whole.ok.end(), [](bool b) { return b; }), "a clean frame failed");
        }
        frames += whole.offsets.size();
        good += static_cast<std::size_t>(std::count(whole.ok.begin(), whole.ok.end(), true));
        bytesTotal += s.bytes.size();
    }
    std::printf("fuzz_streamsync: %d rounds, %zu bytes, %zu frames reported, %zu decoded\n", rounds, bytesTotal, frames,
                good);
    return 0;
}
