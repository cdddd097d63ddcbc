// The satellite modem model through its pseudo-terminals, as the console and
// the aircraft use it: a serial port opened on each side's device, commands
// written to it, and waits on what it hears. Times are shortened so that the
// suite takes seconds; nothing here asserts how long anything took.
#include "QuickSatellite.h"
#include "link/satmodem/SatelliteModem.h"

#include <QFileInfo>
#include <QProcess>
#include <QSerialPort>
#include <QSignalSpy>
#include <QTemporaryDir>
#include <QtTest>

#include <memory>

using namespace std::chrono_literals;

namespace {

// Long enough for a loaded machine; a wait ends as soon as what it waits for comes.
constexpr int kWaitMs = 10000;
// Longer than the guard time the tests set (ATS12=5: a tenth of a second).
constexpr int kSilenceMs = 300;

const QByteArray kOk = "\r\nOK\r\n";
const QByteArray kError = "\r\nERROR\r\n";
const QByteArray kRing = "\r\nRING\r\n";
const QByteArray kConnect = "\r\nCONNECT 9600\r\n";
const QByteArray kNoCarrier = "\r\nNO CARRIER\r\n";

SatelliteModem::Options quickOptions()
{
    return rcm::test::quickSatellite(50);  // a test answering a ring must not race the last one
}

// Bytes that show their order: every value, none of them twice in a row.
QByteArray pattern(int size, int start)
{
    QByteArray bytes(size, Qt::Uninitialized);
    for (int i = 0; i < size; ++i)
        bytes[i] = char((start + i * 7) % 251);
    return bytes;
}

// A program on one side's pty: what it writes, and everything it has heard.
class Terminal {
public:
    explicit Terminal(const QString& device)
    {
        m_port.setPortName(device);
        QObject::connect(&m_port, &QSerialPort::readyRead, [this] {
            const QByteArray bytes = m_port.readAll();
            all += bytes;
            m_unread += bytes;
        });
    }
    bool open() { return m_port.open(QIODevice::ReadWrite); }
    void close() { m_port.close(); }
    void send(const QByteArray& bytes) { m_port.write(bytes); }

    // True once `text` has come since what was put aside.
    bool hears(const QByteArray& text) const { return m_unread.contains(text); }
    // What came up to the end of `text`, so that the next wait looks past it.
    void putAside(const QByteArray& text) { m_unread.remove(0, m_unread.indexOf(text) + text.size()); }
    // Everything heard since the last forget(), none of it put aside.
    QByteArray all;
    void forget()
    {
        all.clear();
        m_unread.clear();
    }

private:
    QSerialPort m_port;
    QByteArray m_unread;
};

// QTRY_VERIFY evaluates its condition once more after it holds: the
// condition must not change anything, so what was heard is put aside after.
#define WAIT_HEARD(terminal, text)                                        \
    do {                                                                  \
        QTRY_VERIFY_WITH_TIMEOUT((terminal).hears(text), kWaitMs);        \
        (terminal).putAside(text);                                        \
    } while (false)

// The model and a program on each side of it.
struct Bench {
    explicit Bench(SatelliteModem::Options options = quickOptions()) : modem(options) {}

    bool open()
    {
        QString error;
        if (!modem.open(&error)) {
            qWarning() << error;
            return false;
        }
        ground = std::make_unique<Terminal>(modem.device(SatelliteModem::Ground));
        aircraft = std::make_unique<Terminal>(modem.device(SatelliteModem::Aircraft));
        return ground->open() && aircraft->open();
    }

    SatelliteModem modem;
    std::unique_ptr<Terminal> ground;
    std::unique_ptr<Terminal> aircraft;
};

// A helper's failed check ends only the helper: this ends the test as well.
#define CHECKED(call)                     \
    do {                                  \
        call;                             \
        if (QTest::currentTestFailed())   \
            return;                       \
    } while (false)

}  // namespace

class TestSatelliteModem : public QObject {
    Q_OBJECT

