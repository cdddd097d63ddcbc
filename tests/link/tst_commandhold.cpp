// A console commands only what its operator chose (issue 24): a console
// that starts, comes back after a loss or is given control sends nothing
// that contradicts what the aircraft reports until its operator resumes;
// the aircraft takes a station up only by the claim that Take control sends.
// Against the real uasim, put in a state other than its resting one by
// another sender first, and against a bare socket standing in for the
// aircraft where the test must choose what it reports. Every frame the
// console sent is decoded and checked. Waits are QSignalSpy and QTRY_*;
// the timeouts only bound a broken build.

#include "UasimProcess.h"

#include "codec/control/ControlArbiter.h"
#include "codec/message/Airframe.h"
#include "codec/message/CommandChanges.h"
#include "codec/message/DigitPairs.h"
#include "codec/message/MessageDecoder.h"
#include "codec/message/MessageEncoder.h"
#include "link/session/ConsoleSession.h"
#include "link/session/LinkController.h"
#include "link/transport/UdpLink.h"

#include <QSignalSpy>
#include <QTemporaryDir>
#include <QTest>
#include <QUdpSocket>

#include <chrono>

using namespace rcm;

namespace {

constexpr int kPatienceMs = 30000;
constexpr StationId kPrimary{44, 30226};
constexpr StationId kBackup{44, 41251};

Message resting()
{
    return restingCommand(Airframe::wellEquipped());
}

// What the other station commanded the aircraft to: every wheel up,
// engine 1's propeller at 64 of 255, lift flaps at 10 degrees.
Message flying()
{
    Message m = resting();
    for (int wheel = 0; wheel < 4; ++wheel)
        m.settings.setFieldCode(ItemId::land_wheels, wheel, code::kRetracted);
    m.engines.at(0).set(ItemId::eng_prop_pitch, 64);
    m.flaps.set(ItemId::F_lift_set, 10);
    return m;
}

bool isFlying(const Message& status)
{
    for (int wheel = 0; wheel < 4; ++wheel)
        if (status.settings.fieldCode(ItemId::land_wheels, wheel) != code::kRetracted)
            return false;
    return !status.engines.empty() && status.engines.at(0).number(ItemId::eng_prop_pitch) == 64 &&
           status.flaps.number(ItemId::F_lift_set) == 10;
}

Message decoded(const QByteArray& bytes)
{
    return decodeFrame(std::span(reinterpret_cast<const std::uint8_t*>(bytes.constData()), std::size_t(bytes.size())))
        .message;
}

// The frame commands nothing: its header alone, no unit, no plan section.
bool commandsNothing(const Message& frame)
{
    return frame == heldCommand(frame);
}

std::optional<StationId> named(const Message& frame, ItemId id)
{
    const Value* v = frame.header.find(id);
    if (!v)
        return std::nullopt;
    return StationId{std::uint16_t(v->number), std::uint16_t(v->second)};
}

// Every frame a session sends, decoded, from the moment its link starts.
class SentFrames : public QObject {
public:
    explicit SentFrames(ConsoleSession& session)
    {
        connect(&session, &ConsoleSession::linkStarted, this, [this](const LinkController* controller) {
            connect(controller, &LinkEvents::frameLogged, this, [this](const LoggedFrame& f) {
                if (f.entry.direction == FrameDirection::Sent)
                    frames.push_back(decoded(f.bytes));
            });
        });
    }
    std::vector<Message> frames;
};

LinkSettings udpTo(quint16 port)
{
    LinkSettings s;
    s.localAddress = QStringLiteral("127.0.0.1");
    s.remoteAddress = QStringLiteral("127.0.0.1");
    s.remotePort = port;
    return s;
}

// Another station's link to uasim's port, commanding `command` until
// uasim reports what `done` looks for.
bool commandUntil(quint16 port, const Message& command, bool (*done)(const Message&))
{
    auto link = std::make_unique<UdpLink>(QHostAddress(QHostAddress::LocalHost), 0,
                                          QHostAddress(QHostAddress::LocalHost), port);
    LinkController other(std::move(link));
    bool reached = false;
    QObject::connect(&other, &LinkEvents::messageReceived, &other,
                     [&](const ReceivedMessage& r) { reached = reached || done(r.message); });
    other.setCommand(command);
    other.start();
    return QTest::qWaitFor([&] { return reached; }, kPatienceMs);
}

// A bare UDP socket standing in for the aircraft: answers each frame from
// the console with `status`, while `answering`.
class FakeAircraft : public QObject {
public:
    FakeAircraft()
    {
        socket.bind(QHostAddress::LocalHost, 0);
        connect(&socket, &QUdpSocket::readyRead, this, [this] {
            while (socket.hasPendingDatagrams()) {
                QHostAddress from;
                quint16 port = 0;
                QByteArray bytes(socket.pendingDatagramSize(), Qt::Uninitialized);
                socket.readDatagram(bytes.data(), bytes.size(), &from, &port);
                if (answering)
                    answer(from, port);
            }
        });
    }
    quint16 port() const { return socket.localPort(); }
    void answer(const QHostAddress& to, quint16 port)
    {
        Message m = status;
        const auto now = std::chrono::system_clock::now();
        m.header.set(ItemId::ID_msg, counter++);
        m.header.set(ItemId::ID_UA_source, Value::station(StationId{44, 133}));
        m.header.set(ItemId::time_UTC, DigitPairs::timeOf(now).packed());
        m.header.set(ItemId::date_UTC, DigitPairs::dateOf(now).packed());
        Diagnostics errors;
        const auto datagram = encodeDatagram(m, errors);
        QVERIFY(datagram);
        socket.writeDatagram(reinterpret_cast<const char*>(datagram->data()), qint64(datagram->size()), to, port);
    }

