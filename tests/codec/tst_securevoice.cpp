// Voice on a keyed link (codec/voice/SecureVoice.h): the spoken phrase sealed
// two 20 ms frames at a time into 24-byte secure frames, 600 bytes a second,
// and opened again into exactly the frames that went in. Every changed bit,
// a wrong key, the other direction, a frame sent again and one from outside
// the clock's window are refused, counted and never played. One frame is
// pinned byte for byte, so that another implementation can check its own.
#include "codec/secure/SecureCodec.h"
#include "codec/voice/SecureVoice.h"
#include "codec/voice/VoiceCodec.h"
#include "codec/voice/WavFile.h"

#include <QtTest>

#include <algorithm>
#include <cstring>
#include <random>
#include <set>
#include <vector>

using namespace rcm;
using namespace rcm::voice;

namespace {

using Bytes = std::vector<std::uint8_t>;

// 2026-11-26 12:00:00 UTC: where the tests' clocks stand.
constexpr std::int64_t kNow = 1795694400LL * 1000000;

secure::SecretKey keyOf(std::uint8_t seed)
{
    std::array<std::uint8_t, secure::kKeySize> bytes;
    for (std::size_t i = 0; i < bytes.size(); ++i)
        bytes[i] = static_cast<std::uint8_t>(seed + i);
    return secure::SecretKey(bytes);
}

secure::VoiceKeys keys(secure::Direction d = secure::Direction::GcsToUa, std::uint8_t seed = 1)
{
    return secure::deriveVoiceKeys(keyOf(seed), d);
}

std::vector<VoiceFrame> phraseFrames()
{
    std::string error;
    const auto audio = WavFile::read(RCM_SOURCE_DIR "/resources/voice/phrase.wav", error);
    if (!audio)
        qFatal("phrase.wav: %s", error.c_str());
    VoiceEncoder encoder;
    Bytes bytes;
    // Idle before and after, as a talk has it; an odd number of them, so
    // that speech starts in the second half of a secure frame.
    for (int i = 0; i < 3; ++i) {
        bytes.resize(bytes.size() + kFrameBytes);
        encoder.idleFrame(FrameSpan(bytes.data() + bytes.size() - kFrameBytes, kFrameBytes));
    }
    encoder.encode(audio->samples, bytes);
    encoder.finish(bytes);
    for (int i = 0; i < 4; ++i) {
        bytes.resize(bytes.size() + kFrameBytes);
        encoder.idleFrame(FrameSpan(bytes.data() + bytes.size() - kFrameBytes, kFrameBytes));
    }
    std::vector<VoiceFrame> frames(bytes.size() / kFrameBytes);
    for (std::size_t i = 0; i < frames.size(); ++i)
        if (!parseFrame(std::span<const std::uint8_t, kFrameBytes>(bytes.data() + i * kFrameBytes, kFrameBytes),
                        frames[i]))
            qFatal("frame %zu does not parse", i);
    if (frames.size() % 2)
        frames.emplace_back();
    return frames;
}

// The frames sealed in pairs, at the sender's clock `utc`.
Bytes sealAll(const std::vector<VoiceFrame>& frames, const secure::VoiceKeys& k, std::int64_t utc = kNow)
{
    SecureVoiceSealer sealer(k, [utc] { return utc; });
    Bytes out(frames.size() / 2 * kSecureFrameBytes);
    for (std::size_t i = 0; i + 1 < frames.size(); i += 2)
        sealer.seal(frames[i], frames[i + 1],
                    std::span<std::uint8_t, kSecureFrameBytes>(out.data() + i / 2 * kSecureFrameBytes, kSecureFrameBytes));
    return out;
}

// What an opener makes of `bytes`, as parsed plain frames.
std::vector<VoiceFrame> openAll(SecureVoiceOpener& opener, const Bytes& bytes, std::size_t piece = 0)
{
    Bytes plain;
    if (piece == 0) {
        opener.open(bytes, plain);
    } else {
        for (std::size_t at = 0; at < bytes.size(); at += piece)
            opener.open(std::span(bytes).subspan(at, std::min(piece, bytes.size() - at)), plain);
    }
    std::vector<VoiceFrame> frames(plain.size() / kFrameBytes);
    for (std::size_t i = 0; i < frames.size(); ++i)
        if (!parseFrame(std::span<const std::uint8_t, kFrameBytes>(plain.data() + i * kFrameBytes, kFrameBytes),
                        frames[i]))
            qFatal("opened frame %zu does not parse", i);
    return frames;
}

// 2,000 frames of random bytes with the sync byte and right parity.
Bytes random2000()
{
    std::mt19937 rng(29);
    Bytes all;
    for (int i = 0; i < 2000; ++i) {
        Bytes random(kSecureFrameBytes);
        for (auto& b : random)
            b = static_cast<std::uint8_t>(rng());
        random[0] = kSecureSyncByte;
        addParity(random);
        all.insert(all.end(), random.begin(), random.end());
    }
    return all;
}

bool sameContent(const VoiceFrame& a, const VoiceFrame& b)
{
    return a.kind == b.kind && (a.kind == FrameKind::Idle || a.payload == b.payload);
}

#define KNOWN_ANSWER "e8 c0 bc 9a 25 f9 3f 66 04 65 2d 07 09 59 7a d6 3b 60 ab 71 7b 32 1e 84"

QString hex(std::span<const std::uint8_t> bytes)
{
    return QString::fromLatin1(QByteArray(reinterpret_cast<const char*>(bytes.data()), qsizetype(bytes.size())).toHex(' '));
}

}  // namespace

