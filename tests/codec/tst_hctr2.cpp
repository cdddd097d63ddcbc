// AES-HCTR2 against the official known-answer vectors (tests/vectors/hctr2),
// plus POLYVAL cross-checks and misuse handling.

#include "codec/secure/Hctr2.h"

#include <QByteArray>
#include <QFile>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QList>
#include <QString>
#include <QtTest>

#include <openssl/evp.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <random>
#include <span>
#include <stdexcept>
#include <utility>
#include <vector>

namespace {

std::span<const std::uint8_t> bytes(const QByteArray& a)
{
    return {reinterpret_cast<const std::uint8_t*>(a.constData()),
            static_cast<std::size_t>(a.size())};
}

std::span<std::uint8_t> bytes(QByteArray& a)
{
    return {reinterpret_cast<std::uint8_t*>(a.data()), static_cast<std::size_t>(a.size())};
}

struct Vector {
    QString name;
    QByteArray key, tweak, plaintext, ciphertext;
};

// The POLYVAL implementations to run: the portable one always, PCLMULQDQ
// where this CPU has it.
QList<rcm::detail::PolyvalImpl> impls()
{
    QList<rcm::detail::PolyvalImpl> r{rcm::detail::PolyvalImpl::Portable};
    if (rcm::detail::polyvalPclmulAvailable())
        r.append(rcm::detail::PolyvalImpl::Pclmul);
    return r;
}

const char* implName(rcm::detail::PolyvalImpl i)
{
    return i == rcm::detail::PolyvalImpl::Pclmul ? "pclmul" : "portable";
}

QByteArray aesEcb(const QByteArray& key, const QByteArray& in, bool encrypt)
{
    EVP_CIPHER_CTX* ctx = EVP_CIPHER_CTX_new();
    const EVP_CIPHER* cipher = key.size() == 16 ? EVP_aes_128_ecb() : EVP_aes_256_ecb();
    QByteArray out(in.size(), '\0');
    int outl = 0;
    const auto* k = reinterpret_cast<const unsigned char*>(key.constData());
    const bool ok = EVP_CipherInit_ex2(ctx, cipher, k, nullptr, encrypt ? 1 : 0, nullptr) == 1
                    && EVP_CIPHER_CTX_set_padding(ctx, 0) == 1
                    && EVP_CipherUpdate(ctx, reinterpret_cast<unsigned char*>(out.data()), &outl,
                                        reinterpret_cast<const unsigned char*>(in.constData()),
                                        static_cast<int>(in.size()))
                           == 1;
    EVP_CIPHER_CTX_free(ctx);
    return ok && outl == in.size() ? out : QByteArray();
}

QByteArray xorBlocks(QByteArray a, const QByteArray& b)
{
    for (qsizetype i = 0; i < a.size(); ++i)
        a[i] = static_cast<char>(a[i] ^ b[i]);
    return a;
}

// bin(i): i as a 128-bit little-endian integer.
QByteArray bin(quint64 i)
{
    QByteArray b(16, '\0');
    for (int k = 0; k < 8; ++k)
        b[k] = static_cast<char>(i >> (8 * k));
    return b;
}

// HCTR2 encryption written straight from the paper's definition, each hash
// one contiguous POLYVAL input. The cipher hashes its length block, tweak,
// message and padding as separate runs, folded in chunks of key powers; the
// official vectors (tweaks of at most 47 bytes) never put a chunk boundary
// inside a tweak or between runs, this does.
QByteArray referenceEncrypt(rcm::detail::PolyvalImpl impl, const QByteArray& key,
                            const QByteArray& tweak, const QByteArray& plaintext)
{
    const QByteArray hl = aesEcb(key, bin(0) + bin(1), true);
    const QByteArray h = hl.left(16), l = hl.mid(16);
    auto hash = [&](const QByteArray& m) {
        QByteArray in = bin(2 * 8 * static_cast<quint64>(tweak.size()) + (m.size() % 16 ? 3 : 2));
        in += tweak + QByteArray((16 - tweak.size() % 16) % 16, '\0');
        in += m;
        if (m.size() % 16)
            in += '\x01' + QByteArray(15 - m.size() % 16, '\0');
        QByteArray out(16, '\0');
        rcm::detail::polyval(impl, bytes(h).first<16>(), bytes(in), bytes(out).first<16>());
        return out;
    };
    const QByteArray m = plaintext.left(16), n = plaintext.mid(16);
    const QByteArray mm = xorBlocks(m, hash(n));
    const QByteArray uu = aesEcb(key, mm, true);
    const QByteArray s = xorBlocks(xorBlocks(mm, uu), l);
    QByteArray counters;
    for (qsizetype i = 1; 16 * (i - 1) < n.size(); ++i)
        counters += xorBlocks(s, bin(static_cast<quint64>(i)));
    const QByteArray v = xorBlocks(n, aesEcb(key, counters, true).left(n.size()));
    return xorBlocks(uu, hash(v)) + v;
}

} // namespace

