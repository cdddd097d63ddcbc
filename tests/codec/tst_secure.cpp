// The secure link (codec/secure/SecureCodec.h) against an attacker without the key
// who can listen, inject, replay and re-encode Reed-Solomon at will.
//
// Because such an attacker re-encodes RS, what reaches the receiver's
// decipher step is exactly the two 223-byte ciphertext blocks the attacker
// chose; the RS parity bytes are not a defence. So the tamper tests hand the
// changed blocks straight to SecureCodec::decryptBlocks (the step after RS
// decoding) instead of going through RS: the same decision, a fraction of
// the time. One test goes the whole way through RS to show the two agree.
//
// Deterministic: fixed seeds, an injected clock, no sleeps.

#include "RandomMessage.h"

#include "codec/frame/Frame.h"
#include "codec/message/MessageDecoder.h"
#include "codec/message/MessageEncoder.h"
#include "codec/secure/SecureCodec.h"

#include <openssl/evp.h>
#include <openssl/kdf.h>

#include <QTemporaryDir>
#include <QtTest>

#include <sys/stat.h>

#include <array>
#include <cctype>
#include <cstdio>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

using namespace rcm;
using namespace rcm::secure;

namespace {

// Thursday 2026-11-12 10:20:30 UTC, the tests' "now".
constexpr std::uint32_t kTime = 102030;
constexpr std::uint32_t kDate = 261112;

std::int64_t nowSeconds() { return *stampSeconds(kTime, kDate); }

SecretKey keyFromSeed(std::uint64_t seed)
{
    std::mt19937_64 rng(seed);
    std::array<std::uint8_t, kKeySize> b{};
    for (auto& x : b)
        x = static_cast<std::uint8_t>(rng());
    return SecretKey(b);
}

std::vector<std::uint8_t> hex(const char* s)
{
    std::vector<std::uint8_t> out;
    for (std::size_t i = 0; s[i] && s[i + 1]; i += 2)
        out.push_back(static_cast<std::uint8_t>(std::stoi(std::string(s + i, 2), nullptr, 16)));
    return out;
}

std::string toHex(std::span<const std::uint8_t> b)
{
    std::string s;
    char buf[3];
    for (std::uint8_t x : b) {
        std::snprintf(buf, sizeof buf, "%02x", x);
        s += buf;
    }
    return s;
}

// A random valid message that fits the secure link: the three header items
// set, BLOCK 1 items within 223 - 16 bytes, at most 199 flight plan bytes.
Message secureMessage(std::mt19937_64& rng, std::uint32_t id, std::uint32_t time = kTime,
                      std::uint32_t date = kDate)
{
    Message m = test::randomMessage(rng);
    m.header.set(ItemId::ID_msg, id);
    m.header.set(ItemId::time_UTC, time);
    m.header.set(ItemId::date_UTC, date);
    while (block1ItemBytes(m) > kBlockSize - kMinBlock1Padding) {
        for (UnitKind kind : {UnitKind::Camera, UnitKind::Radio, UnitKind::Engine}) {
            auto& units = *m.repeated(kind);
            if (!units.empty() && block1ItemBytes(m) > kBlockSize - kMinBlock1Padding)
                units.pop_back();
        }
    }
    if (m.flightPlan.data.size() > kMaxFlightPlanData)
        m.flightPlan.data.resize(kMaxFlightPlanData);
    return m;
}

DecodedBlocks asReceived(const EncodedBlocks& b)
{
    DecodedBlocks d;
    d.block1 = b.block1;
    d.block2 = b.block2;
    return d;
}

EncodedBlocks sealed(const SecureCodec& codec, const Message& m)
{
    Diagnostics errors;
    const std::optional<EncodedBlocks> b = codec.encode(m, errors);
    if (!b) {
        std::string all;
        for (const Diagnostic& d : errors)
            all += d.toString() + "\n";
        qFatal("encode failed: %s", all.c_str());
    }
    return *b;
}

ReplayGuard::Options guardOptions(std::int64_t* now)
{
    ReplayGuard::Options o;
    o.clock = [now] { return *now; };
    return o;
}

std::string readFile(const std::string& path)
{
    std::ifstream f(path, std::ios::binary);
    std::stringstream s;
    s << f.rdbuf();
    return s.str();
}

void writeFile(const std::string& path, const std::string& text, mode_t mode)
{
    {
        std::ofstream f(path, std::ios::binary | std::ios::trunc);
        f << text;
    }
    ::chmod(path.c_str(), mode);
}

}  // namespace

class TestSecure : public QObject {
    Q_OBJECT

private slots:
    // ---- key derivation
    void hkdfRfc5869();
    void derivationMatchesOpenSslDirectly();
    void tweakBytes();

    // ---- round trip
    void roundTripBothDirections();
    void throughReedSolomon();
    void senderRefusesWhatReceiverWouldReject();

    // ---- the attacker
    void everySingleBitAndByteChangeIsRejected();
    void randomCiphertextsAreRejected();
    void splicedBlock2IsRejected();
    void otherDirectionIsRejected();
    void wrongKeyIsRejected();
    void plaintextFrameIsRejected();
    void replayedFrameIsRejectedNextFreshAccepted();
    void timeWindow();
    void messageIdWrapsAround();
    void refusedFramesDoNotAdvanceTheGuard();
    void uncorrectableCodewords();