class TestSecureVoice : public QObject {
    Q_OBJECT

private slots:
    void keysAreDomainSeparated();
    void knownAnswer();
    void phraseRoundTripsExactly();
    void fitsTheVoiceBudgetAndHidesWhatItCarries();
    void everyChangedBitIsRefused();
    void wrongKeyOrDirectionIsRefused();
    void replayedFramesAreRefused();
    void outsideTheWindowIsRefused();
    void lostFramesKeepTheTiming();
    void oneByteErrorIsCorrectedAndGarbageSkipped();
};

void TestSecureVoice::keysAreDomainSeparated()
{
    const secure::SecretKey psk = keyOf(7);
    const secure::VoiceKeys up = secure::deriveVoiceKeys(psk, secure::Direction::GcsToUa);
    const secure::VoiceKeys down = secure::deriveVoiceKeys(psk, secure::Direction::UaToGcs);
    const secure::SecretKey frames = secure::deriveDirectionKey(psk, secure::Direction::GcsToUa);
    const std::vector<std::span<const std::uint8_t, secure::kKeySize>> all = {
        up.cipher.bytes(), up.mac.bytes(), down.cipher.bytes(), down.mac.bytes(), frames.bytes(), psk.bytes()};
    for (std::size_t i = 0; i < all.size(); ++i)
        for (std::size_t j = i + 1; j < all.size(); ++j)
            QVERIFY2(std::memcmp(all[i].data(), all[j].data(), secure::kKeySize) != 0, qPrintable(QString("%1 %2").arg(i).arg(j)));
    QCOMPARE(QString::fromStdString(secure::voiceKeyInfo(secure::Direction::GcsToUa, false)),
             QStringLiteral("RCM-GCS v1 voice AES-256-CTR GCS->UA"));
    QCOMPARE(QString::fromStdString(secure::voiceKeyInfo(secure::Direction::UaToGcs, true)),
             QStringLiteral("RCM-GCS v1 voice HMAC-SHA256 UA->GCS"));
    // The same derivation through OpenSSL's other path: HKDF by hand from HMAC.
    std::array<std::uint8_t, 32> expected;
    const std::string info = secure::voiceKeyInfo(secure::Direction::GcsToUa, true);
    QVERIFY(secure::hkdfSha256({}, psk.bytes(), {reinterpret_cast<const std::uint8_t*>(info.data()), info.size()},
                               expected));
    QVERIFY(std::memcmp(expected.data(), up.mac.bytes().data(), 32) == 0);
}

