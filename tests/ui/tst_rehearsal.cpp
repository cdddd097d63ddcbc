// Rehearsal scenarios (issue 12): the scenario file's vocabulary and its
// errors, runs in process on the virtual clock with exact times and counts,
// and gcs --rehearse on every sample scenario, with its exit status and reports.
#include "RunProgram.h"

#include "codec/frame/Frame.h"
#include "codec/secure/SecureCodec.h"
#include "link/framelog/FrameLogReader.h"
#include "link/rehearsal/ScenarioRunner.h"
#include "ui/rehearsal/RehearsalCommandLine.h"
#include "ui/rehearsal/RehearsalDialog.h"

#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QSignalSpy>
#include <QTemporaryDir>
#include <QtTest>

namespace {

const QString kScenarios = QStringLiteral(RCM_SOURCE_DIR "/resources/scenarios/");

Scenario load(const QString& name)
{
    ScenarioError error;
    auto scenario = Scenario::load(kScenarios + name, RehearsalCommandLine::planLoader(), &error);
    if (!scenario)
        qFatal("%s", qPrintable(error.text()));
    return *scenario;
}

QJsonObject readJson(const QString& path)
{
    QFile file(path);
    if (!file.open(QIODevice::ReadOnly))
        return {};
    return QJsonDocument::fromJson(file.readAll()).object();
}

QString readText(const QString& path)
{
    QFile file(path);
    return file.open(QIODevice::ReadOnly) ? QString::fromUtf8(file.readAll()) : QString();
}

}  // namespace

class TestRehearsal : public QObject {
    Q_OBJECT

private slots:
    void issueExampleParses();
    void setLinesNameTheirUnit();
    void wrongScenariosSayWhere_data();
    void wrongScenariosSayWhere();
    void outageRunsToExactTimes();
    void pacedRunGivesTheSameReport();
    void speedOneRunsTheRealPrograms();
    void frameLogHoldsBothDirections();
    void keyEnciphersTheRun();
    void samplesHold_data();
    void samplesHold();
    void failedStepNamedInBothReports();
    void malformedScenarioExitsTwo();
    void scenarioByName();
    void dialogShowsTheRun();
    void dialogSaysWhereTheScenarioIsWrong();
    void uasimEndsWithTheConsole();
    void withinBesideExpect();
    void unexpectedAlarmFailsTheRun();
    void reportPlotHasTimeAndFaults();
    void oneSectionIsOneSection();
};

void TestRehearsal::issueExampleParses()
{
    const Scenario s = load(QStringLiteral("gear-outage-plan.json"));
    QCOMPARE(s.name, QStringLiteral("gear, outage and a plan"));
    QCOMPARE(s.airframe.engines.size(), std::size_t(3));
    QCOMPARE(s.transport, Scenario::Transport::Udp);
    QCOMPARE(s.key, false);
    QCOMPARE(s.speed, 20.0);
    QCOMPARE(s.duration, 180.0);
    QCOMPARE(s.steps.size(), std::size_t(16));
    using K = ScenarioStep::Kind;
    const std::vector<K> kinds = {K::Set,
                                  K::Set,
                                  K::Set,
                                  K::Set,
                                  K::ExpectReported,
                                  K::Fault,
                                  K::Fault,
                                  K::ExpectAlarm,
                                  K::ExpectAlarm,
                                  K::Fault,
                                  K::Fault,
                                  K::Fault,
                                  K::Upload,
                                  K::ExpectPlan,
                                  K::ExpectWrongFrames,
                                  K::ExpectFramesLost};
    for (std::size_t i = 0; i < kinds.size(); ++i)
        QCOMPARE(s.steps[i].kind, kinds[i]);
    QCOMPARE(s.steps[6].fault.kind, FaultSpec::Kind::Outage);
    QCOMPARE(s.steps[6].fault.value, 15.0);
    QCOMPARE(s.steps[9].fault.kind, FaultSpec::Kind::Slip);
    QCOMPARE(s.steps[10].fault.kind, FaultSpec::Kind::Burst);
    QCOMPARE(s.steps[11].fault.kind, FaultSpec::Kind::Clear);
    QCOMPARE(s.steps[12].plan.size(), 16 + 6 * 34);  // MissionPlan's header and six items
    QCOMPARE(s.steps[15].at.has_value(), false);
    QCOMPARE(s.steps[15].count, 25);
    QCOMPARE(s.steps[4].line, 13);
    QCOMPARE(s.steps[4].column, 5);
    QCOMPARE(s.steps[7].describe(), QStringLiteral("step 8 at 40 s: expect alarm link-lost within 6 s"));
}

void TestRehearsal::setLinesNameTheirUnit()
{
    const rcm::Message command = rcm::restingCommand(rcm::Airframe::wellEquipped());
    QString error;
    const auto engine = parseUnitLine(QStringLiteral("engine 2: eng_prop_pitch 140"), command, &error);
    QVERIFY2(engine, qPrintable(error));
    QCOMPARE(engine->engines.size(), std::size_t(1));
    QCOMPARE(engine->engines[0].number(rcm::ItemId::eng_ID), 2);
    QCOMPARE(engine->engines[0].number(rcm::ItemId::eng_prop_pitch), 140);

    const auto camera = parseUnitLine(QStringLiteral("camera 1: cam_zoom_set 40"), command, &error);
    QVERIFY2(camera, qPrintable(error));
    rcm::Message commanded = command;
    applyItems(commanded, *camera);
    QCOMPARE(commanded.cameras[0].number(rcm::ItemId::cam_zoom_set), 40);
    QCOMPARE(commanded.cameras[1], command.cameras[1]);
    QVERIFY(reportsItems(commanded, *camera));
    QVERIFY(!reportsItems(command, *camera));

    QVERIFY(!parseUnitLine(QStringLiteral("comms_system HF9: Tx_freq 121500"), command, &error));
    QCOMPARE(error, QStringLiteral("the aircraft has no comms_system HF9"));
    QVERIFY(!parseUnitLine(QStringLiteral("flaps 1: F_elev_set 3"), command, &error));
    QCOMPARE(error, QStringLiteral("\"flaps\" is not a repeated unit (engine, comms_system, camera)"));
}

