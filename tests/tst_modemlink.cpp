// The console's and the aircraft's modem control (ModemLink) against the
// satellite modem model (SatelliteModem) over real pseudo-terminals: dial,
// CONNECT, frames both ways, a dropped call noticed and redialled, BUSY and
// NO ANSWER backing off, and the hang-up on close, on destruction and when
// the console session stops. Times are shortened so the suite takes seconds;
// nothing here asserts how long anything took.
#include "QuickSatellite.h"
#include "codec/message/Message.h"
#include "link/session/ConsoleSession.h"
#include "link/simulation/SatelliteModem.h"
#include "link/simulation/SatelliteModemThread.h"
#include "link/transport/ModemLink.h"
#include "link/transport/SerialLink.h"
#include "link/voice/VoiceSerialLink.h"

#include <QProcess>
#include <QSignalSpy>
#include <QSocketNotifier>
#include <QTemporaryDir>
#include <QThread>
#include <QtTest>

#include <fcntl.h>
#include <pty.h>
#include <termios.h>
#include <unistd.h>

#include <memory>

using namespace std::chrono_literals;

namespace {

constexpr int kWaitMs = 15000;  // a wait ends as soon as what it waits for comes
const QString kNumber = QStringLiteral("881612345678");

SatelliteModem::Options quickModem()
{
    return rcm::test::quickSatellite(3);  // an unanswered call rings out quickly
}

// The modems' guard time is S12=5, a tenth of a second; the links keep 150 ms.
ModemLink::Options quickLink(const QString& number)
{
    ModemLink::Options o;
    o.initString = "ATE0V1&C1&D2S12=5";
    o.number = number;
    o.commandTimeout = 3000ms;
    o.dialTimeout = 5000ms;
    o.guardTime = 150ms;
    o.hangUpTimeout = 2000ms;
    o.redialDelay = 200ms;
    o.redialDelayLimit = 400ms;
    o.redialAttempts = 2;
    return o;
}

std::unique_ptr<ModemLink> modemLink(const QString& device, ModemLink::Options options)
{
    return std::make_unique<ModemLink>(std::make_unique<SerialLink>(device, 9600, SerialLink::FlowControl::RtsCts),
                                       std::move(options));
}

QByteArray frame(char seed)
{
    QByteArray bytes(600, Qt::Uninitialized);
    for (int i = 0; i < bytes.size(); ++i)
        bytes[i] = char(seed + i * 13);
    return bytes;
}

bool anyContains(const QSignalSpy& spy, const QString& text)
{
    for (const QList<QVariant>& args : spy)
        if (args.at(0).toString().contains(text))
            return true;
    return false;
}

QStringList texts(const QSignalSpy& spy)
{
    QStringList all;
    for (const QList<QVariant>& args : spy)
        all << args.at(0).toString();
    return all;
}

// The model in its own thread (a hang-up blocks this one), with the hang-ups it saw.
class ModemThread : public SatelliteModemThread {
public:
    explicit ModemThread(SatelliteModem::Options options) : SatelliteModemThread(options)
    {
        connect(this, &SatelliteModemThread::hungUp, this,
                [this](int side, const QString& how) { hangUps.append({side, how}); });
    }

    QList<QPair<int, QString>> hangUps;
};

}  // namespace

class TestModemLink : public QObject {
    Q_OBJECT

private slots:
    void resultCodes();
    void dialsAndCarriesFramesBothWays();
    void droppedCallIsNoticedAndRedialled();
    void busyBacksOffThenGivesUp();
    void noAnswerIsRedialled();
    void closeHangsUp();
    void destroyingHangsUp();
    void sessionStopHangsUpWithoutWaiting();
    void voicePacingWaitsForFlowControl();
    void uasimAnswersTheConsolesCall();
};