// One frame byte for byte (docs/protocol.md section 7): key bytes 01 02 .. 20,
// GCS->UA, the clock at 2026-11-26 12:00:00 UTC (counter 44892360000), the
// first half speech with the Codec 2 bytes 00 11 22 .. 77, the second idle.
void TestSecureVoice::knownAnswer()
{
    SecureVoiceSealer sealer(keys(), [] { return kNow; });
    VoiceFrame speech;
    speech.kind = FrameKind::Speech;
    for (std::size_t i = 0; i < kCodec2Bytes; ++i)
        speech.payload[i] = static_cast<std::uint8_t>(0x11 * i);
    std::array<std::uint8_t, kSecureFrameBytes> out;
    sealer.seal(speech, VoiceFrame{}, out);
    QCOMPARE(counterAt(kNow), std::uint64_t(44892360000));
    QCOMPARE(out[0], kSecureSyncByte);
    QCOMPARE(out[1] & 0x3F, int(44892360000ULL % 64));
    QCOMPARE(hex(out), QStringLiteral(KNOWN_ANSWER));
}

void TestSecureVoice::phraseRoundTripsExactly()
{
    const std::vector<VoiceFrame> frames = phraseFrames();
    const Bytes sealed = sealAll(frames, keys());
    for (const std::size_t piece : {std::size_t(0), std::size_t(1), std::size_t(7), std::size_t(24), std::size_t(100)}) {
        SecureVoiceOpener opener(keys(), [] { return kNow + 500000; });
        const std::vector<VoiceFrame> opened = openAll(opener, sealed, piece);
        QCOMPARE(opened.size(), frames.size());
        for (std::size_t i = 0; i < frames.size(); ++i)
            QVERIFY2(sameContent(opened[i], frames[i]), qPrintable(QString("frame %1, pieces of %2").arg(i).arg(piece)));
        // The sequence follows the counter: consecutive.
        for (std::size_t i = 1; i < opened.size(); ++i)
            QCOMPARE(opened[i].sequence, std::uint8_t((opened[i - 1].sequence + 1) % kSequenceModulus));
        QCOMPARE(opener.stats().accepted, std::uint64_t(frames.size() / 2));
        QCOMPARE(opener.stats().forged + opener.stats().replayed + opener.stats().lostFrames, std::uint64_t(0));
    }
}

void TestSecureVoice::fitsTheVoiceBudgetAndHidesWhatItCarries()
{
    QCOMPARE(kSecureFrameBytes * kSecureFramesPerSecond, std::size_t(600));
    const std::vector<VoiceFrame> frames = phraseFrames();
    const Bytes sealed = sealAll(frames, keys());
    QCOMPARE(sealed.size(), frames.size() * kFrameBytes);  // the same bytes as the plain frames: 600 a second
    // No Codec 2 bytes in the clear, and idle frames unlike one another: a
    // listener cannot tell speech from silence by the bytes.
    std::set<QString> idlePayloads;
    std::array<int, 4> flagPatterns{};
    for (std::size_t f = 0; f < sealed.size() / kSecureFrameBytes; ++f) {
        const std::uint8_t* s = sealed.data() + f * kSecureFrameBytes;
        for (std::size_t h = 0; h < 2; ++h) {
            const VoiceFrame& plain = frames[2 * f + h];
            if (plain.kind == FrameKind::Speech)
                QVERIFY(std::memcmp(s + 2 + 8 * h, plain.payload.data(), 8) != 0);
        }
        if (frames[2 * f].kind == FrameKind::Idle && frames[2 * f + 1].kind == FrameKind::Idle)
            idlePayloads.insert(hex({s + 2, 16}));
        if (frames[2 * f].kind == FrameKind::Speech && frames[2 * f + 1].kind == FrameKind::Speech)
            ++flagPatterns[s[1] >> 6];
    }
    QVERIFY(idlePayloads.size() >= 3);  // every idle frame different
    QVERIFY(std::count_if(flagPatterns.begin(), flagPatterns.end(), [](int n) { return n > 0; }) >= 3);
}