    // ---- keys and state on disk
    void keyFileRoundTrip();
    void keyFileReadableByOthersIsRefused();
    void keyFileWithBadContentIsRefused();
    void replayStateSurvivesRestart();
    void replayStateUnderAnotherKeyOrCorrupt();
    void messageCounterNeverReusesAnId();
};

// ------------------------------------------------------------------ derivation

void TestSecure::hkdfRfc5869()
{
    // RFC 5869 A.1: SHA-256 with salt and info.
    {
        const auto ikm = hex("0b0b0b0b0b0b0b0b0b0b0b0b0b0b0b0b0b0b0b0b0b0b");
        const auto salt = hex("000102030405060708090a0b0c");
        const auto info = hex("f0f1f2f3f4f5f6f7f8f9");
        std::array<std::uint8_t, 42> okm{};
        QVERIFY(hkdfSha256(salt, ikm, info, okm));
        QCOMPARE(toHex(okm), std::string("3cb25f25faacd57a90434f64d0362f2a2d2d0a90cf1a5a4c5db02d56ecc4c5bf"
                                         "34007208d5b887185865"));
    }
    // RFC 5869 A.3: no salt, no info, the case our derivation relies on for the salt.
    {
        const auto ikm = hex("0b0b0b0b0b0b0b0b0b0b0b0b0b0b0b0b0b0b0b0b0b0b");
        std::array<std::uint8_t, 42> okm{};
        QVERIFY(hkdfSha256({}, ikm, {}, okm));
        QCOMPARE(toHex(okm), std::string("8da4e775a563c18f715f802a063c5a31b8a11f5c5ee1879ec3454e5f3c738d2d"
                                         "9d201395faa4b61a96c8"));
    }
}

// Our derivation against OpenSSL's other HKDF interface (EVP_PKEY_derive),
// with the salt spelled out as RFC 5869's default of 32 zero bytes and the
// info strings as documented.
void TestSecure::derivationMatchesOpenSslDirectly()
{
    const SecretKey psk = keyFromSeed(7);
    auto viaPkey = [&](std::string_view info, std::size_t len) {
        std::vector<std::uint8_t> out(len);
        const std::array<std::uint8_t, 32> zeros{};
        EVP_PKEY_CTX* ctx = EVP_PKEY_CTX_new_id(EVP_PKEY_HKDF, nullptr);
        bool ok = ctx && EVP_PKEY_derive_init(ctx) == 1 && EVP_PKEY_CTX_set_hkdf_md(ctx, EVP_sha256()) == 1 &&
                  EVP_PKEY_CTX_set1_hkdf_salt(ctx, zeros.data(), 32) == 1 &&
                  EVP_PKEY_CTX_set1_hkdf_key(ctx, psk.bytes().data(), 32) == 1 &&
                  EVP_PKEY_CTX_add1_hkdf_info(ctx, reinterpret_cast<const unsigned char*>(info.data()),
                                              static_cast<int>(info.size())) == 1;
        std::size_t n = len;
        ok = ok && EVP_PKEY_derive(ctx, out.data(), &n) == 1 && n == len;
        EVP_PKEY_CTX_free(ctx);
        if (!ok)
            qFatal("EVP_PKEY HKDF failed");
        return toHex(out);
    };
    QCOMPARE(std::string(keyInfo(Direction::GcsToUa)), std::string("RCM-GCS v1 AES-256-HCTR2 GCS->UA"));
    QCOMPARE(std::string(keyInfo(Direction::UaToGcs)), std::string("RCM-GCS v1 AES-256-HCTR2 UA->GCS"));
    const SecretKey up = deriveDirectionKey(psk, Direction::GcsToUa);
    const SecretKey down = deriveDirectionKey(psk, Direction::UaToGcs);
    QCOMPARE(toHex(up.bytes()), viaPkey("RCM-GCS v1 AES-256-HCTR2 GCS->UA", 32));
    QCOMPARE(toHex(down.bytes()), viaPkey("RCM-GCS v1 AES-256-HCTR2 UA->GCS", 32));
    QVERIFY(toHex(up.bytes()) != toHex(down.bytes()));
    QVERIFY(toHex(up.bytes()) != toHex(psk.bytes()));
    QCOMPARE(fingerprint(psk), viaPkey("RCM-GCS v1 key fingerprint", 8));
    QCOMPARE(fingerprint(psk).size(), std::size_t(16));
}

void TestSecure::tweakBytes()
{
    QCOMPARE(toHex(block1Tweak(Direction::GcsToUa)), std::string("52434d010101"));
    QCOMPARE(toHex(block1Tweak(Direction::UaToGcs)), std::string("52434d010201"));
    const HeaderStamp s{133, 163523, 71114};  // ID_msg 133, 16:35:23, 2007-11-14
    QCOMPARE(toHex(block2Tweak(Direction::GcsToUa, s)), std::string("52434d010102" "000085" "027ec3" "0115ca"));
    QCOMPARE(toHex(block2Tweak(Direction::UaToGcs, s)), std::string("52434d010202" "000085" "027ec3" "0115ca"));
}

// ------------------------------------------------------------------ round trip

