// VoiceMultiplexer and VoiceDemultiplexer: control and voice bytes
// interleaved C V C V ..., split again by finding the preamble, through a
// stream joined at an odd byte, lost bytes and bit errors. The frames must
// come out as they would from the control stream alone.

// First: it names a member emit(), which Qt's headers define as a macro.
#include "codec/frame/StreamSync.h"

#include "codec/frame/Frame.h"
#include "codec/voice/VoiceMux.h"

#include <QtTest>

#include <algorithm>
#include <cstdint>
#include <random>
#include <vector>

using namespace rcm;

namespace {

using Bytes = std::vector<std::uint8_t>;

Block randomBlock(std::mt19937& rng, std::size_t padding)
{
    Block b;
    for (auto& x : b)
        x = static_cast<std::uint8_t>(rng());
    // The encoder's BLOCK 1 starts with 55 padding, which lines up with the preamble's.
    std::fill_n(b.begin(), padding, std::uint8_t{0x55});
    return b;
}

Bytes randomBytes(std::mt19937& rng, std::size_t n)
{
    Bytes b(n);
    for (auto& x : b)
        x = static_cast<std::uint8_t>(rng());
    return b;
}

// `frames` frames back to back, as the control phase carries them.
struct ControlStream {
    Bytes bytes;
    std::vector<Block> block1;
};

ControlStream controlStream(std::mt19937& rng, std::size_t frames)
{
    ControlStream s;
    for (std::size_t i = 0; i < frames; ++i) {
        const Block b1 = randomBlock(rng, rng() % 40);
        const FrameBytes f = makeFrame(b1, randomBlock(rng, 0));
        s.bytes.insert(s.bytes.end(), f.begin(), f.end());
        s.block1.push_back(b1);
    }
    return s;
}

Bytes interleaved(const Bytes& control, const Bytes& voice)
{
    Bytes out(2 * control.size());
    interleave(control, voice, out);
    return out;
}

struct Found {
    std::int64_t offset;
    DecodedBlocks blocks;
    int preambleBitErrors;

    bool operator==(const Found& o) const
    {
        return offset == o.offset && blocks.block1 == o.blocks.block1 && blocks.block2 == o.blocks.block2 &&
               blocks.corrected.block1 == o.blocks.corrected.block1 && blocks.corrected.block2 == o.blocks.corrected.block2 &&
               preambleBitErrors == o.preambleBitErrors;
    }
};

// A demultiplexer whose control phase feeds a StreamSync, as the serial
// link's receiver does.
struct Receiver {
    std::vector<Found> frames;
    Bytes control;
    Bytes voice;
    std::size_t largestPiece = 0;
    StreamSync sync{[this](const SyncedFrame& f) { frames.push_back({f.offset, f.blocks, f.preambleBitErrors}); }};
    VoiceDemultiplexer demux{[this](std::span<const std::uint8_t> b) {
                                 control.insert(control.end(), b.begin(), b.end());
                                 largestPiece = std::max(largestPiece, b.size());
                                 sync.feed(b);
                             },
                             [this](std::span<const std::uint8_t> b) {
                                 voice.insert(voice.end(), b.begin(), b.end());
                                 largestPiece = std::max(largestPiece, b.size());
                             }};

    Receiver() = default;
    Receiver(const Receiver&) = delete;
    Receiver& operator=(const Receiver&) = delete;