void TestModemLink::resultCodes()
{
    using modem::Result;
    using modem::ResultCode;
    QCOMPARE(modem::parseResult("CONNECT 9600"), (Result{ResultCode::Connect, 9600}));
    QCOMPARE(modem::parseResult("CONNECT 9600/ARQ"), (Result{ResultCode::Connect, 9600}));
    QCOMPARE(modem::parseResult("CONNECT"), (Result{ResultCode::Connect, 0}));
    QCOMPARE(modem::parseResult("NO CARRIER"), (Result{ResultCode::NoCarrier, 0}));
    QCOMPARE(modem::parseResult("NO DIALTONE"), (Result{ResultCode::NoDialtone, 0}));
    QCOMPARE(modem::parseResult(" BUSY "), (Result{ResultCode::Busy, 0}));
    QVERIFY(!modem::parseResult("ATD881612345678"));
    QVERIFY(!modem::parseResult("CONNECTED"));
    QCOMPARE(modem::resultLine({ResultCode::Connect, 9600}), QByteArray("\r\nCONNECT 9600\r\n"));
}

void TestModemLink::dialsAndCarriesFramesBothWays()
{
    SatelliteModem model(quickModem());
    QString error;
    QVERIFY2(model.open(&error), qPrintable(error));
    auto ground = modemLink(model.device(SatelliteModem::Ground), quickLink(kNumber));
    auto aircraft = modemLink(model.device(SatelliteModem::Aircraft), quickLink(QString()));
    QSignalSpy groundStatus(ground.get(), &Link::statusChanged);
    QSignalSpy groundOpened(ground.get(), &Link::opened);
    QSignalSpy aircraftOpened(aircraft.get(), &Link::opened);
    QSignalSpy aircraftStatus(aircraft.get(), &Link::statusChanged);
    QByteArray atGround, atAircraft;
    connect(ground.get(), &Link::bytesReceived, this, [&](const QByteArray& b) { atGround += b; });
    connect(aircraft.get(), &Link::bytesReceived, this, [&](const QByteArray& b) { atAircraft += b; });

    aircraft->open();
    QTRY_COMPARE_WITH_TIMEOUT(aircraft->callState(), ModemLink::CallState::AwaitingCall, kWaitMs);
    ground->open();
    QTRY_COMPARE_WITH_TIMEOUT(groundOpened.count(), 1, kWaitMs);
    QTRY_COMPARE_WITH_TIMEOUT(aircraftOpened.count(), 1, kWaitMs);
    QVERIFY(ground->isOpen());
    QCOMPARE(ground->connectRate(), 9600);
    QCOMPARE(model.dialledNumber(SatelliteModem::Ground), kNumber.toLatin1());
    QVERIFY2(anyContains(groundStatus, QStringLiteral("dialling 881612345678")), qPrintable(texts(groundStatus).join('\n')));
    QVERIFY2(anyContains(groundStatus, QStringLiteral("connected at 9600 bit/s after")),
             qPrintable(texts(groundStatus).join('\n')));
    QVERIFY(anyContains(aircraftStatus, QStringLiteral("answering a call")));

    const QByteArray command = frame(1) + frame(2);
    const QByteArray status = frame(3);
    QVERIFY(ground->write(command));
    QVERIFY(aircraft->write(status));
    QTRY_COMPARE_WITH_TIMEOUT(atAircraft.size(), command.size(), kWaitMs);
    QCOMPARE(atAircraft, command);
    QTRY_COMPARE_WITH_TIMEOUT(atGround.size(), status.size(), kWaitMs);
    QCOMPARE(atGround, status);
}