void TestSecure::roundTripBothDirections()
{
    std::mt19937_64 rng(1);
    const SecretKey psk = keyFromSeed(1);
    for (Direction dir : {Direction::GcsToUa, Direction::UaToGcs}) {
        const SecureCodec codec(psk, dir);
        for (int i = 0; i < 1000; ++i) {
            const Message m = secureMessage(rng, static_cast<std::uint32_t>(i));
            Diagnostics errors;
            const EncodedBlocks plain = *encodeBlocks(m, errors, encodeOptions());
            const EncodedBlocks c = sealed(codec, m);
            QVERIFY(c.block1 != plain.block1);
            QVERIFY(c.block2 != plain.block2);
            const Authenticated a = codec.decryptBlocks(asReceived(c));
            QVERIFY2(a.authentic, a.detail.c_str());
            QVERIFY(!a.rejection);
            QVERIFY(a.decoded.diagnostics.empty());
            QCOMPARE(a.decoded.message, m);
            QCOMPARE(a.stamp, (HeaderStamp{static_cast<std::uint32_t>(i), kTime, kDate}));
        }
    }
}

// The whole way: frame bytes, RS with errors, then the secure receive path.
void TestSecure::throughReedSolomon()
{
    std::mt19937_64 rng(2);
    const SecretKey psk = keyFromSeed(2);
    const SecureCodec codec(psk, Direction::GcsToUa);
    std::int64_t now = nowSeconds();
    ReplayGuard guard(guardOptions(&now));
    for (std::uint32_t id = 1; id <= 50; ++id) {
        const Message m = secureMessage(rng, id);
        const EncodedBlocks c = sealed(codec, m);
        FrameBytes frame = makeFrame(c.block1, c.block2);
        for (int e = 0; e < 16; ++e) {  // 16 byte errors in each codeword: still correctable
            frame[kPreambleSize + static_cast<std::size_t>(e) * 15] ^= 0xA5;
            frame[kPreambleSize + kCodewordSize + static_cast<std::size_t>(e) * 15] ^= 0x3C;
        }
        const DecodedBlocks d =
            decodeCodewords(std::span<const std::uint8_t, kDatagramSize>(frame.data() + kPreambleSize, kDatagramSize));
        QCOMPARE(d.corrected.block1, 16);
        QCOMPARE(d.corrected.block2, 16);
        const Opened o = openFrame(codec, &guard, d);
        QVERIFY2(o.accepted, o.detail.c_str());
        QCOMPARE(o.decoded.message, m);
        QCOMPARE(o.decoded.corrected.block1, 16);

        // And a change to the ciphertext that the attacker RS-encodes anew.
        EncodedBlocks t = c;
        t.block1[100] ^= 0x01;
        const DatagramBytes forged = makeDatagram(t.block1, t.block2);
        const DecodedBlocks fd = decodeCodewords(forged);
        QCOMPARE(fd.corrected.block1, 0);
        const Opened f = openFrame(codec, &guard, fd);
        QVERIFY(!f.accepted);
        QCOMPARE(f.rejection, std::optional<Rejection>(Rejection::Forged));
    }
}

void TestSecure::senderRefusesWhatReceiverWouldReject()
{
    std::mt19937_64 rng(3);
    const SecureCodec codec(keyFromSeed(3), Direction::GcsToUa);
    Message m = secureMessage(rng, 5);

    // Each of the three header items is required.
    for (ItemId id : {ItemId::ID_msg, ItemId::time_UTC, ItemId::date_UTC}) {
        Message n = m;
        n.header.erase(id);
        Diagnostics errors;
        QVERIFY(!codec.encode(n, errors));
        QVERIFY(!errors.empty());
        QCOMPARE(errors.back().kind, Diagnostic::Kind::MissingKey);
        QVERIFY(errors.back().message.find(std::string(itemInfo(id).name)) != std::string::npos);
    }
    // 200 flight plan bytes: one more than a secure section carries.
    {
        Message n = m;
        n.flightPlan.planId = 9;
        n.flightPlan.data.assign(200, 0x11);
        Diagnostics errors;
        QVERIFY(!codec.encode(n, errors));
        QCOMPARE(errors.front().kind, Diagnostic::Kind::DoesNotFit);
        n.flightPlan.data.resize(199);
        QVERIFY(codec.encode(n, errors));
    }
    // Blocks encoded without the secure options and with fewer than 16
    // padding bytes: encryptBlocks refuses them.
    {
        Message n;
        n.header.set(ItemId::ID_msg, 1);
        n.header.set(ItemId::time_UTC, kTime);
        n.header.set(ItemId::date_UTC, kDate);
        n.header.set(ItemId::ID_UA_source, Value::pair(44, 133));
        for (int e = 0; n.engines.size() < 60 && block1ItemBytes(n) + 5 <= kBlockSize - 10; ++e) {
            Unit& u = n.addEngine(static_cast<std::uint8_t>(e));
            u.set(ItemId::eng_prop_pitch, 1);
        }
        Diagnostics errors;
        EncodedBlocks b = *encodeBlocks(n, errors);
        const EncodedBlocks before = b;
        std::string error;
        QVERIFY(!codec.encryptBlocks(b, error));
        QVERIFY(error.find("16 padding bytes") != std::string::npos);
        QVERIFY(b.block1 == before.block1);
        QVERIFY(!codec.encode(n, errors));
        QCOMPARE(errors.front().kind, Diagnostic::Kind::DoesNotFit);
    }
}

