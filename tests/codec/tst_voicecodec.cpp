// The voice codec: Codec 2 3200 in 12-byte frames with sync, sequence and
// RS(12,10), exactly 600 bytes a second. A spoken phrase
// (resources/voice/phrase.wav, made with espeak-ng) goes through the byte
// stream with bit errors and lost bytes and must come out as long as it went
// in, with its energy in the same frequency bands.
#include "BandEnergy.h"

#include "codec/frame/Frame.h"
#include "codec/voice/VoiceCodec.h"
#include "codec/voice/VoiceMux.h"
#include "codec/voice/WavFile.h"

#include <QtTest>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <vector>

using namespace rcm;
using namespace rcm::voice;

namespace {

using Bytes = std::vector<std::uint8_t>;
using Pcm = std::vector<std::int16_t>;

// How far, in dB, each band's energy may stray from the input's. Codec 2
// models the envelope from harmonics of the pitch and its post filter
// deepens the valleys between formants: on this phrase the bands above
// 1.5 kHz come out 4 to 5 dB low, those below within 1.5 dB. Frames lost to
// errors become silence and pull every band down a little further. Speech
// with another spectrum misses by far more (see spectrumOfOtherSoundDiffers).
constexpr double kToleranceDb = 6.0;
constexpr double kWeakBandDb = 30.0;

Pcm phrase()
{
    std::string error;
    const auto audio = WavFile::read(RCM_SOURCE_DIR "/resources/voice/phrase.wav", error);
    if (!audio || audio->sampleRate != kSampleRate)
        qFatal("phrase.wav: %s", error.c_str());
    return audio->samples;
}

Bytes encodeAll(const Pcm& pcm)
{
    VoiceEncoder encoder;
    Bytes bytes;
    encoder.encode(pcm, bytes);
    encoder.finish(bytes);
    return bytes;
}

Pcm decodeAll(const Bytes& bytes, std::size_t piece = 0, VoiceDecoder::Stats* stats = nullptr)
{
    VoiceDecoder decoder;
    Pcm out;
    if (piece == 0) {
        decoder.decode(bytes, out);
    } else {
        for (std::size_t at = 0; at < bytes.size(); at += piece)
            decoder.decode(std::span(bytes).subspan(at, std::min(piece, bytes.size() - at)), out);
    }
    if (stats)
        *stats = decoder.stats();
    return out;
}

void flipBits(Bytes& bytes, double ber, std::mt19937& rng)
{
    std::geometric_distribution<std::size_t> gap(ber);
    for (std::size_t bit = gap(rng); bit < 8 * bytes.size(); bit += 1 + gap(rng))
        bytes[bit / 8] ^= static_cast<std::uint8_t>(0x80u >> (bit % 8));
}

QString bandsText(const std::array<double, test::kBands>& db)
{
    QStringList parts;
    for (double d : db)
        parts << QString::number(d, 'f', 1);
    return parts.join(QLatin1Char(' '));
}

// Every band within `tolerance` dB of the input's, or, where the input's
// band is weak, no stronger than the weak bound either.
void compareBands(const Pcm& in, const Pcm& out, double tolerance)
{
    const auto a = test::bandEnergyDb(in);
    const auto b = test::bandEnergyDb(out);
    const double strongest = *std::max_element(a.begin(), a.end());
    const QString detail = QStringLiteral("in  %1\nout %2").arg(bandsText(a), bandsText(b));
    for (std::size_t i = 0; i < test::kBands; ++i) {
        if (a[i] < strongest - kWeakBandDb)
            QVERIFY2(b[i] < strongest - kWeakBandDb + tolerance, qPrintable(detail));
        else
            QVERIFY2(
                std::abs(a[i] - b[i]) <= tolerance,
                qPrintable(QStringLiteral("band %1 (%2-%3 Hz)\n").arg(i).arg(i * 500).arg(i * 500 + 500) + detail));
    }
}

}  // namespace

class TestVoiceCodec : public QObject {
    Q_OBJECT

private slots:
    void frameLayout();
    void oneWrongByteCorrected();
    void idleFillDecodesToSilence();
    void sixHundredBytesASecond();
    void phraseThroughTheStream_data();
    void phraseThroughTheStream();
    void anyPiecesGiveTheSameFrames();
    void wrongPhaseForASecond();
    void spectrumOfOtherSoundDiffers();
    void voiceNeverLooksLikeThePreamble();
    void wavFileRoundTrip();
};