    // The aircraft answers by itself; both sides use a short guard time.
    // Each side hears the call's CONNECT, and nothing before it is kept.
    void connectCall(Bench& b)
    {
        b.aircraft->send("ATE0S0=1S12=5\r");
        WAIT_HEARD(*b.aircraft, kOk);
        b.ground->send("ATE0S12=5\r");
        WAIT_HEARD(*b.ground, kOk);
        b.ground->send("ATD8816\r");
        WAIT_HEARD(*b.ground, kConnect);
        WAIT_HEARD(*b.aircraft, kConnect);
        QCOMPARE(b.modem.callState(), SatelliteModem::CallState::Connected);
        b.ground->forget();
        b.aircraft->forget();
    }

    // Silence, the escape, and silence again: command mode with the call up.
    void escape(Terminal& t)
    {
        QTest::qWait(kSilenceMs);  // the guard time before: silence is what is being made here
        t.send(modem::kEscapeSequence);
        WAIT_HEARD(t, kOk);
    }

private slots:
    void atIsOkWithAndWithoutEcho()
    {
        Bench b;
        QVERIFY(b.open());
        b.ground->send("AT\r");
        QTRY_COMPARE_WITH_TIMEOUT(b.ground->all, "AT\r" + kOk, kWaitMs);
        b.ground->forget();
        b.ground->send("ate0\r\n");  // CR LF ends a line as CR does
        QTRY_COMPARE_WITH_TIMEOUT(b.ground->all, "ate0\r" + kOk, kWaitMs);
        b.ground->forget();
        b.ground->send("AT\r");
        QTRY_COMPARE_WITH_TIMEOUT(b.ground->all, kOk, kWaitMs);
        b.ground->forget();
        b.ground->send("ATE1\rAT\r");
        QTRY_COMPARE_WITH_TIMEOUT(b.ground->all, kOk + "AT\r" + kOk, kWaitMs);
        QVERIFY(b.aircraft->all.isEmpty());
    }

    void commandsAndErrors()
    {
        Bench b;
        QVERIFY(b.open());
        QSignalSpy commands(&b.modem, &SatelliteModem::commandReceived);
        b.aircraft->send("ATE0\r");
        WAIT_HEARD(*b.aircraft, kOk);
        b.aircraft->forget();
        const auto exchange = [&](const QByteArray& line, const QByteArray& answer) {
            b.aircraft->send(line + '\r');
            QTRY_COMPARE_WITH_TIMEOUT(b.aircraft->all, answer, kWaitMs);
            b.aircraft->forget();
        };
        exchange("ATJ", kError);
        exchange("ATV0", kError);  // only verbose results
        exchange("AT&F&C1&D2&K3", kOk);  // typed with echo off; &F puts it back on
        exchange("ATE0S0=2S12=5", "ATE0S0=2S12=5\r" + kOk);
        exchange("ATS0?", "\r\n002\r\n" + kOk);
        exchange("ats12?", "\r\n005\r\n" + kOk);
        exchange("ATS0=999", kError);
        exchange("ATA", kNoCarrier);  // nothing ringing
        exchange("ATO", kError);      // no call to go back to
        exchange("ATH", kOk);
        exchange("ATZ", kOk);
        exchange("ATS0?", "ATS0?\r\r\n000\r\n" + kOk);
        QVERIFY(!commands.isEmpty());
        QCOMPARE(commands.first().at(0).toInt(), int(SatelliteModem::Aircraft));
        QCOMPARE(commands.at(1).at(1).toByteArray(), QByteArray("ATJ"));
        QVERIFY(b.ground->all.isEmpty());
    }

    void dialRingsTheFarSideAndAnswerConnectsBoth()
    {
        Bench b;
        QVERIFY(b.open());
        QSignalSpy states(&b.modem, &SatelliteModem::callStateChanged);
        b.ground->send("ATD 00870 776 123456\r");
        WAIT_HEARD(*b.aircraft, kRing);
        b.aircraft->send("ATA\r");
        WAIT_HEARD(*b.aircraft, kConnect);
        WAIT_HEARD(*b.ground, kConnect);
        QCOMPARE(b.ground->all, "ATD 00870 776 123456\r" + kConnect);  // no OK after a dial
        QCOMPARE(b.modem.dialledNumber(SatelliteModem::Ground), QByteArray("00870776123456"));
        QCOMPARE(b.modem.callState(), SatelliteModem::CallState::Connected);
        QCOMPARE(states.size(), 3);
        QCOMPARE(states.at(0).at(0).value<SatelliteModem::CallState>(), SatelliteModem::CallState::Dialling);
        QCOMPARE(states.at(1).at(0).value<SatelliteModem::CallState>(), SatelliteModem::CallState::Ringing);
        QCOMPARE(states.at(2).at(0).value<SatelliteModem::CallState>(), SatelliteModem::CallState::Connected);
        QCOMPARE(b.modem.counters().calls, 1);
    }