// ------------------------------------------------------------------ attacker

void TestSecure::everySingleBitAndByteChangeIsRejected()
{
    // 1,000 random frames. For every one of the 446 ciphertext bytes: each of
    // its 8 single-bit flips, and one change of the whole byte to a random
    // other value. For the first 4 frames, every one of the 255 other values
    // of every byte. Each changed frame must be rejected as forged.
    std::mt19937_64 rng(4);
    const SecretKey psk = keyFromSeed(4);
    const SecureCodec codec(psk, Direction::GcsToUa);
    std::uint64_t checked = 0, rejected = 0;
    for (int f = 0; f < 1000; ++f) {
        const Message m = secureMessage(rng, static_cast<std::uint32_t>(f));
        const DecodedBlocks good = asReceived(sealed(codec, m));
        QVERIFY(codec.decryptBlocks(good).authentic);
        auto attempt = [&](std::size_t pos, std::uint8_t mask) {
            DecodedBlocks t = good;
            Block& b = pos < kBlockSize ? t.block1 : t.block2;
            b[pos % kBlockSize] ^= mask;
            const Authenticated a = codec.decryptBlocks(t);
            ++checked;
            if (!a.authentic && a.rejection == Rejection::Forged)
                ++rejected;
            else
                qWarning("frame %d byte %zu mask %02x: not rejected as forged", f, pos, mask);
        };
        for (std::size_t pos = 0; pos < 2 * kBlockSize; ++pos) {
            for (int bit = 0; bit < 8; ++bit)
                attempt(pos, static_cast<std::uint8_t>(1u << bit));
            if (f < 4) {
                for (unsigned mask = 1; mask < 256; ++mask)
                    if ((mask & (mask - 1)) != 0)  // the single bits were done above
                        attempt(pos, static_cast<std::uint8_t>(mask));
            } else {
                std::uint8_t mask;
                do
                    mask = static_cast<std::uint8_t>(rng());
                while ((mask & (mask - 1)) == 0);  // a byte change that is not a single bit
                attempt(pos, mask);
            }
        }
    }
    qInfo("%llu changed frames, %llu rejected as forged", static_cast<unsigned long long>(checked),
          static_cast<unsigned long long>(rejected));
    QCOMPARE(checked, std::uint64_t(996) * 446 * 9 + std::uint64_t(4) * 446 * 255);
    QCOMPARE(rejected, checked);
}

void TestSecure::randomCiphertextsAreRejected()
{
    std::mt19937_64 rng(5);
    const SecureCodec up(keyFromSeed(5), Direction::GcsToUa);
    const SecureCodec down(keyFromSeed(5), Direction::UaToGcs);
    int rejected = 0;
    const int n = 100000;
    for (int i = 0; i < n; ++i) {
        DecodedBlocks d;
        for (auto& x : d.block1)
            x = static_cast<std::uint8_t>(rng());
        for (auto& x : d.block2)
            x = static_cast<std::uint8_t>(rng());
        const Authenticated a = (i & 1 ? down : up).decryptBlocks(d);
        rejected += !a.authentic && a.rejection == Rejection::Forged;
    }
    QCOMPARE(rejected, n);
}

void TestSecure::splicedBlock2IsRejected()
{
    std::mt19937_64 rng(6);
    const SecureCodec codec(keyFromSeed(6), Direction::GcsToUa);
    for (std::uint32_t i = 0; i < 200; ++i) {
        // Two messages with identical BLOCK 2 plaintext, differing only in
        // ID_msg, then in time, then in date: BLOCK 2 moved from one to the
        // other is refused.
        Message a = secureMessage(rng, 1000 + i);
        a.flightPlan.planId = 0xDEADBEEF;
        a.flightPlan.sectionId = static_cast<std::uint16_t>(i);
        a.flightPlan.data.assign(50, static_cast<std::uint8_t>(i));
        for (int which = 0; which < 3; ++which) {
            Message b = a;
            if (which == 0)
                b.header.set(ItemId::ID_msg, 1001 + i);
            else if (which == 1)
                b.header.set(ItemId::time_UTC, kTime + 1);
            else
                b.header.set(ItemId::date_UTC, kDate + 1);
            const EncodedBlocks ca = sealed(codec, a);
            const EncodedBlocks cb = sealed(codec, b);
            QVERIFY(ca.block2 != cb.block2);  // same plaintext, different tweak
            DecodedBlocks spliced = asReceived(ca);
            spliced.block2 = cb.block2;
            const Authenticated r = codec.decryptBlocks(spliced);
            QVERIFY(!r.authentic);
            QCOMPARE(r.rejection, std::optional<Rejection>(Rejection::Forged));
            QVERIFY(r.detail.find("BLOCK 2") != std::string::npos);
        }
        // And BLOCK 2 of an unrelated message.
        const Message c = secureMessage(rng, 5000 + i);
        DecodedBlocks spliced = asReceived(sealed(codec, a));
        spliced.block2 = sealed(codec, c).block2;
        QCOMPARE(codec.decryptBlocks(spliced).rejection, std::optional<Rejection>(Rejection::Forged));
    }
}

