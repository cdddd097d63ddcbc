// Rehearsal faults: counted, not timed. Each check runs a seeded injector over
// many frames and compares what it did with the binomial or Poisson
// expectation, within five standard deviations.
#include "link/aircraft/FaultInjector.h"

#include <QtTest>

#include <bit>
#include <cmath>
#include <vector>

using namespace std::chrono_literals;

namespace {

constexpr std::size_t kFrameBytes = 600;

std::vector<std::uint8_t> frameOf(std::uint8_t fill)
{
    return std::vector<std::uint8_t>(kFrameBytes, fill);
}

std::size_t bitsDiffering(const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b)
{
    std::size_t n = 0;
    for (std::size_t i = 0; i < a.size(); ++i)
        n += static_cast<std::size_t>(std::popcount(static_cast<unsigned>(a[i] ^ b[i])));
    return n;
}

// |observed - n p| within five standard deviations of a binomial(n, p).
bool withinBinomial(double observed, double n, double p)
{
    return std::abs(observed - n * p) <= 5.0 * std::sqrt(n * p * (1.0 - p));
}

}  // namespace

class TestFaults : public QObject {
    Q_OBJECT

private slots:
    void noFaultsChangeNothing()
    {
        FaultInjector injector;
        QVERIFY(!injector.settings().any());
        for (int i = 0; i < 100; ++i) {
            auto frame = frameOf(0x55);
            const auto out = injector.outgoing(frame, std::chrono::seconds(i));
            QVERIFY(out.sent());
            QCOMPARE(out.flippedBits, std::size_t{0});
            QCOMPARE(out.delay, 0ms);
            QVERIFY(frame == frameOf(0x55));
        }
        QCOMPARE(injector.counters().framesSent, 100u);
    }

    void bitErrorRate_data()
    {
        QTest::addColumn<double>("rate");
        QTest::newRow("1e-4") << 1e-4;
        QTest::newRow("1e-3") << 1e-3;
        QTest::newRow("1e-2") << 1e-2;
        QTest::newRow("0.5") << 0.5;
    }

    void bitErrorRate()
    {
        QFETCH(double, rate);
        FaultSettings s;
        s.bitErrorRate = rate;
        s.seed = 42;
        FaultInjector injector(s);
        constexpr int kFrames = 2000;
        std::size_t measured = 0;
        for (int i = 0; i < kFrames; ++i) {
            auto frame = frameOf(static_cast<std::uint8_t>(i));
            const auto out = injector.outgoing(frame, std::chrono::seconds(i));
            QVERIFY(out.sent());
            const std::size_t differing = bitsDiffering(frame, frameOf(static_cast<std::uint8_t>(i)));
            QCOMPARE(out.flippedBits, differing);  // independent flips never land twice on a bit
            measured += differing;
        }
        QCOMPARE(injector.counters().bitsFlipped, measured);
        const double bits = double(kFrames) * kFrameBytes * 8;
        QVERIFY2(withinBinomial(double(measured), bits, rate),
                 qPrintable(QStringLiteral("%1 bits flipped of %2 at %3").arg(measured).arg(bits).arg(rate)));
    }

    void sameSeedSameDamage()
    {
        FaultSettings s;
        s.bitErrorRate = 1e-3;
        s.burstLength = 24;
        s.burstRate = 0.5;
        s.dropProbability = 0.1;
        s.seed = 7;
        FaultInjector a(s), b(s);
        s.seed = 8;
        FaultInjector c(s);
        bool differs = false;
        for (int i = 0; i < 200; ++i) {
            auto fa = frameOf(0), fb = frameOf(0), fc = frameOf(0);
            const auto oa = a.outgoing(fa, std::chrono::seconds(i));
            const auto ob = b.outgoing(fb, std::chrono::seconds(i));
            const auto oc = c.outgoing(fc, std::chrono::seconds(i));
            QCOMPARE(oa.fate, ob.fate);
            QVERIFY(fa == fb);
            differs = differs || oa.fate != oc.fate || fa != fc;
        }
        QVERIFY(differs);
    }