    void autoAnswerAfterTheSetRings()
    {
        Bench b;
        QVERIFY(b.open());
        b.aircraft->send("ATS0=2\r");
        WAIT_HEARD(*b.aircraft, kOk);
        b.ground->send("ATDT5551234\r");
        WAIT_HEARD(*b.aircraft, kRing + kRing + kConnect);
        WAIT_HEARD(*b.ground, kConnect);
        QCOMPARE(b.modem.dialledNumber(SatelliteModem::Ground), QByteArray("5551234"));
    }

    void theAircraftMayCallTheGround()
    {
        Bench b;
        QVERIFY(b.open());
        b.aircraft->send("ATDP1\r");
        WAIT_HEARD(*b.ground, kRing);
        b.ground->send("ATA\r");
        WAIT_HEARD(*b.ground, kConnect);
        WAIT_HEARD(*b.aircraft, kConnect);
        QCOMPARE(b.modem.dialledNumber(SatelliteModem::Aircraft), QByteArray("1"));
    }

    void bytesArriveExactAndInOrderBothWays()
    {
        Bench b;
        QVERIFY(b.open());
        CHECKED(connectCall(b));
        QByteArray up, down;
        for (int i = 0; i < 3; ++i) {
            up += pattern(600, i);
            down += pattern(600, 100 + i);
            b.ground->send(pattern(600, i));
            b.aircraft->send(pattern(600, 100 + i));
        }
        QTRY_COMPARE_WITH_TIMEOUT(b.aircraft->all.size(), up.size(), kWaitMs);
        QTRY_COMPARE_WITH_TIMEOUT(b.ground->all.size(), down.size(), kWaitMs);
        QCOMPARE(b.aircraft->all, up);
        QCOMPARE(b.ground->all, down);
        QCOMPARE(b.modem.counters().bytesCarried[SatelliteModem::Ground], up.size());
        QCOMPARE(b.modem.counters().bytesCarried[SatelliteModem::Aircraft], down.size());
    }

    void escapeKeepsTheCallAndHangUpEndsIt()
    {
        Bench b;
        QVERIFY(b.open());
        CHECKED(connectCall(b));
        QSignalSpy hungUp(&b.modem, &SatelliteModem::hungUp);
        b.ground->send("hello");
        WAIT_HEARD(*b.aircraft, "hello");
        CHECKED(escape(*b.ground));
        b.ground->send("ATO\r");
        WAIT_HEARD(*b.ground, kConnect);
        b.ground->send("again");
        WAIT_HEARD(*b.aircraft, "again");
        QCOMPARE(b.aircraft->all, QByteArray("helloagain"));  // the escape was not passed on
        CHECKED(escape(*b.ground));
        b.ground->send("ATH\r");
        WAIT_HEARD(*b.ground, kOk);
        WAIT_HEARD(*b.aircraft, kNoCarrier);
        QCOMPARE(b.modem.callState(), SatelliteModem::CallState::Idle);
        QCOMPARE(hungUp.size(), 1);
        QCOMPARE(hungUp.first().at(0).toInt(), int(SatelliteModem::Ground));
        QCOMPARE(hungUp.first().at(1).toString(), QStringLiteral("ATH"));
        b.aircraft->send("AT\r");  // back in command mode, echo as it was set
        WAIT_HEARD(*b.aircraft, kOk);
    }

    void plusesWithoutGuardSilenceAreData()
    {
        Bench b;
        QVERIFY(b.open());
        CHECKED(connectCall(b));
        b.ground->send("abc+++def");  // no silence either side
        WAIT_HEARD(*b.aircraft, "abc+++def");
        b.ground->send("ghi+++");  // silence after, none before
        WAIT_HEARD(*b.aircraft, "ghi+++");
        QTest::qWait(kSilenceMs);  // silence before, none after
        b.ground->send("+++xyz");
        WAIT_HEARD(*b.aircraft, "+++xyz");
        b.ground->send("more");
        WAIT_HEARD(*b.aircraft, "more");
        QCOMPARE(b.aircraft->all, QByteArray("abc+++defghi++++++xyzmore"));
        QVERIFY(b.ground->all.isEmpty());  // no OK: never in command mode
    }