    QUdpSocket socket;
    Message status = resting();
    bool answering = true;
    std::int64_t counter = 0;
};

}  // namespace

class TestCommandHold : public QObject {
    Q_OBJECT

private slots:
    void initTestCase()
    {
        LinkWorker::registerMetaTypes();
        QVERIFY(m_dir.isValid());
    }

    // A console started (again) beside an aircraft another station put in
    // flight: its own panels, at rest or as saved, never reach the aircraft.
    // It sends frames that name nobody and carry no unit until its operator
    // resumes, adopts the report into its panels meanwhile, and says what
    // differed; resuming then sends what the aircraft does already.
    void startingConsoleSendsNothingTheAircraftDidNotReport()
    {
        test::UasimProcess aircraft;
        QVERIFY(aircraft.start());
        QTRY_VERIFY_WITH_TIMEOUT(aircraft.listening(), kPatienceMs);
        QVERIFY(commandUntil(aircraft.port(), flying(), isFlying));

        ConsoleSession session(m_dir.filePath(QStringLiteral("start")));
        SentFrames sent(session);
        QSignalSpy adopted(&session, &ConsoleSession::commandAdopted);
        // Saved panels: lights on, the rest at rest.
        Message saved = resting();
        saved.settings.setFieldCode(ItemId::lights, 0, code::kOn);
        session.setCommand(saved);
        session.connectWith(udpTo(aircraft.port()));
        QTRY_COMPARE_WITH_TIMEOUT(adopted.count(), 1, kPatienceMs);
        QVERIFY(!session.commanding());
        QCOMPARE(session.commandHold()->reason(), CommandHold::Reason::NewLink);
        // The report is in the panels, what they held before is said.
        QVERIFY(isFlying(*session.command()));
        QCOMPARE(session.command()->settings.fieldCode(ItemId::lights, 0), code::kOff);
        QCOMPARE(adopted.at(0).at(0).value<Message>(), *session.command());
        const std::vector<ItemChange>& differences = session.commandHold()->differences();
        QCOMPARE(differences.size(), std::size_t(7));  // four wheels, a light, the pitch, the flaps
        QCOMPARE(differences[0].id, ItemId::eng_prop_pitch);
        QCOMPARE(differences[0].from->number, 0);
        QCOMPARE(differences[0].to->number, 64);

        // Held for as long as the operator does nothing.
        const std::size_t before = sent.frames.size();
        QTRY_VERIFY_WITH_TIMEOUT(sent.frames.size() >= before + 3, kPatienceMs);
        QVERIFY(!sent.frames.empty());
        for (const Message& frame : sent.frames) {
            QVERIFY(commandsNothing(frame));
            QVERIFY(!frame.header.has(ItemId::ID_GCS_destination));
        }
        QVERIFY(isFlying(*session.commandHold()->lastReport()));

        QString whyNot;
        QVERIFY2(session.resumeCommanding(&whyNot), qPrintable(whyNot));
        QVERIFY(session.commanding());
        QTRY_VERIFY_WITH_TIMEOUT(!commandsNothing(sent.frames.back()), kPatienceMs);
        QVERIFY(isFlying(sent.frames.back()));
        // The aircraft goes on doing what it did.
        QSignalSpy statusFrames(session.controller(), &LinkEvents::messageReceived);
        QTRY_VERIFY_WITH_TIMEOUT(statusFrames.count() >= 2, kPatienceMs);
        QVERIFY(isFlying(statusFrames.last().at(0).value<ReceivedMessage>().message));
    }