void TestRehearsal::wrongScenariosSayWhere_data()
{
    QTest::addColumn<QByteArray>("json");
    QTest::addColumn<QString>("error");
    QTest::newRow("syntax") << QByteArray("{\n  \"duration\": 10,\n  \"steps\": [}\n")
                            << QStringLiteral("s.json:3:14: object is missing after a comma");
    QTest::newRow("no duration") << QByteArray("{\"steps\": []}")
                                 << QStringLiteral("s.json:1:1: duration is seconds, more than 0");
    QTest::newRow("transport") << QByteArray("{\"duration\": 5,\n \"transport\": \"tcp\"}")
                               << QStringLiteral("s.json:2:15: transport is \"udp\", \"serial\" or \"modem\"");
    QTest::newRow("unknown fault")
        << QByteArray("{\"duration\": 5, \"steps\": [\n  {\"at\": 1, \"fault\": {\"drop\": 0.1}}]}")
        << QStringLiteral("s.json:2:31: step 1: unknown fault \"drop\" (ber, outage, slip, burst, direction)");
    QTest::newRow("ber over 1") << QByteArray("{\"duration\": 5, \"steps\": [\n {\"at\": 1, \"fault\": {\"ber\": 2}}]}")
                                << QStringLiteral("s.json:2:29: step 1: ber is a probability from 0 to 1");
    QTest::newRow("at past the end") << QByteArray(
                                            "{\"duration\": 5, \"steps\": [{\"at\": 0, \"set\": \"F_elev_set 3\"},\n "
                                            "{\"at\": 9, \"set\": \"F_elev_set 3\"}]}")
                                     << QStringLiteral("s.json:2:9: step 2: at is seconds from 0 to the duration, 5");
    QTest::newRow("bad item")
        << QByteArray("{\"duration\": 5, \"steps\": [\n {\"at\": 0, \"set\": \"F_elev_set 900\"}]}")
        << QStringLiteral("s.json:2:19: step 1: \"F_elev_set 900\": 900 is above the maximum 127 by 773");
    QTest::newRow("alarm name")
        << QByteArray(
               "{\"duration\": 5, \"steps\": [\n {\"at\": 0, \"expect\": {\"alarm\": \"lost\", \"within\": 3}}]}")
        << QStringLiteral("s.json:2:32: step 1: alarm is \"link-lost\" or \"link-regained\"");
    QTest::newRow("within missing")
        << QByteArray("{\"duration\": 5, \"steps\": [\n {\"at\": 0, \"expect\": {\"alarm\": \"link-lost\"}}]}")
        << QStringLiteral("s.json:2:22: step 1: this expectation needs \"at\" and \"within\" (seconds)");
    QTest::newRow("ber through the modem")
        << QByteArray("{\"transport\": \"modem\", \"duration\": 5, \"steps\": [\n {\"at\": 1, \"fault\": {\"ber\": 0.1}}]}")
        << QStringLiteral("s.json:2:21: step 1: the modem transport's faults are \"call-drop\" and \"clear\": its bytes "
                          "go through the modem model, not the fault channel");
    QTest::newRow("call-drop without the modem")
        << QByteArray("{\"duration\": 5, \"steps\": [\n {\"at\": 1, \"fault\": \"call-drop\"}]}")
        << QStringLiteral("s.json:2:21: step 1: call-drop needs \"transport\": \"modem\"");
    QTest::newRow("the modem faster than real time")
        << QByteArray("{\"transport\": \"modem\", \"speed\": 10, \"duration\": 5, \"steps\": []}")
        << QStringLiteral("s.json:1:33: the modem transport runs at speed 1: the modem model keeps real time");
    QTest::newRow("within on a set")
        << QByteArray("{\"duration\": 5, \"steps\": [\n {\"at\": 0, \"set\": \"F_elev_set 3\", \"within\": 5}]}")
        << QStringLiteral("s.json:2:45: step 1: within goes with expect: the seconds after \"at\" it may take to hold");
    QTest::newRow("within twice")
        << QByteArray(
               "{\"duration\": 5, \"steps\": [\n {\"at\": 0, \"expect\": {\"alarm\": \"link-lost\", \"within\": 3},"
               " \"within\": 3}]}")
        << QStringLiteral("s.json:2:69: step 1: within is given twice, beside expect and in it; give it once");
    QTest::newRow("within over the whole run")
        << QByteArray("{\"duration\": 5, \"steps\": [\n {\"expect\": {\"wrong-frames\": 0}, \"within\": 3}]}")
        << QStringLiteral("s.json:2:44: step 1: wrong-frames holds over the whole run: no \"within\"");
    QTest::newRow("missing plan")
        << QByteArray("{\"duration\": 5, \"steps\": [\n {\"at\": 0, \"upload\": \"nowhere.plan\"}]}")
        << QStringLiteral("s.json:2:22: step 1: /nonexistent/nowhere.plan: No such file or directory");
}