    void dropCallGivesBothSidesNoCarrier()
    {
        Bench b;
        QVERIFY(b.open());
        CHECKED(connectCall(b));
        QSignalSpy hungUp(&b.modem, &SatelliteModem::hungUp);
        b.ground->send(pattern(600, 0));  // on its way when the call drops: lost
        b.modem.dropCall();
        WAIT_HEARD(*b.ground, kNoCarrier);
        WAIT_HEARD(*b.aircraft, kNoCarrier);
        QCOMPARE(hungUp.size(), 1);
        QCOMPARE(hungUp.first().at(0).toInt(), -1);
        QCOMPARE(hungUp.first().at(1).toString(), QStringLiteral("dropped"));
        QCOMPARE(b.modem.counters().drops, 1);
        QCOMPARE(b.modem.callState(), SatelliteModem::CallState::Idle);
        b.aircraft->send("AT\r");
        WAIT_HEARD(*b.aircraft, kOk);
    }

    void callsDropAtRandomWhenAsked()
    {
        SatelliteModem::Options o = quickOptions();
        o.meanTimeBetweenDrops = 200ms;
        o.seed = 7;
        Bench b(o);
        QVERIFY(b.open());
        QSignalSpy hungUp(&b.modem, &SatelliteModem::hungUp);
        // Not connectCall(): the call may be gone before it could look at it.
        b.aircraft->send("ATS0=1\r");
        WAIT_HEARD(*b.aircraft, kOk);
        b.ground->send("ATD1\r");
        WAIT_HEARD(*b.ground, kConnect + kNoCarrier);
        WAIT_HEARD(*b.aircraft, kConnect + kNoCarrier);
        QCOMPARE(b.modem.counters().drops, 1);
        QCOMPARE(hungUp.size(), 1);
        QCOMPARE(hungUp.first().at(1).toString(), QStringLiteral("dropped"));
    }

    void busyFarSide()
    {
        SatelliteModem::Options o = quickOptions();
        o.busy = true;
        Bench b(o);
        QVERIFY(b.open());
        b.ground->send("ATD1\r");
        WAIT_HEARD(*b.ground, "\r\nBUSY\r\n");
        QVERIFY(b.aircraft->all.isEmpty());
        QCOMPARE(b.modem.callState(), SatelliteModem::CallState::Idle);
    }

    void refusingARingingCallIsBusyForTheCaller()
    {
        Bench b;
        QVERIFY(b.open());
        b.ground->send("ATD1\r");
        WAIT_HEARD(*b.aircraft, kRing);
        b.aircraft->send("ATH\r");
        WAIT_HEARD(*b.aircraft, kOk);
        WAIT_HEARD(*b.ground, "\r\nBUSY\r\n");
    }

    void noAnswerAfterTheRingLimit()
    {
        SatelliteModem::Options o = quickOptions();
        o.ringLimit = 3;
        Bench b(o);
        QVERIFY(b.open());
        b.ground->send("ATD1\r");
        WAIT_HEARD(*b.ground, "\r\nNO ANSWER\r\n");
        QCOMPARE(b.aircraft->all.count(kRing), qsizetype(3));
        QCOMPARE(b.modem.callState(), SatelliteModem::CallState::Idle);
    }

    void noDialtoneWithoutService()
    {
        SatelliteModem::Options o = quickOptions();
        o.noService = true;
        Bench b(o);
        QVERIFY(b.open());
        QSignalSpy states(&b.modem, &SatelliteModem::callStateChanged);
        b.ground->send("ATD1\r");
        WAIT_HEARD(*b.ground, "\r\nNO DIALTONE\r\n");
        QVERIFY(states.isEmpty());
    }