class TestHctr2 : public QObject {
    Q_OBJECT

private slots:
    void initTestCase();
    void cleanup();
    void vectorCount();
    void knownAnswers_data();
    void knownAnswers();
    void polyvalRfc8452();
    void polyvalImplementationsAgree();
    void roundTripOddLengths();
    void matchesReferenceAcrossChunks();
    void rejectsShortMessage();
    void rejectsSizeMismatchAndOverlap();
    void rejectsBadKeyLength();

private:
    bool load(const QString& file, int expectedKeyLen);

    QList<Vector> m_vectors;
    int m_count128 = 0;
    int m_count256 = 0;
};

bool TestHctr2::load(const QString& file, int expectedKeyLen)
{
    QFile f(QStringLiteral(RCM_VECTORS_DIR "/hctr2/") + file);
    if (!f.open(QIODevice::ReadOnly)) {
        qWarning("cannot open %s", qPrintable(f.fileName()));
        return false;
    }
    QJsonParseError err{};
    const QJsonDocument doc = QJsonDocument::fromJson(f.readAll(), &err);
    if (err.error != QJsonParseError::NoError || !doc.isArray()) {
        qWarning("%s: %s", qPrintable(file), qPrintable(err.errorString()));
        return false;
    }
    const QJsonArray arr = doc.array();
    int index = 0;
    for (const QJsonValue& v : arr) {
        const QJsonObject o = v.toObject();
        const QJsonObject in = o.value(QLatin1String("input")).toObject();
        Vector vec;
        vec.name = QStringLiteral("%1 #%2 %3")
                       .arg(file)
                       .arg(++index, 3, 10, QLatin1Char('0'))
                       .arg(o.value(QLatin1String("description")).toString());
        vec.key = QByteArray::fromHex(in.value(QLatin1String("key_hex")).toString().toLatin1());
        vec.tweak = QByteArray::fromHex(in.value(QLatin1String("tweak_hex")).toString().toLatin1());
        vec.plaintext = QByteArray::fromHex(o.value(QLatin1String("plaintext_hex")).toString().toLatin1());
        vec.ciphertext = QByteArray::fromHex(o.value(QLatin1String("ciphertext_hex")).toString().toLatin1());
        if (vec.key.size() != expectedKeyLen || vec.plaintext.size() < 16
            || vec.plaintext.size() != vec.ciphertext.size()) {
            qWarning("%s: malformed vector", qPrintable(vec.name));
            return false;
        }
        m_vectors.append(vec);
        (expectedKeyLen == 16 ? m_count128 : m_count256)++;
    }
    return true;
}

void TestHctr2::initTestCase()
{
    QVERIFY(load(QStringLiteral("HCTR2_AES128.json"), 16));
    QVERIFY(load(QStringLiteral("HCTR2_AES256.json"), 32));
    qInfo("POLYVAL implementations under test: portable%s",
          rcm::detail::polyvalPclmulAvailable() ? ", pclmul" : " (no PCLMULQDQ on this CPU)");
}

void TestHctr2::cleanup()
{
    rcm::detail::setForcePortablePolyval(false);
}

void TestHctr2::vectorCount()
{
    QCOMPARE(m_count128, 200);
    QCOMPARE(m_count256, 350);
    QCOMPARE(m_vectors.size(), 550);
}

void TestHctr2::knownAnswers_data()
{
    QTest::addColumn<QByteArray>("key");
    QTest::addColumn<QByteArray>("tweak");
    QTest::addColumn<QByteArray>("plaintext");
    QTest::addColumn<QByteArray>("ciphertext");
    for (const Vector& v : std::as_const(m_vectors))
        QTest::newRow(qPrintable(v.name)) << v.key << v.tweak << v.plaintext << v.ciphertext;
}