void TestRehearsal::wrongScenariosSayWhere()
{
    QFETCH(QByteArray, json);
    QFETCH(QString, error);
    ScenarioError e;
    QVERIFY(!Scenario::fromJson(json, QStringLiteral("/nonexistent/s.json"), RehearsalCommandLine::planLoader(), &e));
    QCOMPARE(e.text(), QStringLiteral("/nonexistent/") + error);
}

void TestRehearsal::outageRunsToExactTimes()
{
    ScenarioRunner runner(load(QStringLiteral("outage.json")), QString());
    QSignalSpy finished(&runner, &ScenarioRunner::finished);
    runner.runToEnd();
    QCOMPARE(finished.count(), 1);
    const RehearsalReport& r = runner.report();
    QVERIFY(r.passed());
    QCOMPARE(r.expectations.size(), std::size_t(5));
    QCOMPARE(r.expectations[0].measured, 2.0);  // commanded at 1 s, reported at 2 s
    QCOMPARE(r.expectations[1].measured, 3.0);  // the silence timeout
    QCOMPARE(r.expectations[2].measured, 1.0);  // the first status after the outage
    QCOMPARE(r.frames.sentUp, 90);
    QCOMPARE(r.frames.sentDown, 90);
    QCOMPARE(r.frames.inOutage, 40);
    QCOMPARE(r.frames.receivedUp, 70);
    QCOMPARE(r.frames.receivedDown, 70);
    QCOMPARE(r.frames.lost, 0);
    QCOMPARE(r.frames.wrong, 0);
    QCOMPARE(r.latencies.size(), std::size_t(1));
    QCOMPARE(r.latencies[0].seconds, 2.0);
    QStringList alarms;
    for (const auto& t : r.timeline)
        if (t.kind == QLatin1String("alarm"))
            alarms << QStringLiteral("%1 %2").arg(t.time).arg(t.text);
    QCOMPARE(alarms, (QStringList{QStringLiteral("33 link-lost"), QStringLiteral("51 link-regained")}));
    // Quality over the last 10 s: none during the outage, all again 10 s after it.
    QCOMPARE(r.quality.size(), std::size_t(91));
    QCOMPARE(r.quality[45].up, 0.0);
    QCOMPARE(r.quality[45].down, 0.0);
    QCOMPARE(r.quality[62].up, 1.0);
}

void TestRehearsal::pacedRunGivesTheSameReport()
{
    ScenarioRunner fast(load(QStringLiteral("burst.json")), QString());
    fast.runToEnd();
    ScenarioRunner paced(load(QStringLiteral("burst.json")), QString());
    QSignalSpy progress(&paced, &ScenarioRunner::progress);
    QSignalSpy finished(&paced, &ScenarioRunner::finished);
    paced.start(100000);
    QVERIFY(finished.wait(30000));
    QVERIFY(progress.count() >= 1);
    QCOMPARE(progress.constLast().at(0).toDouble(), 120.0);
    QCOMPARE(paced.report().toJson(), fast.report().toJson());
    QCOMPARE(fast.report().frames.wrong, 0);
    QVERIFY(fast.report().frames.lost > 0);  // the bursts cost frames: the run did inject them
}

// The verdicts of a run's expectations, "3 held" or the step and why not.
static QStringList verdictsOf(const RehearsalReport& report)
{
    QStringList v;
    for (const auto& e : report.expectations)
        v << QStringLiteral("%1 %2").arg(e.step).arg(e.held ? QStringLiteral("held") : e.detail);
    return v;
}

// real-time.json, over UDP or serial.
static Scenario realTimeScenario(bool serial)
{
    Scenario s = load(QStringLiteral("real-time.json"));
    if (serial)
        s.transport = Scenario::Transport::Serial;
    return s;
}

// A run of real-time.json with the real programs, against the same run in process.
static void checkRealTimeRun(const ScenarioRunner& real, const QString& transport, const QString& logPath,
                             const RehearsalReport& inProcess)
{
    const RehearsalReport& r = real.report();
    QCOMPARE(r.transport, transport);
    QCOMPARE(verdictsOf(r), verdictsOf(inProcess));
    QCOMPARE(verdictsOf(r), (QStringList{QStringLiteral("3 held"), QStringLiteral("6 held"),
                                         QStringLiteral("7 held"), QStringLiteral("9 held")}));
    QVERIFY(r.passed());
    QCOMPARE(r.frames.wrong, 0);
    // uasim said which commands it took: they are counted, and were sent.
    QVERIFY2(r.frames.receivedUp > 10, qPrintable(QString::number(r.frames.receivedUp)));
    QVERIFY(r.frames.receivedDown > 10);
    QVERIFY(r.frames.inOutage > 0);
    // The frame log holds the console's side of the real sockets.
    FrameLogReader reader;
    QVERIFY(reader.open(logPath));
    QVERIFY(reader.count() >= int(r.frames.sentUp));
}