void TestModemLink::droppedCallIsNoticedAndRedialled()
{
    SatelliteModem model(quickModem());
    QString error;
    QVERIFY2(model.open(&error), qPrintable(error));
    auto ground = modemLink(model.device(SatelliteModem::Ground), quickLink(kNumber));
    auto aircraft = modemLink(model.device(SatelliteModem::Aircraft), quickLink(QString()));
    QSignalSpy groundOpened(ground.get(), &Link::opened);
    QSignalSpy groundClosed(ground.get(), &Link::closed);
    QSignalSpy groundErrors(ground.get(), &Link::errorOccurred);
    QSignalSpy aircraftClosed(aircraft.get(), &Link::closed);
    QSignalSpy aircraftErrors(aircraft.get(), &Link::errorOccurred);
    aircraft->open();
    QTRY_COMPARE_WITH_TIMEOUT(aircraft->callState(), ModemLink::CallState::AwaitingCall, kWaitMs);
    ground->open();
    QTRY_COMPARE_WITH_TIMEOUT(groundOpened.count(), 1, kWaitMs);

    model.dropCall();
    QTRY_COMPARE_WITH_TIMEOUT(groundClosed.count(), 1, kWaitMs);
    QVERIFY(!ground->isOpen());
    QCOMPARE(groundErrors.count(), 1);
    const QString said = groundErrors.at(0).at(0).toString();
    QVERIFY2(said.startsWith(QStringLiteral("call dropped (NO CARRIER) after ")), qPrintable(said));
    QVERIFY2(said.contains(QStringLiteral("; redialling in 0 s, attempt 2 of 3")), qPrintable(said));
    // The aircraft's side takes it as link loss and waits for the next call.
    QTRY_COMPARE_WITH_TIMEOUT(aircraftClosed.count(), 1, kWaitMs);
    QVERIFY(aircraftErrors.count() == 1 &&
            aircraftErrors.at(0).at(0).toString().endsWith(QStringLiteral("; waiting for a call")));

    // Redialled, answered, and carrying again.
    QTRY_COMPARE_WITH_TIMEOUT(groundOpened.count(), 2, kWaitMs);
    QTRY_VERIFY_WITH_TIMEOUT(aircraft->isOpen(), kWaitMs);
    QCOMPARE(model.counters().calls, 2);
    QCOMPARE(ground->calls(), 2);
    QByteArray atAircraft;
    connect(aircraft.get(), &Link::bytesReceived, this, [&](const QByteArray& b) { atAircraft += b; });
    QVERIFY(ground->write(frame(7)));
    QTRY_COMPARE_WITH_TIMEOUT(atAircraft, frame(7), kWaitMs);
}

void TestModemLink::busyBacksOffThenGivesUp()
{
    SatelliteModem::Options busy = quickModem();
    busy.busy = true;
    SatelliteModem model(busy);
    QString error;
    QVERIFY2(model.open(&error), qPrintable(error));
    ModemLink::Options options = quickLink(kNumber);
    options.redialDelay = 1000ms;
    options.redialDelayLimit = 10000ms;
    auto ground = modemLink(model.device(SatelliteModem::Ground), options);
    QSignalSpy status(ground.get(), &Link::statusChanged);
    QSignalSpy errors(ground.get(), &Link::errorOccurred);
    ground->open();
    QTRY_COMPARE_WITH_TIMEOUT(ground->callState(), ModemLink::CallState::GaveUp, kWaitMs);
    QCOMPARE(model.counters().dials, 3);
    // The delay doubles; the first failure and the giving up are errors, the rest statuses.
    const QStringList said = texts(status);
    QVERIFY2(said.filter(QRegularExpression(QStringLiteral("^BUSY after \\d+ s; redialling in 1 s, attempt 2 of 3$"))).size() == 1,
             qPrintable(said.join('\n')));
    QVERIFY2(said.filter(QRegularExpression(QStringLiteral("^BUSY after \\d+ s; redialling in 2 s, attempt 3 of 3$"))).size() == 1,
             qPrintable(said.join('\n')));
    QVERIFY(said.contains(QStringLiteral("dialling 881612345678, attempt 3 of 3")));
    QCOMPARE(errors.count(), 2);
    QVERIFY(errors.at(0).at(0).toString().contains(QStringLiteral("redialling in 1 s, attempt 2 of 3")));
    QVERIFY2(errors.at(1).at(0).toString().contains(QStringLiteral("; gave up after 3 attempts; hang up and dial again to retry")),
             qPrintable(errors.at(1).at(0).toString()));
    QVERIFY(!ground->isOpen());
}

