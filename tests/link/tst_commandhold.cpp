// A console commands only what its operator chose (issue 24): a console
// that starts, comes back after a loss or is given control sends nothing
// that contradicts what the aircraft reports until its operator resumes;
// the aircraft takes a station up only by the claim that Take control sends.
// Against uasim's simulator in process (InProcessUasim), put in a state
// other than its resting one by another sender first, and against a bare
// link end standing in for the aircraft where the test must choose what it
// reports. The console's link runs in its thread as in the console, on
// simulated time: its 1 Hz cadence, silence timeout and the aircraft's
// failover take no wall-clock time (the real uasim over UDP is
// tst_rehearsal's). Every frame the console sent is decoded and checked.
// Waits are simulated time run until what is awaited happened; the limits
// only bound a broken build.

#include "InProcessUasim.h"
#include "SimulatedTime.h"

#include "codec/control/ControlArbiter.h"
#include "codec/message/Airframe.h"
#include "codec/message/CommandChanges.h"
#include "codec/message/DigitPairs.h"
#include "codec/message/MessageDecoder.h"
#include "codec/message/MessageEncoder.h"
#include "link/session/ConsoleSession.h"
#include "link/session/LinkController.h"

#include <QSignalSpy>
#include <QTemporaryDir>
#include <QTest>

#include <chrono>

using namespace rcm;

namespace {

constexpr std::chrono::seconds kPatience{30};  // simulated
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

// Another station's link to the aircraft's channel, commanding `command`
// until the aircraft reports what `done` looks for; its end is then cut
// off as the console plugs in.
bool commandUntil(test::InProcessUasim& uasim, const Message& command, bool (*done)(const Message&))
{
    LinkWorker::Options options;
    options.clock = uasim.clock;
    LinkWorker other(uasim.consoleEnd(), nullptr, options);
    bool reached = false;
    QObject::connect(&other, &LinkEvents::messageReceived, &other,
                     [&](const ReceivedMessage& r) { reached = reached || done(r.message); });
    other.setCommand(command);
    other.start();
    return uasim.runUntil([&] { return reached; }, kPatience);
}

// The console connected to `link`, its link started in its thread.
bool connected(ConsoleSession& session, std::unique_ptr<Link> link)
{
    session.connectLink(std::move(link), QStringLiteral("in-process"));
    // Its frame log is made in the thread pool, in real time.
    return QTest::qWaitFor([&] { return session.isRunning(); });
}

// A bare link end standing in for the aircraft: answers each frame from
// the console with `status`, while `answering`.
class FakeAircraft : public QObject {
public:
    FakeAircraft()
    {
        auto [consoleEnd, aircraftEnd] = test::InProcessLink::pair(test::InProcessLink::Kind::Datagrams);
        m_consoleEnd = std::move(consoleEnd);
        m_end = std::move(aircraftEnd);
        time.watch(m_end.get());
        connect(m_end.get(), &Link::datagramReceived, this, [this] {
            if (answering)
                answer();
        });
        m_end->open();
    }
    std::unique_ptr<Link> consoleEnd() { return std::move(m_consoleEnd); }
    void answer()
    {
        Message m = status;
        const auto now = std::chrono::system_clock::time_point(std::chrono::microseconds(time.clock->utcMicros()));
        m.header.set(ItemId::ID_msg, counter++);
        m.header.set(ItemId::ID_UA_source, Value::station(StationId{44, 133}));
        m.header.set(ItemId::time_UTC, DigitPairs::timeOf(now).packed());
        m.header.set(ItemId::date_UTC, DigitPairs::dateOf(now).packed());
        Diagnostics errors;
        const auto datagram = encodeDatagram(m, errors);
        QVERIFY(datagram);
        m_end->write(QByteArray(reinterpret_cast<const char*>(datagram->data()), qsizetype(datagram->size())));
    }