    // Back after a loss (a redial, an outage): the command goes on when the
    // aircraft still reports it, and is held, not adopted, when it does not.
    void linkBackHoldsWhenTheReportDiffers_data()
    {
        QTest::addColumn<int>("elevatorAfter");
        QTest::addColumn<bool>("holds");
        QTest::newRow("the same") << 3 << false;
        QTest::newRow("another") << 9 << true;
    }
    void linkBackHoldsWhenTheReportDiffers()
    {
        QFETCH(int, elevatorAfter);
        QFETCH(bool, holds);
        FakeAircraft aircraft;
        aircraft.status.flaps.set(ItemId::F_elev_set, 3);
        ConsoleSession session(m_dir.filePath(QStringLiteral("regain")));
        SentFrames sent(session);
        QSignalSpy adopted(&session, &ConsoleSession::commandAdopted);
        session.setCommand(resting());
        session.connectWith(udpTo(aircraft.port()));
        QTRY_COMPARE_WITH_TIMEOUT(adopted.count(), 1, kPatienceMs);
        QVERIFY(session.resumeCommanding());
        QTRY_VERIFY_WITH_TIMEOUT(!commandsNothing(sent.frames.back()), kPatienceMs);
        QCOMPARE(sent.frames.back().flaps.number(ItemId::F_elev_set), 3);

        QSignalSpy lost(session.controller(), &LinkEvents::linkLost);
        QSignalSpy regained(session.controller(), &LinkEvents::linkRegained);
        aircraft.answering = false;
        QTRY_COMPARE_WITH_TIMEOUT(lost.count(), 1, kPatienceMs);
        aircraft.status.flaps.set(ItemId::F_elev_set, elevatorAfter);
        aircraft.answering = true;
        QTRY_COMPARE_WITH_TIMEOUT(regained.count(), 1, kPatienceMs);
        const std::size_t back = sent.frames.size();
        QTRY_VERIFY_WITH_TIMEOUT(sent.frames.size() >= back + 2, kPatienceMs);
        QCOMPARE(!session.commanding(), holds);
        // Not adopted: the panels keep what the operator commanded.
        QCOMPARE(session.command()->flaps.number(ItemId::F_elev_set), 3);
        QCOMPARE(commandsNothing(sent.frames.back()), holds);
        if (holds) {
            QCOMPARE(session.commandHold()->reason(), CommandHold::Reason::LinkRegained);
            QCOMPARE(session.commandHold()->differences().size(), std::size_t(1));
            QCOMPARE(session.commandHold()->differences()[0].id, ItemId::F_elev_set);
            QCOMPARE(session.commandHold()->differences()[0].to->number, 9);
            // Resuming sends what the operator commanded.
            QVERIFY(session.resumeCommanding());
            QTRY_VERIFY_WITH_TIMEOUT(!commandsNothing(sent.frames.back()), kPatienceMs);
            QCOMPARE(sent.frames.back().flaps.number(ItemId::F_elev_set), 3);
        }
    }

