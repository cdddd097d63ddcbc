// Decoding with a prediction: the RS trial (exact corrections, the margin),
// the prediction of the next message, and a realistic session through bit
// errors far beyond the Reed-Solomon bound, plain and secure, never a wrong frame.
#include "BerSession.h"

#include "codec/frame/ReedSolomon.h"
#include "codec/frame/TrialDecode.h"
#include "codec/message/MessagePrediction.h"

#include <QtTest>

#include <array>
#include <numeric>
#include <vector>
#include <cstdint>
#include <random>

using namespace rcm;

namespace {

using Codeword = std::array<std::uint8_t, rs::kCodewordSize>;

Codeword randomCodeword(std::mt19937_64& rng)
{
    Codeword c;
    for (std::size_t i = 0; i < rs::kDataSize; ++i)
        c[i] = static_cast<std::uint8_t>(rng());
    rs::encode(c.data(), c.data() + rs::kDataSize);
    return c;
}

// Adds a non-zero error to each byte at `positions`.
Codeword withErrors(Codeword c, std::initializer_list<int> positions)
{
    for (int p : positions)
        c[static_cast<std::size_t>(p)] ^= static_cast<std::uint8_t>(0x5A + p % 7);
    return c;
}

// `count` byte errors at distinct positions from `first` on, `step` apart,
// of varied values (evenly spaced equal errors can sit next to a codeword).
Codeword withSpreadErrors(Codeword c, int first, int count, int step)
{
    for (int i = 0; i < count; ++i)
        c[static_cast<std::size_t>(first + i * step)] ^= static_cast<std::uint8_t>(1 + (i * 73 + 29) % 255);
    return c;
}

}  // namespace

class TstTrialDecode : public QObject {
    Q_OBJECT

private slots:
    void encodeMatchesLibfec()
    {
        std::mt19937_64 rng(11);
        for (int i = 0; i < 1000; ++i) {
            std::uint8_t data[rs::kDataSize];
            for (std::uint8_t& b : data)
                b = static_cast<std::uint8_t>(rng());
            std::uint8_t ours[rs::kParitySize], libfec[rs::kParitySize];
            rs::encode(data, ours);
            rs::encodeLibfec(data, libfec);
            QVERIFY(std::equal(ours, ours + rs::kParitySize, libfec));
        }
    }

    // The decoder's own steps from the remainder give libfec's result, byte
    // for byte and count for count, for clean words, words within reach,
    // words just beyond it and random words.
    void decodeMatchesLibfec()
    {
        std::mt19937_64 rng(12);
        int decoded = 0, failed = 0;
        for (int i = 0; i < 20000; ++i) {
            Codeword c = randomCodeword(rng);
            const int errors = i < 1000 ? 255 : static_cast<int>(rng() % 41);
            for (int e = 0; e < errors; ++e)
                c[rng() % rs::kCodewordSize] ^= static_cast<std::uint8_t>(1 + rng() % 255);
            Codeword ours = c, theirs = c;
            const int n = rs::decode(ours.data());
            int m = rs::decodeLibfec(theirs.data());
            if (m < 0) {
                m = -1;
                theirs = c;
            }
            QCOMPARE(n, m);
            QCOMPARE(ours, theirs);
            Codeword within = c;
            const int limit = static_cast<int>(rng() % 17);
            const int w = rs::decodeWithin(within.data(), limit);
            QCOMPARE(w, n <= limit ? n : -1);
            QCOMPARE(within, n <= limit ? ours : c);
            (n >= 0 ? decoded : failed)++;
        }
        QVERIFY(decoded > 5000 && failed > 5000);
    }

    // A trial gives what libfec gives for the trial word, within the margin.
    void trialMatchesLibfec()
    {
        std::mt19937_64 rng(13);
        for (int i = 0; i < 20000; ++i) {
            const Codeword sent = randomCodeword(rng);
            Codeword predicted = sent;
            const int wrong = static_cast<int>(rng() % 20);
            for (int e = 0; e < wrong; ++e)
                predicted[rng() % rs::kDataSize] ^= static_cast<std::uint8_t>(1 + rng() % 255);
            rs::encode(predicted.data(), predicted.data() + rs::kDataSize);
            Codeword received = sent;
            const int noise = static_cast<int>(rng() % 12);
            for (int e = 0; e < noise; ++e)
                received[rng() % rs::kCodewordSize] ^= static_cast<std::uint8_t>(1 + rng() % 255);
            Codeword trial = predicted;
            std::copy(received.begin() + rs::kDataSize, received.end(), trial.begin() + rs::kDataSize);
            int expected = rs::decodeLibfec(trial.data());
            if (expected > rs::kTrialMargin)
                expected = -1;
            Codeword out{};
            const int got = rs::decodeWithPrediction(received.data(), predicted.data(), out.data());
            QCOMPARE(got < 0 ? -1 : got, expected < 0 ? -1 : expected);
            if (got >= 0)
                QCOMPARE(out, trial);
        }
    }