// A GCS->UA frame reflected back at the GCS (or the reverse) is refused.
void TestSecure::otherDirectionIsRejected()
{
    std::mt19937_64 rng(7);
    const SecretKey psk = keyFromSeed(7);
    const SecureCodec up(psk, Direction::GcsToUa);
    const SecureCodec down(psk, Direction::UaToGcs);
    for (std::uint32_t i = 0; i < 500; ++i) {
        const Message m = secureMessage(rng, i);
        QCOMPARE(down.decryptBlocks(asReceived(sealed(up, m))).rejection,
                 std::optional<Rejection>(Rejection::Forged));
        QCOMPARE(up.decryptBlocks(asReceived(sealed(down, m))).rejection,
                 std::optional<Rejection>(Rejection::Forged));
    }
}

void TestSecure::wrongKeyIsRejected()
{
    std::mt19937_64 rng(8);
    const SecureCodec right(keyFromSeed(8), Direction::GcsToUa);
    SecretKey near = keyFromSeed(8);
    near.mutableBytes()[31] ^= 0x01;  // one bit away
    const SecureCodec wrong(near, Direction::GcsToUa);
    const SecureCodec other(keyFromSeed(9), Direction::GcsToUa);
    for (std::uint32_t i = 0; i < 500; ++i) {
        const Message m = secureMessage(rng, i);
        const DecodedBlocks d = asReceived(sealed(right, m));
        QVERIFY(right.decryptBlocks(d).authentic);
        QCOMPARE(wrong.decryptBlocks(d).rejection, std::optional<Rejection>(Rejection::Forged));
        QCOMPARE(other.decryptBlocks(d).rejection, std::optional<Rejection>(Rejection::Forged));
    }
}

// No downgrade: a frame sent without encryption is refused, and named so.
void TestSecure::plaintextFrameIsRejected()
{
    std::mt19937_64 rng(10);
    const SecureCodec codec(keyFromSeed(10), Direction::GcsToUa);
    std::int64_t now = nowSeconds();
    ReplayGuard guard(guardOptions(&now));
    for (std::uint32_t i = 0; i < 500; ++i) {
        const Message m = secureMessage(rng, i);
        for (const EncodeOptions& options : {EncodeOptions{}, encodeOptions()}) {
            Diagnostics errors;
            const EncodedBlocks plain = *encodeBlocks(m, errors, options);
            const Opened o = openFrame(codec, &guard, asReceived(plain));
            QVERIFY(!o.accepted);
            QCOMPARE(o.rejection, std::optional<Rejection>(Rejection::Plaintext));
            QVERIFY(o.decoded.message == Message{});
        }
    }
    QVERIFY(!guard.lastAccepted());
}

void TestSecure::replayedFrameIsRejectedNextFreshAccepted()
{
    std::mt19937_64 rng(11);
    const SecureCodec codec(keyFromSeed(11), Direction::UaToGcs);
    std::int64_t now = nowSeconds();
    ReplayGuard guard(guardOptions(&now));

    const DecodedBlocks first = asReceived(sealed(codec, secureMessage(rng, 41)));
    QVERIFY(openFrame(codec, &guard, first).accepted);
    QCOMPARE(guard.lastAccepted(), std::optional<std::uint32_t>(41));

    const Opened again = openFrame(codec, &guard, first);
    QVERIFY(!again.accepted);
    QCOMPARE(again.rejection, std::optional<Rejection>(Rejection::Replayed));
    QCOMPARE(again.stamp.messageId, 41u);
    QVERIFY(again.detail.find("41") != std::string::npos);

    const DecodedBlocks next = asReceived(sealed(codec, secureMessage(rng, 42)));
    QVERIFY(openFrame(codec, &guard, next).accepted);
    // An older message that was never delivered is refused too: IDs only go forward.
    const DecodedBlocks older = asReceived(sealed(codec, secureMessage(rng, 40)));
    QCOMPARE(openFrame(codec, &guard, older).rejection, std::optional<Rejection>(Rejection::Replayed));
    // A gap (frames lost) is fine.
    QVERIFY(openFrame(codec, &guard, asReceived(sealed(codec, secureMessage(rng, 90)))).accepted);
    QCOMPARE(guard.lastAccepted(), std::optional<std::uint32_t>(90));
}