// Any change to the frame's bytes, parity made right again so that RS
// passes: refused as forged, nothing played.
void TestSecureVoice::everyChangedBitIsRefused()
{
    const std::vector<VoiceFrame> frames = phraseFrames();
    const Bytes sealed = sealAll(frames, keys());
    const Bytes first(sealed.begin() + 10 * kSecureFrameBytes, sealed.begin() + 11 * kSecureFrameBytes);
    std::uint64_t tried = 0;
    for (std::size_t bit = 8; bit < 22 * 8; ++bit) {
        Bytes changed = first;
        changed[bit / 8] ^= static_cast<std::uint8_t>(0x80 >> (bit % 8));
        addParity(changed);
        SecureVoiceOpener opener(keys(), [] { return kNow; });
        Bytes plain;
        opener.open(changed, plain);
        QVERIFY2(plain.empty(), qPrintable(QString("bit %1 passed").arg(bit)));
        QCOMPARE(opener.stats().forged, std::uint64_t(1));
        ++tried;
    }
    // Random frames with the sync and right parity.
    SecureVoiceOpener opener(keys(), [] { return kNow; });
    Bytes plain;
    opener.open(random2000(), plain);
    QVERIFY(plain.empty());
    QCOMPARE(opener.stats().forged, std::uint64_t(2000));
    QCOMPARE(opener.stats().accepted, std::uint64_t(0));
    // A flood costs at most the budget of window searches a second (the
    // clock stands still here): the rest are refused unchecked.
    QCOMPARE(opener.stats().unchecked, std::uint64_t(2000 - SecureVoiceOpener::kMaxSearchesPerSecond));
    // And the genuine stream still opens: in step, a frame needs no search.
    const Bytes genuine = sealAll(frames, keys());
    opener.open(genuine, plain);
    QCOMPARE(opener.stats().accepted, std::uint64_t(0));  // its first frame needed a search: over the budget
    std::int64_t later = kNow + 1000000;
    SecureVoiceOpener next(keys(), [&later] { return later; });
    next.open(random2000(), plain);
    later += 1000000;  // a second on: the budget is there again
    plain.clear();
    next.open(genuine, plain);
    QCOMPARE(next.stats().accepted, std::uint64_t(genuine.size() / kSecureFrameBytes));
    QCOMPARE(tried, std::uint64_t(21 * 8));
}

void TestSecureVoice::wrongKeyOrDirectionIsRefused()
{
    const Bytes sealed = sealAll(phraseFrames(), keys());
    for (const secure::VoiceKeys& wrong :
         {keys(secure::Direction::UaToGcs), keys(secure::Direction::GcsToUa, 2)}) {
        SecureVoiceOpener opener(wrong, [] { return kNow; });
        Bytes plain;
        opener.open(sealed, plain);
        QVERIFY(plain.empty());
        QVERIFY(opener.stats().forged > 0);
        QCOMPARE(opener.stats().accepted, std::uint64_t(0));
    }
}

// A frame accepted once is never played again, in step or hunting; a frame
// from before the last accepted one (a recording) neither.
void TestSecureVoice::replayedFramesAreRefused()
{
    const std::vector<VoiceFrame> frames = phraseFrames();
    const Bytes sealed = sealAll(frames, keys());
    const auto frame = [&](std::size_t i) {
        return Bytes(sealed.begin() + std::ptrdiff_t(i * kSecureFrameBytes),
                     sealed.begin() + std::ptrdiff_t((i + 1) * kSecureFrameBytes));
    };
    SecureVoiceOpener opener(keys(), [] { return kNow; });
    Bytes stream;
    const auto append = [&](std::size_t i) {
        const Bytes f = frame(i);
        stream.insert(stream.end(), f.begin(), f.end());
    };
    for (std::size_t i = 0; i < 10; ++i)
        append(i);
    for (const std::size_t again : {std::size_t(9), std::size_t(5), std::size_t(0)})
        append(again);
    for (std::size_t i = 10; i < 12; ++i)
        append(i);
    const std::vector<VoiceFrame> opened = openAll(opener, stream);
    QCOMPARE(opener.stats().replayed, std::uint64_t(3));
    QCOMPARE(opener.stats().accepted, std::uint64_t(12));
    QCOMPARE(opened.size(), std::size_t(24));
    for (std::size_t i = 0; i < opened.size(); ++i)
        QVERIFY(sameContent(opened[i], frames[i]));
    QCOMPARE(opener.stats().lostFrames, std::uint64_t(0));
}