    // Two stations. The primary takes control by its operator's Take control
    // (the claim) and puts the gear up; killed, control fails over to the
    // backup, which is given it but sends nothing until its operator takes
    // it. The backup restarted after the failover names itself as any
    // console in its place would, and the aircraft does not take it up.
    void restartedBackupIsNotTakenUp()
    {
        test::UasimProcess aircraft(test::kTwoStations, {QStringLiteral("--failover"), QStringLiteral("2")});
        QVERIFY(aircraft.start());
        QTRY_VERIFY_WITH_TIMEOUT(aircraft.listening(), kPatienceMs);

        auto primary = std::make_unique<ConsoleSession>(m_dir.filePath(QStringLiteral("primary")));
        primary->stationControl()->setStation(kPrimary);
        SentFrames primarySent(*primary);
        primary->setCommand(resting());
        primary->connectWith(udpTo(aircraft.ports[0]));
        QTRY_COMPARE_WITH_TIMEOUT(primary->stationControl()->role(), StationControl::Role::Offered, kPatienceMs);
        // Configured first, yet not taken up by naming itself.
        QTRY_VERIFY_WITH_TIMEOUT(primarySent.frames.size() >= 3, kPatienceMs);
        QVERIFY2(!aircraft.said("taken up: "), aircraft.stderrText().constData());
        for (const Message& frame : primarySent.frames)
            QVERIFY(commandsNothing(frame));
        QVERIFY(primary->resumeCommanding());
        QTRY_VERIFY_WITH_TIMEOUT(aircraft.said("taken up: GB_30226 in control, GB_41251 backup"), kPatienceMs);
        const Message& claim = primarySent.frames.back();
        QCOMPARE(named(claim, ItemId::ID_GCS_destination), std::optional(kPrimary));
        QCOMPARE(named(claim, ItemId::ID_GCS_backup), std::optional(kPrimary));
        primary->setCommand(flying());
        QTRY_VERIFY_WITH_TIMEOUT(primary->commandHold()->lastReport() && isFlying(*primary->commandHold()->lastReport()),
                                 kPatienceMs);

        auto backup = std::make_unique<ConsoleSession>(m_dir.filePath(QStringLiteral("backup")));
        backup->stationControl()->setStation(kBackup);
        backup->setCommand(resting());
        backup->connectWith(udpTo(aircraft.ports[1]));
        QTRY_COMPARE_WITH_TIMEOUT(backup->stationControl()->role(), StationControl::Role::Backup, kPatienceMs);

        primary.reset();  // the primary console killed
        QTRY_COMPARE_WITH_TIMEOUT(backup->stationControl()->role(), StationControl::Role::Offered, kPatienceMs);
        QVERIFY(aircraft.said("failover: nothing from GB_30226"));
        QVERIFY(!backup->commanding());
        QCOMPARE(backup->commandHold()->reason(), CommandHold::Reason::ControlGiven);
        QVERIFY(isFlying(*backup->command()));

        // Restarted: a new console for the same station.
        backup.reset();
        backup = std::make_unique<ConsoleSession>(m_dir.filePath(QStringLiteral("backup-again")));
        backup->stationControl()->setStation(kBackup);
        SentFrames backupSent(*backup);
        backup->setCommand(resting());
        backup->connectWith(udpTo(aircraft.ports[1]));
        QTRY_COMPARE_WITH_TIMEOUT(backup->stationControl()->role(), StationControl::Role::Offered, kPatienceMs);
        const std::size_t offered = backupSent.frames.size();
        QTRY_VERIFY_WITH_TIMEOUT(backupSent.frames.size() >= offered + 4, kPatienceMs);
        QVERIFY2(!aircraft.said("taken up: GB_41251"), aircraft.stderrText().constData());
        for (const Message& frame : backupSent.frames) {
            QVERIFY(commandsNothing(frame));
            QVERIFY(!ControlArbiter::isClaim(kBackup, named(frame, ItemId::ID_GCS_destination),
                                             named(frame, ItemId::ID_GCS_backup)));
        }
        QVERIFY(isFlying(*backup->commandHold()->lastReport()));

        // Its operator takes control: the claim, with the aircraft's own state.
        QVERIFY(backup->resumeCommanding());
        QTRY_VERIFY_WITH_TIMEOUT(aircraft.said("taken up: GB_41251 in control"), kPatienceMs);
        QVERIFY(isFlying(backupSent.frames.back()));
        QSignalSpy statusFrames(backup->controller(), &LinkEvents::messageReceived);
        QTRY_VERIFY_WITH_TIMEOUT(statusFrames.count() >= 2, kPatienceMs);
        QVERIFY(isFlying(statusFrames.last().at(0).value<ReceivedMessage>().message));
    }

private:
    QTemporaryDir m_dir;
};

QTEST_MAIN(TestCommandHold)
#include "tst_commandhold.moc"