// The modem run of call-drop.json, against the same run in process.
static void checkModemRun(const ScenarioRunner& real, const RehearsalReport& inProcess)
{
    const RehearsalReport& r = real.report();
    QCOMPARE(r.transport, QStringLiteral("modem (uasim --modem as a process, the satellite modem model)"));
    QCOMPARE(verdictsOf(r), verdictsOf(inProcess));
    QCOMPARE(verdictsOf(r), (QStringList{QStringLiteral("2 held"), QStringLiteral("4 held"), QStringLiteral("5 held"),
                                         QStringLiteral("7 held"), QStringLiteral("8 held")}));
    QCOMPARE(r.frames.wrong, 0);
    QVERIFY(r.frames.receivedUp > 10);
    QStringList events;
    for (const auto& t : r.timeline)
        events << t.text;
    QVERIFY2(events.filter(QStringLiteral("console's modem: call dropped (NO CARRIER)")).size() == 1,
             qPrintable(events.join('\n')));
    QVERIFY(events.filter(QStringLiteral("console's modem: connected at 9600 bit/s")).size() == 2);
    QVERIFY(events.contains(QStringLiteral("modem model: the network hung up (dropped)")));
}

// At speed 1, the real programs on the system clock: the real-time suite
// of every transport (tests/CMakeLists.txt). Over UDP, uasim as a process,
// real sockets and the faults in a proxy between them; over serial, the
// same on pseudo-terminal pairs; through the modem, the console's modem
// dials uasim --modem through the satellite modem model, the call drops
// and is redialled. Each takes its scenario's duration on the wall clock,
// so the three run side by side. Every expectation is judged as the run
// in process judges it, and holds in both.
void TestRehearsal::speedOneRunsTheRealPrograms()
{
    ScenarioRunner udpInProcess(realTimeScenario(false), QString());
    udpInProcess.runToEnd();
    QVERIFY(!udpInProcess.realPrograms());
    ScenarioRunner serialInProcess(realTimeScenario(true), QString());
    serialInProcess.runToEnd();
    ScenarioRunner modemInProcess(load(QStringLiteral("call-drop.json")), QString());
    modemInProcess.runToEnd();

    QTemporaryDir dir;
    const QString udpLog = dir.filePath(QStringLiteral("udp.pcapng"));
    const QString serialLog = dir.filePath(QStringLiteral("serial.pcapng"));
    ScenarioRunner udp(realTimeScenario(false), udpLog);
    ScenarioRunner serial(realTimeScenario(true), serialLog);
    ScenarioRunner modem(load(QStringLiteral("call-drop.json")), QString());
    int finished = 0;
    for (ScenarioRunner* run : {&udp, &serial, &modem}) {
        connect(run, &ScenarioRunner::finished, this, [&finished] { ++finished; });
        run->start(0, QStringLiteral(RCM_BIN_DIR "/uasim"));
        QVERIFY(run->realPrograms());
    }
    QTRY_COMPARE_WITH_TIMEOUT(finished, 3, 120'000);

    checkRealTimeRun(udp, QStringLiteral("udp (uasim as a process, real sockets)"), udpLog, udpInProcess.report());
    if (QTest::currentTestFailed())
        return;
    checkRealTimeRun(serial, QStringLiteral("serial (uasim as a process, pseudo-terminal pairs)"), serialLog,
                     serialInProcess.report());
    if (QTest::currentTestFailed())
        return;
    checkModemRun(modem, modemInProcess.report());
}

void TestRehearsal::frameLogHoldsBothDirections()
{
    QTemporaryDir dir;
    const QString path = dir.filePath(QStringLiteral("session.pcapng"));
    qint64 sent = 0;
    qint64 received = 0;
    {
        ScenarioRunner runner(load(QStringLiteral("ber.json")), path);
        QCOMPARE(runner.frameLogError(), QString());
        runner.runToEnd();
        sent = runner.report().frames.sentUp;
        received = runner.report().frames.receivedDown;
    }
    FrameLogReader reader;
    QVERIFY2(reader.open(path), qPrintable(reader.errorString()));
    int up = 0, down = 0;
    for (const FrameIndexEntry& e : reader.index())
        ++(e.direction == FrameDirection::Sent ? up : down);
    QCOMPARE(up, sent);
    QCOMPARE(down, received);  // every frame arrived, each corrected
    QCOMPARE(sent, 120);
}

// The first frame the console sent in a run of `scenario`, as the session log has it.
static QByteArray firstSentFrame(const QString& scenario, RehearsalReport* report)
{
    QTemporaryDir dir;
    const QString path = dir.filePath(QStringLiteral("session.pcapng"));
    {
        ScenarioRunner runner(load(scenario), path);
        runner.runToEnd();
        *report = runner.report();
    }
    FrameLogReader reader;
    if (!reader.open(path) || reader.count() == 0)
        return {};
    return reader.recordAt(0).bytes;
}

static bool plaintext(const QByteArray& datagram)
{
    if (datagram.size() != int(rcm::kDatagramSize))
        return false;
    return rcm::secure::looksLikePlaintext(rcm::decodeCodewords(std::span<const std::uint8_t, rcm::kDatagramSize>(
        reinterpret_cast<const std::uint8_t*>(datagram.constData()), rcm::kDatagramSize)));
}

void TestRehearsal::keyEnciphersTheRun()
{
    RehearsalReport secure;
    const QByteArray enciphered = firstSentFrame(QStringLiteral("secure.json"), &secure);
    QCOMPARE(enciphered.size(), int(rcm::kDatagramSize));
    QVERIFY(!plaintext(enciphered));
    QCOMPARE(secure.transport, QStringLiteral("udp (in process), secure link"));
    QVERIFY(secure.passed());
    QCOMPARE(secure.frames.wrong, 0);

    RehearsalReport plain;
    QVERIFY(plaintext(firstSentFrame(QStringLiteral("gear-outage-plan.json"), &plain)));
    QCOMPARE(plain.transport, QStringLiteral("udp (in process)"));
}

void TestRehearsal::samplesHold_data()
{
    QTest::addColumn<QString>("scenario");
    for (const char* name : {"ber.json", "outage.json", "slip.json", "burst.json", "gear-outage-plan.json",
                             "secure.json", "slip-serial.json", "real-time.json", "plans-from-other-programs.json"})
        QTest::newRow(name) << QString::fromLatin1(name);
}

void TestRehearsal::samplesHold()
{
    QFETCH(QString, scenario);
    QTemporaryDir dir;
    const auto run = rcm::test::runProgram(
        QStringLiteral("gcs"), {QStringLiteral("--rehearse"), kScenarios + scenario, QStringLiteral("--report"),
                                dir.path(), QStringLiteral("--rehearse-speed"), QStringLiteral("0")});
    QVERIFY2(run.exitCode == 0, run.err.constData());
    const QJsonObject report = readJson(dir.filePath(QStringLiteral("report.json")));
    QCOMPARE(report.value(QStringLiteral("verdict")).toString(), QStringLiteral("passed"));
    QCOMPARE(report.value(QStringLiteral("frames")).toObject().value(QStringLiteral("wrong")).toInt(), 0);
    for (const QJsonValue& e : report.value(QStringLiteral("expectations")).toArray())
        QCOMPARE(e.toObject().value(QStringLiteral("result")).toString(), QStringLiteral("held"));
    const QString html = readText(dir.filePath(QStringLiteral("report.html")));
    QVERIFY(html.indexOf(QStringLiteral("PASSED: every expectation held")) < html.indexOf(QStringLiteral("<h2>")));
    QVERIFY(html.contains(QStringLiteral("<svg")));
    QVERIFY(!html.contains(QStringLiteral("src=")));  // self-contained
    QVERIFY(QFileInfo(dir.filePath(QStringLiteral("session.pcapng"))).size() > 0);
}

void TestRehearsal::failedStepNamedInBothReports()
{
    QTemporaryDir dir;
    const auto run = rcm::test::runProgram(
        QStringLiteral("gcs"),
        {QStringLiteral("--rehearse"), kScenarios + QStringLiteral("cannot-hold.json"), QStringLiteral("--report"),
         dir.path(), QStringLiteral("--rehearse-speed"), QStringLiteral("0")});
    QCOMPARE(run.exitCode, 1);
    QVERIFY(
        run.err.contains("gcs: failed: step 2 at 0 s: expect \"engine 1: eng_prop_pitch 150\" reported within 10 s "
                         "(not seen by 10 s)\n"));
    const QJsonObject report = readJson(dir.filePath(QStringLiteral("report.json")));
    QCOMPARE(report.value(QStringLiteral("verdict")).toString(), QStringLiteral("failed"));
    const QJsonArray expectations = report.value(QStringLiteral("expectations")).toArray();
    QCOMPARE(expectations.size(), 3);
    const QJsonObject never = expectations[0].toObject();
    QCOMPARE(never.value(QStringLiteral("step")).toInt(), 2);
    QCOMPARE(never.value(QStringLiteral("result")).toString(), QStringLiteral("failed"));
    QCOMPARE(never.value(QStringLiteral("measured")).isNull(), true);
    QCOMPARE(never.value(QStringLiteral("detail")).toString(), QStringLiteral("not seen by 10 s"));
    const QJsonObject regained = expectations[1].toObject();
    QCOMPARE(regained.value(QStringLiteral("expectation")).toString(),
             QStringLiteral("step 4 at 20 s: expect alarm link-regained within 2 s"));
    QCOMPARE(regained.value(QStringLiteral("result")).toString(), QStringLiteral("failed"));
    QCOMPARE(expectations[2].toObject().value(QStringLiteral("result")).toString(), QStringLiteral("held"));

    const QString html = readText(dir.filePath(QStringLiteral("report.html")));
    // The outage raised the link-loss alarm, which no step expected: a failure too.
    QVERIFY(html.contains(
        QStringLiteral("<p class=\"verdict fail\">FAILED: 2 of 3 expectations failed; 1 alarm no step expected</p>")));
    QVERIFY(
        run.err.contains("gcs: rehearsal \"expectations that cannot hold\": 2 of 3 expectations failed; 1 alarm no "
                         "step expected; report in "));
    QVERIFY(run.err.contains("gcs: failed: link-lost alarm at 23.0 s, which no step expected\n"));
    QCOMPARE(
        report.value(QStringLiteral("alarms")).toArray().at(0).toObject().value(QStringLiteral("result")).toString(),
        QStringLiteral("unexpected"));
    QVERIFY(
        html.contains(QStringLiteral("<tr><td>2</td><td>step 2 at 0 s: expect &quot;engine 1: eng_prop_pitch "
                                     "150&quot; reported within 10 s</td><td class=\"failed\">failed</td>")));
    QVERIFY(
        html.contains(QStringLiteral("<td>step 4 at 20 s: expect alarm link-regained within 2 s</td><td "
                                     "class=\"failed\">failed</td>")));
}

void TestRehearsal::malformedScenarioExitsTwo()
{
    QTemporaryDir dir;
    const QString path = kScenarios + QStringLiteral("malformed.json");
    const auto run = rcm::test::runProgram(
        QStringLiteral("gcs"), {QStringLiteral("--rehearse"), path, QStringLiteral("--report"), dir.path()});
    QCOMPARE(run.exitCode, 2);
    QVERIFY2(
        run.err.contains(QStringLiteral("gcs: %1:7:22: step 2: the aircraft has no engine 7\n").arg(path).toUtf8()),
        run.err.constData());
    QVERIFY(!QFile::exists(dir.filePath(QStringLiteral("report.json"))));
}

// A name that is no file is one of the scenarios that come with gcs, in
// share/rcm-gcs/scenarios beside its bin folder: /usr/share/rcm-gcs installed,
// in the build tree a link to resources/ (cmake/Packaging.cmake).
void TestRehearsal::scenarioByName()
{
    QTemporaryDir dir;
    const QString shipped = QDir::cleanPath(QStringLiteral(RCM_BIN_DIR "/../share/rcm-gcs/scenarios/malformed.json"));
    QCOMPARE(QFileInfo(shipped).canonicalFilePath(),
             QFileInfo(kScenarios + QStringLiteral("malformed.json")).canonicalFilePath());
    const auto run = rcm::test::runProgram(
        QStringLiteral("gcs"),
        {QStringLiteral("--rehearse"), QStringLiteral("malformed"), QStringLiteral("--report"), dir.path()});
    QCOMPARE(run.exitCode, 2);
    QVERIFY2(
        run.err.contains(QStringLiteral("gcs: %1:7:22: step 2: the aircraft has no engine 7\n").arg(shipped).toUtf8()),
        run.err.constData());

    const auto unknown = rcm::test::runProgram(
        QStringLiteral("gcs"),
        {QStringLiteral("--rehearse"), QStringLiteral("no-such-scenario"), QStringLiteral("--report"), dir.path()});
    QCOMPARE(unknown.exitCode, 2);
    QVERIFY2(unknown.err.contains("gcs: no-such-scenario:0:0: cannot read: "), unknown.err.constData());
}

void TestRehearsal::dialogShowsTheRun()
{
    QTemporaryDir dir;
    RehearsalDialog dialog;
    QSignalSpy finished(&dialog, &RehearsalDialog::finished);
    QVERIFY(dialog.run(kScenarios + QStringLiteral("outage.json"), dir.path(), 100000));
    QVERIFY(finished.wait(30000));
    QCOMPARE(dialog.progressMaximum(), 900);
    QCOMPARE(dialog.progressValue(), 900);
    QCOMPARE(dialog.verdict(), QStringLiteral("PASSED: every expectation held (5).\nReport in %1").arg(dir.path()));
    QVERIFY2(dialog.timeline().contains(QStringLiteral("  33.0 s  alarm  link-lost\n")), qPrintable(dialog.timeline()));
    QVERIFY(dialog.timeline().contains(QStringLiteral("  51.0 s  alarm  link-regained")));
    QCOMPARE(readJson(dir.filePath(QStringLiteral("report.json"))).value(QStringLiteral("verdict")).toString(),
             QStringLiteral("passed"));
    QVERIFY(QFileInfo(dir.filePath(QStringLiteral("session.pcapng"))).size() > 0);
}

void TestRehearsal::dialogSaysWhereTheScenarioIsWrong()
{
    RehearsalDialog dialog;
    const QString path = kScenarios + QStringLiteral("malformed.json");
    QVERIFY(!dialog.run(path, QDir::tempPath()));
    QCOMPARE(dialog.verdict(), QStringLiteral("%1:7:22: step 2: the aircraft has no engine 7").arg(path));
}

namespace {

// The processes `pid` started, from Linux's /proc.
QList<qint64> childrenOf(qint64 pid)
{
    QFile file(QStringLiteral("/proc/%1/task/%1/children").arg(pid));
    QList<qint64> children;
    if (file.open(QIODevice::ReadOnly))
        for (const QByteArray& id : file.readAll().split(' '))
            if (!id.trimmed().isEmpty())
                children << id.trimmed().toLongLong();
    return children;
}

// Gone, or a zombie nobody reaped: either way it no longer runs.
bool hasEnded(qint64 pid)
{
    QFile stat(QStringLiteral("/proc/%1/stat").arg(pid));
    if (!stat.open(QIODevice::ReadOnly))
        return true;
    const QByteArray text = stat.readAll();
    const qsizetype close = text.lastIndexOf(')');
    return close < 0 || text.mid(close + 2, 1) == "Z";
}

}  // namespace

void TestRehearsal::uasimEndsWithTheConsole()
{
#ifndef Q_OS_LINUX
    QSKIP("reads /proc");
#endif
    QTemporaryDir home;
    QProcess gcs;
    QProcessEnvironment environment = QProcessEnvironment::systemEnvironment();
    environment.insert(QStringLiteral("HOME"), home.path());
    environment.insert(QStringLiteral("XDG_CONFIG_HOME"), home.filePath(QStringLiteral("config")));
    environment.insert(QStringLiteral("XDG_DATA_HOME"), home.filePath(QStringLiteral("data")));
    environment.insert(QStringLiteral("QT_QPA_PLATFORM"), QStringLiteral("offscreen"));
    gcs.setProcessEnvironment(environment);
    gcs.start(QStringLiteral(RCM_BIN_DIR "/gcs"), {QStringLiteral("--rehearsal")});
    QVERIFY(gcs.waitForStarted());
    QList<qint64> children;
    QTRY_VERIFY_WITH_TIMEOUT(!(children = childrenOf(gcs.processId())).isEmpty(), 30000);
    // Between its fork and its exec the child is still called gcs.
    const auto name = [](qint64 pid) {
        QFile comm(QStringLiteral("/proc/%1/comm").arg(pid));
        return comm.open(QIODevice::ReadOnly) ? comm.readAll().trimmed() : QByteArray();
    };
    QTRY_COMPARE_WITH_TIMEOUT(name(children.first()), QByteArray("uasim"), 30000);
    // Killed, with no chance to stop its rehearsal: the aircraft goes too.
    gcs.kill();
    QVERIFY(gcs.waitForFinished());
    QTRY_VERIFY_WITH_TIMEOUT(hasEnded(children.first()), 30000);
}

// docs/rehearsal.md writes "within" beside "expect"; the samples inside it.
void TestRehearsal::withinBesideExpect()
{
    ScenarioError error;
    const auto s = Scenario::fromJson(R"({"duration": 60, "steps": [
        {"at": 10, "expect": {"alarm": "link-lost"}, "within": 6},
        {"at": 20, "expect": {"reported": "F_elev_set 12", "within": 5}},
        {"at": 30, "expect": {"plan": "acknowledged"}, "within": 15}]})",
                                      QStringLiteral("w.json"), RehearsalCommandLine::planLoader(), &error);
    QVERIFY2(s, qPrintable(error.text()));
    QCOMPARE(s->steps[0].within, 6.0);
    QCOMPARE(s->steps[1].within, 5.0);
    QCOMPARE(s->steps[2].within, 15.0);
    QCOMPARE(s->steps[0].describe(), QStringLiteral("step 1 at 10 s: expect alarm link-lost within 6 s"));
}