    // In pieces of random size, as a serial port delivers.
    void feed(const Bytes& line, std::mt19937& rng, std::size_t maxPiece = 700)
    {
        std::size_t at = 0;
        while (at < line.size()) {
            const std::size_t n = std::min<std::size_t>(line.size() - at, 1 + rng() % maxPiece);
            demux.feed(std::span(line).subspan(at, n));
            at += n;
        }
        sync.flush();
    }
};

std::vector<Found> framesOf(const Bytes& control)
{
    std::vector<Found> frames;
    StreamSync sync([&](const SyncedFrame& f) { frames.push_back({f.offset, f.blocks, f.preambleBitErrors}); });
    sync.feed(control);
    sync.flush();
    return frames;
}

bool containsBlock(const std::vector<Found>& frames, const Block& b1)
{
    return std::any_of(frames.begin(), frames.end(),
                       [&](const Found& f) { return f.blocks.ok() && f.blocks.block1 == b1; });
}

void flipBits(Bytes& bytes, double ber, std::mt19937& rng)
{
    std::geometric_distribution<std::size_t> gap(ber);
    for (std::size_t bit = gap(rng); bit < 8 * bytes.size(); bit += 1 + gap(rng))
        bytes[bit / 8] ^= static_cast<std::uint8_t>(0x80u >> (bit % 8));
}

}  // namespace

class TestVoiceMux : public QObject {
    Q_OBJECT

private slots:
    void interleaveIsControlFirst();
    void randomRoundTrip_data();
    void randomRoundTrip();
    void streamingFormMatchesBlockForm();
    void framesBackToBackAndFill();
    void queueDropsOldest();
    void holdDelaysOnlyTheStartAfterFill();
    void startAtOddByte_data();
    void startAtOddByte();
    void lostBytes_data();
    void lostBytes();
    void bitErrorsAsWithoutVoice_data();
    void bitErrorsAsWithoutVoice();
    void memoryStaysBounded();
};

void TestVoiceMux::interleaveIsControlFirst()
{
    std::mt19937 rng(1);
    const ControlStream c = controlStream(rng, 1);
    const Bytes voice = randomBytes(rng, kFrameSize);
    const auto line = multiplexFrame(std::span<const std::uint8_t, kFrameSize>(c.bytes.data(), kFrameSize),
                                     std::span<const std::uint8_t, kFrameSize>(voice.data(), kFrameSize));
    QCOMPARE(line.size(), std::size_t(1200));
    for (std::size_t i = 0; i < kFrameSize; ++i) {
        QCOMPARE(line[2 * i], c.bytes[i]);
        QCOMPARE(line[2 * i + 1], voice[i]);
    }
}

void TestVoiceMux::randomRoundTrip_data()
{
    QTest::addColumn<unsigned>("seed");
    for (unsigned seed = 1; seed <= 5; ++seed)
        QTest::addRow("seed %u", seed) << seed;
}

// Random voice, random blocks, random pieces: both streams come out as they
// went in, and every frame is found.
void TestVoiceMux::randomRoundTrip()
{
    QFETCH(unsigned, seed);
    std::mt19937 rng(seed);
    const ControlStream c = controlStream(rng, 8);
    const Bytes voice = randomBytes(rng, c.bytes.size());
    Receiver r;
    r.feed(interleaved(c.bytes, voice), rng);

    QCOMPARE(r.demux.controlPhase(), 0);
    QCOMPARE(r.demux.stats().phaseChanges, std::uint64_t(0));
    QVERIFY(r.control == c.bytes);
    QVERIFY(r.voice == voice);
    QCOMPARE(r.frames.size(), c.block1.size());
    for (std::size_t i = 0; i < r.frames.size(); ++i) {
        QVERIFY(r.frames[i].blocks.ok());
        QCOMPARE(r.frames[i].offset, std::int64_t(i * kFrameSize));
        QVERIFY(r.frames[i].blocks.block1 == c.block1[i]);
    }
}

// Pairs produced a few at a time, as the serial link's pacing asks for
// them, are the frames interleaved with the voice, frame after frame.
void TestVoiceMux::streamingFormMatchesBlockForm()
{
    std::mt19937 rng(7);
    const ControlStream c = controlStream(rng, 2);
    const Bytes voice = randomBytes(rng, c.bytes.size());
    VoiceMultiplexer mux;
    QVERIFY(mux.queueFrame(std::span<const std::uint8_t, kFrameSize>(c.bytes.data(), kFrameSize)));
    QVERIFY(mux.queueFrame(std::span<const std::uint8_t, kFrameSize>(c.bytes.data() + kFrameSize, kFrameSize)));
    Bytes line;
    std::size_t at = 0;
    while (at < voice.size()) {
        const std::size_t n = std::min<std::size_t>(voice.size() - at, 1 + rng() % 13);
        Bytes out(2 * n);
        mux.multiplex(std::span(voice).subspan(at, n), out);
        line.insert(line.end(), out.begin(), out.end());
        at += n;
    }
    QVERIFY(line == interleaved(c.bytes, voice));
    QCOMPARE(mux.stats().framesStarted, std::uint64_t(2));
    QCOMPARE(mux.stats().fillBytes, std::uint64_t(0));
    QVERIFY(!mux.sendingFrame());
}

