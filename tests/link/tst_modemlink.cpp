// The console's and the aircraft's modem control (ModemLink) against the
// satellite modem model (SatelliteModem) over real pseudo-terminals: dial,
// CONNECT, frames both ways, a dropped call noticed and redialled, BUSY and
// NO ANSWER backing off, and the hang-up on close, on destruction and when
// the console session stops. Times are shortened so the suite takes seconds;
// nothing here asserts how long anything took.
#include "QuickSatellite.h"
#include "codec/message/Message.h"
#include "link/satmodem/SatelliteModem.h"
#include "link/satmodem/SatelliteModemThread.h"
#include "link/session/ConsoleSession.h"
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

bool startsWith(const QStringList& list, const QStringList& first)
{
    return list.mid(0, first.size()) == first;
}

QStringList texts(const QSignalSpy& spy)
{
    QStringList all;
    for (const QList<QVariant>& args : spy)
        all << args.at(0).toString();
    return all;
}

// The model in its own thread, with the hang-ups it saw: a hang-up blocks
// this one, the links' (on close, on destruction at the end of a case),
// and with the model in this thread it would wait out every timeout for
// the OK that the model could not send meanwhile.
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
    void serviceLinesParsedLiberally();
    void noDialWithoutServiceThenDials();
    void iridiumIndicationsEndTheWait();
    void staleCallIsEscapedBeforeInit();
    void callsThatDropAtOnceCountAsFailures();
    void profileSetUpRefusedIsSaid();
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
    // Liberal in case and spaces.
    QCOMPARE(modem::parseResult("ok"), (Result{ResultCode::Ok, 0}));
    QCOMPARE(modem::parseResult("No  Carrier"), (Result{ResultCode::NoCarrier, 0}));
    QCOMPARE(modem::parseResult("connect 9600"), (Result{ResultCode::Connect, 9600}));
    QCOMPARE(modem::resultLine({ResultCode::Connect, 9600}), QByteArray("\r\nCONNECT 9600\r\n"));
}