void TestSecure::timeWindow()
{
    std::mt19937_64 rng(12);
    const SecureCodec codec(keyFromSeed(12), Direction::GcsToUa);
    std::int64_t now = nowSeconds();
    ReplayGuard guard(guardOptions(&now));
    std::uint32_t id = 0;
    auto open = [&](std::uint32_t time, std::uint32_t date) {
        return openFrame(codec, &guard, asReceived(sealed(codec, secureMessage(rng, ++id, time, date))));
    };
    QVERIFY(open(102000, kDate).accepted);  // 30 s behind: the edge of the default window
    QVERIFY(open(102100, kDate).accepted);  // 30 s ahead
    Opened o = open(102101, kDate);         // 31 s ahead
    QCOMPARE(o.rejection, std::optional<Rejection>(Rejection::StaleTime));
    QVERIFY(o.detail.find("31 s ahead") != std::string::npos);
    QCOMPARE(open(101959, kDate).rejection, std::optional<Rejection>(Rejection::StaleTime));
    QCOMPARE(open(kTime, 261111).rejection, std::optional<Rejection>(Rejection::StaleTime));  // a day old
    QCOMPARE(open(kTime, 251112).rejection, std::optional<Rejection>(Rejection::StaleTime));  // a year old

    // Across midnight and the turn of a year.
    now = *stampSeconds(5, 270101);  // 2027-01-01 00:00:05
    QVERIFY(open(235950, 261231).accepted);
    QVERIFY(open(20, 270101).accepted);
    QCOMPARE(open(235930, 261231).rejection, std::optional<Rejection>(Rejection::StaleTime));

    // A configurable window.
    ReplayGuard::Options wide = guardOptions(&now);
    wide.windowSeconds = 120;
    ReplayGuard wideGuard(wide);
    const DecodedBlocks late = asReceived(sealed(codec, secureMessage(rng, ++id, 235830, 261231)));  // 95 s
    QCOMPARE(openFrame(codec, &guard, late).rejection, std::optional<Rejection>(Rejection::StaleTime));
    QVERIFY(openFrame(codec, &wideGuard, late).accepted);

    // Calendar arithmetic.
    QCOMPARE(*stampSeconds(0, 101), std::int64_t(946684800));  // 2000-01-01
    QCOMPARE(*stampSeconds(235959, 991231), std::int64_t(4102444799));  // 2099-12-31 23:59:59
    QVERIFY(!stampSeconds(240000, kDate));
    QVERIFY(!stampSeconds(kTime, 260230));  // 30 February
    QVERIFY(stampSeconds(kTime, 240229));   // 2024 is a leap year
}

void TestSecure::messageIdWrapsAround()
{
    constexpr std::uint32_t kMax = kMessageIdModulus - 1;
    QVERIFY(messageIdAhead(1, 0));
    QVERIFY(!messageIdAhead(0, 0));
    QVERIFY(!messageIdAhead(0, 1));
    QVERIFY(messageIdAhead(0, kMax));
    QVERIFY(messageIdAhead(5, kMax - 5));
    QVERIFY(messageIdAhead((1u << 23) - 1, 0));  // just under half the space
    QVERIFY(!messageIdAhead(1u << 23, 0));       // half: refused
    QVERIFY(!messageIdAhead(kMax, 0));           // one behind, across the wrap

    std::mt19937_64 rng(13);
    const SecureCodec codec(keyFromSeed(13), Direction::GcsToUa);
    std::int64_t now = nowSeconds();
    ReplayGuard guard(guardOptions(&now));
    for (std::uint32_t id : {kMax - 2, kMax - 1, kMax, 0u, 1u, 2u})
        QVERIFY(openFrame(codec, &guard, asReceived(sealed(codec, secureMessage(rng, id)))).accepted);
    QCOMPARE(openFrame(codec, &guard, asReceived(sealed(codec, secureMessage(rng, kMax)))).rejection,
             std::optional<Rejection>(Rejection::Replayed));
}

// Only an authenticated, fresh message moves the guard.
void TestSecure::refusedFramesDoNotAdvanceTheGuard()
{
    std::mt19937_64 rng(14);
    const SecretKey psk = keyFromSeed(14);
    const SecureCodec codec(psk, Direction::GcsToUa);
    std::int64_t now = nowSeconds();
    ReplayGuard guard(guardOptions(&now));
    QVERIFY(openFrame(codec, &guard, asReceived(sealed(codec, secureMessage(rng, 10)))).accepted);

    // Forged (tampered ID 500), wrong key, stale time with a high ID.
    DecodedBlocks t = asReceived(sealed(codec, secureMessage(rng, 500)));
    t.block1[3] ^= 0x80;
    QCOMPARE(openFrame(codec, &guard, t).rejection, std::optional<Rejection>(Rejection::Forged));
    const SecureCodec wrong(keyFromSeed(15), Direction::GcsToUa);
    QCOMPARE(openFrame(codec, &guard, asReceived(sealed(wrong, secureMessage(rng, 600)))).rejection,
             std::optional<Rejection>(Rejection::Forged));
    QCOMPARE(openFrame(codec, &guard, asReceived(sealed(codec, secureMessage(rng, 700, 90000, kDate)))).rejection,
             std::optional<Rejection>(Rejection::StaleTime));
    QCOMPARE(guard.lastAccepted(), std::optional<std::uint32_t>(10));
    QVERIFY(openFrame(codec, &guard, asReceived(sealed(codec, secureMessage(rng, 11)))).accepted);
}