// With no frame waiting, the control phase is fill and the voice goes on; a
// frame queued while another is being sent follows it with no gap, so the
// preambles stand exactly 1,200 line bytes apart.
void TestVoiceMux::framesBackToBackAndFill()
{
    std::mt19937 rng(3);
    const ControlStream c = controlStream(rng, 3);
    VoiceMultiplexer mux;
    Bytes line;
    const auto produce = [&](std::size_t pairs) {
        const Bytes voice = randomBytes(rng, pairs);
        Bytes out(2 * pairs);
        mux.multiplex(voice, out);
        line.insert(line.end(), out.begin(), out.end());
    };
    const auto frame = [&](std::size_t i) {
        return std::span<const std::uint8_t, kFrameSize>(c.bytes.data() + i * kFrameSize, kFrameSize);
    };
    produce(37);  // nothing to send yet: fill
    mux.queueFrame(frame(0));
    produce(250);
    QVERIFY(mux.sendingFrame());
    QCOMPARE(mux.frameBytesLeft(), std::size_t(350));
    mux.queueFrame(frame(1));  // early: waits for frame 0 to end
    produce(400);
    mux.queueFrame(frame(2));
    produce(1500);
    QCOMPARE(mux.stats().fillBytes, std::uint64_t(37 + 250 + 400 + 1500 - 3 * kFrameSize));

    Receiver r;
    r.feed(line, rng);
    QCOMPARE(r.frames.size(), std::size_t(3));
    for (std::size_t i = 0; i < 3; ++i) {
        QVERIFY(r.frames[i].blocks.ok());
        QVERIFY(r.frames[i].blocks.block1 == c.block1[i]);
    }
    // Control-stream offsets: one control byte per line pair.
    QCOMPARE(2 * (r.frames[1].offset - r.frames[0].offset), std::int64_t(kMuxedFrameSize));
    QCOMPARE(2 * (r.frames[2].offset - r.frames[1].offset), std::int64_t(kMuxedFrameSize));
    QCOMPARE(r.frames[0].offset, std::int64_t(37));
}

void TestVoiceMux::queueDropsOldest()
{
    constexpr std::size_t n = VoiceMultiplexer::kMaxQueuedFrames + 1;
    std::mt19937 rng(4);
    const ControlStream c = controlStream(rng, n);
    VoiceMultiplexer mux;
    for (std::size_t i = 0; i < n; ++i)
        QCOMPARE(mux.queueFrame(std::span<const std::uint8_t, kFrameSize>(c.bytes.data() + i * kFrameSize, kFrameSize)),
                 i < VoiceMultiplexer::kMaxQueuedFrames);
    QCOMPARE(mux.stats().framesDropped, std::uint64_t(1));
    Bytes out(2 * (n - 1) * kFrameSize);
    mux.multiplex(Bytes((n - 1) * kFrameSize, 0xA5), out);
    Receiver r;
    r.feed(out, rng);
    QCOMPARE(r.frames.size(), n - 1);
    for (std::size_t i = 0; i + 1 < n; ++i)
        QVERIFY(r.frames[i].blocks.block1 == c.block1[i + 1]);
}