void TestModemLink::noAnswerIsRedialled()
{
    SatelliteModem model(quickModem());  // the aircraft's side has no one on it: it rings out
    QString error;
    QVERIFY2(model.open(&error), qPrintable(error));
    auto ground = modemLink(model.device(SatelliteModem::Ground), quickLink(kNumber));
    QSignalSpy errors(ground.get(), &Link::errorOccurred);
    ground->open();
    QTRY_COMPARE_WITH_TIMEOUT(errors.count(), 1, kWaitMs);
    QVERIFY2(errors.at(0).at(0).toString().startsWith(QStringLiteral("NO ANSWER after ")),
             qPrintable(errors.at(0).at(0).toString()));
    QCOMPARE(ground->callState(), ModemLink::CallState::WaitingToRedial);
    // Someone picks up the aircraft's phone before the next attempt.
    auto aircraft = modemLink(model.device(SatelliteModem::Aircraft), quickLink(QString()));
    aircraft->open();
    QTRY_VERIFY_WITH_TIMEOUT(ground->isOpen(), kWaitMs);
    QVERIFY(model.counters().dials >= 2);
}

void TestModemLink::closeHangsUp()
{
    ModemThread model(quickModem());
    QString error;
    QVERIFY2(model.open(&error), qPrintable(error));
    ModemLink::Options options = quickLink(kNumber);
    options.costPerMinute = 1.25;
    auto ground = modemLink(model.device(SatelliteModem::Ground), options);
    auto aircraft = modemLink(model.device(SatelliteModem::Aircraft), quickLink(QString()));
    QSignalSpy status(ground.get(), &Link::statusChanged);
    QSignalSpy closed(ground.get(), &Link::closed);
    QSignalSpy aircraftClosed(aircraft.get(), &Link::closed);
    aircraft->open();
    QTRY_COMPARE_WITH_TIMEOUT(aircraft->callState(), ModemLink::CallState::AwaitingCall, kWaitMs);
    ground->open();
    QTRY_VERIFY_WITH_TIMEOUT(ground->isOpen() && aircraft->isOpen(), kWaitMs);

    ground->close();  // Disconnect: blocks the link's thread, here the test's, for the hang-up
    QCOMPARE(closed.count(), 1);
    QCOMPARE(ground->callState(), ModemLink::CallState::Closed);
    QVERIFY2(status.last().at(0).toString().startsWith(QStringLiteral("hung up: ")), qPrintable(texts(status).join('\n')));
    QVERIFY2(status.last().at(0).toString().endsWith(QStringLiteral(" s, 1 min billed, cost 1.25")),
             qPrintable(status.last().at(0).toString()));
    QTRY_COMPARE_WITH_TIMEOUT(model.hangUps.size(), 1, kWaitMs);
    QCOMPARE(model.hangUps.at(0), (QPair<int, QString>(SatelliteModem::Ground, QStringLiteral("ATH"))));
    QTRY_COMPARE_WITH_TIMEOUT(aircraftClosed.count(), 1, kWaitMs);
    QCOMPARE(model.callState(), SatelliteModem::CallState::Idle);
}

void TestModemLink::destroyingHangsUp()
{
    ModemThread model(quickModem());
    QString error;
    QVERIFY2(model.open(&error), qPrintable(error));
    auto ground = modemLink(model.device(SatelliteModem::Ground), quickLink(kNumber));
    auto aircraft = modemLink(model.device(SatelliteModem::Aircraft), quickLink(QString()));
    aircraft->open();
    QTRY_COMPARE_WITH_TIMEOUT(aircraft->callState(), ModemLink::CallState::AwaitingCall, kWaitMs);
    ground->open();
    QTRY_VERIFY_WITH_TIMEOUT(ground->isOpen() && aircraft->isOpen(), kWaitMs);

    ground.reset();  // Quit: the link is destroyed with the call up
    // By its own words, not by the port closing under the call.
    QTRY_COMPARE_WITH_TIMEOUT(model.hangUps.size(), 1, kWaitMs);
    QCOMPARE(model.hangUps.at(0), (QPair<int, QString>(SatelliteModem::Ground, QStringLiteral("ATH"))));
    QTRY_VERIFY_WITH_TIMEOUT(!aircraft->isOpen(), kWaitMs);
}