    void aKeyWhileDiallingAbandonsTheCall()
    {
        SatelliteModem::Options o = quickOptions();
        o.callSetupTime = 60s;  // the key ends it long before
        Bench b(o);
        QVERIFY(b.open());
        QSignalSpy hungUp(&b.modem, &SatelliteModem::hungUp);
        b.ground->send("ATD1\r\n");  // the LF is the CR's partner, not a key
        QTRY_COMPARE_WITH_TIMEOUT(b.modem.callState(), SatelliteModem::CallState::Dialling, kWaitMs);
        b.ground->send("x");
        WAIT_HEARD(*b.ground, kNoCarrier);
        QCOMPARE(b.modem.callState(), SatelliteModem::CallState::Idle);
        QCOMPARE(hungUp.size(), 1);
        QCOMPARE(hungUp.first().at(1).toString(), QStringLiteral("aborted"));
    }

    void aProgramGoingAwayHangsUpAndAnotherMayComeBack()
    {
        Bench b;
        QVERIFY(b.open());
        CHECKED(connectCall(b));
        QSignalSpy hungUp(&b.modem, &SatelliteModem::hungUp);
        b.ground->send(pattern(600, 0));  // unread by anyone when the aircraft's program goes
        b.aircraft->close();
        WAIT_HEARD(*b.ground, kNoCarrier);
        QCOMPARE(hungUp.size(), 1);
        QCOMPARE(hungUp.first().at(0).toInt(), int(SatelliteModem::Aircraft));
        QCOMPARE(hungUp.first().at(1).toString(), QStringLiteral("slave closed"));

        // A new program finds a modem in command mode and nothing stale.
        Terminal again(b.modem.device(SatelliteModem::Aircraft));
        QVERIFY(again.open());
        again.send("ATS0?\r");
        QTRY_COMPARE_WITH_TIMEOUT(again.all, "\r\n001\r\n" + kOk, kWaitMs);  // settings kept: E0, S0=1
        b.ground->send("ATD2\r");
        WAIT_HEARD(again, kConnect);
        WAIT_HEARD(*b.ground, kConnect);
        b.ground->send("after");
        WAIT_HEARD(again, "after");
    }

    void backPressureStopsTheSenderAndLosesNothing()
    {
        SatelliteModem::Options o = quickOptions();
        o.bufferLimit = 256;
        Bench b(o);
        QVERIFY(b.open());
        CHECKED(connectCall(b));
        QSignalSpy flow(&b.modem, &SatelliteModem::flowControlChanged);
        const QByteArray bytes = pattern(5000, 3);
        b.ground->send(bytes);
        QTRY_VERIFY_WITH_TIMEOUT(!flow.isEmpty(), kWaitMs);
        QCOMPARE(flow.first().at(0).toInt(), int(SatelliteModem::Ground));
        QCOMPARE(flow.first().at(1).toBool(), true);
        QTRY_COMPARE_WITH_TIMEOUT(b.aircraft->all.size(), bytes.size(), kWaitMs);
        QCOMPARE(b.aircraft->all, bytes);
        QVERIFY(b.modem.counters().flowControlStops[SatelliteModem::Ground] >= 1);
        QTRY_COMPARE_WITH_TIMEOUT(flow.last().at(1).toBool(), false, kWaitMs);
    }