    void bursts()
    {
        FaultSettings s;
        s.burstLength = 32;
        s.burstRate = 1.5;
        s.seed = 3;
        FaultInjector injector(s);
        constexpr int kFrames = 4000;
        std::size_t bursts = 0, single = 0;
        for (int i = 0; i < kFrames; ++i) {
            auto frame = frameOf(0);
            const auto out = injector.outgoing(frame, std::chrono::seconds(i));
            bursts += out.bursts;
            QCOMPARE(out.flippedBits, bitsDiffering(frame, frameOf(0)));
            QCOMPARE(out.flippedBits == 0, out.bursts == 0);
            if (out.bursts != 1)
                continue;
            // A lone burst spans exactly its length: first and last bit flipped.
            ++single;
            std::size_t first = SIZE_MAX, last = 0;
            for (std::size_t bit = 0; bit < kFrameBytes * 8; ++bit) {
                if (frame[bit / 8] & (0x80u >> (bit % 8))) {
                    first = std::min(first, bit);
                    last = bit;
                }
            }
            QCOMPARE(last - first + 1, s.burstLength);
            QVERIFY(out.flippedBits >= 2 && out.flippedBits <= s.burstLength);
        }
        QVERIFY(single > 0);
        QCOMPARE(injector.counters().bursts, bursts);
        // Poisson: variance equals the mean.
        const double mean = kFrames * s.burstRate;
        QVERIFY2(std::abs(double(bursts) - mean) <= 5.0 * std::sqrt(mean), qPrintable(QString::number(bursts)));
    }

    void dropRate()
    {
        FaultSettings s;
        s.dropProbability = 0.2;
        s.seed = 11;
        FaultInjector injector(s);
        constexpr int kFrames = 10000;
        int dropped = 0;
        for (int i = 0; i < kFrames; ++i) {
            auto frame = frameOf(0xAA);
            const auto out = injector.outgoing(frame, std::chrono::seconds(i));
            if (out.fate == FaultInjector::Fate::Dropped)
                ++dropped;
            else
                QVERIFY(frame == frameOf(0xAA));
        }
        QCOMPARE(injector.counters().framesDropped, std::uint64_t(dropped));
        QCOMPARE(injector.counters().framesSent, std::uint64_t(kFrames - dropped));
        QVERIFY2(withinBinomial(dropped, kFrames, 0.2), qPrintable(QString::number(dropped)));
    }

    void outageWindow()
    {
        FaultSettings s;
        s.outageStart = 10s;
        s.outageDuration = 5s;
        FaultInjector injector(s);
        QVERIFY(s.any());
        for (int i = 0; i < 30; ++i) {
            auto frame = frameOf(1);
            const auto t = std::chrono::milliseconds(i * 1000 + 500);
            const bool blanked = i >= 10 && i < 15;
            QCOMPARE(injector.outgoing(frame, t).fate,
                     blanked ? FaultInjector::Fate::Outage : FaultInjector::Fate::Sent);
            QCOMPARE(injector.incoming(t), !blanked);
        }
        // The edges: the start is inside, the end is not.
        QVERIFY(injector.inOutage(10s));
        QVERIFY(injector.inOutage(15s - 1ms));
        QVERIFY(!injector.inOutage(15s));
        QVERIFY(!injector.inOutage(10s - 1ms));
        QCOMPARE(injector.counters().framesLostToOutage, 5u);
        QCOMPARE(injector.counters().framesNotReceived, 5u);
        QCOMPARE(injector.counters().framesSent, 25u);
    }

    void outageDrawsNoRandomNumbers()
    {
        // The frames after an outage carry the same errors as without it.
        FaultSettings s;
        s.bitErrorRate = 1e-3;
        s.seed = 5;
        FaultInjector plain(s);
        s.outageStart = 0s;
        s.outageDuration = 3s;
        FaultInjector withOutage(s);
        for (int i = 0; i < 3; ++i) {
            auto frame = frameOf(0);
            QCOMPARE(withOutage.outgoing(frame, std::chrono::seconds(i)).fate, FaultInjector::Fate::Outage);
        }
        for (int i = 3; i < 50; ++i) {
            auto a = frameOf(0), b = frameOf(0);
            plain.outgoing(a, std::chrono::seconds(i));
            withOutage.outgoing(b, std::chrono::seconds(i));
            QVERIFY(a == b);
        }
    }

    void silentAndDelay()
    {
        FaultSettings s;
        s.silent = true;
        FaultInjector silent(s);
        auto frame = frameOf(0);
        QCOMPARE(silent.outgoing(frame, 1s).fate, FaultInjector::Fate::Silenced);
        QVERIFY(silent.incoming(1s));  // silent still listens
        QCOMPARE(silent.counters().framesSilenced, 1u);

        FaultSettings d;
        d.delay = 250ms;
        FaultInjector delayed(d);
        const auto out = delayed.outgoing(frame, 1s);
        QVERIFY(out.sent());
        QCOMPARE(out.delay, 250ms);
    }
};

QTEST_APPLESS_MAIN(TestFaults)
#include "tst_faults.moc"