void TestVoiceCodec::frameLayout()
{
    VoiceEncoder encoder;
    std::array<std::uint8_t, kFrameBytes> speech;
    std::array<std::uint8_t, kFrameBytes> idle;
    const Pcm tone = [] {
        Pcm p(kFrameSamples);
        for (std::size_t i = 0; i < p.size(); ++i)
            p[i] = static_cast<std::int16_t>(
                8000 * std::sin(2 * std::numbers::pi * 440 * static_cast<double>(i) / kSampleRate));
        return p;
    }();
    encoder.speechFrame(PcmFrame(tone.data(), kFrameSamples), speech);
    encoder.idleFrame(idle);
    QCOMPARE(speech[0], kSyncByte);
    QCOMPARE(speech[1], std::uint8_t(0x40));  // speech, sequence 0
    QCOMPARE(idle[0], kSyncByte);
    QCOMPARE(idle[1], std::uint8_t(0x81));  // idle, sequence 1
    for (std::size_t i = 2; i < 10; ++i)
        QCOMPARE(idle[i], std::uint8_t(0));
    QCOMPARE(encoder.nextSequence(), std::uint8_t(2));

    VoiceFrame f;
    QVERIFY(parseFrame(speech, f));
    QCOMPARE(f.kind, FrameKind::Speech);
    QCOMPARE(f.sequence, std::uint8_t(0));
    QCOMPARE(f.corrected, 0);
    QVERIFY(std::equal(f.payload.begin(), f.payload.end(), speech.begin() + 2));
    QVERIFY(parseFrame(idle, f));
    QCOMPARE(f.kind, FrameKind::Idle);

    // The sequence wraps at 64.
    for (int i = 0; i < 62; ++i)
        encoder.idleFrame(idle);
    QCOMPARE(encoder.nextSequence(), std::uint8_t(0));
}

// RS(12,10) corrects any one wrong byte, wherever it is and however wrong.
void TestVoiceCodec::oneWrongByteCorrected()
{
    VoiceEncoder encoder;
    const Bytes bytes = encodeAll(phrase());
    int frames = 0;
    for (std::size_t at = 0; at + kFrameBytes <= bytes.size(); at += 37 * kFrameBytes) {
        std::array<std::uint8_t, kFrameBytes> good;
        std::copy_n(bytes.begin() + static_cast<std::ptrdiff_t>(at), kFrameBytes, good.begin());
        VoiceFrame expected;
        QVERIFY(parseFrame(good, expected));
        for (std::size_t i = 0; i < kFrameBytes; ++i) {
            for (unsigned e = 1; e < 256; ++e) {
                auto bad = good;
                bad[i] ^= static_cast<std::uint8_t>(e);
                VoiceFrame f;
                QVERIFY(parseFrame(bad, f));
                QCOMPARE(f.corrected, 1);
                QCOMPARE(f.sequence, expected.sequence);
                QVERIFY(f.payload == expected.payload);
            }
        }
        ++frames;
    }
    QVERIFY(frames >= 4);
}

void TestVoiceCodec::idleFillDecodesToSilence()
{
    VoiceEncoder encoder;
    Bytes bytes(kBytesPerSecond);
    for (std::size_t at = 0; at < bytes.size(); at += kFrameBytes)
        encoder.idleFrame(FrameSpan(bytes.data() + at, kFrameBytes));
    VoiceDecoder::Stats stats;
    const Pcm out = decodeAll(bytes, 7, &stats);
    QCOMPARE(out.size(), std::size_t(kSampleRate));
    QVERIFY(std::all_of(out.begin(), out.end(), [](std::int16_t s) { return s == 0; }));
    QCOMPARE(stats.idleFrames, std::uint64_t(kFramesPerSecond));
    QCOMPARE(stats.speechFrames, std::uint64_t(0));
}

// One second of speech is 8,000 samples in and 600 bytes out: half the
// 9,600 bps link.
void TestVoiceCodec::sixHundredBytesASecond()
{
    const Pcm pcm(kSampleRate, 1000);
    QCOMPARE(encodeAll(pcm).size(), std::size_t(600));
    QCOMPARE(kBytesPerSecond * 2, kMuxedFrameSize);
}

void TestVoiceCodec::phraseThroughTheStream_data()
{
    QTest::addColumn<double>("ber");
    QTest::addColumn<QList<int>>("lostAt");  // pairs: offset, count
    QTest::addColumn<int>("piece");
    QTest::addColumn<double>("tolerance");
    QTest::addRow("clean, whole") << 0.0 << QList<int>{} << 0 << kToleranceDb;
    QTest::addRow("clean, byte by byte") << 0.0 << QList<int>{} << 1 << kToleranceDb;
    QTest::addRow("BER 1e-3") << 1e-3 << QList<int>{} << 50 << kToleranceDb;
    // The phrase is 164 frames, 1,968 bytes: every loss lies inside it.
    QTest::addRow("lost bytes") << 0.0 << QList<int>{300, 1, 701, 5, 1200, 30, 1601, 12} << 13 << kToleranceDb;
    QTest::addRow("BER 1e-3 and lost bytes") << 1e-3 << QList<int>{500, 3, 1300, 100} << 64 << kToleranceDb;
}