    void predictionEqualToSent()
    {
        std::mt19937_64 rng(1);
        const Codeword sent = randomCodeword(rng);
        // 40 data byte errors (far beyond 16) and 5 in the parity.
        Codeword received = withSpreadErrors(sent, 0, 40, 5);
        received = withErrors(received, {223, 230, 240, 250, 254});
        Codeword copy = received;
        QCOMPARE(rs::decode(copy.data()), -1);
        Codeword out{};
        QCOMPARE(rs::parityDistance(received.data(), sent.data()), 5);
        QCOMPARE(rs::decodeWithPrediction(received.data(), sent.data(), out.data()), 5);
        QCOMPARE(out, sent);
    }

    void predictionDifferingInACommandByte()
    {
        // The prediction still holds the old eng_carb_SET; the sender sent a
        // new one. The changed byte is an error RS corrects to the sent value.
        std::mt19937_64 rng(2);
        const Codeword sent = randomCodeword(rng);
        Codeword predicted = sent;
        predicted[150] = static_cast<std::uint8_t>(sent[150] ^ 0x1E);
        rs::encode(predicted.data(), predicted.data() + rs::kDataSize);
        QCOMPARE(rs::parityDistance(sent.data(), predicted.data()), 32);
        Codeword received = withSpreadErrors(sent, 1, 30, 7);
        received = withErrors(received, {224, 237, 249, 254});
        Codeword out{};
        QCOMPARE(rs::decodeWithPrediction(received.data(), predicted.data(), out.data()), 5);
        QCOMPARE(out, sent);
    }

    void wrongPredictionGivesNoFrame()
    {
        std::mt19937_64 rng(3);
        const Codeword sent = randomCodeword(rng);
        const Codeword received = withErrors(sent, {10, 20, 230});
        Codeword out{};
        // Another message altogether.
        const Codeword other = randomCodeword(rng);
        QCOMPARE(rs::decodeWithPrediction(received.data(), other.data(), out.data()), -1);
        // The prediction wrong in 13 data bytes and the channel clean: RS
        // could correct them (13 <= 16), but the margin is 12.
        Codeword off = withSpreadErrors(sent, 3, 13, 11);
        rs::encode(off.data(), off.data() + rs::kDataSize);
        QCOMPARE(rs::decodeWithPrediction(sent.data(), off.data(), out.data()), -1);
        QCOMPARE(rs::decodeWithPrediction(sent.data(), off.data(), out.data(), 13), 13);
        QCOMPARE(out, sent);
        // Wrong in 12 and two parity errors on the channel: 14 > 12.
        Codeword off12 = withSpreadErrors(sent, 3, 12, 11);
        rs::encode(off12.data(), off12.data() + rs::kDataSize);
        QCOMPARE(rs::decodeWithPrediction(withErrors(sent, {240, 241}).data(), off12.data(), out.data()), -1);
        QCOMPARE(rs::decodeWithPrediction(sent.data(), off12.data(), out.data()), 12);
        QCOMPARE(out, sent);
    }

    // Errors and erasures: within 2e + f <= 32, the sent codeword, and
    // libfec's decode_rs with eras_pos byte for byte and count for count;
    // beyond, either refused (the word left as it was) or a codeword within
    // the erased places and (32 - f) / 2 other bytes of the word, never more.
    void erasuresMatchLibfec()
    {
        std::mt19937_64 rng(21);
        int within = 0, beyondRefused = 0;
        for (int i = 0; i < 5000; ++i) {
            const Codeword sent = randomCodeword(rng);
            Codeword c = sent;
            std::vector<int> places(rs::kCodewordSize);
            std::iota(places.begin(), places.end(), 0);
            std::shuffle(places.begin(), places.end(), rng);
            const int erased = static_cast<int>(rng() % 33);
            const int errors = static_cast<int>(rng() % 21);
            for (int e = 0; e < erased + errors; ++e)
                if (e >= erased || rng() % 2)
                    c[static_cast<std::size_t>(places[static_cast<std::size_t>(e)])] ^=
                        static_cast<std::uint8_t>(1 + rng() % 255);
            Codeword ours = c;
            const int n = rs::decodeWithErasures(ours.data(), places.data(), erased);
            if (2 * errors + erased <= 32) {
                Codeword theirs = c;
                const int m = rs::decodeLibfecWithErasures(theirs.data(), places.data(), erased);
                QCOMPARE(n, m);
                QCOMPARE(ours, sent);
                QCOMPARE(theirs, sent);
                ++within;
                continue;
            }
            if (n < 0) {
                QCOMPARE(ours, c);
                ++beyondRefused;
                continue;
            }
            QVERIFY(rs::isCodeword(ours.data()));
            int outside = 0;
            for (std::size_t k = static_cast<std::size_t>(erased); k < rs::kCodewordSize; ++k)
                outside += ours[static_cast<std::size_t>(places[k])] != c[static_cast<std::size_t>(places[k])];
            QVERIFY(2 * outside + erased <= 32);
        }
        QVERIFY(within > 1000 && beyondRefused > 1000);
    }