    test::SimulatedTime time;
    Message status = resting();
    bool answering = true;
    std::int64_t counter = 0;

private:
    std::unique_ptr<test::InProcessLink> m_end;
    std::unique_ptr<Link> m_consoleEnd;
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
        test::InProcessUasim aircraft;
        QVERIFY(aircraft.start());
        QVERIFY(commandUntil(aircraft, flying(), isFlying));

        ConsoleSession session(m_dir.filePath(QStringLiteral("start")), nullptr, aircraft.clock);
        SentFrames sent(session);
        QSignalSpy adopted(&session, &ConsoleSession::commandAdopted);
        // Saved panels: lights on, the rest at rest.
        Message saved = resting();
        saved.settings.setFieldCode(ItemId::lights, 0, code::kOn);
        session.setCommand(saved);
        QVERIFY(connected(session, aircraft.consoleEnd()));
        QVERIFY(aircraft.runUntil([&] { return adopted.count() == 1; }, kPatience));
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
        QVERIFY(aircraft.runUntil([&] { return sent.frames.size() >= before + 3; }, kPatience));
        QVERIFY(!sent.frames.empty());
        for (const Message& frame : sent.frames) {
            QVERIFY(commandsNothing(frame));
            QVERIFY(!frame.header.has(ItemId::ID_GCS_destination));
        }
        QVERIFY(isFlying(*session.commandHold()->lastReport()));

        QString whyNot;
        QVERIFY2(session.resumeCommanding(&whyNot), qPrintable(whyNot));
        QVERIFY(session.commanding());
        QVERIFY(aircraft.runUntil([&] { return !commandsNothing(sent.frames.back()); }, kPatience));
        QVERIFY(isFlying(sent.frames.back()));
        // The aircraft goes on doing what it did.
        QSignalSpy statusFrames(session.controller(), &LinkEvents::messageReceived);
        QVERIFY(aircraft.runUntil([&] { return statusFrames.count() >= 2; }, kPatience));
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
        test::SimulatedTime& time = aircraft.time;
        aircraft.status.flaps.set(ItemId::F_elev_set, 3);
        ConsoleSession session(m_dir.filePath(QStringLiteral("regain")), nullptr, time.clock);
        SentFrames sent(session);
        QSignalSpy adopted(&session, &ConsoleSession::commandAdopted);
        session.setCommand(resting());
        QVERIFY(connected(session, aircraft.consoleEnd()));
        QVERIFY(time.runUntil([&] { return adopted.count() == 1; }, kPatience));
        QVERIFY(session.resumeCommanding());
        QVERIFY(time.runUntil([&] { return !commandsNothing(sent.frames.back()); }, kPatience));
        QCOMPARE(sent.frames.back().flaps.number(ItemId::F_elev_set), 3);

        QSignalSpy lost(session.controller(), &LinkEvents::linkLost);
        QSignalSpy regained(session.controller(), &LinkEvents::linkRegained);
        aircraft.answering = false;
        QVERIFY(time.runUntil([&] { return lost.count() == 1; }, kPatience));
        aircraft.status.flaps.set(ItemId::F_elev_set, elevatorAfter);
        aircraft.answering = true;
        QVERIFY(time.runUntil([&] { return regained.count() == 1; }, kPatience));
        const std::size_t back = sent.frames.size();
        QVERIFY(time.runUntil([&] { return sent.frames.size() >= back + 2; }, kPatience));
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
            QVERIFY(time.runUntil([&] { return !commandsNothing(sent.frames.back()); }, kPatience));
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
        SimulatorSession::Settings settings;
        settings.stations = test::InProcessUasim::twoStations();
        settings.failover = std::chrono::seconds(2);
        test::InProcessUasim aircraft(std::move(settings));
        QVERIFY(aircraft.start());
        const auto sessionOn = [&](const char* name) {
            return std::make_unique<ConsoleSession>(m_dir.filePath(QLatin1String(name)), nullptr, aircraft.clock);
        };