    // Iridium's dialect: the V.110 bearer, +CSQ in bars without a space, the
    // +CIER indicator events (the state at once when turned on, then each
    // change), registration lost and found, and no dial without it.
    void iridiumDialect()
    {
        SatelliteModem::Options options = quickOptions();
        options.profile = *modem::findProfile(QStringLiteral("iridium-9522b"));
        Bench b(options);
        QVERIFY(b.open());
        b.ground->send("ATE0\r");
        WAIT_HEARD(*b.ground, kOk);
        b.ground->forget();
        b.ground->send("AT&K3+CBST=71,0,1\r");
        QTRY_COMPARE_WITH_TIMEOUT(b.ground->all, kOk, kWaitMs);
        b.ground->forget();
        b.ground->send("AT+CBST?\r");
        QTRY_COMPARE_WITH_TIMEOUT(b.ground->all, "\r\n+CBST:71,0,1\r\n" + kOk, kWaitMs);
        b.ground->forget();
        b.ground->send("AT+CSQ\r");
        QTRY_COMPARE_WITH_TIMEOUT(b.ground->all, "\r\n+CSQ:4\r\n" + kOk, kWaitMs);
        b.ground->forget();
        b.ground->send("AT+CIER=1,1,1\r");
        QTRY_COMPARE_WITH_TIMEOUT(b.ground->all, kOk + "\r\n+CIEV:0,4\r\n\r\n+CIEV:1,1\r\n", kWaitMs);
        b.ground->forget();
        b.modem.setSignalBars(0);
        QTRY_COMPARE_WITH_TIMEOUT(b.ground->all, "\r\n+CIEV:0,0\r\n\r\n+CIEV:1,0\r\n", kWaitMs);
        b.ground->forget();
        b.ground->send("AT+CREG?\r");
        QTRY_COMPARE_WITH_TIMEOUT(b.ground->all, "\r\n+CREG:0,2\r\n" + kOk, kWaitMs);
        b.ground->forget();
        b.ground->send("ATD8816\r");
        QTRY_COMPARE_WITH_TIMEOUT(b.ground->all, "\r\nNO DIALTONE\r\n", kWaitMs);
        b.ground->forget();
        b.modem.setSignalBars(3);
        QTRY_COMPARE_WITH_TIMEOUT(b.ground->all, "\r\n+CIEV:0,3\r\n\r\n+CIEV:1,1\r\n", kWaitMs);
        b.ground->forget();
        b.ground->send("AT+CSQ\r");
        QTRY_COMPARE_WITH_TIMEOUT(b.ground->all, "\r\n+CSQ:3\r\n" + kOk, kWaitMs);
        b.ground->forget();
        // The GSM family's unsolicited +CREG is not Iridium's way, but it has it too.
        b.ground->send("AT+CIER=0,0,0\r");
        QTRY_COMPARE_WITH_TIMEOUT(b.ground->all, kOk, kWaitMs);
    }

    // The GSM family (3GPP TS 27.007): +CREG: n,stat, the unsolicited
    // +CREG: stat after AT+CREG=1, +CSQ: rssi,ber on 0..31; no +CIER.
    void gsmFamilyDialect()
    {
        Bench b;  // the default profile
        QVERIFY(b.open());
        b.ground->send("ATE0\r");
        WAIT_HEARD(*b.ground, kOk);
        b.ground->forget();
        b.ground->send("AT+CSQ\r");
        QTRY_COMPARE_WITH_TIMEOUT(b.ground->all, "\r\n+CSQ: 22,99\r\n" + kOk, kWaitMs);
        b.ground->forget();
        b.ground->send("AT+CIER=1,1,1\r");
        QTRY_COMPARE_WITH_TIMEOUT(b.ground->all, kError, kWaitMs);
        b.ground->forget();
        b.ground->send("AT+CREG=1;+CREG?\r");
        QTRY_COMPARE_WITH_TIMEOUT(b.ground->all, "\r\n+CREG: 1,1\r\n" + kOk, kWaitMs);
        b.ground->forget();
        b.modem.setSignalBars(0);
        QTRY_COMPARE_WITH_TIMEOUT(b.ground->all, "\r\n+CREG: 2\r\n", kWaitMs);
        b.ground->forget();
        b.modem.setSignalBars(5);
        QTRY_COMPARE_WITH_TIMEOUT(b.ground->all, "\r\n+CREG: 1\r\n", kWaitMs);
        b.ground->forget();
        b.ground->send("at+csq\r");
        QTRY_COMPARE_WITH_TIMEOUT(b.ground->all, "\r\n+CSQ: 28,99\r\n" + kOk, kWaitMs);
    }

    void modemWithoutANetworkHasNoNetworkCommands()
    {
        SatelliteModem::Options options = quickOptions();
        options.profile = *modem::findProfile(QStringLiteral("hayes"));
        Bench b(options);
        QVERIFY(b.open());
        b.ground->send("ATE0\r");
        WAIT_HEARD(*b.ground, kOk);
        b.ground->forget();
        b.ground->send("AT+CSQ\r");
        QTRY_COMPARE_WITH_TIMEOUT(b.ground->all, kError, kWaitMs);
    }