// The phrase through bit errors and lost bytes: as long as it went in
// (within one frame: the last is padded, and a frame hit at either end can
// be gone), with its energy in the same bands.
void TestVoiceCodec::phraseThroughTheStream()
{
    QFETCH(double, ber);
    QFETCH(QList<int>, lostAt);
    QFETCH(int, piece);
    QFETCH(double, tolerance);
    const Pcm in = phrase();
    Bytes bytes = encodeAll(in);
    QCOMPARE(bytes.size(), (in.size() + kFrameSamples - 1) / kFrameSamples * kFrameBytes);
    std::mt19937 rng(42);
    if (ber > 0)
        flipBits(bytes, ber, rng);
    for (qsizetype i = lostAt.size() - 2; i >= 0; i -= 2) {
        QVERIFY(std::size_t(lostAt[i] + lostAt[i + 1]) <= bytes.size());
        bytes.erase(bytes.begin() + lostAt[i], bytes.begin() + lostAt[i] + lostAt[i + 1]);
    }

    VoiceDecoder::Stats stats;
    const Pcm out = decodeAll(bytes, static_cast<std::size_t>(piece), &stats);
    qInfo("%zu samples in, %zu out; %llu speech frames, %llu lost, %llu corrected, %llu resyncs", in.size(), out.size(),
          static_cast<unsigned long long>(stats.speechFrames), static_cast<unsigned long long>(stats.lostFrames),
          static_cast<unsigned long long>(stats.correctedFrames), static_cast<unsigned long long>(stats.resyncs));
    QVERIFY2(out.size() + kFrameSamples >= in.size() && out.size() <= in.size() + kFrameSamples,
             qPrintable(QStringLiteral("%1 samples in, %2 out").arg(in.size()).arg(out.size())));
    compareBands(in, out, tolerance);
    if (ber == 0 && lostAt.isEmpty()) {
        QCOMPARE(stats.lostFrames, std::uint64_t(0));
        QCOMPARE(stats.bytesSkipped, std::uint64_t(0));
    }
}

// Codec 2 draws the phases of unvoiced sound from one random generator for
// the whole process, so two decoders never give the same samples; the frames
// they take, and so the silent slots and the statistics, must be the same.
void TestVoiceCodec::anyPiecesGiveTheSameFrames()
{
    Bytes bytes = encodeAll(phrase());
    std::mt19937 rng(5);
    flipBits(bytes, 2e-3, rng);
    bytes.erase(bytes.begin() + 777, bytes.begin() + 790);
    const auto silentSlots = [](const Pcm& pcm) {
        std::vector<bool> silent;
        for (std::size_t at = 0; at + kFrameSamples <= pcm.size(); at += kFrameSamples)
            silent.push_back(std::all_of(pcm.begin() + static_cast<std::ptrdiff_t>(at),
                                         pcm.begin() + static_cast<std::ptrdiff_t>(at + kFrameSamples),
                                         [](std::int16_t s) { return s == 0; }));
        return silent;
    };
    VoiceDecoder::Stats whole;
    const std::vector<bool> expected = silentSlots(decodeAll(bytes, 0, &whole));
    QVERIFY(whole.lostFrames > 0 && whole.correctedFrames > 0 && whole.resyncs > 0);
    for (std::size_t piece : {1, 2, 11, 12, 13, 500}) {
        VoiceDecoder::Stats stats;
        QVERIFY2(silentSlots(decodeAll(bytes, piece, &stats)) == expected,
                 qPrintable(QStringLiteral("pieces of %1").arg(piece)));
        QCOMPARE(stats.speechFrames, whole.speechFrames);
        QCOMPARE(stats.lostFrames, whole.lostFrames);
        QCOMPARE(stats.correctedFrames, whole.correctedFrames);
        QCOMPARE(stats.bytesSkipped, whole.bytesSkipped);
        QCOMPARE(stats.resyncs, whole.resyncs);
    }
}

// A second of the voice phase replaced by other bytes, as when the receiver
// took the wrong phase for voice until the next preamble: those 50 frames
// are silence, and the phrase goes on after them where it was.
void TestVoiceCodec::wrongPhaseForASecond()
{
    const Pcm in = phrase();
    Bytes bytes = encodeAll(in);
    std::mt19937 rng(11);
    const std::size_t at = 100 * kFrameBytes;
    for (std::size_t i = at; i < at + kBytesPerSecond; ++i)
        bytes[i] = static_cast<std::uint8_t>(rng());
    VoiceDecoder::Stats stats;
    const Pcm out = decodeAll(bytes, 20, &stats);
    QCOMPARE(out.size(), (in.size() + kFrameSamples - 1) / kFrameSamples * kFrameSamples);
    QCOMPARE(stats.lostFrames, std::uint64_t(kFramesPerSecond));
    QCOMPARE(stats.resyncs, std::uint64_t(1));
    const auto silent = [&](std::size_t from, std::size_t to) {
        return std::all_of(out.begin() + static_cast<std::ptrdiff_t>(from),
                           out.begin() + static_cast<std::ptrdiff_t>(to), [](std::int16_t s) { return s == 0; });
    };
    const std::size_t resume = 100 * kFrameSamples + kSampleRate;
    QVERIFY(!silent(100 * kFrameSamples - kFrameSamples, 100 * kFrameSamples));
    QVERIFY(silent(100 * kFrameSamples, resume));
    QVERIFY(!silent(resume, resume + kFrameSamples));
}