void TestHctr2::knownAnswers()
{
    QFETCH(QByteArray, key);
    QFETCH(QByteArray, tweak);
    QFETCH(QByteArray, plaintext);
    QFETCH(QByteArray, ciphertext);

    for (const auto impl : impls()) {
        rcm::detail::setForcePortablePolyval(impl == rcm::detail::PolyvalImpl::Portable);
        const rcm::Hctr2 cipher(bytes(key));
        const QByteArray tag = QByteArray("POLYVAL ") + implName(impl);

        QByteArray out(plaintext.size(), '\0');
        cipher.encrypt(bytes(tweak), bytes(plaintext), bytes(out));
        QVERIFY2(out == ciphertext, (tag + " encrypt: got " + out.toHex()).constData());

        out.fill('\0');
        cipher.decrypt(bytes(tweak), bytes(ciphertext), bytes(out));
        QVERIFY2(out == plaintext, (tag + " decrypt: got " + out.toHex()).constData());

        QByteArray buf = plaintext;
        cipher.encrypt(bytes(tweak), bytes(buf), bytes(buf));
        QVERIFY2(buf == ciphertext, (tag + " in-place encrypt: got " + buf.toHex()).constData());
        cipher.decrypt(bytes(tweak), bytes(buf), bytes(buf));
        QVERIFY2(buf == plaintext, (tag + " in-place decrypt: got " + buf.toHex()).constData());
    }
}

void TestHctr2::polyvalRfc8452()
{
    // RFC 8452, Appendix A, "POLYVAL example".
    const QByteArray h = QByteArray::fromHex("25629347589242761d31f826ba4b757b");
    const QByteArray x = QByteArray::fromHex("4f4f95668c83dfb6401762bb2d01a262"
                                             "d1a24ddd2721d006bbe45f20d3c9f362");
    const QByteArray expected = QByteArray::fromHex("f7a3b47b846119fae5b7866cf5e5b77e");
    for (const auto impl : impls()) {
        QByteArray out(16, '\0');
        rcm::detail::polyval(impl, bytes(h).first<16>(), bytes(x), bytes(out).first<16>());
        QVERIFY2(out == expected, implName(impl));
    }
}

void TestHctr2::polyvalImplementationsAgree()
{
    if (!rcm::detail::polyvalPclmulAvailable())
        QSKIP("no PCLMULQDQ on this CPU: only the portable POLYVAL is built in");
    std::mt19937_64 rng(0x48435452u);
    std::uniform_int_distribution<int> byte(0, 255);
    for (int round = 0; round < 2000; ++round) {
        const int nblocks = round % 41; // 0..40 blocks: every chunk split
        std::vector<std::uint8_t> h(16), x(16 * nblocks);
        for (auto& b : h)
            b = static_cast<std::uint8_t>(byte(rng));
        for (auto& b : x)
            b = static_cast<std::uint8_t>(byte(rng));
        if (round % 97 == 1) { // extremes: all-ones key and data
            std::fill(h.begin(), h.end(), std::uint8_t{0xff});
            std::fill(x.begin(), x.end(), std::uint8_t{0xff});
        }
        std::array<std::uint8_t, 16> a{}, b{};
        rcm::detail::polyval(rcm::detail::PolyvalImpl::Portable,
                             std::span<const std::uint8_t, 16>(h.data(), 16), x, a);
        rcm::detail::polyval(rcm::detail::PolyvalImpl::Pclmul,
                             std::span<const std::uint8_t, 16>(h.data(), 16), x, b);
        QVERIFY2(a == b, qPrintable(QStringLiteral("round %1, %2 blocks").arg(round).arg(nblocks)));
    }
}

void TestHctr2::roundTripOddLengths()
{
    // Lengths and tweaks beyond the vectors' set: every tail length, long
    // messages (several XCTR batches and POLYVAL chunks), and the two
    // implementations agree on the ciphertext.
    std::mt19937 rng(7);
    std::uniform_int_distribution<int> byte(0, 255);
    QByteArray key(32, '\0');
    for (auto& c : key)
        c = static_cast<char>(byte(rng));
    rcm::detail::setForcePortablePolyval(true);
    const rcm::Hctr2 portable(bytes(key));
    rcm::detail::setForcePortablePolyval(false);
    const rcm::Hctr2 fast(bytes(key));
    for (int len : {16, 17, 31, 32, 33, 223, 255, 256, 257, 1000, 4096 + 5}) {
        for (int tlen : {0, 15, 40, 129}) {
            QByteArray msg(len, '\0'), tweak(tlen, '\0');
            for (auto& c : msg)
                c = static_cast<char>(byte(rng));
            for (auto& c : tweak)
                c = static_cast<char>(byte(rng));
            QByteArray c1(len, '\0'), c2(len, '\0'), back(len, '\0');
            portable.encrypt(bytes(tweak), bytes(msg), bytes(c1));
            fast.encrypt(bytes(tweak), bytes(msg), bytes(c2));
            QCOMPARE(c1, c2);
            QVERIFY(c1 != msg);
            fast.decrypt(bytes(tweak), bytes(c1), bytes(back));
            QCOMPARE(back, msg);
            portable.decrypt(bytes(tweak), bytes(c1), bytes(back));
            QCOMPARE(back, msg);
        }
    }
}