// A 20 s outage and no step that expects the link-loss alarm it raises: the
// run fails, however well every expectation held, and says why.
void TestRehearsal::unexpectedAlarmFailsTheRun()
{
    ScenarioError error;
    const auto s = Scenario::fromJson(R"({"name": "an outage nobody expected", "speed": 60, "duration": 60, "steps": [
        {"at": 0, "set": "camera 1: cam_zoom_set 40"},
        {"at": 0, "expect": {"reported": "camera 1: cam_zoom_set 40"}, "within": 5},
        {"at": 20, "fault": {"outage": 20}},
        {"at": 40, "expect": {"alarm": "link-regained"}, "within": 3}]})",
                                      QStringLiteral("u.json"), RehearsalCommandLine::planLoader(), &error);
    QVERIFY2(s, qPrintable(error.text()));
    ScenarioRunner runner(*s, QString());
    runner.runToEnd();
    const RehearsalReport& r = runner.report();
    QVERIFY(std::all_of(r.expectations.begin(), r.expectations.end(), [](const auto& e) { return e.held; }));
    QVERIFY(!r.passed());
    QCOMPARE(r.alarms.size(), std::size_t(2));
    QCOMPARE(r.alarms[0].time, 23.0);
    QCOMPARE(r.alarms[0].name, QStringLiteral("link-lost"));
    QCOMPARE(r.alarms[0].expectedBy, 0);
    QCOMPARE(r.alarms[1].name, QStringLiteral("link-regained"));
    QCOMPARE(r.alarms[1].expectedBy, 4);
    QCOMPARE(r.verdict(), QStringLiteral("1 alarm no step expected"));
    QCOMPARE(r.failures(), QStringList{QStringLiteral("link-lost alarm at 23.0 s, which no step expected")});
    const QJsonObject json = QJsonDocument::fromJson(r.toJson()).object();
    QCOMPARE(json.value(QStringLiteral("verdict")).toString(), QStringLiteral("failed"));
    const QJsonArray alarms = json.value(QStringLiteral("alarms")).toArray();
    QCOMPARE(alarms[0].toObject().value(QStringLiteral("result")).toString(), QStringLiteral("unexpected"));
    QVERIFY(alarms[0].toObject().value(QStringLiteral("expected-by")).isNull());
    QCOMPARE(alarms[1].toObject().value(QStringLiteral("expected-by")).toInt(), 4);
    const QString html = r.toHtml();
    QVERIFY(html.contains(QStringLiteral("<p class=\"verdict fail\">FAILED: 1 alarm no step expected</p>")));
    QVERIFY(
        html.contains(QStringLiteral("<tr><td>23.0</td><td>link-lost</td><td class=\"failed\">by no step</td></tr>")));
    QVERIFY(html.contains(QStringLiteral("<tr><td>41.0</td><td>link-regained</td><td>by step 4</td></tr>")));
    // Marked on the plot, red.
    QVERIFY(
        html.contains(QStringLiteral("stroke=\"#b00\" stroke-width=\"2\" stroke-dasharray=\"4 3\"><title>link-lost at "
                                     "23.0 s, which no step expected</title>")));
    bool said = false;
    for (const auto& t : r.timeline)
        said |= t.kind == QLatin1String("alarm") && t.text == QLatin1String("link-lost: no step expected it");
    QVERIFY(said);

    // A scenario that allows link losses over the run expects them, up to its count.
    for (int allowed : {1, 0}) {
        const auto allowing = Scenario::fromJson(QStringLiteral(R"({"speed": 60, "duration": 60, "steps": [
            {"at": 20, "fault": {"outage": 20}},
            {"expect": {"link-lost-at-most": %1}}]})")
                                                     .arg(allowed)
                                                     .toUtf8(),
                                                 QStringLiteral("a.json"), RehearsalCommandLine::planLoader(), &error);
        QVERIFY2(allowing, qPrintable(error.text()));
        ScenarioRunner run(*allowing, QString());
        run.runToEnd();
        QCOMPARE(run.report().alarms[0].expectedBy, 2);
        QCOMPARE(run.report().expectations[0].description,
                 QStringLiteral("step 2 over the whole run: expect the link-loss alarm at most %1 %2")
                     .arg(allowed)
                     .arg(allowed == 1 ? QStringLiteral("time") : QStringLiteral("times")));
        QCOMPARE(run.report().expectations[0].detail, QStringLiteral("raised 1 time"));
        QCOMPARE(run.report().passed(), allowed == 1);
    }
}