void TestModemLink::dialsAndCarriesFramesBothWays()
{
    ModemThread model(quickModem());
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
    ModemThread model(quickModem());
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
    ModemThread model(quickModem());  // the aircraft's side has no one on it: it rings out
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
    options.costCurrency = QStringLiteral("GBP");
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
    QVERIFY2(status.last().at(0).toString().endsWith(QStringLiteral(" s, 1 min billed at 1.25 GBP a minute, cost 1.25 GBP")),
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
    settings.callCurrency = QStringLiteral("EUR");
    QCOMPARE(settings.summary(), QStringLiteral("serial %1 at 9600 bit/s, phone 881612345678 (Generic (3GPP TS 27.007))")
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
    QVERIFY(anyContains(status, QStringLiteral("1 min billed at 2.00 EUR a minute, cost 2.00 EUR")));

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

// What phones say of their service, in every form they say it.
void TestModemLink::serviceLinesParsedLiberally()
{
    using modem::Registration;
    using modem::SignalScale;
    const auto creg = [](const char* line) {
        modem::Service s;
        return modem::parseServiceLine(line, SignalScale::Rssi27007, s) ? s.registration : Registration(-9);
    };
    QCOMPARE(creg("+CREG: 0,1"), Registration::Home);
    QCOMPARE(creg("+creg:0,5"), Registration::Roaming);
    QCOMPARE(creg(" +CREG : 2 , 2 "), Registration::Searching);
    QCOMPARE(creg("+CREG: 1"), Registration::Home);  // unsolicited: <stat> alone
    QCOMPARE(creg("+CREG: 0"), Registration::NotSearching);
    QCOMPARE(creg("+CREG: 2,1,\"00A1\",\"1B2C\""), Registration::Home);
    QCOMPARE(creg("+CREG: 1,\"00A1\",\"1B2C\""), Registration::Home);  // unsolicited with the location
    QCOMPARE(creg("+CREG:000,001"), Registration::Home);              // Iridium's zero padding
    QCOMPARE(creg("+CREG: 3"), Registration::Denied);
    QCOMPARE(creg("+CREG: 0,9"), Registration(-9));
    QCOMPARE(creg("+CREG:"), Registration(-9));
    QCOMPARE(creg("OK"), Registration(-9));

    const auto bars = [](const char* line, SignalScale scale) {
        modem::Service s;
        return modem::parseServiceLine(line, scale, s) ? s.bars : -9;
    };
    QCOMPARE(bars("+CSQ: 0,99", SignalScale::Rssi27007), 0);
    QCOMPARE(bars("+CSQ: 99,99", SignalScale::Rssi27007), -1);
    QCOMPARE(bars("+csq: 15, 0", SignalScale::Rssi27007), 3);
    QCOMPARE(bars("+CSQ: 31,0", SignalScale::Rssi27007), 5);
    QCOMPARE(bars("+CSQ: 1,0", SignalScale::Rssi27007), 1);
    QCOMPARE(bars("+CSQ:4", SignalScale::Bars), 4);
    QCOMPARE(bars("+CSQF:0", SignalScale::Bars), 0);
    QCOMPARE(bars("+CIEV:0,3", SignalScale::Rssi27007), 3);  // Iridium's indicator is in bars whatever the profile
    QCOMPARE(bars("+CIEV: 0 , 5", SignalScale::Bars), 5);
    modem::Service s;
    QVERIFY(modem::parseServiceLine("+CIEV:1,0", SignalScale::Bars, s));
    QCOMPARE(s.available, std::optional<bool>(false));
    QVERIFY(!s.canDial());
    QVERIFY(modem::parseServiceLine("+ciev: 1,1", SignalScale::Bars, s));
    QVERIFY(s.canDial());  // service available, signal not known: Iridium's indicator speaks for the network
    QVERIFY(!modem::parseServiceLine("+CIEV:2,1", SignalScale::Bars, s));

    // The model's answers read back as what it meant.
    for (int b = 0; b <= 5; ++b) {
        QCOMPARE(modem::barsFromSignal(modem::signalFromBars(b, SignalScale::Rssi27007), SignalScale::Rssi27007), b);
        QCOMPARE(modem::barsFromSignal(modem::signalFromBars(b, SignalScale::Bars), SignalScale::Bars), b);
    }
    QCOMPARE(modem::Service{}.text(), QStringLiteral("registration not known, signal not known"));
    QCOMPARE((modem::Service{Registration::Searching, 0, {}}.text()),
             QStringLiteral("not registered, searching for the network, no signal"));
    QCOMPARE((modem::Service{Registration::Home, 3, {}}.text()), QStringLiteral("registered, signal 3 of 5"));
}

// No registration and no signal: no ATD, said once as an error; the phone
// asked again until it has service, then dialled at once.
void TestModemLink::noDialWithoutServiceThenDials()
{
    ModemThread model(quickModem());
    QString error;
    QVERIFY2(model.open(&error), qPrintable(error));
    model.setSignalBars(0);
    QStringList commands;
    connect(&model, &SatelliteModemThread::commandReceived, &model,
            [&](int side, const QByteArray& line) {
                if (side == SatelliteModem::Ground)
                    commands << QString::fromLatin1(line);
            });
    ModemLink::Options options = quickLink(kNumber);
    options.servicePollInterval = 100ms;
    auto ground = modemLink(model.device(SatelliteModem::Ground), options);
    auto aircraft = modemLink(model.device(SatelliteModem::Aircraft), quickLink(QString()));
    QSignalSpy errors(ground.get(), &Link::errorOccurred);
    QSignalSpy service(ground.get(), &Link::serviceChanged);
    aircraft->open();
    QTRY_COMPARE_WITH_TIMEOUT(aircraft->callState(), ModemLink::CallState::AwaitingCall, kWaitMs);
    ground->open();
    QTRY_COMPARE_WITH_TIMEOUT(ground->callState(), ModemLink::CallState::WaitingForService, kWaitMs);
    // Asked again, more than once, and never dialled.
    QTRY_VERIFY_WITH_TIMEOUT(commands.count(QStringLiteral("AT+CREG?")) >= 3, kWaitMs);
    QCOMPARE(ground->dials(), 0);
    for (const QString& c : commands)
        QVERIFY2(!c.startsWith(QStringLiteral("ATD")), qPrintable(commands.join(' ')));
    QCOMPARE(errors.count(), 1);
    QCOMPARE(errors.at(0).at(0).toString(),
             QStringLiteral("not dialling 881612345678: not registered, searching for the network, no signal; "
                            "dialling as soon as the phone has service"));
    QVERIFY(service.count() >= 1);
    QCOMPARE(service.last().at(0).toInt(), 0);
    QCOMPARE(service.last().at(1).toBool(), false);
    QVERIFY(startsWith(commands, {QStringLiteral("AT"), QStringLiteral("ATE0V1&C1&D2S12=5"),
                                 QStringLiteral("AT+CREG=1"), QStringLiteral("AT+CREG?"), QStringLiteral("AT+CSQ")}));

    model.setSignalBars(3);
    QTRY_VERIFY_WITH_TIMEOUT(ground->isOpen() && aircraft->isOpen(), kWaitMs);
    QCOMPARE(ground->dials(), 1);
    QCOMPARE(service.last().at(0).toInt(), 3);
    QCOMPARE(service.last().at(1).toBool(), true);
    QCOMPARE(service.last().at(2).toString(), QStringLiteral("registered, signal 3 of 5"));
    QCOMPARE(errors.count(), 1);
}

// An Iridium phone says its service by itself (+CIEV): the wait ends with
// the report, not the next poll.
void TestModemLink::iridiumIndicationsEndTheWait()
{
    SatelliteModem::Options modelOptions = quickModem();
    modelOptions.profile = *modem::findProfile(QStringLiteral("iridium-9523"));
    ModemThread model(modelOptions);
    QString error;
    QVERIFY2(model.open(&error), qPrintable(error));
    model.setSignalBars(0);
    QStringList commands;
    connect(&model, &SatelliteModemThread::commandReceived, &model, [&](int side, const QByteArray& line) {
        if (side == SatelliteModem::Ground)
            commands << QString::fromLatin1(line);
    });
    ModemLink::Options options = quickLink(kNumber);
    options.profile = modelOptions.profile;
    options.servicePollInterval = 3600s;  // only the phone's own report can end the wait
    auto ground = modemLink(model.device(SatelliteModem::Ground), options);
    auto aircraft = modemLink(model.device(SatelliteModem::Aircraft), quickLink(QString()));
    QSignalSpy service(ground.get(), &Link::serviceChanged);
    aircraft->open();
    QTRY_COMPARE_WITH_TIMEOUT(aircraft->callState(), ModemLink::CallState::AwaitingCall, kWaitMs);
    ground->open();
    QTRY_COMPARE_WITH_TIMEOUT(ground->callState(), ModemLink::CallState::WaitingForService, kWaitMs);
    QVERIFY(startsWith(commands, {QStringLiteral("AT"), QStringLiteral("ATE0V1&C1&D2S12=5"), QStringLiteral("AT&K3"),
                                 QStringLiteral("AT+CBST=71,0,1"), QStringLiteral("AT+CIER=1,1,1"),
                                 QStringLiteral("AT+CREG?"), QStringLiteral("AT+CSQ")}));
    model.setSignalBars(2);
    QTRY_VERIFY_WITH_TIMEOUT(ground->isOpen(), kWaitMs);
    QCOMPARE(service.last().at(0).toInt(), 2);
}

// A modem still in a call from an earlier session (set to &D0, so the
// console's going did not end it) answers no "AT": it is escaped with the
// guard times and hung up before the init string, then dialled afresh.
void TestModemLink::staleCallIsEscapedBeforeInit()
{
    ModemThread model(quickModem());
    QString error;
    QVERIFY2(model.open(&error), qPrintable(error));
    QStringList commands;
    connect(&model, &SatelliteModemThread::commandReceived, &model, [&](int side, const QByteArray& line) {
        if (side == SatelliteModem::Ground)
            commands << QString::fromLatin1(line);
    });
    // The aircraft stays in its call, and answers the next one.
    auto aircraft = modemLink(model.device(SatelliteModem::Aircraft), quickLink(QString()));
    aircraft->open();
    QTRY_COMPARE_WITH_TIMEOUT(aircraft->callState(), ModemLink::CallState::AwaitingCall, kWaitMs);
    QSignalSpy userGone(&model, &SatelliteModemThread::userGone);
    {
        // The earlier session: its call up, then gone without hanging up.
        ModemLink::Options o = quickLink(kNumber);
        o.initString = "ATE0V1&C1&D0S12=5";
        auto earlier = modemLink(model.device(SatelliteModem::Ground), o);
        earlier->open();
        QTRY_VERIFY_WITH_TIMEOUT(earlier->isOpen(), kWaitMs);
        // Killed: the port closes, with no +++ and no ATH.
        static_cast<SerialLink*>(earlier->inner())->close();
    }
    // The model has seen the port close (DTR dropped) and kept the call, as &D0 says.
    QTRY_VERIFY_WITH_TIMEOUT(userGone.contains(QVariantList{int(SatelliteModem::Ground)}), kWaitMs);
    QCOMPARE(model.callState(), SatelliteModem::CallState::Connected);
    QCOMPARE(model.hangUps.size(), 0);
    QVERIFY(aircraft->isOpen());

    ModemLink::Options options = quickLink(kNumber);
    options.probeTimeout = 400ms;
    auto ground = modemLink(model.device(SatelliteModem::Ground), options);
    QSignalSpy status(ground.get(), &Link::statusChanged);
    const qsizetype before = commands.size();
    ground->open();
    QTRY_VERIFY_WITH_TIMEOUT(!model.hangUps.isEmpty(), kWaitMs);
    QCOMPARE(model.hangUps.at(0), (QPair<int, QString>(SatelliteModem::Ground, QStringLiteral("ATH"))));
    QVERIFY2(anyContains(status, QStringLiteral("taken to be still in a call, escaped (+++) and hung up (ATH)")),
             qPrintable(texts(status).join('\n')));
    // Hung up before the init string, then dialled afresh.
    QTRY_VERIFY_WITH_TIMEOUT(ground->isOpen() && aircraft->isOpen(), kWaitMs);
    const QStringList after = commands.mid(before);
    QVERIFY2(startsWith(after, {QStringLiteral("ATH"), QStringLiteral("ATE0V1&C1&D2S12=5")}), qPrintable(after.join(' ')));
    QCOMPARE(commands.count(QStringLiteral("ATD881612345678")), 2);
    QCOMPARE(model.counters().calls, 2);
}

// A call that connects and drops at once is a failed attempt: the redials
// run out and the link gives up, instead of dialling for ever.
void TestModemLink::callsThatDropAtOnceCountAsFailures()
{
    SatelliteModem model(quickModem());
    QString error;
    QVERIFY2(model.open(&error), qPrintable(error));
    connect(&model, &SatelliteModem::callStateChanged, &model, [&](SatelliteModem::CallState state) {
        if (state == SatelliteModem::CallState::Connected)
            QTimer::singleShot(50, &model, &SatelliteModem::dropCall);
    });
    ModemLink::Options options = quickLink(kNumber);
    options.minimumCallDuration = 60s;
    auto ground = modemLink(model.device(SatelliteModem::Ground), options);
    auto aircraft = modemLink(model.device(SatelliteModem::Aircraft), quickLink(QString()));
    QSignalSpy status(ground.get(), &Link::statusChanged);
    QSignalSpy opened(ground.get(), &Link::opened);
    aircraft->open();
    QTRY_COMPARE_WITH_TIMEOUT(aircraft->callState(), ModemLink::CallState::AwaitingCall, kWaitMs);
    ground->open();
    QTRY_COMPARE_WITH_TIMEOUT(ground->callState(), ModemLink::CallState::GaveUp, 3 * kWaitMs);
    QCOMPARE(opened.count(), 3);  // the first call and its two redials, all connected
    QCOMPARE(model.counters().calls, 3);
    QVERIFY2(anyContains(status, QStringLiteral("sooner than the 60 s a call must last to count as good")),
             qPrintable(texts(status).join('\n')));
    QVERIFY2(texts(status).last().contains(QStringLiteral("gave up after 3 attempts")),
             qPrintable(texts(status).last()));
}

// A profile whose set-up the phone refuses does not dial; it says which command and why.
void TestModemLink::profileSetUpRefusedIsSaid()
{
    SatelliteModem::Options modelOptions = quickModem();
    modelOptions.profile = *modem::findProfile(QStringLiteral("hayes"));  // no +CBST
    ModemThread model(modelOptions);
    QString error;
    QVERIFY2(model.open(&error), qPrintable(error));
    ModemLink::Options options = quickLink(kNumber);
    options.profile = *modem::findProfile(QStringLiteral("thuraya"));
    auto ground = modemLink(model.device(SatelliteModem::Ground), options);
    QSignalSpy errors(ground.get(), &Link::errorOccurred);
    ground->open();
    QTRY_COMPARE_WITH_TIMEOUT(ground->callState(), ModemLink::CallState::GaveUp, kWaitMs);
    QCOMPARE(errors.count(), 1);
    QVERIFY2(errors.at(0).at(0).toString().startsWith(
                 QStringLiteral("the modem refused AT+CBST=7,0,1 (ERROR), part of the Thuraya profile's set-up")),
             qPrintable(errors.at(0).at(0).toString()));
    QCOMPARE(ground->dials(), 0);
}

QTEST_MAIN(TestModemLink)
#include "tst_modemlink.moc"