void TestHctr2::matchesReferenceAcrossChunks()
{
    // 16 key powers: a chunk boundary falls after the length block plus 15
    // tweak blocks (tweak 240), inside the tweak or its padded block (241..
    // 256, 300), inside or at the end of a message's run (17 * 16 + 16 and
    // around), and on a padded last block (+5).
    std::mt19937 rng(11);
    std::uniform_int_distribution<int> byte(0, 255);
    for (const int keyLen : {16, 32}) {
        QByteArray key(keyLen, '\0');
        for (auto& c : key)
            c = static_cast<char>(byte(rng));
        for (const int tlen : {0, 6, 15, 239, 240, 241, 255, 256, 257, 300}) {
            for (const int len : {16, 223, 16 + 255, 16 + 256, 16 + 257, 16 + 16 * 17, 16 + 16 * 32 + 5}) {
                QByteArray msg(len, '\0'), tweak(tlen, '\0');
                for (auto& c : msg)
                    c = static_cast<char>(byte(rng));
                for (auto& c : tweak)
                    c = static_cast<char>(byte(rng));
                const QString where = QStringLiteral("key %1, tweak %2, message %3").arg(keyLen).arg(tlen).arg(len);
                for (const auto impl : impls()) {
                    const QByteArray expected = referenceEncrypt(impl, key, tweak, msg);
                    QCOMPARE(expected.size(), len);
                    rcm::detail::setForcePortablePolyval(impl == rcm::detail::PolyvalImpl::Portable);
                    const rcm::Hctr2 cipher(bytes(key));
                    QByteArray out(len, '\0'), back(len, '\0');
                    cipher.encrypt(bytes(tweak), bytes(msg), bytes(out));
                    QVERIFY2(out == expected, qPrintable(where + QLatin1String(", POLYVAL ") + implName(impl)));
                    cipher.decrypt(bytes(tweak), bytes(out), bytes(back));
                    QVERIFY2(back == msg, qPrintable(where + QLatin1String(", POLYVAL ") + implName(impl)));
                }
            }
        }
    }
}

void TestHctr2::rejectsShortMessage()
{
    const QByteArray key(32, '\x42');
    const rcm::Hctr2 cipher(bytes(key));
    QByteArray in(15, 'a'), out(15, '\0'), empty;
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, cipher.encrypt({}, bytes(in), bytes(out)));
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, cipher.decrypt({}, bytes(in), bytes(out)));
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, cipher.encrypt({}, bytes(empty), bytes(empty)));
    QCOMPARE(out, QByteArray(15, '\0')); // nothing written
}

void TestHctr2::rejectsSizeMismatchAndOverlap()
{
    const QByteArray key(16, '\x42');
    const rcm::Hctr2 cipher(bytes(key));
    QByteArray in(32, 'a'), shortOut(31, '\0'), longOut(33, '\0');
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, cipher.encrypt({}, bytes(in), bytes(shortOut)));
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, cipher.decrypt({}, bytes(in), bytes(longOut)));
    QByteArray buf(48, 'b');
    const auto all = bytes(buf);
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument,
                             cipher.encrypt({}, all.first(32), all.subspan(8, 32)));
}

void TestHctr2::rejectsBadKeyLength()
{
    for (int len : {0, 1, 15, 17, 24, 31, 33, 64}) {
        const QByteArray key(len, '\x01');
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, rcm::Hctr2 cipher(bytes(key)));
    }
    try {
        const QByteArray key(24, '\x01');
        rcm::Hctr2 cipher(bytes(key));
        QFAIL("no exception");
    } catch (const std::invalid_argument& e) {
        QVERIFY2(QByteArray(e.what()).contains("16 or 32"), e.what());
    }
}

QTEST_APPLESS_MAIN(TestHctr2)
#include "tst_hctr2.moc"