// The link quality plot: a time axis with round ticks, each fault's period
// shaded; the expectations in four columns, what was seen said once.
void TestRehearsal::reportPlotHasTimeAndFaults()
{
    ScenarioRunner runner(load(QStringLiteral("outage.json")), QString());
    runner.runToEnd();
    const RehearsalReport& r = runner.report();
    QVERIFY(r.passed());
    QCOMPARE(r.faults.size(), std::size_t(1));
    QCOMPARE(r.faults[0].start, 30.0);
    QCOMPARE(r.faults[0].end, 50.0);
    QCOMPARE(r.faults[0].text, QStringLiteral("fault outage 20"));
    const QString html = r.toHtml();
    QStringList ticks;
    static const QRegularExpression tick(QStringLiteral("<line class=\"tick\"[^>]*/><text[^>]*>([^<]*)</text>"));
    for (auto it = tick.globalMatch(html); it.hasNext();)
        ticks << it.next().captured(1);
    QCOMPARE(ticks,
             (QStringList{QStringLiteral("0"), QStringLiteral("10 s"), QStringLiteral("20 s"), QStringLiteral("30 s"),
                          QStringLiteral("40 s"), QStringLiteral("50 s"), QStringLiteral("60 s"),
                          QStringLiteral("70 s"), QStringLiteral("80 s"), QStringLiteral("90 s")}));
    // 30 s to 50 s of 90 on 730 px from x = 40: 283.3 to 445.6; shaded, and named under the axis.
    QVERIFY2(html.contains(QStringLiteral("<rect class=\"fault\" x=\"283.3\" y=\"10\" width=\"162.2\" height=\"170\" "
                                          "fill=\"#f0a030\" fill-opacity=\"0.25\"><title>fault outage 20 (30.0 s to "
                                          "50.0 s)</title></rect>")),
             qPrintable(html));
    QVERIFY(
        html.contains(QStringLiteral("<text x=\"286.3\" y=\"235.0\" font-size=\"11\">fault outage 20 (30.0 s to "
                                     "50.0 s)</text>")));
    QVERIFY(html.contains(
        QStringLiteral("<tr><th>Step</th><th>Expectation</th><th>Result</th><th>What was seen</th></tr>")));
    QVERIFY(!html.contains(QStringLiteral("Measured")));
    QVERIFY(html.contains(QStringLiteral("<td class=\"held\">held</td><td>after 2 s</td></tr>")));
    QVERIFY(html.contains(QStringLiteral("<td class=\"held\">held</td><td>0 wrong frames</td></tr>")));

    // An hour: ticks every 10 minutes.
    RehearsalReport empty;
    empty.duration = 3600;
    QStringList minutes;
    const QString hourHtml = empty.toHtml();
    for (auto it = tick.globalMatch(hourHtml); it.hasNext();)
        minutes << it.next().captured(1);
    QCOMPARE(minutes, (QStringList{QStringLiteral("0"), QStringLiteral("10 min"), QStringLiteral("20 min"),
                                   QStringLiteral("30 min"), QStringLiteral("40 min"), QStringLiteral("50 min"),
                                   QStringLiteral("60 min")}));
}