    // The service script, in time order, and a call that loses its signal drops.
    void serviceScriptAndSignalLoss()
    {
        QString error;
        QVERIFY(!SatelliteModem::parseService(QStringLiteral("0:0,10"), &error));
        QVERIFY2(error.contains(QStringLiteral("\"10\"")), qPrintable(error));
        QVERIFY(!SatelliteModem::parseService(QStringLiteral("5:1,2:3"), &error));
        QVERIFY(!SatelliteModem::parseService(QStringLiteral("0:6"), &error));
        const auto parsed = SatelliteModem::parseService(QStringLiteral("0:0, 0.3:2"), &error);
        QVERIFY2(parsed, qPrintable(error));
        QCOMPARE(parsed->size(), std::size_t(2));
        QCOMPARE(parsed->at(1).at, 300ms);
        QCOMPARE(parsed->at(1).bars, 2);

        SatelliteModem::Options options = quickOptions();
        options.service = *parsed;
        Bench b(options);
        QSignalSpy signal(&b.modem, &SatelliteModem::signalChanged);
        QVERIFY(b.open());
        QTRY_COMPARE_WITH_TIMEOUT(signal.count(), 2, kWaitMs);
        QCOMPARE(signal.at(0).at(0).toInt(), 0);
        QCOMPARE(signal.at(1).at(0).toInt(), 2);
        CHECKED(connectCall(b));
        b.modem.setSignalBars(0);
        WAIT_HEARD(*b.ground, kNoCarrier);
        WAIT_HEARD(*b.aircraft, kNoCarrier);
        QCOMPARE(b.modem.callState(), SatelliteModem::CallState::Idle);
    }

    // With &D0 the modem ignores DTR: the program goes, the call stays up,
    // and the next program finds the modem in data mode.
    void callOutlivesTheProgramWithAmpersandD0()
    {
        Bench b;
        QVERIFY(b.open());
        QSignalSpy hungUp(&b.modem, &SatelliteModem::hungUp);
        QSignalSpy userGone(&b.modem, &SatelliteModem::userGone);
        b.ground->send("AT&D0\r");
        WAIT_HEARD(*b.ground, kOk);
        CHECKED(connectCall(b));
        b.ground->close();
        b.aircraft->send("still there?");
        // The model has seen the program go and acted on it: the call is kept.
        QTRY_VERIFY(userGone.contains(QVariantList{int(SatelliteModem::Ground)}));
        QCOMPARE(b.modem.callState(), SatelliteModem::CallState::Connected);
        QCOMPARE(hungUp.count(), 0);
        QVERIFY(b.ground->open());
        b.aircraft->send("yes");
        WAIT_HEARD(*b.ground, "yes");
    }

    // satmodem makes a missing --link-dir; a directory it cannot make is said with the reason.
    void satmodemMakesItsLinkDirectory()
    {
        QTemporaryDir dir;
        QVERIFY(dir.isValid());
        const QString links = dir.filePath(QStringLiteral("not/yet"));
        QProcess satmodem;
        satmodem.start(QStringLiteral(RCM_BIN_DIR "/satmodem"), {QStringLiteral("--link-dir"), links});
        QVERIFY2(satmodem.waitForStarted(), "build satmodem first");
        QTRY_VERIFY_WITH_TIMEOUT(satmodem.readAllStandardOutput().contains("aircraft: /dev/pts/") ||
                                     QFileInfo(links + QStringLiteral("/aircraft")).isSymLink(),
                                 kWaitMs);
        QVERIFY(QFileInfo(links + QStringLiteral("/ground")).isSymLink());
        QVERIFY(QFileInfo(links + QStringLiteral("/aircraft")).isSymLink());
        satmodem.terminate();
        QVERIFY(satmodem.waitForFinished(kWaitMs));
        QCOMPARE(satmodem.exitCode(), 0);
        QVERIFY(!QFileInfo::exists(links + QStringLiteral("/ground")));

        QFile blocker(dir.filePath(QStringLiteral("file")));
        QVERIFY(blocker.open(QIODevice::WriteOnly));
        blocker.close();
        QProcess refused;
        refused.start(QStringLiteral(RCM_BIN_DIR "/satmodem"),
                      {QStringLiteral("--link-dir"), blocker.fileName() + QStringLiteral("/sub")});
        QVERIFY(refused.waitForFinished(kWaitMs));
        QCOMPARE(refused.exitCode(), 1);
        const QString said = QString::fromLocal8Bit(refused.readAllStandardError());
        QVERIFY2(said.contains(QStringLiteral("cannot make the directory")) &&
                     said.contains(QStringLiteral("Not a directory")),
                 qPrintable(said));
    }
};

QTEST_GUILESS_MAIN(TestSatelliteModem)
#include "tst_satmodem.moc"