void TestSecureVoice::outsideTheWindowIsRefused()
{
    const Bytes sealed = sealAll(phraseFrames(), keys());
    for (const std::int64_t offset : {-31LL * 1000000, 40LL * 1000000, 3600LL * 1000000}) {
        SecureVoiceOpener opener(keys(), [offset] { return kNow + offset; });
        Bytes plain;
        opener.open(sealed, plain);
        QVERIFY2(plain.empty(), qPrintable(QString::number(offset)));
        QCOMPARE(opener.stats().accepted, std::uint64_t(0));
    }
    SecureVoiceOpener near(keys(), [] { return kNow - 25LL * 1000000; });
    Bytes plain;
    near.open(sealed, plain);
    QCOMPARE(near.stats().accepted, std::uint64_t(sealed.size() / kSecureFrameBytes));
}

// Frames lost in the middle, and an outage of more than 64 of them: the
// decoder gets the silence the counter says, so the phrase keeps its time.
void TestSecureVoice::lostFramesKeepTheTiming()
{
    const std::vector<VoiceFrame> frames = phraseFrames();
    const Bytes sealed = sealAll(frames, keys());
    for (const std::size_t gap : {std::size_t(3), std::size_t(40)}) {
        Bytes cut = sealed;
        cut.erase(cut.begin() + 20 * kSecureFrameBytes, cut.begin() + std::ptrdiff_t((20 + gap) * kSecureFrameBytes));
        SecureVoiceOpener opener(keys(), [] { return kNow; });
        Bytes plain;
        opener.open(cut, plain);
        QCOMPARE(opener.stats().lostFrames, std::uint64_t(gap));
        QCOMPARE(opener.stats().accepted, std::uint64_t(sealed.size() / kSecureFrameBytes - gap));
        VoiceDecoder decoder;
        std::vector<std::int16_t> pcm;
        decoder.decode(plain, pcm);
        // The decoder places the frames by their sequence, modulo 64 slots.
        QCOMPARE(decoder.stats().lostFrames, std::uint64_t(2 * gap % kSequenceModulus));
    }
}

void TestSecureVoice::oneByteErrorIsCorrectedAndGarbageSkipped()
{
    const std::vector<VoiceFrame> frames = phraseFrames();
    Bytes sealed = sealAll(frames, keys());
    std::mt19937 rng(5);
    for (std::size_t f = 0; f < sealed.size() / kSecureFrameBytes; ++f)
        sealed[f * kSecureFrameBytes + rng() % kSecureFrameBytes] ^= static_cast<std::uint8_t>(1 + rng() % 255);
    Bytes stream(97);
    for (auto& b : stream)
        b = static_cast<std::uint8_t>(rng());
    stream.insert(stream.end(), sealed.begin(), sealed.end());
    SecureVoiceOpener opener(keys(), [] { return kNow; });
    const std::vector<VoiceFrame> opened = openAll(opener, stream, 50);
    QCOMPARE(opened.size(), frames.size());
    for (std::size_t i = 0; i < frames.size(); ++i)
        QVERIFY(sameContent(opened[i], frames[i]));
    QCOMPARE(opener.stats().correctedFrames, std::uint64_t(sealed.size() / kSecureFrameBytes));
    QCOMPARE(opener.stats().forged, std::uint64_t(0));
}

QTEST_GUILESS_MAIN(TestSecureVoice)
#include "tst_securevoice.moc"