// The comparison can fail: noise with the phrase's power, and the phrase
// with its top half-band removed, both miss the tolerance.
void TestVoiceCodec::spectrumOfOtherSoundDiffers()
{
    const Pcm in = phrase();
    const auto a = test::bandEnergyDb(in);
    double power = 0;
    for (std::int16_t s : in)
        power += double(s) * s;
    const double rms = std::sqrt(power / static_cast<double>(in.size()));
    std::mt19937 rng(3);
    std::normal_distribution<double> gauss(0, rms);
    Pcm noise(in.size());
    for (auto& s : noise)
        s = static_cast<std::int16_t>(std::clamp(gauss(rng), -32768.0, 32767.0));
    const auto b = test::bandEnergyDb(noise);
    double worst = 0;
    for (std::size_t i = 0; i < test::kBands; ++i)
        worst = std::max(worst, std::abs(a[i] - b[i]));
    QVERIFY2(worst > kToleranceDb, qPrintable(QString::number(worst)));

    // Two-point moving average: a gentle low-pass, -3 dB at 2 kHz, zero at 4 kHz.
    Pcm dull(in.size());
    for (std::size_t i = 1; i < in.size(); ++i)
        dull[i] = static_cast<std::int16_t>((in[i] + in[i - 1]) / 2);
    const auto c = test::bandEnergyDb(dull);
    worst = 0;
    for (std::size_t i = 0; i < test::kBands; ++i)
        worst = std::max(worst, std::abs(a[i] - c[i]));
    QVERIFY2(worst > kToleranceDb, qPrintable(QString::number(worst)));
}

// The demultiplexer takes the phase where the preamble's last 16 bytes
// appear within 6 bits for control: voice frames must never come that close.
// The sync bytes alone keep them 7 bits away; with Codec 2's bits it is far more.
void TestVoiceCodec::voiceNeverLooksLikeThePreamble()
{
    Bytes bytes = encodeAll(phrase());
    VoiceEncoder encoder;
    for (int i = 0; i < 100; ++i) {
        bytes.resize(bytes.size() + kFrameBytes);
        encoder.idleFrame(FrameSpan(bytes.data() + bytes.size() - kFrameBytes, kFrameBytes));
    }
    const std::array<std::uint8_t, 16> tail = {0x55, 0x55, 0x55, 0x55, 0x55, 0x55, 0x55, 0x55,
                                               0x55, 0x55, 0x55, 0x55, 0x55, 0x55, 0x0F, 0x0F};
    int closest = 128;
    for (std::size_t at = 0; at + tail.size() <= bytes.size(); ++at) {
        int d = 0;
        for (std::size_t i = 0; i < tail.size(); ++i)
            d += std::popcount(static_cast<unsigned>(bytes[at + i] ^ tail[i]));
        closest = std::min(closest, d);
    }
    qInfo("closest voice window: %d bits from the preamble's last 16 bytes", closest);
    QVERIFY(closest > 6 + 6);
}

void TestVoiceCodec::wavFileRoundTrip()
{
    QTemporaryDir dir;
    QVERIFY(dir.isValid());
    const std::string path = (dir.path() + QStringLiteral("/x.wav")).toStdString();
    const Pcm in = phrase();
    {
        WavFile out;
        std::string error;
        QVERIFY2(out.create(path, kSampleRate, error), error.c_str());
        for (std::size_t at = 0; at < in.size(); at += 1000)
            QVERIFY(out.append(std::span(in).subspan(at, std::min<std::size_t>(1000, in.size() - at))));
        // Readable before it is closed: the header is kept up to date.
        const auto partial = WavFile::read(path, error);
        QVERIFY2(partial, error.c_str());
        QVERIFY(partial->samples == in);
    }
    std::string error;
    const auto back = WavFile::read(path, error);
    QVERIFY2(back, error.c_str());
    QCOMPARE(back->sampleRate, kSampleRate);
    QVERIFY(back->samples == in);
    QVERIFY(!WavFile::read(RCM_SOURCE_DIR "/README.md", error));
    QVERIFY(error.find("not a WAV") != std::string::npos);
}

QTEST_APPLESS_MAIN(TestVoiceCodec)
#include "tst_voicecodec.moc"