void TestSecure::uncorrectableCodewords()
{
    std::mt19937_64 rng(16);
    const SecureCodec codec(keyFromSeed(16), Direction::GcsToUa);
    std::int64_t now = nowSeconds();
    ReplayGuard guard(guardOptions(&now));
    Message m = secureMessage(rng, 3);
    m.flightPlan = {7, 1, {1, 2, 3}};

    // BLOCK 2 lost: BLOCK 1 authenticates on its own and is accepted, without the section.
    DecodedBlocks d = asReceived(sealed(codec, m));
    d.corrected.block2 = -1;
    const Opened o = openFrame(codec, &guard, d);
    QVERIFY2(o.accepted, o.detail.c_str());
    QVERIFY(o.decoded.message.flightPlan.empty());
    QCOMPARE(o.decoded.diagnostics.size(), std::size_t(1));
    QCOMPARE(o.decoded.diagnostics[0].kind, Diagnostic::Kind::Uncorrectable);

    // BLOCK 1 lost: nothing to check, neither accepted nor counted as a rejection.
    DecodedBlocks e = asReceived(sealed(codec, secureMessage(rng, 4)));
    e.corrected.block1 = -1;
    const Opened u = openFrame(codec, &guard, e);
    QVERIFY(!u.accepted);
    QVERIFY(!u.rejection);
    QCOMPARE(guard.lastAccepted(), std::optional<std::uint32_t>(3));
}

// ------------------------------------------------------------------ on disk

void TestSecure::keyFileRoundTrip()
{
    QTemporaryDir dir;
    QVERIFY(dir.isValid());
    const std::string path = dir.filePath("aircraft.key").toStdString();
    const SecretKey key = keyFromSeed(20);
    std::string error;
    QVERIFY2(writeKeyFile(path, key, error), error.c_str());
    struct stat st {};
    QCOMPARE(::stat(path.c_str(), &st), 0);
    QCOMPARE(st.st_mode & 0777, mode_t(0600));
    QCOMPARE(readFile(path), toHex(key.bytes()) + "\n");

    const std::optional<SecretKey> back = readKeyFile(path, error);
    QVERIFY2(back, error.c_str());
    QCOMPARE(toHex(back->bytes()), toHex(key.bytes()));

    QVERIFY(!writeKeyFile(path, keyFromSeed(21), error));  // never overwritten
    QVERIFY(error.find("exists already") != std::string::npos);
    QCOMPARE(readFile(path), toHex(key.bytes()) + "\n");

    // Upper case, CRLF, no newline, mode 0400: all fine.
    const std::string upper = dir.filePath("upper.key").toStdString();
    std::string text = toHex(key.bytes());
    for (char& c : text)
        c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    for (const std::string& ending : {std::string("\r\n"), std::string()}) {
        writeFile(upper, text + ending, 0400);
        const std::optional<SecretKey> k = readKeyFile(upper, error);
        QVERIFY2(k, error.c_str());
        QCOMPARE(toHex(k->bytes()), toHex(key.bytes()));
        ::chmod(upper.c_str(), 0600);
    }
    QCOMPARE(generateKey().bytes().size(), kKeySize);
    QVERIFY(toHex(generateKey().bytes()) != toHex(generateKey().bytes()));
}

void TestSecure::keyFileReadableByOthersIsRefused()
{
    QTemporaryDir dir;
    const std::string path = dir.filePath("open.key").toStdString();
    const std::string secret = toHex(keyFromSeed(22).bytes());
    for (mode_t mode : {mode_t(0644), mode_t(0640), mode_t(0604), mode_t(0620), mode_t(0660)}) {
        writeFile(path, secret + "\n", mode);
        std::string error;
        QVERIFY(!readKeyFile(path, error));
        char modeText[8];
        std::snprintf(modeText, sizeof modeText, "%04o", static_cast<unsigned>(mode));
        QVERIFY2(error.find(std::string("mode ") + modeText) != std::string::npos, error.c_str());
        QVERIFY2(error.find("chmod 600 " + path) != std::string::npos, error.c_str());
        QVERIFY(error.find(secret) == std::string::npos);
        QVERIFY(error.find(secret.substr(0, 8)) == std::string::npos);
    }
    std::string error;
    QVERIFY(!readKeyFile(dir.filePath("absent.key").toStdString(), error));
    QVERIFY(error.find("absent.key") != std::string::npos);
    QVERIFY(!readKeyFile(dir.path().toStdString(), error));  // a directory
}

void TestSecure::keyFileWithBadContentIsRefused()
{
    QTemporaryDir dir;
    const std::string path = dir.filePath("bad.key").toStdString();
    const std::string good = toHex(keyFromSeed(23).bytes());
    const std::string cases[] = {
        good.substr(0, 63) + "\n",              // 63 digits
        good + "0\n",                           // 65
        good.substr(0, 63) + "g\n",             // not hex
        good + "\n\n",                          // a second newline
        " " + good + "\n",                      // leading space
        good.substr(0, 32),                     // 32 raw-looking bytes: not the format
        std::string(),                          // empty
        good + "\n" + good + "\n",              // two keys
    };
    for (const std::string& text : cases) {
        writeFile(path, text, 0600);
        std::string error;
        QVERIFY2(!readKeyFile(path, error), text.c_str());
        QVERIFY(error.find("64 hexadecimal digits") != std::string::npos);
        QVERIFY(error.find(good.substr(0, 16)) == std::string::npos);
    }
}