    // Two copies of one codeword, each with 17 to 20 byte errors (beyond RS
    // alone) at different places: combined, the sent codeword, every time.
    void twoCopiesBeyondReachCombined()
    {
        std::mt19937_64 rng(22);
        for (int round = 0; round < 200; ++round) {
            const Codeword sent = randomCodeword(rng);
            std::vector<int> places(rs::kCodewordSize);
            std::iota(places.begin(), places.end(), 0);
            std::shuffle(places.begin(), places.end(), rng);
            const int inA = 17 + static_cast<int>(rng() % 4), inB = 17 + static_cast<int>(rng() % 4);
            Codeword a = sent, b = sent;
            for (int e = 0; e < inA + inB; ++e)
                (e < inA ? a : b)[static_cast<std::size_t>(places[static_cast<std::size_t>(e)])] ^=
                    static_cast<std::uint8_t>(1 + rng() % 255);
            Codeword alone = a;
            QCOMPARE(rs::decode(alone.data()), -1);
            alone = b;
            QCOMPARE(rs::decode(alone.data()), -1);
            const std::uint8_t* copies[] = {a.data(), b.data()};
            Codeword out{};
            const rs::CopiesDecode r = rs::decodeFromCopies(copies, 2, out.data(), 1 << 12);
            QVERIFY(r.found);
            QCOMPARE(out, sent);
            QCOMPARE(r.noCopy, 0);
            QVERIFY(r.decodes >= 1 && r.decodes <= 1 << rs::kMaxCopiesGuessed);
        }
    }

    // The same with the channel's errors anywhere (two copies may both be
    // wrong at one place, then neither holds the sent byte): mostly found,
    // never wrong; and the decodes spent stay within the limit given.
    void twoNoisyCopiesNeverWrong()
    {
        std::mt19937_64 rng(23);
        int found = 0;
        for (int round = 0; round < 200; ++round) {
            const Codeword sent = randomCodeword(rng);
            Codeword a = sent, b = sent;
            for (Codeword* copy : {&a, &b})
                for (int e = 0; e < 17 + static_cast<int>(rng() % 4); ++e)
                    (*copy)[rng() % rs::kCodewordSize] ^= static_cast<std::uint8_t>(1 + rng() % 255);
            const std::uint8_t* copies[] = {a.data(), b.data()};
            Codeword out{};
            const rs::CopiesDecode r = rs::decodeFromCopies(copies, 2, out.data(), 100);
            QVERIFY(r.decodes <= 100);
            if (r.found) {
                QCOMPARE(out, sent);
                ++found;
            }
        }
        QVERIFY2(found >= 120, qPrintable(QString::number(found)));
    }

    // Copies of two different sections never combine into a wrong codeword:
    // unrelated ones are too far apart to try (no decode spent); two that
    // differ in one data byte (33 bytes of their codewords) give the last
    // copy's codeword, never the other's.
    void copiesOfDifferentSectionsDoNotCombine()
    {
        std::mt19937_64 rng(24);
        const Codeword s1 = randomCodeword(rng);
        const Codeword s2 = randomCodeword(rng);
        const Codeword a = withSpreadErrors(s1, 0, 18, 7), b = withSpreadErrors(s2, 3, 18, 7);
        const std::uint8_t* unrelated[] = {a.data(), b.data()};
        Codeword out{};
        rs::CopiesDecode r = rs::decodeFromCopies(unrelated, 2, out.data(), 1 << 12);
        QVERIFY(!r.found);
        QCOMPARE(r.decodes, 0);

        Codeword near = s1;
        near[100] ^= 0x21;
        rs::encode(near.data(), near.data() + rs::kDataSize);
        QVERIFY(std::inner_product(near.begin(), near.end(), s1.begin(), 0, std::plus<>(), std::not_equal_to<>()) >= 33);
        const Codeword older = withErrors(s1, {5}), newer = withErrors(near, {7, 60, 200});
        const std::uint8_t* olderFirst[] = {older.data(), newer.data()};
        r = rs::decodeFromCopies(olderFirst, 2, out.data(), 1 << 12);
        QVERIFY(r.found);
        QCOMPARE(out, near);
        const std::uint8_t* newerFirst[] = {newer.data(), older.data()};
        r = rs::decodeFromCopies(newerFirst, 2, out.data(), 1 << 12);
        QVERIFY(r.found);
        QCOMPARE(out, s1);
    }