// Held, a queued frame waits while fill goes on; a frame that follows
// another is not held.
void TestVoiceMux::holdDelaysOnlyTheStartAfterFill()
{
    std::mt19937 rng(6);
    const ControlStream c = controlStream(rng, 2);
    VoiceMultiplexer mux;
    Bytes line;
    const auto produce = [&](std::size_t pairs) {
        Bytes out(2 * pairs);
        mux.multiplex(Bytes(pairs, 0xA5), out);
        line.insert(line.end(), out.begin(), out.end());
    };
    mux.queueFrame(std::span<const std::uint8_t, kFrameSize>(c.bytes.data(), kFrameSize));
    mux.queueFrame(std::span<const std::uint8_t, kFrameSize>(c.bytes.data() + kFrameSize, kFrameSize));
    mux.setHoldFill(true);
    produce(100);
    QVERIFY(!mux.sendingFrame());
    QCOMPARE(mux.stats().fillBytes, std::uint64_t(100));
    mux.setHoldFill(false);
    produce(kFrameSize);
    mux.setHoldFill(true);  // frame 1 follows frame 0 all the same
    produce(kFrameSize + 10);
    QCOMPARE(mux.stats().framesStarted, std::uint64_t(2));
    QCOMPARE(mux.stats().fillBytes, std::uint64_t(110));
    Receiver r;
    r.feed(line, rng);
    QCOMPARE(r.frames.size(), std::size_t(2));
    QCOMPARE(r.frames[0].offset, std::int64_t(100));
    QCOMPARE(r.frames[1].offset, std::int64_t(100 + kFrameSize));
}

void TestVoiceMux::startAtOddByte_data()
{
    QTest::addColumn<int>("start");
    for (int start : {1, 3, 91, 179, 181, 601, 1199})
        QTest::addRow("byte %d", start) << start;
}

// Joined at an odd byte, the receiver first takes voice for control; the
// first preamble sets it right, and every frame from there on is found.
void TestVoiceMux::startAtOddByte()
{
    QFETCH(int, start);
    std::mt19937 rng(static_cast<unsigned>(start));
    const ControlStream c = controlStream(rng, 6);
    const Bytes voice = randomBytes(rng, c.bytes.size());
    const Bytes line = interleaved(c.bytes, voice);
    Receiver r;
    r.feed(Bytes(line.begin() + start, line.end()), rng);

    QCOMPARE(r.demux.controlPhase(), 1);
    QCOMPARE(r.demux.stats().phaseChanges, std::uint64_t(1));
    // Frame i's preamble ends at line byte 1200 i + 179 (its last control byte).
    const std::size_t firstWhole = (static_cast<std::size_t>(start) + kMuxedFrameSize - 1) / kMuxedFrameSize;
    for (std::size_t i = firstWhole; i < c.block1.size(); ++i)
        QVERIFY2(containsBlock(r.frames, c.block1[i]), qPrintable(QStringLiteral("frame %1").arg(i)));
    // After the swap, the voice is the voice: its last bytes arrive intact.
    const std::size_t tail = 300;
    QVERIFY(r.voice.size() > tail);
    QVERIFY(std::equal(voice.end() - tail, voice.end(), r.voice.end() - tail));
}

void TestVoiceMux::lostBytes_data()
{
    QTest::addColumn<int>("at");
    QTest::addColumn<int>("lost");
    QTest::addColumn<bool>("flips");
    QTest::addRow("1 in codewords") << 2500 << 1 << true;
    QTest::addRow("1 in preamble") << 2450 << 1 << true;
    QTest::addRow("3 in voice") << 2401 << 3 << true;
    QTest::addRow("2 in codewords") << 2500 << 2 << false;
    QTest::addRow("17 across frames") << 3590 << 17 << true;
    QTest::addRow("600 (half a frame)") << 2700 << 600 << false;
    QTest::addRow("601") << 2700 << 601 << true;
}