void TestModemLink::sessionStopHangsUpWithoutWaiting()
{
    ModemThread model(quickModem());
    QString error;
    QVERIFY2(model.open(&error), qPrintable(error));
    auto aircraft = modemLink(model.device(SatelliteModem::Aircraft), quickLink(QString()));
    aircraft->open();
    QTRY_COMPARE_WITH_TIMEOUT(aircraft->callState(), ModemLink::CallState::AwaitingCall, kWaitMs);

    QTemporaryDir logs;
    auto session = std::make_unique<ConsoleSession>(logs.path());
    QSignalSpy started(session.get(), &ConsoleSession::linkStarted);
    LinkSettings settings = *LinkSettings::serial(model.device(SatelliteModem::Ground), QStringLiteral("9600"));
    settings.dialNumber = kNumber;
    settings.modemInit = QStringLiteral("ATE0V1&C1&D2S12=5");
    settings.callCostPerMinute = 2;
    QCOMPARE(settings.summary(), QStringLiteral("serial %1 at 9600 bit/s, dialling 881612345678")
                                     .arg(model.device(SatelliteModem::Ground)));
    session->connectWith(settings);
    QTRY_COMPARE_WITH_TIMEOUT(started.count(), 1, kWaitMs);
    QSignalSpy status(session->controller(), &LinkController::transportStatusChanged);
    QTRY_VERIFY_WITH_TIMEOUT(aircraft->isOpen(), kWaitMs);
    QTRY_VERIFY_WITH_TIMEOUT(anyContains(status, QStringLiteral("connected at 9600 bit/s")), kWaitMs);

    // Disconnect returns at once; the call is hung up in the link's thread
    // (guard time, +++, ATH), and the controller still says how it ended.
    session->stop();
    QVERIFY(!session->isRunning());
    QCOMPARE(model.hangUps.size(), 0);
    QTRY_COMPARE_WITH_TIMEOUT(model.hangUps.size(), 1, kWaitMs);
    QCOMPARE(model.hangUps.at(0).second, QStringLiteral("ATH"));
    QTRY_VERIFY_WITH_TIMEOUT(anyContains(status, QStringLiteral("hung up: ")), kWaitMs);
    QVERIFY(anyContains(status, QStringLiteral("1 min billed, cost 2.00")));

    // Quit with a call up: the session's end hangs up before it returns.
    QTRY_COMPARE_WITH_TIMEOUT(aircraft->callState(), ModemLink::CallState::AwaitingCall, kWaitMs);
    session->connectWith(settings);
    QTRY_VERIFY_WITH_TIMEOUT(aircraft->isOpen(), kWaitMs);
    session.reset();
    QTRY_COMPARE_WITH_TIMEOUT(model.hangUps.size(), 2, kWaitMs);
    QCOMPARE(model.hangUps.at(1).second, QStringLiteral("ATH"));
}