void TestSecure::replayStateSurvivesRestart()
{
    QTemporaryDir dir;
    const std::string keyPath = dir.filePath("ua.key").toStdString();
    const SecretKey psk = keyFromSeed(24);
    const std::string state = replayStatePath(keyPath, Direction::GcsToUa);
    QCOMPARE(state, keyPath + ".replay-gcs-to-ua");
    QCOMPARE(replayStatePath(keyPath, Direction::UaToGcs), keyPath + ".replay-ua-to-gcs");
    QCOMPARE(counterStatePath(keyPath, Direction::GcsToUa), keyPath + ".sent-gcs-to-ua");

    std::mt19937_64 rng(24);
    const SecureCodec codec(psk, Direction::GcsToUa);
    std::int64_t now = nowSeconds();
    ReplayGuard::Options o = guardOptions(&now);
    o.stateFile = state;
    o.keyFingerprint = fingerprint(psk);
    const DecodedBlocks f100 = asReceived(sealed(codec, secureMessage(rng, 100)));
    {
        ReplayGuard guard(o);
        QVERIFY(!guard.lastAccepted());
        const Opened a = openFrame(codec, &guard, f100);
        QVERIFY(a.accepted);
        QVERIFY2(a.persistError.empty(), a.persistError.c_str());
    }
    QCOMPARE(readFile(state), "rcm-replay-state 1\nkey " + fingerprint(psk) + "\nlast_accepted_id 100\n");
    struct stat st {};
    QCOMPARE(::stat(state.c_str(), &st), 0);
    QCOMPARE(st.st_mode & 0777, mode_t(0600));
    QVERIFY(readFile(state).find(toHex(psk.bytes())) == std::string::npos);

    // "Restart": a new guard reads the file and refuses the replay.
    ReplayGuard restarted(o);
    QCOMPARE(restarted.lastAccepted(), std::optional<std::uint32_t>(100));
    QCOMPARE(openFrame(codec, &restarted, f100).rejection, std::optional<Rejection>(Rejection::Replayed));
    QVERIFY(openFrame(codec, &restarted, asReceived(sealed(codec, secureMessage(rng, 101)))).accepted);
    QCOMPARE(ReplayGuard(o).lastAccepted(), std::optional<std::uint32_t>(101));

    // No temporary files left behind.
    QCOMPARE(QDir(dir.path()).entryList(QDir::Files).size(), 1);
}

void TestSecure::replayStateUnderAnotherKeyOrCorrupt()
{
    QTemporaryDir dir;
    const std::string state = dir.filePath("k.replay-ua-to-gcs").toStdString();
    std::int64_t now = nowSeconds();
    ReplayGuard::Options o = guardOptions(&now);
    o.stateFile = state;
    o.keyFingerprint = fingerprint(keyFromSeed(25));

    writeFile(state, "rcm-replay-state 1\nkey 0011223344556677\nlast_accepted_id 9000\n", 0600);
    const ReplayGuard fresh(o);
    QVERIFY(!fresh.lastAccepted());
    QVERIFY(fresh.notice().find("another key") != std::string::npos);

    for (const char* bad : {"rcm-replay-state 1\nkey x\n", "garbage", "rcm-replay-state 2\nkey a\nlast_accepted_id 1\n",
                            "rcm-replay-state 1\nkey a\nlast_accepted_id 16777216\n",
                            "rcm-replay-state 1\nkey a\nlast_accepted_id 5\nextra\n"}) {
        writeFile(state, bad, 0600);
        QVERIFY_THROWS_EXCEPTION(std::runtime_error, ReplayGuard{o});
    }
    try {
        ReplayGuard{o};
    } catch (const std::runtime_error& e) {
        QVERIFY(std::string(e.what()).find(state) != std::string::npos);
    }
}

void TestSecure::messageCounterNeverReusesAnId()
{
    QTemporaryDir dir;
    const std::string state = dir.filePath("gcs.key.sent-gcs-to-ua").toStdString();
    std::int64_t now = nowSeconds();
    MessageCounter::Options o;
    o.stateFile = state;
    o.keyFingerprint = "0123456789abcdef";
    o.reserve = 10;
    o.clock = [&now] { return now; };

    // No state: starts at the clock (seconds mod 2^24).
    std::uint32_t last = 0;
    {
        MessageCounter c(o);
        QCOMPARE(c.peek(), static_cast<std::uint32_t>(now % kMessageIdModulus));
        for (int i = 0; i < 25; ++i) {
            const std::uint32_t id = c.next();
            if (i > 0)
                QVERIFY(messageIdAhead(id, last));
            last = id;
        }
    }
    // A "crash" after 25 IDs: the next session starts ahead of all of them,
    // having skipped at most one reservation.
    {
        MessageCounter c(o);
        QVERIFY(messageIdAhead(c.peek(), last));
        QVERIFY(((c.peek() - last) & (kMessageIdModulus - 1)) <= o.reserve);
        last = c.next();
    }
    // Even with the clock set back a day, the stored counter wins.
    now -= 86400;
    {
        MessageCounter c(o);
        QVERIFY(messageIdAhead(c.peek(), last));
    }
    // Memory only: counts from the clock, wraps at 2^24.
    MessageCounter::Options m;
    m.clock = [] { return std::int64_t(kMessageIdModulus - 2); };
    MessageCounter mem(m);
    QCOMPARE(mem.next(), kMessageIdModulus - 2);
    QCOMPARE(mem.next(), kMessageIdModulus - 1);
    QCOMPARE(mem.next(), 0u);
}

QTEST_APPLESS_MAIN(TestSecure)
#include "tst_secure.moc"