// Bytes lost: an odd number swaps the phases. The frame hit may be lost; the
// next preamble shows the new phase and every frame after it is found, as
// is the voice.
void TestVoiceMux::lostBytes()
{
    QFETCH(int, at);
    QFETCH(int, lost);
    QFETCH(bool, flips);
    std::mt19937 rng(static_cast<unsigned>(at * 31 + lost));
    const ControlStream c = controlStream(rng, 8);
    const Bytes voice = randomBytes(rng, c.bytes.size());
    Bytes line = interleaved(c.bytes, voice);
    line.erase(line.begin() + at, line.begin() + at + lost);
    Receiver r;
    r.feed(line, rng);

    QCOMPARE(r.demux.controlPhase(), flips ? 1 : 0);
    QCOMPARE(r.demux.stats().phaseChanges, std::uint64_t(flips ? 1 : 0));
    // Frames before the loss, and from the first whole one after it.
    const std::size_t hit = static_cast<std::size_t>(at) / kMuxedFrameSize;
    const std::size_t resumed = (static_cast<std::size_t>(at + lost) + kMuxedFrameSize - 1) / kMuxedFrameSize;
    for (std::size_t i = 0; i < c.block1.size(); ++i) {
        if (i < hit || i >= resumed)
            QVERIFY2(containsBlock(r.frames, c.block1[i]), qPrintable(QStringLiteral("frame %1").arg(i)));
    }
    const std::size_t tail = 300;
    QVERIFY(std::equal(voice.end() - tail, voice.end(), r.voice.end() - tail));
}

void TestVoiceMux::bitErrorsAsWithoutVoice_data()
{
    QTest::addColumn<unsigned>("seed");
    QTest::addColumn<bool>("silentVoice");
    for (unsigned seed = 1; seed <= 6; ++seed)
        QTest::addRow("seed %u, random voice", seed) << seed << false;
    for (unsigned seed = 7; seed <= 8; ++seed)
        QTest::addRow("seed %u, zero voice", seed) << seed << true;
}

// BER 1e-3 on the line: the frames found through the demultiplexer are
// exactly those a StreamSync finds in the control stream alone with the same
// errors on its bytes: same offsets, same corrections, same failures.
void TestVoiceMux::bitErrorsAsWithoutVoice()
{
    QFETCH(unsigned, seed);
    QFETCH(bool, silentVoice);
    std::mt19937 rng(seed);
    const ControlStream c = controlStream(rng, 40);
    const Bytes voice = silentVoice ? Bytes(c.bytes.size(), 0) : randomBytes(rng, c.bytes.size());
    Bytes line = interleaved(c.bytes, voice);
    flipBits(line, 1e-3, rng);

    Bytes damagedControl(c.bytes.size());
    for (std::size_t i = 0; i < damagedControl.size(); ++i)
        damagedControl[i] = line[2 * i];
    const std::vector<Found> alone = framesOf(damagedControl);

    Receiver r;
    r.feed(line, rng);
    QCOMPARE(r.demux.stats().phaseChanges, std::uint64_t(0));
    QCOMPARE(r.frames.size(), alone.size());
    QVERIFY(r.frames == alone);
    // And they are nearly all there: BER 1e-3 is well within RS(255,223).
    const auto good = std::count_if(r.frames.begin(), r.frames.end(), [](const Found& f) { return f.blocks.ok(); });
    QVERIFY2(good >= 39, qPrintable(QStringLiteral("%1 good frames of 40").arg(good)));
}

// However large a feed, the handlers get bounded pieces and the
// demultiplexer holds nothing but its fixed history.
void TestVoiceMux::memoryStaysBounded()
{
    std::mt19937 rng(9);
    const ControlStream c = controlStream(rng, 200);
    const Bytes line = interleaved(c.bytes, randomBytes(rng, c.bytes.size()));
    Receiver r;
    r.demux.feed(line);
    r.sync.flush();
    QCOMPARE(r.frames.size(), std::size_t(200));
    QVERIFY(r.largestPiece <= 4096);
    QCOMPARE(r.demux.stats().bytesIn, std::uint64_t(line.size()));
    QCOMPARE(r.demux.stats().controlBytes + r.demux.stats().voiceBytes, std::uint64_t(line.size()));
}

QTEST_APPLESS_MAIN(TestVoiceMux)
#include "tst_voicemux.moc"