void TestModemLink::voicePacingWaitsForFlowControl()
{
    // A modem that has stopped taking bytes: the far end of a pty nobody reads.
    int master = -1, slave = -1;
    char name[64] = {};
    termios raw{};
    cfmakeraw(&raw);
    QCOMPARE(::openpty(&master, &slave, name, &raw, nullptr), 0);
    VoiceSerialLink::Options fast;
    fast.bytesPerSecond = 400000;  // the kernel's buffer fills in a moment
    VoiceSerialLink link(std::make_unique<SerialLink>(QString::fromLatin1(name)), nullptr, nullptr, fast);
    QSignalSpy opened(&link, &Link::opened);
    link.open();
    QCOMPARE(opened.count(), 1);
    QTRY_VERIFY_WITH_TIMEOUT(link.flowControlHolds() >= 20, kWaitMs);
    // Held, not queued: the port keeps no more than one tick's bytes beyond the lead.
    const qint64 tickBytes = fast.bytesPerSecond * fast.tick.count() / 1000;
    QVERIFY2(link.bytesToWrite() <= fast.lead + (4 + 1) * tickBytes, qPrintable(QString::number(link.bytesToWrite())));
    // The modem takes bytes again: the line goes on.
    const std::uint64_t before = link.lineBytesWritten();
    QSocketNotifier drain(master, QSocketNotifier::Read);
    connect(&drain, &QSocketNotifier::activated, this, [master] {
        char buffer[65536];
        while (::read(master, buffer, sizeof buffer) > 0) {
        }
    });
    ::fcntl(master, F_SETFL, ::fcntl(master, F_GETFL) | O_NONBLOCK);
    QTRY_VERIFY_WITH_TIMEOUT(link.lineBytesWritten() > before + 100000, kWaitMs);
    link.close();
    ::close(slave);
    ::close(master);
}

// The console's session dials, uasim --modem (the real program) answers,
// commands and status frames go both ways through the model at a
// satellite's 1.5 s each way; a dropped call is link loss for uasim too.
void TestModemLink::uasimAnswersTheConsolesCall()
{
    SatelliteModem::Options satellite = quickModem();
    satellite.oneWayDelay = 1500ms;
    satellite.airRate = 1200;
    ModemThread model(satellite);
    QString error;
    QVERIFY2(model.open(&error), qPrintable(error));
    QProcess uasim;
    QByteArray said;
    connect(&uasim, &QProcess::readyReadStandardError, this, [&] { said += uasim.readAllStandardError(); });
    uasim.start(QStringLiteral(RCM_BIN_DIR "/uasim"),
                {QStringLiteral("--serial"), model.device(SatelliteModem::Aircraft), QStringLiteral("--modem"),
                 QStringLiteral("--verbose")});
    QVERIFY(uasim.waitForStarted());
    QTRY_VERIFY_WITH_TIMEOUT(said.contains("waiting for a call"), kWaitMs);

    QTemporaryDir logs;
    ConsoleSession session(logs.path());
    QSignalSpy started(&session, &ConsoleSession::linkStarted);
    LinkSettings settings = *LinkSettings::serial(model.device(SatelliteModem::Ground), QStringLiteral("9600"));
    settings.dialNumber = kNumber;
    settings.modemInit = QStringLiteral("ATE0V1&C1&D2S12=5");
    rcm::Message command;
    command.header.set(rcm::ItemId::ID_UA_source, rcm::Value::pair(44, 133));
    session.setCommand(command);
    session.connectWith(settings);
    QTRY_COMPARE_WITH_TIMEOUT(started.count(), 1, kWaitMs);
    QSignalSpy received(session.controller(), &LinkController::messageReceived);
    QTRY_VERIFY_WITH_TIMEOUT(received.count() >= 2, 4 * kWaitMs);
    QVERIFY2(said.contains("answering a call") && said.contains("uasim: command "), said.constData());

    QSignalSpy lost(session.controller(), &LinkController::linkLost);
    model.dropCall();
    QTRY_VERIFY_WITH_TIMEOUT(lost.count() == 1, kWaitMs);
    QTRY_VERIFY_WITH_TIMEOUT(said.contains("uasim: link lost"), kWaitMs);
    // Said once: the error, not again as the status that repeats it.
    QVERIFY2(said.count("call dropped (NO CARRIER)") == 1, said.constData());
    session.stop();
    uasim.terminate();
    QVERIFY(uasim.waitForFinished());
}

QTEST_MAIN(TestModemLink)
#include "tst_modemlink.moc"