    // Three copies: the bytes two of them agree on are kept, the places where
    // all three differ erased.
    void threeCopiesByMajorityAndErasures()
    {
        std::mt19937_64 rng(25);
        const Codeword sent = randomCodeword(rng);
        const Codeword a = withSpreadErrors(sent, 0, 30, 8), b = withSpreadErrors(sent, 1, 30, 8);
        Codeword c = withSpreadErrors(sent, 2, 30, 8);
        for (int p : {0, 8, 16})  // all three wrong here, each its own way
            c[static_cast<std::size_t>(p)] ^= 0x0F;
        const std::uint8_t* copies[] = {a.data(), b.data(), c.data()};
        Codeword out{};
        const rs::CopiesDecode r = rs::decodeFromCopies(copies, 3, out.data(), 1);
        QVERIFY(r.found);
        QCOMPARE(out, sent);
        QCOMPARE(r.decodes, 1);
        QCOMPARE(r.noCopy, 0);
    }

    void majorityOfNoisyCopies()
    {
        std::mt19937_64 rng(4);
        const Codeword sent = randomCodeword(rng);
        const Codeword a = withErrors(sent, {1, 2, 3});
        const Codeword b = withErrors(sent, {3, 4});
        const Codeword c = withErrors(sent, {5});
        const std::uint8_t* copies[] = {a.data(), b.data(), c.data()};
        Codeword vote{};
        rs::majorityBytes(copies, 3, vote.data());
        // Byte 3 is wrong in two copies, the same way: the majority keeps it.
        Codeword expected = sent;
        expected[3] = a[3];
        QCOMPARE(vote, expected);
        // Two copies that disagree: the last one's byte.
        const std::uint8_t* two[] = {a.data(), c.data()};
        rs::majorityBytes(two, 2, vote.data());
        QCOMPARE(vote, c);
    }

    void advanceTimeAndDateRollsOver()
    {
        std::uint32_t t = 235959, d = 261231;
        QVERIFY(advanceTimeAndDate(t, d, 1));
        QCOMPARE(t, 0u);
        QCOMPARE(d, 270101u);
        t = 235958, d = 280228;  // 2028 is a leap year
        QVERIFY(advanceTimeAndDate(t, d, 3));
        QCOMPARE(t, 1u);
        QCOMPARE(d, 280229u);
        t = 120000, d = 260228;
        QVERIFY(advanceTimeAndDate(t, d, 86400 + 61));
        QCOMPARE(t, 120101u);
        QCOMPARE(d, 260301u);
        t = 126000, d = 260101;  // 60 minutes: not a time
        QVERIFY(!advanceTimeAndDate(t, d, 1));
        QCOMPARE(t, 126000u);
        QCOMPARE(d, 260101u);
    }

    void advanceMessageKeepsCommands()
    {
        Message last = test::sessionStartMessage();
        last.header.set(ItemId::ID_msg, 16'777'214);
        const Message next = advanceMessage(last, 3);
        QCOMPARE(next.header.number(ItemId::ID_msg), 1);
        QCOMPARE(next.header.number(ItemId::time_UTC), 235803);
        QCOMPARE(next.header.number(ItemId::date_UTC), 261231);
        Message expected = next;
        expected.header = last.header;
        QCOMPARE(expected, last);
    }

    void sessionThroughBitErrors_data()
    {
        QTest::addColumn<bool>("secure");
        QTest::addColumn<double>("ber");
        QTest::addColumn<double>("atLeast");
        QTest::newRow("plain 1e-2") << false << 1e-2 << 0.99;
        QTest::newRow("plain 2e-2") << false << 2e-2 << 0.90;
        QTest::newRow("secure 1e-2") << true << 1e-2 << 0.99;
        QTest::newRow("secure 2e-2") << true << 2e-2 << 0.90;
    }

    void sessionThroughBitErrors()
    {
        // 1,000 frames with a 400-byte plan (two sections, three passes):
        // the plan's frames are the ones predictions cannot read.
        QFETCH(bool, secure);
        QFETCH(double, ber);
        QFETCH(double, atLeast);
        test::BerSessionOptions o;
        o.ber = ber;
        o.frames = 1000;
        o.secure = secure;
        o.planBytes = 400;
        const test::BerSessionResult r = test::runBerSession(o);
        QCOMPARE(r.frames, 1000u);
        QCOMPARE(r.deliveredWrong, 0u);
        QVERIFY2(r.deliveredCorrect >= atLeast * r.frames, qPrintable(QString::number(r.deliveredCorrect)));
        // Plain RS alone reads at most 5.3 % of these frames at 1e-2.
        QVERIFY(r.fromPrediction > r.deliveredCorrect * 9 / 10);
    }
};

QTEST_GUILESS_MAIN(TstTrialDecode)
#include "tst_trialdecode.moc"