// A plan of one item goes in one section: "1 section", in the step and in
// the aircraft's word that it has it.
void TestRehearsal::oneSectionIsOneSection()
{
    QTemporaryDir dir;
    QFile plan(dir.filePath(QStringLiteral("one.waypoints")));
    QVERIFY(plan.open(QIODevice::WriteOnly));
    plan.write("QGC WPL 110\n1\t0\t3\t16\t0\t0\t0\t0\t52.2151260\t0.1302118\t120\t1\n");
    plan.close();
    ScenarioError error;
    const auto s =
        Scenario::fromJson(R"({"speed": 60, "duration": 10, "steps": [
        {"at": 1, "upload": "one.waypoints"},
        {"at": 1, "expect": {"plan": "acknowledged"}, "within": 5}]})",
                           dir.filePath(QStringLiteral("one.json")), RehearsalCommandLine::planLoader(), &error);
    QVERIFY2(s, qPrintable(error.text()));
    ScenarioRunner runner(*s, QString());
    runner.runToEnd();
    QVERIFY(runner.report().passed());
    QStringList said;
    for (const auto& t : runner.report().timeline)
        said << t.text;
    QVERIFY2(said.contains(QStringLiteral("step 1 at 1 s: upload one.waypoints (flight plan 0x52450001, 1 section)")),
             qPrintable(said.join(QLatin1Char('\n'))));
    QVERIFY2(std::any_of(said.begin(), said.end(),
                         [](const QString& t) {
                             return t.endsWith(QStringLiteral(
                                 "flight plan 0x52450001 complete: 50 bytes in 1 section: 1 mission item, no fence, "
                                 "no rally points"));
                         }),
             qPrintable(said.join(QLatin1Char('\n'))));
}

QTEST_MAIN(TestRehearsal)
#include "tst_rehearsal.moc"