        auto primary = sessionOn("primary");
        primary->stationControl()->setStation(kPrimary);
        SentFrames primarySent(*primary);
        primary->setCommand(resting());
        QVERIFY(connected(*primary, aircraft.consoleEnd(0)));
        QVERIFY(aircraft.runUntil(
            [&] { return primary->stationControl()->role() == StationControl::Role::Offered; }, kPatience));
        // Configured first, yet not taken up by naming itself.
        QVERIFY(aircraft.runUntil([&] { return primarySent.frames.size() >= 3; }, kPatience));
        QVERIFY2(!aircraft.said("taken up: "), aircraft.stderrText().constData());
        for (const Message& frame : primarySent.frames)
            QVERIFY(commandsNothing(frame));
        QVERIFY(primary->resumeCommanding());
        QVERIFY(aircraft.runUntil([&] { return aircraft.said("taken up: GB_30226 in control, GB_41251 backup"); },
                                  kPatience));
        const Message& claim = primarySent.frames.back();
        QCOMPARE(named(claim, ItemId::ID_GCS_destination), std::optional(kPrimary));
        QCOMPARE(named(claim, ItemId::ID_GCS_backup), std::optional(kPrimary));
        primary->setCommand(flying());
        QVERIFY(aircraft.runUntil(
            [&] { return primary->commandHold()->lastReport() && isFlying(*primary->commandHold()->lastReport()); },
            kPatience));

        auto backup = sessionOn("backup");
        backup->stationControl()->setStation(kBackup);
        backup->setCommand(resting());
        QVERIFY(connected(*backup, aircraft.consoleEnd(1)));
        QVERIFY(aircraft.runUntil(
            [&] { return backup->stationControl()->role() == StationControl::Role::Backup; }, kPatience));

        primary.reset();  // the primary console killed
        QVERIFY(aircraft.runUntil(
            [&] { return backup->stationControl()->role() == StationControl::Role::Offered; }, kPatience));
        QVERIFY(aircraft.said("failover: nothing from GB_30226"));
        QVERIFY(!backup->commanding());
        QCOMPARE(backup->commandHold()->reason(), CommandHold::Reason::ControlGiven);
        QVERIFY(isFlying(*backup->command()));

        // Restarted: a new console for the same station.
        backup.reset();
        backup = sessionOn("backup-again");
        backup->stationControl()->setStation(kBackup);
        SentFrames backupSent(*backup);
        backup->setCommand(resting());
        QVERIFY(connected(*backup, aircraft.consoleEnd(1)));
        QVERIFY(aircraft.runUntil(
            [&] { return backup->stationControl()->role() == StationControl::Role::Offered; }, kPatience));
        const std::size_t offered = backupSent.frames.size();
        QVERIFY(aircraft.runUntil([&] { return backupSent.frames.size() >= offered + 4; }, kPatience));
        QVERIFY2(!aircraft.said("taken up: GB_41251"), aircraft.stderrText().constData());
        for (const Message& frame : backupSent.frames) {
            QVERIFY(commandsNothing(frame));
            QVERIFY(!ControlArbiter::isClaim(kBackup, named(frame, ItemId::ID_GCS_destination),
                                             named(frame, ItemId::ID_GCS_backup)));
        }
        QVERIFY(isFlying(*backup->commandHold()->lastReport()));

        // Its operator takes control: the claim, with the aircraft's own state.
        QVERIFY(backup->resumeCommanding());
        QVERIFY(aircraft.runUntil([&] { return aircraft.said("taken up: GB_41251 in control"); }, kPatience));
        QVERIFY(isFlying(backupSent.frames.back()));
        QSignalSpy statusFrames(backup->controller(), &LinkEvents::messageReceived);
        QVERIFY(aircraft.runUntil([&] { return statusFrames.count() >= 2; }, kPatience));
        QVERIFY(isFlying(statusFrames.last().at(0).value<ReceivedMessage>().message));
    }

private:
    QTemporaryDir m_dir;
};

QTEST_MAIN(TestCommandHold)
#include "tst_commandhold.moc"
