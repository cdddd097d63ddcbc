// The operator console as a whole: the window built with the default
// airframe, airframe files, the `--screenshot` picture made by the real
// program, the QGroundControl plan import and its bytes, the next-frame
// preview's marks, the link-lost alarm, a replay, and a rehearsal against the
// simulated aircraft on loopback carrying status frames and a flight plan.
// Every wait is a QTRY_* on state the console exposes; the timeouts only bound
// a broken build.

#include "AnswerBox.h"
#include "InProcessLink.h"
#include "ResumeCommanding.h"
#include "codec/message/Airframe.h"
#include "codec/message/MessageDecoder.h"
#include "codec/message/MessageEncoder.h"
#include "codec/frame/Frame.h"
#include "codec/secure/SecureCodec.h"
#include "link/clock/VirtualClock.h"
#include "link/framelog/FrameLog.h"
#include "link/session/LinkWorker.h"
#include "link/framelog/FrameLogReader.h"
#include "link/airframe/AirframeLoader.h"
#include "link/transport/UdpLink.h"
#include "ui/alerts/RefusalDigest.h"
#include "ui/panels/CommandPreview.h"
#include "ui/panels/CommandState.h"
#include "ui/panels/FieldButtonGroup.h"
#include "ui/panels/ReportedState.h"
#include "ui/plan/FlightPlanUpload.h"
#include "ui/plan/FlightPlanWidget.h"
#include "ui/framelog/FrameLogModel.h"
#include "ui/framelog/FrameLogView.h"
#include "ui/window/ReplayControls.h"
#include "link/session/LinkSettings.h"
#include "link/satmodem/SatelliteModemThread.h"
#include "ui/window/LinkSettingsWidget.h"
#include "ui/window/MainWindow.h"
#include "ui/window/WindowFit.h"
#include "link/plan/MissionPlan.h"
#include "link/plan/PlanFile.h"
#include "link/plan/QgcPlanFile.h"
#include "ui/window/StatusBarWidget.h"
#include "ui/window/ConsoleDocks.h"
#include "ui/alerts/LinkAlarmBanner.h"
#include "ui/alerts/LinkStateStrip.h"
#include "ui/alerts/ToneAlarmSound.h"
#include "ui/eventlog/EventLogView.h"
#include "ui/overview/LinkQualityHistory.h"
#include "link/eventlog/EventLog.h"
#include "link/session/RehearsalLauncher.h"
#include "ui/window/StatusFigure.h"
#include "ui/alerts/ConsoleAlerts.h"
#include "ui/alerts/ErrorBanner.h"
#include "ui/alerts/LinkAlarm.h"
#include "ui/eventlog/EventLogModel.h"
#include "link/session/StationControl.h"
#include "ui/control/StationControlWidget.h"
#include "ui/overview/OverviewPage.h"
#include <QTextDocumentFragment>
#include <QUdpSocket>

#include <QAction>
#include <QApplication>
#include <QDateTime>
#include <QLabel>
#include <QMessageBox>
#include <QPushButton>
#include <QTimer>
#include <QDockWidget>
#include <QImage>
#include <QProcess>
#include <QSettings>
#include <QSignalSpy>
#include <QTabWidget>
#include <QTextEdit>
#include <QStatusBar>
#include <QGridLayout>
#include <QGroupBox>
#include <QScrollArea>
#include <QScrollBar>
#include <QTabBar>
#include <QTabWidget>
#include <QAbstractSpinBox>
#include <QWheelEvent>
#include <QComboBox>
#include <QTableWidget>
#include <QTemporaryDir>
#include <QTest>
#include <QTextBlock>
#include <QTextDocument>

#include <cmath>
#include <csignal>
#include <set>

namespace {

const QString kSamplePlan = QStringLiteral(RCM_SOURCE_DIR "/resources/plans/sample.plan");
const QString kAirframes = QStringLiteral(RCM_SOURCE_DIR "/resources/airframes/");
constexpr int kProcessTimeoutMs = 60000;
constexpr int kLinkTimeoutMs = 30000;

// A replay on simulated time: the window's session on `clock`, stepped a
// second at a time (the replay's pace and the link's silence timeout),
// the link thread's reports taken in after each step, until `done` holds;
// false after `limitSeconds` of simulated time. The replay's link is made
// off the GUI thread (its log indexed first): waited for in real time.
bool runReplayUntil(VirtualClock& clock, const std::function<bool()>& done, int limitSeconds = 60)
{
    QCoreApplication::processEvents();
    if (!QTest::qWaitFor([&] { return done() || clock.activeTimers() > 0; }, kLinkTimeoutMs))
        return false;
    for (int second = 0; second < limitSeconds; ++second) {
        QCoreApplication::processEvents();
        if (done())
            return true;
        clock.advance(std::chrono::seconds(1));
    }
    QCoreApplication::processEvents();
    return done();
}

void compareAirframes(const rcm::Airframe& a, const rcm::Airframe& b)
{
    QCOMPARE(a.name, b.name);
    QCOMPARE(a.senseAndAvoid, b.senseAndAvoid);
    QCOMPARE(a.engines.size(), b.engines.size());
    for (std::size_t i = 0; i < a.engines.size(); ++i) {
        QCOMPARE(a.engines[i].id, b.engines[i].id);
        QCOMPARE(a.engines[i].name, b.engines[i].name);
    }
    QCOMPARE(a.radios.size(), b.radios.size());
    for (std::size_t i = 0; i < a.radios.size(); ++i) {
        QCOMPARE(a.radios[i].systemId, b.radios[i].systemId);
        QCOMPARE(a.radios[i].name, b.radios[i].name);
    }
    QCOMPARE(a.cameras.size(), b.cameras.size());
    for (std::size_t i = 0; i < a.cameras.size(); ++i) {
        QCOMPARE(a.cameras[i].maker, b.cameras[i].maker);
        QCOMPARE(a.cameras[i].number, b.cameras[i].number);
        QCOMPARE(a.cameras[i].name, b.cameras[i].name);
    }
}

QString airframeError(const QByteArray& json)
{
    QString error;
    const auto airframe = AirframeLoader::fromJson(json, QStringLiteral("test.json"), &error);
    return airframe ? QString() : error;
}

}  // namespace

class TestMainWindow : public QObject {
    Q_OBJECT

private slots:
    void initTestCase();
    void buildsWithTheDefaultAirframe();
    void airframeFiles();
    void screenshotOfTheRealProgram();
    void importsTheSamplePlan();
    void planBytes();
    void refusesPlansItCannotSend();
    void openedPlanIsBroughtForward();
    void refusedPlanFileSaysWhyNotHow();
    void previewMarksChangedItems();
    void previewFollowsOncePerPass();
    void previewShowsTheBytesTheLinkSends();
    void linkLostAlarm();
    void statusFiguresNameTheirValues();
    void linkSettingsAreKept();
    void replaysAFrameLog();
    void replayOfAMissingLogSaysWhy();
    void replayShowsTheLogsCommandReadOnly();
    void keyedReplayShowsWhatWasCommanded();
    void rehearsalAgainstUasim();
    void keyedUploadUses199ByteSections();
    void refusedKeyFileSaysWhy();
    void failedOpenSaysWhy();
    void secureRehearsalWithMatchingKeys();
    void wrongKeyIsRejectedAsForged();
    void statusBarListsRefusalsByReason();
    void asksBeforeEndingALiveLink_data();
    void asksBeforeEndingALiveLink();
    void quitEndsTheLinkOnceConfirmed();
    void linkButtonsNeverHoldTheFocus();
    void controlAlarmsReachBannerAndEventLog();
    void aModemIsDialledAndHungUp();
    void satelliteRoundTripIsNoMismatch();
    void fitsASmallScreen();
    void resetLayoutRestoresTheDefault();
    void nightThemeIsKept();
    void alarmShowsInFloatingDocks();
    void noSoundCardIsSaidAtStart();
    void statusBarMessagesShow();
    void defaultGeometryFitsTheScreen();
    void controlBannerClearsOnceTaken();
    void redialBannerClearsWithItsCause();
    void replayShowsTheLogsPlotAndEvents();
    void deadSimulatedAircraftIsALinkLoss();

private:
    MainWindow::Options options() const;
    // A new key file, mode 0600, in the test's directory.
    QString keyFile(const QString& name) const;
    QTemporaryDir m_dir;
};

void TestMainWindow::initTestCase()
{
    QVERIFY(m_dir.isValid());
    // Nothing of this run lands in the user's settings.
    QCoreApplication::setOrganizationName(QStringLiteral("rcm-tests"));
    QSettings::setDefaultFormat(QSettings::IniFormat);
    QSettings::setPath(QSettings::IniFormat, QSettings::UserScope, m_dir.filePath(QStringLiteral("settings")));
}

MainWindow::Options TestMainWindow::options() const
{
    MainWindow::Options o;
    o.restoreSettings = false;
    o.frameLogDirectory = m_dir.filePath(QStringLiteral("framelogs"));
    return o;
}

QString TestMainWindow::keyFile(const QString& name) const
{
    const QString path = m_dir.filePath(name);
    std::string error;
    if (!rcm::secure::writeKeyFile(path.toStdString(), rcm::secure::generateKey(), error))
        qWarning("%s", error.c_str());
    return path;
}

void TestMainWindow::buildsWithTheDefaultAirframe()
{
    MainWindow window(options());
    compareAirframes(window.command()->airframe(), rcm::Airframe::wellEquipped());
    QVERIFY(window.windowTitle().contains(QStringLiteral("Well-equipped UA")));
    // The overview, the eight panels and the flight plan, each behind its Alt+digit.
    auto* panels = window.findChild<QTabWidget*>(QStringLiteral("panels"));
    QVERIFY(panels);
    QCOMPARE(panels->count(), 10);
    QCOMPARE(panels->widget(0), window.overview());
    QCOMPARE(panels->widget(9), window.flightPlan());
    QCOMPARE(panels->tabText(9), QStringLiteral("Flight plan"));
    QCOMPARE(panels->tabToolTip(9), QStringLiteral("Flight plan (Alt+0)"));
    window.showPanel(6);
    QCOMPARE(panels->currentIndex(), 6);
    // The docks the layout is saved by.
    std::set<QString> docks;
    for (QDockWidget* d : window.findChildren<QDockWidget*>())
        docks.insert(d->objectName());
    QCOMPARE(docks, (std::set<QString>{QStringLiteral("linkDock"), QStringLiteral("previewDock"),
                                       QStringLiteral("frameLogDock"), QStringLiteral("voiceDock"),
                                       QStringLiteral("eventsDock")}));
    window.resize(1400, 900);
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    window.activateWindow();
    QVERIFY(QTest::qWaitForWindowActive(&window));
    QTest::keyClick(&window, Qt::Key_3, Qt::AltModifier);
    QCOMPARE(panels->currentIndex(), 2);
    QTest::keyClick(&window, Qt::Key_8, Qt::AltModifier);
    QCOMPARE(panels->currentIndex(), 7);
    QTest::keyClick(&window, Qt::Key_0, Qt::AltModifier);
    QCOMPARE(panels->currentIndex(), 9);
    QVERIFY(!window.isLinkRunning());
    QVERIFY(!window.linkStatus()->alarmActive());

    // Another built-in airframe: the command follows it.
    QVERIFY(window.loadAirframe(QStringLiteral(":/airframes/single-engine.json")));
    QCOMPARE(window.command()->airframe().engines.size(), std::size_t(1));
    QCOMPARE(window.command()->message().engines.size(), std::size_t(1));
}

void TestMainWindow::airframeFiles()
{
    QCOMPARE(AirframeLoader::builtIn(), QStringList({QStringLiteral(":/airframes/single-engine.json"),
                                                     QStringLiteral(":/airframes/well-equipped.json")}));
    QString error;
    const auto builtIn = AirframeLoader::load(AirframeLoader::kDefaultPath, &error);
    QVERIFY2(builtIn, qPrintable(error));
    compareAirframes(*builtIn, rcm::Airframe::wellEquipped());
    // The source tree's copy is the one embedded.
    const auto file = AirframeLoader::load(kAirframes + QStringLiteral("well-equipped.json"), &error);
    QVERIFY2(file, qPrintable(error));
    compareAirframes(*file, rcm::Airframe::wellEquipped());
    const auto small = AirframeLoader::load(kAirframes + QStringLiteral("single-engine.json"), &error);
    QVERIFY2(small, qPrintable(error));
    QCOMPARE(small->engines.size(), std::size_t(1));
    QVERIFY(!small->senseAndAvoid);
    // toJson is read back as it was.
    const auto again = AirframeLoader::fromJson(AirframeLoader::toJson(*small), QStringLiteral("again"), &error);
    QVERIFY2(again, qPrintable(error));
    compareAirframes(*again, *small);

    // Clear errors, naming the file and the place.
    QVERIFY(!AirframeLoader::load(kAirframes + QStringLiteral("missing.json"), &error));
    QVERIFY(error.contains(QStringLiteral("missing.json")));
    QCOMPARE(airframeError("{\n  \"name\": \"x\",\n  \"engines\": [ {\"id\": 1,} ]\n}"),
             QStringLiteral("test.json: line 3, column 26: object is missing after a comma"));
    QCOMPARE(airframeError(R"({"name": "x", "engine": [{"id": 1}]})"),
             QStringLiteral("test.json: unknown member \"engine\" (known: name, engines, radios, cameras, "
                            "senseAndAvoid)"));
    QCOMPARE(airframeError(R"({"name": "x", "engines": [{"id": 1}, {"id": 1}]})"),
             QStringLiteral("test.json: engines[1]: engine 1 is listed twice"));
    QCOMPARE(airframeError(R"({"name": "x", "engines": [{"id": 256}]})"),
             QStringLiteral("test.json: engines[0]: \"id\" must be a whole number 0..255"));
    QCOMPARE(airframeError(R"({"name": "x", "radios": [{"systemId": "TOOLONGID"}]})"),
             QStringLiteral("test.json: radios[0]: \"systemId\" must be 1 to 8 printable ASCII characters, not "
                            "ending in a space"));
    QCOMPARE(airframeError(R"({"name": "x", "cameras": [{"maker": "NI", "number": 1}]})"),
             QStringLiteral("test.json: cameras[0]: \"maker\" must be 3 printable ASCII characters"));
    QCOMPARE(airframeError(R"({"engines": []})"), QStringLiteral("test.json: \"name\" must be a non-empty string"));
    // More units than a frame holds.
    QByteArray many = R"({"name": "x", "radios": [)";
    for (int i = 0; i < 20; ++i)
        many += (i ? ", " : "") + QStringLiteral(R"({"systemId": "R%1"})").arg(i).toUtf8();
    many += "]}";
    QVERIFY(airframeError(many).startsWith(QStringLiteral("test.json: these units do not fit in one message: ")));
}

void TestMainWindow::screenshotOfTheRealProgram()
{
    QVERIFY2(QFileInfo(QStringLiteral(RCM_BIN_DIR "/gcs")).isExecutable(), "build the gcs target first");
    const QString png = m_dir.filePath(QStringLiteral("gcs.png"));
    QProcess gcs;
    gcs.setProcessChannelMode(QProcess::ForwardedErrorChannel);
    QProcessEnvironment environment = QProcessEnvironment::systemEnvironment();
    environment.insert(QStringLiteral("QT_QPA_PLATFORM"), QStringLiteral("offscreen"));
    gcs.setProcessEnvironment(environment);
    QSignalSpy finished(&gcs, &QProcess::finished);
    gcs.start(QStringLiteral(RCM_BIN_DIR "/gcs"), {QStringLiteral("--screenshot"), png});
    QTRY_COMPARE_WITH_TIMEOUT(finished.count(), 1, kProcessTimeoutMs);
    QCOMPARE(gcs.exitStatus(), QProcess::NormalExit);
    QCOMPARE(gcs.exitCode(), 0);

    const QImage image(png);
    QVERIFY(!image.isNull());
    QCOMPARE(image.size(), QSize(1600, 1000));
    QVERIFY2(QFileInfo(png).size() > 30'000, qPrintable(QString::number(QFileInfo(png).size())));
    // A drawn window, not a blank: many colours, text and frames among them.
    std::set<QRgb> colours;
    for (int y = 0; y < image.height(); y += 7)
        for (int x = 0; x < image.width(); x += 7)
            colours.insert(image.pixel(x, y));
    QVERIFY2(colours.size() > 50, qPrintable(QString::number(colours.size())));

    // --help answers and exits 0; a wrong option is a usage error.
    QProcess help;
    QSignalSpy helpDone(&help, &QProcess::finished);
    help.setProcessEnvironment(environment);
    help.start(QStringLiteral(RCM_BIN_DIR "/gcs"), {QStringLiteral("--help")});
    QTRY_COMPARE_WITH_TIMEOUT(helpDone.count(), 1, kProcessTimeoutMs);
    QCOMPARE(help.exitCode(), 0);
    QVERIFY(help.readAllStandardOutput().contains("--rehearsal"));
    QProcess wrong;
    QSignalSpy wrongDone(&wrong, &QProcess::finished);
    wrong.setProcessEnvironment(environment);
    wrong.start(QStringLiteral(RCM_BIN_DIR "/gcs"), {QStringLiteral("--udp-remote"), QStringLiteral("nohost")});
    QTRY_COMPARE_WITH_TIMEOUT(wrongDone.count(), 1, kProcessTimeoutMs);
    QCOMPARE(wrong.exitCode(), 2);
}

void TestMainWindow::importsTheSamplePlan()
{
    MainWindow window(options());
    FlightPlanWidget* widget = window.flightPlan();
    QCOMPARE(window.panels()->currentIndex(), 0);
    QString error;
    QVERIFY2(widget->loadPlan(kSamplePlan, &error), qPrintable(error));
    // The plan opened is brought forward: its page.
    QCOMPARE(window.panels()->currentWidget(), widget);
    const MissionPlan& plan = *widget->plan();
    QCOMPARE(plan.items.size(), 9);
    QCOMPARE(widget->table()->rowCount(), 9);
    QCOMPARE(widget->summary(), QStringLiteral("9 mission items, 322 bytes, 2 BLOCK 2 sections, 2 s a pass"));

    const MissionItem& takeoff = plan.items[0];
    QCOMPARE(takeoff.seq, quint16(0));
    QCOMPARE(takeoff.command, quint16(22));
    QCOMPARE(takeoff.commandName(), QStringLiteral("TAKEOFF"));
    QCOMPARE(takeoff.frame, quint8(3));
    QCOMPARE(takeoff.params[0], 15.0);
    QVERIFY(std::isnan(takeoff.params[3]));  // null in the plan
    QCOMPARE(*takeoff.latitude, 52.2093412);
    QCOMPARE(*takeoff.longitude, 0.1189255);
    QCOMPARE(*takeoff.altitude, 60.0);

    const MissionItem& speed = plan.items[2];
    QCOMPARE(speed.command, quint16(178));
    QCOMPARE(speed.frame, quint8(2));
    QCOMPARE(speed.params[1], 25.0);

    const MissionItem& loiter = plan.items[5];
    QCOMPARE(loiter.commandName(), QStringLiteral("LOITER_TIME"));
    QCOMPARE(loiter.params[0], 60.0);
    QCOMPARE(*loiter.altitude, 150.0);
    QCOMPARE(plan.items[8].commandName(), QStringLiteral("RETURN_TO_LAUNCH"));
    QCOMPARE(*plan.homeLatitude, 52.2076813);
    QCOMPARE(*plan.homeAltitude, 14.2);

    // The table shows what was read.
    QCOMPARE(widget->table()->item(0, FlightPlanWidget::CommandColumn)->text(), QStringLiteral("TAKEOFF"));
    QCOMPARE(widget->table()->item(1, FlightPlanWidget::LatitudeColumn)->text(), QStringLiteral("52.2151260"));
    QCOMPARE(widget->table()->item(1, FlightPlanWidget::AltitudeColumn)->text(), QStringLiteral("120.0"));
    QCOMPARE(widget->table()->item(2, FlightPlanWidget::LatitudeColumn)->text(), QStringLiteral("\u2014"));
}

void TestMainWindow::planBytes()
{
    QString error;
    const auto plan = PlanFile::load(kSamplePlan, &error);
    QVERIFY2(plan, qPrintable(error));
    const QByteArray bytes = plan->toBytes();
    QCOMPARE(bytes.size(), MissionPlan::kHeaderBytes + 9 * MissionPlan::kItemBytes);
    QCOMPARE(bytes.size(), 322);
    // Header: format 1, reserved, N = 9, home 52.2076813 deg = 522076813 = 0x1F1E428D.
    QCOMPARE(bytes.left(8).toHex(), QByteArray("010000091f1e428d"));
    // Home altitude 14.2 m = 14200 mm.
    QCOMPARE(bytes.mid(12, 4).toHex(), QByteArray("00003778"));
    // Item 0: seq 0, NAV_TAKEOFF (22), frame 3, autocontinue, param1 15.0f, param2 0, param3 0, param4 NaN.
    QCOMPARE(bytes.mid(16, 22).toHex(), QByteArray("0000001603014170000000000000000000007fc00000"));
    // Item 2 (DO_CHANGE_SPEED) has no position: x, y, z are params 5-7, all 0.
    QCOMPARE(bytes.mid(16 + 2 * 34 + 22, 12).toHex(), QByteArray("000000000000000000000000"));

    const auto back = MissionPlan::fromBytes(bytes, &error);
    QVERIFY2(back, qPrintable(error));
    QCOMPARE(back->items.size(), plan->items.size());
    for (qsizetype i = 0; i < plan->items.size(); ++i) {
        const MissionItem& a = plan->items[i];
        const MissionItem& b = back->items[i];
        QCOMPARE(b.seq, a.seq);
        QCOMPARE(b.command, a.command);
        QCOMPARE(b.frame, a.frame);
        QCOMPARE(b.autoContinue, a.autoContinue);
        for (int p = 0; p < 4; ++p)
            QVERIFY(std::isnan(a.params[p]) ? std::isnan(b.params[p]) : float(a.params[p]) == float(b.params[p]));
        QVERIFY(std::abs(*b.latitude - *a.latitude) < 0.6e-7);
        QVERIFY(std::abs(*b.longitude - *a.longitude) < 0.6e-7);
        QVERIFY(std::abs(*b.altitude - *a.altitude) < 0.6e-3);
    }
    // The plan goes out in two BLOCK 2 sections.
    FlightPlanUpload upload;
    QVERIFY(upload.start(bytes));
    QCOMPARE(upload.progress().total, 2);
    QVERIFY(!MissionPlan::fromBytes(bytes.left(100), &error));
    QCOMPARE(error, QStringLiteral("byte 84: mission item 3 of 9 needs 34 bytes; 16 left"));
}

void TestMainWindow::refusesPlansItCannotSend()
{
    const auto error = [](const QByteArray& json) {
        QString e;
        return QgcPlanFile::read(json, QStringLiteral("p.plan"), &e) ? QString() : e;
    };
    QCOMPARE(error(R"({"fileType": "Plan", "mission": {"items": [{"type": "ComplexItem",
             "complexItemType": "survey"}]}})"),
             QStringLiteral("p.plan: mission item 1 (a survey) has no \"TransectStyleComplexItem\" with the waypoints "
                            "QGroundControl saved: it is in QGroundControl 3.3's layout; open the plan in a later "
                            "QGroundControl and save it again"));
    QCOMPARE(error(R"({"fileType": "Fence"})"),
             QStringLiteral("p.plan: not a QGroundControl plan (its \"fileType\" is not \"Plan\")"));
    QCOMPARE(error(R"({"fileType": "Plan", "mission": {"items": [{"type": "SimpleItem", "command": 16,
             "frame": 3, "params": [0, 0, 0, 0, 95.0, 0, 10]}]}})"),
             QStringLiteral("p.plan: mission item 1: latitude must be within +-90 and longitude within +-180 "
                            "degrees"));
    QCOMPARE(error(R"({"fileType": "Plan", "mission": {"items": [{"type": "SimpleItem", "command": 16,
             "frame": 3, "params": [0, 0, 0]}]}})"),
             QStringLiteral("p.plan: mission item 1: \"params\" must hold 7 values (numbers or null)"));
    QVERIFY2(error("{\n  not json").startsWith(QStringLiteral("p.plan: line 2, column ")),
             qPrintable(error("{\n  not json")));
}

// gcs --plan (and File > Open flight plan): the plan is what the window
// shows, in front of the frame log it shares its place with, before the
// first layout and after it.
void TestMainWindow::openedPlanIsBroughtForward()
{
    // A page behind another in its tabs is hidden: in front is what the window shows of it.
    const auto inFront = [](QWidget* content) { return !content->visibleRegion().isEmpty(); };
    {
        MainWindow window(options());
        QVERIFY(window.flightPlan()->loadPlan(kSamplePlan));
        window.show();
        QVERIFY(QTest::qWaitForWindowExposed(&window));
        QTRY_VERIFY(inFront(window.flightPlan()));
        QVERIFY(!inFront(window.overview()));
    }
    MainWindow window(options());
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    QTRY_VERIFY(inFront(window.overview()));  // the overview in front by default
    QVERIFY(!inFront(window.flightPlan()));
    QVERIFY(window.flightPlan()->loadPlan(kSamplePlan));
    QTRY_VERIFY(inFront(window.flightPlan()));
    QVERIFY(!inFront(window.overview()));
    // The plan is a page of its own: the frame log stays in view below it.
    QVERIFY(inFront(window.findChild<FrameLogView*>()));
}

// A plan file gcs --plan cannot read: the file, the line and what is wrong,
// and not the options' help, which was not what was wrong.
void TestMainWindow::refusedPlanFileSaysWhyNotHow()
{
    const QString path = m_dir.filePath(QStringLiteral("broken.plan"));
    QFile file(path);
    QVERIFY(file.open(QIODevice::WriteOnly));
    file.write(
        "{\"fileType\": \"Plan\", \"mission\": {\"items\": [\n"
        "  {\"type\": \"SimpleItem\", \"command\": 16, \"frame\": 3,\n"
        "   \"params\": [0, 0, 0, 0, 95, 0, 10]}]}}\n");
    file.close();
    QProcess gcs;
    QProcessEnvironment environment = QProcessEnvironment::systemEnvironment();
    environment.insert(QStringLiteral("QT_QPA_PLATFORM"), QStringLiteral("offscreen"));
    environment.insert(QStringLiteral("XDG_CONFIG_HOME"), m_dir.path());
    gcs.setProcessEnvironment(environment);
    QSignalSpy finished(&gcs, &QProcess::finished);
    gcs.start(QStringLiteral(RCM_BIN_DIR "/gcs"), {QStringLiteral("--plan"), path});
    QTRY_COMPARE_WITH_TIMEOUT(finished.count(), 1, kProcessTimeoutMs);
    QCOMPARE(gcs.exitCode(), 2);
    const QString said = QString::fromUtf8(gcs.readAllStandardError());
    QVERIFY2(said.contains(QStringLiteral("gcs: --plan: %1: line 2: mission item 1: latitude must be within +-90 and "
                                          "longitude within +-180 degrees\n")
                               .arg(path)),
             qPrintable(said));
    QVERIFY2(!said.contains(QStringLiteral("Usage:")) && !said.contains(QStringLiteral("--udp-remote")),
             qPrintable(said));
    QCOMPARE(gcs.readAllStandardOutput(), QByteArray());
}

void TestMainWindow::previewMarksChangedItems()
{
    CommandState command;
    CommandPreview preview;
    preview.setCommand(command.message());
    QCOMPARE(preview.changedItems(), 0);  // nothing sent yet: nothing to compare with
    QVERIFY(preview.text().contains(QStringLiteral("eng_prop_pitch 0")));
    QVERIFY(preview.hex().contains(QStringLiteral("BLOCK 1 data (223 bytes)")));
    QVERIFY(preview.hex().contains(QStringLiteral("Preamble")) == false);  // UDP by default

    preview.frameSent(41);
    QCOMPARE(preview.changedItems(), 0);
    QVERIFY(preview.text().contains(QStringLiteral("ID_msg 42")));
    QVERIFY(command.setNumber(UnitRef{rcm::UnitKind::Engine, 1}, rcm::ItemId::eng_prop_pitch, 200));
    QVERIFY(command.setNumber(UnitRef{rcm::UnitKind::Flaps, 0}, rcm::ItemId::F_rudder_set, -12));
    preview.setCommand(command.message());
    QCOMPARE(preview.changedItems(), 2);
    // The lines marked on screen are the changed items, and only they.
    auto* items = preview.findChild<QTextEdit*>(QStringLiteral("previewItems"));
    QVERIFY(items);
    const auto marked = [items] {
        QStringList lines;
        for (QTextBlock b = items->document()->begin(); b.isValid(); b = b.next())
            if (b.begin().fragment().charFormat().background().color() == QColor(0xff, 0xe0, 0x8a))
                lines << b.text().trimmed();
        return lines;
    };
    QCOMPARE(marked(), QStringList({QStringLiteral("eng_prop_pitch 200"), QStringLiteral("F_rudder_set -12")}));
    QCOMPARE(items->document()->blockCount(), preview.text().count(QLatin1Char('\n')) + 1);
    preview.frameSent(42);
    QCOMPARE(preview.changedItems(), 0);
    QCOMPARE(marked(), QStringList());
    QVERIFY(preview.text().contains(QStringLiteral("ID_msg 43")));

    preview.setDatagram(false);
    QVERIFY(preview.hex().contains(QStringLiteral("Preamble (90 bytes)")));
}

// On screen the preview follows changes once per pass of the event loop,
// and the hex dump only while its tab is the one shown.
void TestMainWindow::previewFollowsOncePerPass()
{
    CommandState command;
    CommandPreview preview;
    preview.show();
    QVERIFY(QTest::qWaitForWindowExposed(&preview));
    auto* items = preview.findChild<QTextEdit*>(QStringLiteral("previewItems"));
    auto* hex = preview.findChild<QTextEdit*>(QStringLiteral("previewBytes"));
    QVERIFY(items && hex);
    const QString hexBefore = hex->toPlainText();
    for (int id = 100; id < 110; ++id)
        preview.frameSent(quint32(id));
    QVERIFY(!items->toPlainText().contains(QStringLiteral("ID_msg 110")));  // not yet: within this pass
    QTRY_VERIFY(items->toPlainText().contains(QStringLiteral("ID_msg 110")));
    QCOMPARE(hex->toPlainText(), hexBefore);  // its tab is not shown
    preview.findChild<QTabWidget*>()->setCurrentWidget(hex);
    QVERIFY(hex->toPlainText() != hexBefore);
}

// The preview builds the next frame through the link's own send path, on
// its clock and with its key: the bytes it shows are the bytes the worker
// then sends, to the byte.
void TestMainWindow::previewShowsTheBytesTheLinkSends()
{
    // 2026-11-22 08:00:00.3 UTC: between two ticks.
    const auto clock = std::make_shared<VirtualClock>(1'795'334'400'300'000);
    std::string error;
    LinkWorker::Options options;
    options.clock = clock;
    options.secure = rcm::secure::SecureEndpoint::fromKey(
        rcm::secure::generateKey(), rcm::secure::Direction::GcsToUa, std::string(), error,
        {rcm::secure::kDefaultWindowSeconds, false, [clock] { return clock->utcMicros() / 1'000'000; }});
    QVERIFY2(options.secure, error.c_str());
    auto [near, far] = rcm::test::InProcessLink::pair(rcm::test::InProcessLink::Kind::Datagrams);
    QList<QByteArray> sent;
    connect(far.get(), &Link::datagramReceived, this, [&sent](const QByteArray& bytes) { sent << bytes; });
    far->open();
    const std::shared_ptr<const rcm::secure::SecureCodec> cipher(options.secure, options.secure->sender.get());
    LinkWorker worker(std::move(near), nullptr, options);

    CommandState command;
    CommandPreview preview;
    preview.setDatagram(true);
    preview.setCipher(cipher);
    preview.setClock([clock] { return clock->utcMicros(); });
    connect(&worker, &LinkWorker::frameSent, &preview, &CommandPreview::frameSent);
    preview.setCommand(command.message());
    preview.resetSent(options.secure->counter->peek());  // as LinkController::firstMessageId() reads it
    worker.setCommand(command.message());
    worker.start();
    const QByteArray shownFirst = preview.bytes();
    clock->advance(std::chrono::seconds(1));
    QCOMPARE(sent.size(), 1);
    QCOMPARE(sent[0].toHex(' '), shownFirst.toHex(' '));
    QVERIFY(command.setNumber(UnitRef{rcm::UnitKind::Engine, 1}, rcm::ItemId::eng_prop_pitch, 200));
    preview.setCommand(command.message());
    worker.setCommand(command.message());
    const QByteArray shown = preview.bytes();
    QCOMPARE(shown.size(), qsizetype(rcm::kDatagramSize));
    QCOMPARE(preview.changedItems(), 1);
    clock->advance(std::chrono::seconds(1));
    QCOMPARE(sent.size(), 2);
    QCOMPARE(sent[1].toHex(' '), shown.toHex(' '));
    worker.stop();
}

// Each figure is its name and its value as plain text, the value red when
// frames were beyond correction and the window's own colour when none were.
void TestMainWindow::statusFiguresNameTheirValues()
{
    StatusBarWidget status;
    LinkStatistics s;
    s.state = LinkState::Connected;
    s.framesSent = 1234;
    s.framesReceived = 1230;
    s.correctedBytesBlock1 = 40;
    s.correctedBytesBlock2 = 2;
    s.refused[std::size_t(rcm::Refusal::Uncorrectable)] = 3;
    status.setStatistics(s);
    QStringList texts;
    StatusFigure* uncorrectable = nullptr;
    for (StatusFigure* figure : status.findChildren<StatusFigure*>()) {
        texts << figure->text();
        if (figure->text().startsWith(QStringLiteral("Uncorrectable")))
            uncorrectable = figure;
    }
    for (const char* expected : {"Sent 1,234", "Received 1,230", "Corrected bytes 42", "Uncorrectable 3"})
        QVERIFY2(texts.contains(QLatin1String(expected)), qPrintable(texts.join(QStringLiteral(" | "))));
    QVERIFY(uncorrectable);
    auto* value = uncorrectable->findChildren<QLabel*>().constLast();
    QCOMPARE(value->text(), QStringLiteral("3"));
    QCOMPARE(value->textFormat(), Qt::PlainText);
    QCOMPARE(value->palette().color(QPalette::WindowText), QColor(0xb0, 0x1c, 0x1c));
    s.refused[std::size_t(rcm::Refusal::Uncorrectable)] = 0;
    status.setStatistics(s);
    QCOMPARE(uncorrectable->text(), QStringLiteral("Uncorrectable 0"));
    QCOMPARE(value->palette().color(QPalette::WindowText), status.palette().color(QPalette::WindowText));
}

void TestMainWindow::linkLostAlarm()
{
    StatusBarWidget status;
    QSignalSpy alarm(&status, &StatusBarWidget::alarm);
    status.setState(LinkState::Waiting);
    QCOMPARE(alarm.count(), 0);
    status.setState(LinkState::Lost);
    QCOMPARE(alarm.count(), 1);
    QCOMPARE(alarm.at(0).at(0).toBool(), true);
    QVERIFY(status.alarmActive());
    status.setState(LinkState::Lost);
    QCOMPARE(alarm.count(), 1);  // once per outage
    LinkStatistics back;
    back.state = LinkState::Connected;
    back.framesReceived = 7;
    back.lastGoodFrameUtcMicros = QDateTime::currentMSecsSinceEpoch() * 1000;
    status.setStatistics(back);
    QCOMPARE(alarm.count(), 2);
    QCOMPARE(alarm.at(1).at(0).toBool(), false);
    QVERIFY(status.stateText().contains(QStringLiteral("Connected")));
    QVERIFY(status.ageText().contains(QStringLiteral(" s ago")));
    // Disconnecting while lost ends the alarm too.
    status.setState(LinkState::Lost);
    status.setState(LinkState::Closed);
    QCOMPARE(alarm.count(), 4);
    QVERIFY(!status.alarmActive());
}

void TestMainWindow::linkSettingsAreKept()
{
    LinkSettings s;
    s.transport = LinkSettings::Transport::Serial;
    s.serialPort = QStringLiteral("/dev/pts/7");
    s.baudRate = 19200;
    s.remoteAddress = QStringLiteral("10.0.0.2");
    s.remotePort = 6000;
    s.keyPath = QStringLiteral("/etc/rcm/aircraft.key");
    {
        QSettings settings(m_dir.filePath(QStringLiteral("link.ini")), QSettings::IniFormat);
        s.save(settings);
    }
    const QSettings settings(m_dir.filePath(QStringLiteral("link.ini")), QSettings::IniFormat);
    QCOMPARE(LinkSettings::load(settings), s);

    LinkSettingsWidget widget;
    widget.setSettings(s);
    QCOMPARE(widget.settings(), s);

    QString error;
    QVERIFY(!LinkSettings::udpRemote(QStringLiteral("10.0.0.2"), &error));
    const auto udp = LinkSettings::udpRemote(QStringLiteral("10.0.0.2:5601"), &error);
    QVERIFY(udp);
    QCOMPARE(udp->remotePort, quint16(5601));
    LinkSettings noPort;
    noPort.transport = LinkSettings::Transport::Serial;
    QVERIFY(!noPort.createLink(&error));
    QCOMPARE(error, QStringLiteral("Choose a serial port"));
}

void TestMainWindow::replaysAFrameLog()
{
    // Twenty status frames half a second apart: ten seconds of log, one at 10x.
    const QString path = m_dir.filePath(QStringLiteral("replay.pcapng"));
    {
        FrameLog log;
        QVERIFY(log.open(path));
        rcm::Message status = rcm::restingCommand(rcm::Airframe::wellEquipped());
        for (int i = 0; i < 20; ++i) {
            status.header.set(rcm::ItemId::ID_msg, i);
            // 2026-11-22T07:32:00Z + i/2 s, as the record's time says.
            status.header.set(rcm::ItemId::time_UTC, std::int64_t(73200 + i / 2));
            status.header.set(rcm::ItemId::date_UTC, std::int64_t(261122));
            rcm::Diagnostics errors;
            const auto datagram = rcm::encodeDatagram(status, errors);
            QVERIFY(datagram);
            FrameRecord r;
            r.bytes = QByteArray(reinterpret_cast<const char*>(datagram->data()), qsizetype(datagram->size()));
            r.utcMicros = 1795332720000000 + i * 500'000;
            r.direction = FrameDirection::Received;
            r.transport = FrameTransport::Udp;
            r.status = FrameStatus::Decoded;
            r.correctedSymbols = {0, 0};
            QVERIFY(log.append(r));
        }
    }
    const auto clock = std::make_shared<VirtualClock>(1'795'334'400'000'000);
    MainWindow::Options onSimulatedTime = options();
    onSimulatedTime.clock = clock;
    MainWindow window(onSimulatedTime);
    QSignalSpy finished(&window, &MainWindow::replayFinished);
    window.setReplaySpeed(10.0);
    window.openFrameLog(path);
    // The replay's controls at once, saying what happens while the log is indexed.
    QVERIFY(!window.replayControls()->isHidden());
    QCOMPARE(window.replayControls()->timeText(), QStringLiteral("Opening the log\u2026"));
    // Indexed off the GUI thread, then shown whole.
    QTRY_COMPARE_WITH_TIMEOUT(window.frameLog()->rowCount(), 20, kLinkTimeoutMs);
    QCOMPARE(window.replayControls()->timeText().right(11), QStringLiteral(" / 00:00:09"));  // ten seconds of frames
    QCOMPARE(window.frameLog()->logPath(), path);
    QVERIFY(runReplayUntil(*clock, [&] { return finished.count() == 1; }));
    QTRY_COMPARE_WITH_TIMEOUT(window.statistics().framesReceived, quint64(20), kLinkTimeoutMs);
    QCOMPARE(window.frameLog()->playedRows(), 20);
    QCOMPARE(window.statistics().framesSent, quint64(0));  // a replay sends nothing
    // It says Replay with the log's own time, and its end raises no alarm.
    const auto plain = [](const QString& html) { return QTextDocumentFragment::fromHtml(html).toPlainText(); };
    QVERIFY2(plain(window.linkStatus()->stateText()).contains(QStringLiteral("Replay")),
             qPrintable(window.linkStatus()->stateText()));
    QCOMPARE(plain(window.linkStatus()->ageText()), QStringLiteral("Log time 2026-11-22 07:32:09 UTC"));
    QCOMPARE(window.overview()->figure(QStringLiteral("state")), QStringLiteral("Replay"));
    QCOMPARE(window.overview()->figure(QStringLiteral("age")), QStringLiteral("log 07:32:09 UTC"));
    QVERIFY(runReplayUntil(*clock, [&] { return window.statistics().state == LinkState::Lost; }));
    QVERIFY(!window.alerts()->alarm()->isActive());
    QVERIFY(!window.linkStatus()->alarmActive());
    window.disconnectLink();
    QVERIFY(!window.isLinkRunning());
}

// A log that cannot be opened says why, and takes its replay controls away.
void TestMainWindow::replayOfAMissingLogSaysWhy()
{
    MainWindow window(options());
    window.openFrameLog(m_dir.filePath(QStringLiteral("no such log.pcapng")));
    QVERIFY(!window.replayControls()->isHidden());
    QTRY_VERIFY_WITH_TIMEOUT(window.replayControls()->isHidden(), kLinkTimeoutMs);
    QVERIFY2(window.alerts()->errorBanner()->currentText().startsWith(QStringLiteral("Cannot open the frame log: ")),
             qPrintable(window.alerts()->errorBanner()->currentText()));
    QVERIFY(!window.isLinkRunning());
    QCOMPARE(window.frameLog()->rowCount(), 0);
}

void TestMainWindow::replayShowsTheLogsCommandReadOnly()
{
    // A log the link's FrameLog wrote: each second a command with the
    // rudder at 7 degrees went out, and the aircraft reported doing that.
    using rcm::ItemId;
    const UnitRef flaps{rcm::UnitKind::Flaps, 0};
    CommandState logged;
    QVERIFY(logged.setNumber(flaps, ItemId::F_rudder_set, 7));
    const QString path = m_dir.filePath(QStringLiteral("commanded.pcapng"));
    {
        FrameLog log;
        QVERIFY(log.open(path));
        for (int i = 0; i < 10; ++i) {
            for (const FrameDirection direction : {FrameDirection::Sent, FrameDirection::Received}) {
                rcm::Message message = logged.message();
                message.header.set(ItemId::ID_msg, i);
                // 2026-11-22T07:32:00Z + i s, as the record's time says: the
                // replay's receive path refuses a frame without its time.
                message.header.set(ItemId::time_UTC, std::int64_t(73200 + i));
                message.header.set(ItemId::date_UTC, std::int64_t(261122));
                rcm::Diagnostics errors;
                const auto datagram = rcm::encodeDatagram(message, errors);
                QVERIFY(datagram);
                FrameRecord r;
                r.bytes = QByteArray(reinterpret_cast<const char*>(datagram->data()), qsizetype(datagram->size()));
                r.utcMicros = 1795332720000000 + i * 1'000'000 + (direction == FrameDirection::Sent ? 0 : 100'000);
                r.direction = direction;
                r.transport = FrameTransport::Udp;
                r.status = direction == FrameDirection::Sent ? FrameStatus::NotChecked : FrameStatus::Decoded;
                QVERIFY(log.append(r));
            }
        }
    }
    const auto clock = std::make_shared<VirtualClock>(1'795'334'400'000'000);
    MainWindow::Options onSimulatedTime = options();
    onSimulatedTime.clock = clock;
    MainWindow window(onSimulatedTime);
    CommandState* command = window.command();
    const rcm::Message own = command->message();
    QCOMPARE(command->value(flaps, ItemId::F_rudder_set)->number, 0);
    QSignalSpy finished(&window, &MainWindow::replayFinished);
    window.setReplaySpeed(10.0);
    window.openFrameLog(path);
    QVERIFY(runReplayUntil(*clock, [&] { return finished.count() == 1; }));
    QTRY_COMPARE_WITH_TIMEOUT(window.reported()->statusFrames(), 10, kLinkTimeoutMs);

    // The panels show what the log commanded, and the reports agree with it.
    QCOMPARE(command->value(flaps, ItemId::F_rudder_set)->number, 7);
    QCOMPARE(window.reported()->value(flaps, ItemId::F_rudder_set)->number, 7);
    QCOMPARE(window.reported()->mismatchFrames(flaps, ItemId::F_rudder_set), 0);
    QVERIFY(window.linkStatus()->stateText().contains(QStringLiteral("<b>Replay</b>")));
    QVERIFY(window.linkStatus()->ageText().contains(QStringLiteral("2026-11-22 07:32:09 UTC")));

    // Read only: a click on a command button changes nothing.
    auto* nose = window.findChild<FieldButtonGroup*>(QStringLiteral("land_wheels.NOSE"));
    QVERIFY(nose);
    auto* retract = nose->findChild<QAbstractButton*>(QStringLiteral("RETRACTED"));
    QVERIFY(retract);
    for (int i = 0; i < window.panels()->count(); ++i)
        if (window.panels()->tabText(i) == QStringLiteral("Landing gear"))
            window.showPanel(i);
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    const rcm::Message shown = command->message();
    QTest::mouseClick(retract, Qt::LeftButton);
    QCOMPARE(command->message(), shown);
    // The flight plan page is no command of the log's: it still takes clicks.
    window.showPanel(window.panels()->indexOf(window.flightPlan()));
    QPushButton* editPlan = nullptr;
    for (QPushButton* b : window.flightPlan()->findChildren<QPushButton*>())
        if (b->text() == QStringLiteral("Edit plan"))
            editPlan = b;
    QVERIFY(editPlan);
    QTest::mouseClick(editPlan, Qt::LeftButton);
    QVERIFY(window.flightPlan()->isEditing());
    QTest::mouseClick(editPlan, Qt::LeftButton);
    QVERIFY(!window.flightPlan()->isEditing());

    // The log's silence after its end is the link's Lost, but no alarm, and
    // the reports age in the log's time: not stale.
    QVERIFY(runReplayUntil(*clock, [&] { return window.statistics().state == LinkState::Lost; }));
    QVERIFY(!window.linkStatus()->alarmActive());
    QVERIFY(window.linkStatus()->stateText().contains(QStringLiteral("<b>Replay</b>")));
    window.reported()->checkAge();
    QVERIFY(!window.reported()->stale());

    // Afterwards the console's own command, and its panels take clicks again.
    window.disconnectLink();
    QCOMPARE(command->message(), own);
    rcm::test::SeenBox retracting;  // retracting a wheel is confirmed first
    rcm::test::answerNextBox(&retracting, false);
    QTest::mouseClick(retract, Qt::LeftButton);
    QVERIFY(retracting.shown);
    QVERIFY(command->message() != own);
}

// A keyed session's log, replayed with its key: the panels show what the
// session commanded, read through the receive path for logged frames with
// the session's key; replayed without it, they show nothing of it (its
// frames are ciphertext, never read as plain).
void TestMainWindow::keyedReplayShowsWhatWasCommanded()
{
    using rcm::ItemId;
    const QString keyPath = keyFile(QStringLiteral("replayed.key"));
    std::string error;
    const std::optional<rcm::secure::SecretKey> psk = rcm::secure::readKeyFile(keyPath.toStdString(), error);
    QVERIFY2(psk, error.c_str());
    const rcm::secure::SecureCodec up(*psk, rcm::secure::Direction::GcsToUa);
    const rcm::secure::SecureCodec down(*psk, rcm::secure::Direction::UaToGcs);
    const UnitRef flaps{rcm::UnitKind::Flaps, 0};
    CommandState logged;
    QVERIFY(logged.setNumber(flaps, ItemId::F_rudder_set, 9));
    const QString path = m_dir.filePath(QStringLiteral("keyed.pcapng"));
    {
        FrameLog log;
        QVERIFY(log.open(path));
        for (int i = 0; i < 5; ++i) {
            for (const FrameDirection direction : {FrameDirection::Sent, FrameDirection::Received}) {
                rcm::Message message = logged.message();
                message.header.set(ItemId::ID_msg, 100 + i);
                message.header.set(ItemId::time_UTC, std::int64_t(73200 + i));
                message.header.set(ItemId::date_UTC, std::int64_t(261122));
                rcm::Diagnostics errors;
                const std::optional<rcm::EncodedBlocks> blocks =
                    (direction == FrameDirection::Sent ? up : down).encode(message, errors);
                QVERIFY2(blocks, errors.empty() ? "" : errors.front().toString().c_str());
                const rcm::DatagramBytes datagram = rcm::makeDatagram(blocks->block1, blocks->block2);
                FrameRecord r;
                r.bytes = QByteArray(reinterpret_cast<const char*>(datagram.data()), qsizetype(datagram.size()));
                r.utcMicros = 1795332720000000 + i * 1'000'000 + (direction == FrameDirection::Sent ? 0 : 100'000);
                r.direction = direction;
                r.transport = FrameTransport::Udp;
                r.status = direction == FrameDirection::Sent ? FrameStatus::NotChecked : FrameStatus::Decoded;
                r.enciphered = true;
                QVERIFY(log.append(r));
            }
        }
    }
    MainWindow window(options());
    CommandState* command = window.command();
    const rcm::Message own = command->message();
    QCOMPARE(command->value(flaps, ItemId::F_rudder_set)->number, 0);
    QSignalSpy finished(&window, &MainWindow::replayFinished);
    window.setReplaySpeed(10.0);

    // Without the key: ciphertext, never shown as a command.
    window.openFrameLog(path);
    QTRY_COMPARE_WITH_TIMEOUT(finished.count(), 1, kLinkTimeoutMs);
    QCOMPARE(window.session()->kind(), ConsoleSession::Kind::Replay);
    QCOMPARE(command->message(), own);
    window.disconnectLink();

    // With it: what the session commanded, and the aircraft's reports.
    window.openFrameLog(path, keyPath);
    QTRY_COMPARE_WITH_TIMEOUT(finished.count(), 2, kLinkTimeoutMs);
    QVERIFY(window.session()->logKey());
    QCOMPARE(command->value(flaps, ItemId::F_rudder_set)->number, 9);
    QCOMPARE(command->message().header.number(ItemId::ID_msg), std::int64_t(104));
    QTRY_COMPARE_WITH_TIMEOUT(window.reported()->statusFrames(), 5, kLinkTimeoutMs);
    QCOMPARE(window.reported()->value(flaps, ItemId::F_rudder_set)->number, 9);

    // Afterwards the console's own command.
    window.disconnectLink();
    QCOMPARE(command->message(), own);
}

void TestMainWindow::rehearsalAgainstUasim()
{
    QVERIFY2(QFileInfo(QStringLiteral(RCM_BIN_DIR "/uasim")).isExecutable(), "build the uasim target first");
    MainWindow window(options());
    window.show();
    QVERIFY(window.flightPlan()->loadPlan(kSamplePlan));
    window.startRehearsalWith(QStringLiteral(RCM_BIN_DIR "/uasim"));
    QTRY_VERIFY_WITH_TIMEOUT(window.isLinkRunning(), kLinkTimeoutMs);
    // Status frames come back once a second, each answering a command.
    QTRY_VERIFY_WITH_TIMEOUT(window.statistics().framesReceived >= 2, kLinkTimeoutMs);
    QTRY_VERIFY_WITH_TIMEOUT(window.linkStatus()->stateText().contains(QStringLiteral("Connected")), kLinkTimeoutMs);
    QVERIFY(window.statistics().framesSent >= 2);
    QCOMPARE(window.statistics().refusedFor(rcm::Refusal::Uncorrectable), quint64(0));
    // Both directions reach the frame log view, and the session's log file.
    QTRY_VERIFY_WITH_TIMEOUT(window.frameLog()->rowCount() >= 4, kLinkTimeoutMs);
    QVERIFY(QFileInfo::exists(window.sessionLogPath()));
    // The rows are the log file's records, one for one and in order: each row
    // reads its frame back from the file at the offset the link reported. The
    // file may be ahead by the frames still on their way to the view.
    FrameLogModel* log = window.frameLog();
    QCOMPARE(log->rowsWithBytesInMemory(), 0);
    FrameLogReader reader;
    QVERIFY2(reader.open(window.sessionLogPath()), qPrintable(reader.errorString()));
    const int rows = log->rowCount();
    QVERIFY(reader.count() >= rows);
    std::set<FrameDirection> directions;
    for (int row = 0; row < rows; ++row) {
        const FrameRecord logged = reader.recordAt(row);
        QCOMPARE(log->record(row), logged);
        QCOMPARE(logged.bytes.size(), 510);
        directions.insert(logged.direction);
        // The very frame: its ID_msg is the one the link reported for the row.
        const rcm::DecodeResult decoded = rcm::decodeFrame(std::span<const std::uint8_t>(
            reinterpret_cast<const std::uint8_t*>(logged.bytes.constData()), std::size_t(logged.bytes.size())));
        QVERIFY(log->messageId(row).has_value());
        QCOMPARE(quint32(decoded.message.header.number(rcm::ItemId::ID_msg)), *log->messageId(row));
    }
    QCOMPARE(directions.size(), std::size_t(2));

    // The sample plan goes up in BLOCK 2 and the aircraft acknowledges it,
    // once the operator commands.
    QVERIFY(rcm::test::resumeCommanding(window, kLinkTimeoutMs));
    auto* upload = window.findChild<FlightPlanUpload*>();
    QVERIFY(upload);
    window.flightPlan()->uploadPlan();
    QCOMPARE(upload->progress().state, FlightPlanUpload::State::Sending);
    QTRY_COMPARE_WITH_TIMEOUT(upload->progress().state, FlightPlanUpload::State::Acknowledged, kLinkTimeoutMs);
    QCOMPARE(upload->progress().total, 2);

    window.disconnectLink();
    QVERIFY(!window.isLinkRunning());
    QVERIFY(!window.linkStatus()->alarmActive());
}

namespace {

// A message the aircraft would send now, under `endpoint`'s key.
QByteArray statusDatagram(const rcm::secure::SecureEndpoint& endpoint, std::uint32_t id)
{
    const QDateTime now = QDateTime::currentDateTimeUtc();
    rcm::Message m;
    m.header.set(rcm::ItemId::ID_msg, std::int64_t(id));
    m.header.set(rcm::ItemId::ID_UA_source, rcm::Value::station({44, 133}));
    m.header.set(rcm::ItemId::time_UTC, std::int64_t(now.toString(QStringLiteral("hhmmss")).toInt()));
    m.header.set(rcm::ItemId::date_UTC, std::int64_t(now.toString(QStringLiteral("yyMMdd")).toInt()));
    rcm::Diagnostics errors;
    const std::optional<rcm::EncodedBlocks> blocks = endpoint.sender->encode(m, errors);
    if (!blocks)
        return {};
    const auto datagram = rcm::makeDatagram(blocks->block1, blocks->block2);
    return QByteArray(reinterpret_cast<const char*>(datagram.data()), qsizetype(datagram.size()));
}

std::shared_ptr<rcm::secure::SecureEndpoint> endpointInMemory(rcm::secure::Direction sends)
{
    std::string error;
    rcm::secure::SecureEndpoint::Options options;
    options.persistState = false;
    std::shared_ptr<rcm::secure::SecureEndpoint> endpoint =
        rcm::secure::SecureEndpoint::fromKey(rcm::secure::generateKey(), sends, std::string(), error, options);
    if (!endpoint)
        qWarning("%s", error.c_str());
    return endpoint;
}

}  // namespace

void TestMainWindow::keyedUploadUses199ByteSections()
{
    const std::shared_ptr<rcm::secure::SecureEndpoint> endpoint = endpointInMemory(rcm::secure::Direction::GcsToUa);
    QVERIFY(endpoint);
    // The frames the link would encode, with each section the uploader hands it.
    const auto encodes = [&](const rcm::FlightPlanSection& section) {
        rcm::Message m = rcm::restingCommand(rcm::Airframe::wellEquipped());
        m.header.set(rcm::ItemId::ID_msg, std::int64_t(1));
        m.header.set(rcm::ItemId::time_UTC, std::int64_t(120000));
        m.header.set(rcm::ItemId::date_UTC, std::int64_t(261122));
        m.flightPlan = section;
        rcm::Diagnostics errors;
        return endpoint->sender->encode(m, errors).has_value();
    };
    const QByteArray plan(1000, '\x5a');

    // On the plain link, 215-byte sections: one of them the keyed link cannot send.
    FlightPlanUpload plain;
    const LinkWorker::Options plainOptions = plain.linkOptions();
    QCOMPARE(plain.sectionSize(), 215);
    QVERIFY(plain.start(plan));
    const std::optional<rcm::FlightPlanSection> big = plainOptions.block2Source();
    QVERIFY(big);
    QCOMPARE(big->data.size(), std::size_t(215));
    QVERIFY(!encodes(*big));

    // Keyed: 199-byte sections, every one of which goes out, so the upload gets through the plan.
    FlightPlanUpload keyed;
    LinkWorker::Options options;
    options.secure = endpoint;
    options = keyed.linkOptions(options);
    QCOMPARE(keyed.sectionSize(), int(rcm::secure::kMaxFlightPlanData));
    QVERIFY(keyed.start(plan));
    const int total = keyed.progress().total;
    QVERIFY(total > plain.progress().total);
    for (int i = 0; i < total; ++i) {
        const std::optional<rcm::FlightPlanSection> section = options.block2Source();
        QVERIFY(section);
        QVERIFY(section->data.size() <= rcm::secure::kMaxFlightPlanData);
        QVERIFY2(encodes(*section), qPrintable(QStringLiteral("section %1").arg(i)));
        QCOMPARE(keyed.progress().sent, i + 1);
    }
    QCOMPARE(keyed.progress().state, FlightPlanUpload::State::Sending);  // every section out, awaiting the answer
}

void TestMainWindow::refusedKeyFileSaysWhy()
{
    const QString path = keyFile(QStringLiteral("shared.key"));
    QVERIFY(QFile::setPermissions(path, QFile::ReadOwner | QFile::WriteOwner | QFile::ReadGroup | QFile::ReadOther));
    MainWindow window(options());
    LinkSettings s;
    s.keyPath = path;
    QSignalSpy failed(window.session(), &ConsoleSession::failed);
    window.connectWith(s);
    QTRY_COMPARE_WITH_TIMEOUT(failed.count(), 1, kLinkTimeoutMs);
    QVERIFY(!window.isLinkRunning());
    QVERIFY(!window.session()->isActive());
    const QString message = window.linkStatus()->messageText();
    QVERIFY2(message.contains(QStringLiteral("chmod 600")), qPrintable(message));
    QVERIFY2(message.contains(QStringLiteral("shared.key")), qPrintable(message));
    // On the banner, and in the event log as the key's.
    QCOMPARE(window.alerts()->errorBanner()->currentText(), message);
    const EventLogModel* events = window.alerts()->model();
    QCOMPARE(events->event(events->rowCount() - 1).text, message);
    QCOMPARE(events->event(events->rowCount() - 1).source, EventSource::Key);
    // The rehearsal checks the key before it starts uasim.
    window.linkStatus()->showMessage(QString());
    window.linkSettings()->setSettings(s);
    window.startRehearsalWith(QStringLiteral(RCM_BIN_DIR "/uasim"));
    QTRY_COMPARE_WITH_TIMEOUT(failed.count(), 2, kLinkTimeoutMs);
    QVERIFY(!window.isLinkRunning());
    QVERIFY(window.linkStatus()->messageText().contains(QStringLiteral("chmod 600")));
}

// A serial port that does not exist and a UDP port already in use: the
// reason, word for word, on the banner and in the event log, not only stderr.
void TestMainWindow::failedOpenSaysWhy()
{
    QUdpSocket holder;
    QVERIFY(holder.bind(QHostAddress::LocalHost, 0));
    MainWindow window(options());
    LinkSettings serial;
    serial.transport = LinkSettings::Transport::Serial;
    serial.serialPort = QStringLiteral("/dev/rcm-no-such-port");
    LinkSettings udp;
    udp.localAddress = QStringLiteral("127.0.0.1");
    udp.localPort = holder.localPort();
    udp.remoteAddress = QStringLiteral("127.0.0.1");
    udp.remotePort = 9;
    const QString reasons[] = {
        QStringLiteral("/dev/rcm-no-such-port: cannot open: No such file or directory; retrying"),
        QStringLiteral("udp: cannot bind 127.0.0.1:%1: The bound address is already in use").arg(holder.localPort()),
    };
    int i = 0;
    for (const LinkSettings& s : {serial, udp}) {
        window.connectWith(s);
        QTRY_COMPARE_WITH_TIMEOUT(window.alerts()->errorBanner()->currentText(), reasons[i], kLinkTimeoutMs);
        const EventLogModel* events = window.alerts()->model();
        int found = 0;
        for (int row = 0; row < events->rowCount(); ++row)
            found += events->event(row).text == reasons[i] && events->event(row).source == EventSource::Link &&
                     events->event(row).severity == EventSeverity::Error;
        QCOMPARE(found, 1);
        ++i;
    }
    window.disconnectLink();
}

void TestMainWindow::secureRehearsalWithMatchingKeys()
{
    QVERIFY2(QFileInfo(QStringLiteral(RCM_BIN_DIR "/uasim")).isExecutable(), "build the uasim target first");
    MainWindow window(options());
    window.show();
    LinkSettings s = window.linkSettings()->settings();
    s.keyPath = keyFile(QStringLiteral("rehearsal.key"));
    window.linkSettings()->setSettings(s);
    QVERIFY(window.flightPlan()->loadPlan(kSamplePlan));
    window.startRehearsalWith(QStringLiteral(RCM_BIN_DIR "/uasim"));
    QTRY_VERIFY_WITH_TIMEOUT(window.isLinkRunning(), kLinkTimeoutMs);
    QTRY_VERIFY_WITH_TIMEOUT(window.statistics().framesReceived >= 2, kLinkTimeoutMs);
    QTRY_VERIFY_WITH_TIMEOUT(window.linkStatus()->stateText().contains(QStringLiteral("Connected")), kLinkTimeoutMs);
    QVERIFY(window.statistics().secure);
    QCOMPARE(window.linkStatus()->securityText(), QStringLiteral("encrypted and authenticated"));
    QCOMPARE(window.linkStatus()->rejectedText(), QString());
    QCOMPARE(window.statistics().refusedFor(rcm::Refusal::Forged), quint64(0));

    // The flight plan goes up in 199-byte sections and uasim acknowledges it.
    QVERIFY(rcm::test::resumeCommanding(window, kLinkTimeoutMs));
    auto* upload = window.findChild<FlightPlanUpload*>();
    QVERIFY(upload);
    QCOMPARE(upload->sectionSize(), int(rcm::secure::kMaxFlightPlanData));
    window.flightPlan()->uploadPlan();
    QTRY_COMPARE_WITH_TIMEOUT(upload->progress().state, FlightPlanUpload::State::Acknowledged, kLinkTimeoutMs);
    window.disconnectLink();
    QVERIFY(!window.isLinkRunning());
}

// Every reason the receive path refuses for, but uncorrectable (a counter
// of its own), in the order of rcm::Refusal, with its count.
void TestMainWindow::statusBarListsRefusalsByReason()
{
    StatusBarWidget bar;
    LinkStatistics s;
    s.refused[std::size_t(rcm::Refusal::Uncorrectable)] = 5;
    s.refused[std::size_t(rcm::Refusal::TimeStep)] = 2;
    s.refused[std::size_t(rcm::Refusal::WrongSize)] = 1;
    s.refused[std::size_t(rcm::Refusal::BadPadding)] = 3;
    bar.setStatistics(s);
    QCOMPARE(bar.rejectedText(),
             QStringLiteral("wrong size 1, not exact: bad padding 3, implausible: time step 2"));
}

void TestMainWindow::wrongKeyIsRejectedAsForged()
{
    // The aircraft, standing in: a bare UDP end answering the console under another key.
    UdpLink far(QHostAddress::LocalHost, 0);
    far.setReplyToSender(true);
    far.open();
    QSignalSpy farReceived(&far, &Link::datagramReceived);
    const std::shared_ptr<rcm::secure::SecureEndpoint> aircraft = endpointInMemory(rcm::secure::Direction::UaToGcs);
    QVERIFY(aircraft);

    MainWindow window(options());
    LinkSettings s;
    s.localAddress = QStringLiteral("127.0.0.1");
    s.remoteAddress = QStringLiteral("127.0.0.1");
    s.remotePort = far.boundPort();
    s.keyPath = keyFile(QStringLiteral("console.key"));
    window.connectWith(s);
    QTRY_VERIFY_WITH_TIMEOUT(farReceived.count() >= 1, kLinkTimeoutMs);
    QList<QByteArray> answers;
    for (std::uint32_t id = 1; id <= 3; ++id) {
        answers << statusDatagram(*aircraft, id);
        QCOMPARE(answers.last().size(), 510);
        QVERIFY(far.write(answers.last()));
    }
    QTRY_COMPARE_WITH_TIMEOUT(window.linkStatus()->rejectedText(), QStringLiteral("forged 3"), kLinkTimeoutMs);
    QCOMPARE(window.linkStatus()->securityText(), QStringLiteral("encrypted and authenticated"));
    QCOMPARE(window.statistics().framesReceived, quint64(0));
    QVERIFY(!window.linkStatus()->stateText().contains(QStringLiteral("Connected")));
    // Each refusal reaches the operator with its reason.
    const QString refused = window.linkStatus()->messageText();
    QVERIFY2(refused.startsWith(QStringLiteral("A frame was refused: forged")), qPrintable(refused));
    // The event log has the first whole; the two after it within the minute
    // are counted, to be told when the minute is up (RefusalDigest).
    const EventLogModel* events = window.alerts()->model();
    QStringList forged;
    for (int row = 0; row < events->rowCount(); ++row)
        if (events->event(row).text.contains(QStringLiteral("forged")))
            forged << events->event(row).text;
    QCOMPARE(forged.size(), 1);
    QVERIFY2(forged.first().startsWith(QStringLiteral("A frame was refused: forged")), qPrintable(forged.first()));
    window.alerts()->refusals()->flush();
    QVERIFY2(events->event(events->rowCount() - 1).text.startsWith(QStringLiteral("2 more frames refused as forged")),
             qPrintable(events->event(events->rowCount() - 1).text));

    // The log view has them as rejected, with the ciphertext as it arrived.
    FrameLogModel* log = window.frameLog();
    QList<QByteArray> rejected;
    QTRY_VERIFY_WITH_TIMEOUT(
        [&] {
            rejected.clear();
            for (int row = 0; row < log->rowCount(); ++row)
                if (log->status(row) == FrameStatus::Rejected)
                    rejected << log->record(row).bytes;
            return rejected.size() == 3;
        }(),
        kLinkTimeoutMs);
    QCOMPARE(rejected, answers);
    window.disconnectLink();
}

namespace {

using rcm::test::answerNextBox;

// The console connected over UDP to a bare socket standing in for the aircraft.
void connectToABareSocket(MainWindow& window, UdpLink& aircraft)
{
    aircraft.open();
    LinkSettings s;
    s.localAddress = QStringLiteral("127.0.0.1");
    s.remoteAddress = QStringLiteral("127.0.0.1");
    s.remotePort = aircraft.boundPort();
    window.connectWith(s);
}

QAction* menuAction(MainWindow& window, const QString& text)
{
    for (QAction* a : window.findChildren<QAction*>())
        if (a->text() == text)
            return a;
    return nullptr;
}

}  // namespace

void TestMainWindow::asksBeforeEndingALiveLink_data()
{
    QTest::addColumn<QString>("action");
    QTest::addColumn<QString>("asks");
    QTest::newRow("Connect") << QString() << QStringLiteral("Connect ends the live link: UDP");
    QTest::newRow("Start rehearsal") << QStringLiteral("Start &rehearsal with uasim")
                                     << QStringLiteral("Start rehearsal ends the live link: UDP");
    QTest::newRow("Open log for replay") << QStringLiteral("&Open frame log for replay\u2026")
                                         << QStringLiteral("Open log for replay ends the live link: UDP");
    QTest::newRow("Quit") << QStringLiteral("&Quit") << QStringLiteral("Quit ends the live link: UDP");
    QTest::newRow("Disconnect") << QStringLiteral("&Disconnect") << QStringLiteral("Disconnect ends the live link: UDP");
}

void TestMainWindow::asksBeforeEndingALiveLink()
{
    QFETCH(QString, action);
    QFETCH(QString, asks);
    UdpLink aircraft(QHostAddress::LocalHost, 0);
    MainWindow window(options());
    window.show();
    connectToABareSocket(window, aircraft);
    QTRY_VERIFY_WITH_TIMEOUT(window.isLinkRunning(), kLinkTimeoutMs);
    const LinkController* live = window.session()->controller();

    rcm::test::SeenBox seen;
    answerNextBox(&seen, true);
    if (action.isEmpty()) {
        window.connectLink();  // its button and menu item are disabled while connected; Ctrl+K is the slot
    } else {
        QAction* a = menuAction(window, action);
        QVERIFY(a);
        a->trigger();
    }
    QVERIFY(seen.shown);
    QVERIFY2(seen.text.startsWith(asks), qPrintable(seen.text));
    QVERIFY(seen.cancelIsDefault);
    QVERIFY(seen.cancelHasFocus);
    // Cancel keeps the link as it was, and the window.
    QCOMPARE(window.session()->controller(), live);
    QCOMPARE(window.session()->kind(), ConsoleSession::Kind::Live);
    QCOMPARE(window.session()->preparing(), ConsoleSession::Kind::None);
    QVERIFY(window.isVisible());
    window.disconnectLink();
}

void TestMainWindow::quitEndsTheLinkOnceConfirmed()
{
    UdpLink aircraft(QHostAddress::LocalHost, 0);
    MainWindow window(options());
    window.show();
    // Nothing live: no question.
    QVERIFY(window.close());
    window.show();
    connectToABareSocket(window, aircraft);
    QTRY_VERIFY_WITH_TIMEOUT(window.isLinkRunning(), kLinkTimeoutMs);
    rcm::test::SeenBox seen;
    answerNextBox(&seen, false);
    QVERIFY(window.close());
    QVERIFY(seen.shown);
    QVERIFY(!window.isVisible());
    QVERIFY(!window.session()->isActive());
}

void TestMainWindow::linkButtonsNeverHoldTheFocus()
{
    UdpLink aircraft(QHostAddress::LocalHost, 0);
    MainWindow window(options());
    window.show();
    QApplication::setActiveWindow(&window);
    QVERIFY(QTest::qWaitForWindowActive(&window));
    std::set<QString> linkButtons;
    for (QPushButton* b : window.findChildren<QPushButton*>())
        if (b->text() == QStringLiteral("Connect") || b->text() == QStringLiteral("Disconnect") ||
            b->text() == QStringLiteral("Start rehearsal"))
            linkButtons.insert(b->text());
    QCOMPARE(linkButtons.size(), std::size_t(3));
    // Clicked, a button takes no focus; Tab through the whole window never lands on one.
    auto* connect = window.findChild<QPushButton*>();
    for (QPushButton* b : window.findChildren<QPushButton*>())
        if (b->text() == QStringLiteral("Connect"))
            connect = b;
    QTest::mouseClick(connect, Qt::LeftButton);
    QTRY_VERIFY_WITH_TIMEOUT(window.isLinkRunning(), kLinkTimeoutMs);
    for (int i = 0; i < 300; ++i) {
        QWidget* focus = QApplication::focusWidget();
        auto* button = qobject_cast<QPushButton*>(focus);
        QVERIFY2(!button || !linkButtons.count(button->text()), qPrintable(button ? button->text() : QString()));
        QTest::keyClick(focus ? focus : &window, Qt::Key_Tab);
    }
    window.disconnectLink();
}

// Control moving without this station asking: on the banner and in the event
// log as an error of "control"; the header panel names the stations sent.
void TestMainWindow::controlAlarmsReachBannerAndEventLog()
{
    MainWindow window(options());
    window.stationControl()->setStationText(QStringLiteral("GB_30226"));
    StationControl* control = window.session()->stationControl();
    const auto status = [](rcm::StationId c, rcm::StationId b) {
        rcm::Message m;
        m.header.set(rcm::ItemId::ID_GCS_destination, rcm::Value::station(c));
        m.header.set(rcm::ItemId::ID_GCS_backup, rcm::Value::station(b));
        return m;
    };
    const rcm::StationId primary{44, 30226}, backup{44, 41251};
    control->statusReceived(status(primary, backup));
    const EventLogModel* events = window.alerts()->model();
    QCOMPARE(events->event(events->rowCount() - 1).text,
             QStringLiteral("The aircraft names this station in control: check what it reports, then Take control "
                            "to command it"));
    QCOMPARE(events->event(events->rowCount() - 1).source, EventSource::Control);
    // Not taken yet: the frames name this station and claim nothing.
    QCOMPARE(window.command()->message().header.find(rcm::ItemId::ID_GCS_destination)->second, 30226);
    QVERIFY(!window.command()->message().header.has(rcm::ItemId::ID_GCS_backup));
    control->takeControl();
    QCOMPARE(events->event(events->rowCount() - 1).text,
             QStringLiteral("Taking control: the next frames claim control for this station"));
    QCOMPARE(window.command()->message().header.find(rcm::ItemId::ID_GCS_backup)->second, 30226);

    control->statusReceived(status(backup, primary));
    const QString alarm = QStringLiteral(
        "Control lost: the aircraft names GB_41251 in control, and this station did not hand over");
    QCOMPARE(window.alerts()->errorBanner()->currentText(), alarm);
    QCOMPARE(events->event(events->rowCount() - 1).text, alarm);
    QCOMPARE(events->event(events->rowCount() - 1).severity, EventSeverity::Error);
    QCOMPARE(events->event(events->rowCount() - 1).source, EventSource::Control);
    // The frames now name the station in control, this one as its backup.
    QCOMPARE(window.command()->message().header.find(rcm::ItemId::ID_GCS_destination)->second, 41251);
    QCOMPARE(window.command()->message().header.find(rcm::ItemId::ID_GCS_backup)->second, 30226);
}

void TestMainWindow::aModemIsDialledAndHungUp()
{
    MainWindow window(options());
    const auto buttonTexts = [&] {
        QStringList texts;
        for (QPushButton* b : window.findChildren<QPushButton*>())
            texts << b->text();
        return texts;
    };
    QVERIFY(buttonTexts().contains(QStringLiteral("Connect")));
    LinkSettings modem = *LinkSettings::serial(QStringLiteral("/dev/ttyUSB7"), QStringLiteral("19200"));
    modem.dialNumber = QStringLiteral("881612345678");
    window.linkSettings()->setSettings(modem);
    QVERIFY2(buttonTexts().contains(QStringLiteral("Dial")), qPrintable(buttonTexts().join(',')));
    QVERIFY(!buttonTexts().contains(QStringLiteral("Connect")));
    // Kept with the link settings, as the operator set them.
    QCOMPARE(window.linkSettings()->settings().dialNumber, QStringLiteral("881612345678"));
    QCOMPARE(window.linkSettings()->settings().rtsCts, true);
    QCOMPARE(window.linkSettings()->settings().satelliteDelayMs, 1500);
    QCOMPARE(window.linkSettings()->settings().oneWayDelay(), std::chrono::milliseconds(2000));  // and a frame's airtime
    modem.dialNumber.clear();
    window.linkSettings()->setSettings(modem);
    QVERIFY(buttonTexts().contains(QStringLiteral("Connect")));
    QCOMPARE(window.linkSettings()->settings().oneWayDelay(), std::chrono::milliseconds(0));
}

// Through the satellite modem model at 1.5 s each way, to uasim --modem: a
// changed command is answered some 4 to 6 s later, and the panels do not
// call the reports in between a mismatch. The same reports compared without
// the delay would have been one.
void TestMainWindow::satelliteRoundTripIsNoMismatch()
{
    SatelliteModem::Options satellite;
    satellite.callSetupTime = std::chrono::milliseconds(200);
    satellite.oneWayDelay = std::chrono::milliseconds(1500);
    SatelliteModemThread model(satellite);
    QString error;
    QVERIFY2(model.open(&error), qPrintable(error));
    QProcess uasim;
    QByteArray said;
    connect(&uasim, &QProcess::readyReadStandardError, this, [&] { said += uasim.readAllStandardError(); });
    uasim.start(QStringLiteral(RCM_BIN_DIR "/uasim"), {QStringLiteral("--serial"), model.device(SatelliteModem::Aircraft),
                                                      QStringLiteral("--modem"), QStringLiteral("--verbose")});
    QVERIFY(uasim.waitForStarted());
    QTRY_VERIFY_WITH_TIMEOUT(said.contains("waiting for a call"), kLinkTimeoutMs);

    MainWindow window(options());
    LinkSettings modem = *LinkSettings::serial(model.device(SatelliteModem::Ground), QStringLiteral("9600"));
    modem.dialNumber = QStringLiteral("881612345678");
    modem.modemInit = QStringLiteral("ATE0V1&C1&D2S12=5");
    window.connectWith(modem);
    ReportedState* reported = window.reported();
    const UnitRef flaps{rcm::UnitKind::Flaps, 0};
    QTRY_VERIFY_WITH_TIMEOUT(reported->statusFrames() >= 2, 4 * kLinkTimeoutMs);
    QVERIFY(rcm::test::resumeCommanding(window, kLinkTimeoutMs));
    ReportedState direct(window.command());
    connect(window.session()->controller(), &LinkController::messageReceived, &direct, &ReportedState::onReceived);
    int mostDirect = 0;
    bool mismatch = false;
    connect(reported, &ReportedState::updated, this, [&] {
        mismatch = mismatch || reported->mismatchPersistent(flaps, rcm::ItemId::F_rudder_set);
        mostDirect = std::max(mostDirect, direct.mismatchFrames(flaps, rcm::ItemId::F_rudder_set));
    });
    window.command()->setNumber(flaps, rcm::ItemId::F_rudder_set, 7);
    QTRY_VERIFY_WITH_TIMEOUT(reported->value(flaps, rcm::ItemId::F_rudder_set) &&
                                 reported->value(flaps, rcm::ItemId::F_rudder_set)->number == 7,
                             4 * kLinkTimeoutMs);
    QVERIFY(!mismatch);
    QVERIFY2(mostDirect > ReportedState::kTransientFrames, qPrintable(QString::number(mostDirect)));
    window.disconnectLink();
    uasim.terminate();
    QVERIFY(uasim.waitForFinished());
}

namespace {

// The strip at the top of `dock`, which shows while it floats.
LinkStateStrip* stripOf(QDockWidget* dock)
{
    return dock ? dock->findChild<LinkStateStrip*>() : nullptr;
}

// The rows of `events` whose text is `text`.
int eventRow(const EventLogModel* events, const QString& text)
{
    for (int row = events->rowCount() - 1; row >= 0; --row)
        if (events->event(row).text == text)
            return row;
    return -1;
}

// A UDP frame log of `count` status frames half a second apart from `startMicros`.
bool writeStatusLog(const QString& path, int count, qint64 startMicros)
{
    FrameLog log;
    if (!log.open(path))
        return false;
    rcm::Message status = rcm::restingCommand(rcm::Airframe::wellEquipped());
    for (int i = 0; i < count; ++i) {
        status.header.set(rcm::ItemId::ID_msg, i);
        const QDateTime at = QDateTime::fromMSecsSinceEpoch((startMicros + i * 500'000) / 1000, Qt::UTC);
        status.header.set(rcm::ItemId::time_UTC,
                          std::int64_t(at.time().hour() * 10000 + at.time().minute() * 100 + at.time().second()));
        status.header.set(rcm::ItemId::date_UTC,
                          std::int64_t(at.date().year() % 100 * 10000 + at.date().month() * 100 + at.date().day()));
        rcm::Diagnostics errors;
        const auto datagram = rcm::encodeDatagram(status, errors);
        if (!datagram)
            return false;
        FrameRecord r;
        r.bytes = QByteArray(reinterpret_cast<const char*>(datagram->data()), qsizetype(datagram->size()));
        r.utcMicros = startMicros + i * 500'000;
        r.direction = FrameDirection::Received;
        r.transport = FrameTransport::Udp;
        r.status = FrameStatus::Decoded;
        r.correctedSymbols = {0, 0};
        if (!log.append(r))
            return false;
    }
    return true;
}

}  // namespace

// Issue 28: the Flight plan dock floated over the main window (maximised, the
// only way to a usable map) hid the LINK LOST banner. Each floating dock
// shows the link's state and the alarm itself, and the main window and the
// floating docks ask for attention (the urgency hint) as the link is lost.
void TestMainWindow::alarmShowsInFloatingDocks()
{
    MainWindow window(options());
    window.resize(1366, 768);
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    auto* logDock = window.findChild<QDockWidget*>(QStringLiteral("frameLogDock"));
    auto* events = window.findChild<QDockWidget*>(QStringLiteral("eventsDock"));
    QVERIFY(stripOf(logDock) && stripOf(events));
    // Docked, the main window's banner and status bar say it: no strip.
    QVERIFY(!stripOf(logDock)->isVisible());
    logDock->setFloating(true);
    QTRY_VERIFY(stripOf(logDock)->isVisible());
    QVERIFY(!stripOf(events)->isVisible());
    QCOMPARE(stripOf(logDock)->text(), QStringLiteral("Link: Not connected"));

    QSignalSpy attention(window.docks(), &ConsoleDocks::attentionRequested);
    ConsoleAlerts* alerts = window.alerts();
    const qint64 now = alerts->events()->now();
    LinkStatistics s;
    s.state = LinkState::Connected;
    s.framesReceived = 40;
    s.lastGoodFrameUtcMicros = now - 3'000'000;
    alerts->setStatistics(s);
    QCOMPARE(stripOf(logDock)->text(), QStringLiteral("Link: Connected"));
    QVERIFY(!stripOf(logDock)->isAlarm());
    QCOMPARE(attention.count(), 0);
    s.state = LinkState::Lost;
    alerts->setStatistics(s);
    QVERIFY(stripOf(logDock)->isAlarm());
    QCOMPARE(stripOf(logDock)->text(), QStringLiteral("LINK LOST \u2014 no frame from the aircraft for 3 s"));
    QCOMPARE(alerts->alarmBanner()->text(), stripOf(logDock)->text());
    QVERIFY(stripOf(logDock)->silenceButton()->isVisible());
    // Once, for the main window and the floating dock.
    QCOMPARE(attention.count(), 1);
    const auto windows = attention.at(0).at(0).value<QList<QWidget*>>();
    QCOMPARE(windows, (QList<QWidget*>{&window, logDock}));
    alerts->setStatistics(s);
    QCOMPARE(attention.count(), 1);
    // Silenced from the floating dock: the alarm stays, the tone stops.
    stripOf(logDock)->silenceButton()->click();
    QVERIFY(alerts->alarm()->isAcknowledged());
    QCOMPARE(stripOf(logDock)->text(), QStringLiteral("LINK LOST \u2014 no frame from the aircraft for 3 s (silenced)"));
    QVERIFY(!stripOf(logDock)->silenceButton()->isVisible());
    // Back: the strip says so, and a dock docked again hides its strip.
    s.state = LinkState::Connected;
    s.framesReceived = 41;
    s.lastGoodFrameUtcMicros = alerts->events()->now();
    alerts->setStatistics(s);
    QVERIFY(!stripOf(logDock)->isAlarm());
    QCOMPARE(stripOf(logDock)->text(), QStringLiteral("Link: Connected"));
    logDock->setFloating(false);
    QTRY_VERIFY(!stripOf(logDock)->isVisible());
}

// Without a sound card the operator hears of it at start, in the event log
// and on the banner, not first when the link is lost.
void TestMainWindow::noSoundCardIsSaidAtStart()
{
    MainWindow window(options());
    const EventLogModel* events = window.alerts()->model();
    const QString text = QStringLiteral("No sound card: the link-loss alarm will be shown but not heard");
    QCOMPARE(ConsoleAlerts::noSoundText(), text);
    const int row = eventRow(events, text);
    if (ToneAlarmSound::hasSoundCard()) {
        QCOMPARE(row, -1);
    } else {
        QVERIFY(row >= 0);
        QCOMPARE(events->event(row).severity, EventSeverity::Error);
        QCOMPARE(window.alerts()->errorBanner()->currentText(), text);
    }
    // Either way, as the check says it.
    const int before = window.alerts()->errorBanner()->count();
    QVERIFY(window.alerts()->checkSound(true));
    QCOMPARE(window.alerts()->errorBanner()->count(), before);
    QVERIFY(!window.alerts()->checkSound(false));
    QCOMPARE(window.alerts()->errorBanner()->currentText(), text);
    QCOMPARE(events->event(events->rowCount() - 1).text, text);
}

// The status bar's messages (an export, a refused frame) were never seen: the
// link's figures took the whole bar. They show among the figures now, whole
// in the room left at 1366 px, beside the link's state.
void TestMainWindow::statusBarMessagesShow()
{
    MainWindow window(options());
    window.resize(1366, 768);
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    const QString message = QStringLiteral("Exported /tmp/session-2026-11-26.csv");
    window.linkStatus()->showMessage(message, 8000);
    QCOMPARE(window.linkStatus()->messageText(), message);
    // Once, beside the state: QStatusBar's own copy would be painted over it.
    QCOMPARE(window.statusBar()->currentMessage(), QString());
    const QLabel* shown = window.linkStatus()->messageLabel();
    QVERIFY(shown->isVisible());
    // Beside the link's state, not over it.
    const QLabel* state = window.linkStatus()->stateLabel();
    QVERIFY2(!shown->geometry().intersects(state->geometry()),
             qPrintable(QStringLiteral("message at x %1, state to x %2")
                            .arg(shown->geometry().left())
                            .arg(state->geometry().right())));
    QVERIFY2(shown->width() >= shown->fontMetrics().horizontalAdvance(message),
             qPrintable(QStringLiteral("%1 px for the message").arg(shown->width())));
    QCOMPARE(window.linkStatus()->stateText().contains(QStringLiteral("Not connected")), true);
    window.linkStatus()->showMessage(QString());
    QCOMPARE(window.linkStatus()->messageText(), QString());
}

// The window's first size leaves room for the window manager's frame, so the
// status bar is on the screen at 1366x768 and 1600x1000, and the window can
// be that small.
void TestMainWindow::defaultGeometryFitsTheScreen()
{
    const QMargins frame(4, 32, 4, 4);
    QCOMPARE(WindowFit::fittingSize(QSize(1366, 768), frame), QSize(1358, 732));
    QCOMPARE(WindowFit::fittingSize(QSize(1600, 1000), frame), QSize(1592, 964));
    QCOMPARE(WindowFit::fittingSize(QSize(2560, 1440), frame), QSize(1600, 1000));
    MainWindow window(options());
    const QSize minimum = window.minimumSizeHint();
    QVERIFY2(minimum.width() <= 1358 && minimum.height() <= 732,
             qPrintable(QStringLiteral("%1x%2").arg(minimum.width()).arg(minimum.height())));
    window.resize(1358, 732);
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    QCOMPARE(window.size(), QSize(1358, 732));
    QVERIFY(window.statusBar()->isVisible());
    QCOMPARE(window.statusBar()->geometry().bottom(), window.height() - 1);
    QVERIFY(window.linkStatus()->isVisible());
    // The window's own default on this screen, inside its available area with the frame.
    const QRect available = window.screen()->availableGeometry();
    const QSize fitted = window.defaultSize();
    QVERIFY(fitted.width() <= available.width() && fitted.height() <= available.height());
}

// "Take control" on the banner went on asking after control was taken.
void TestMainWindow::controlBannerClearsOnceTaken()
{
    MainWindow window(options());
    window.stationControl()->setStationText(QStringLiteral("GB_30226"));
    StationControl* control = window.session()->stationControl();
    const auto status = [](rcm::StationId c, rcm::StationId b) {
        rcm::Message m;
        m.header.set(rcm::ItemId::ID_GCS_destination, rcm::Value::station(c));
        m.header.set(rcm::ItemId::ID_GCS_backup, rcm::Value::station(b));
        return m;
    };
    const rcm::StationId self{44, 30226}, other{44, 41251};
    control->statusReceived(status(other, self));
    QCOMPARE(control->role(), StationControl::Role::Backup);
    ErrorBanner* banner = window.alerts()->errorBanner();
    const int before = banner->count();
    control->statusReceived(status(self, other));
    const QString offer = QStringLiteral(
        "The aircraft gave control to this station (GB_41251 was in control): check what it reports, then Take "
        "control to command it");
    QCOMPARE(banner->currentText(), offer);
    QCOMPARE(banner->count(), before + 1);
    control->takeControl();
    QCOMPARE(control->role(), StationControl::Role::InControl);
    QCOMPARE(banner->count(), before);
    QVERIFY(banner->currentText() != offer);
    const EventLogModel* events = window.alerts()->model();
    QCOMPARE(events->event(events->rowCount() - 1).text,
             QStringLiteral("Off the banner, control was taken: ") + offer);
}

// A satellite call dropped and redialled: "redialling in 10 s" leaves the
// banner once frames come again, and again at Hang up; the title names the
// link and its state, never "dialling" during the call.
void TestMainWindow::redialBannerClearsWithItsCause()
{
    SatelliteModem::Options satellite;
    satellite.callSetupTime = std::chrono::milliseconds(200);
    satellite.oneWayDelay = std::chrono::milliseconds(100);
    SatelliteModemThread model(satellite);
    QString error;
    QVERIFY2(model.open(&error), qPrintable(error));
    // Before the process: what it says as its destructor ends it must not land in a string gone.
    QByteArray said;
    QProcess uasim;
    connect(&uasim, &QProcess::readyReadStandardError, this, [&] { said += uasim.readAllStandardError(); });
    uasim.start(QStringLiteral(RCM_BIN_DIR "/uasim"),
                {QStringLiteral("--serial"), model.device(SatelliteModem::Aircraft), QStringLiteral("--modem"),
                 QStringLiteral("--verbose")});
    QVERIFY(uasim.waitForStarted());
    QTRY_VERIFY_WITH_TIMEOUT(said.contains("waiting for a call"), kLinkTimeoutMs);

    MainWindow window(options());
    LinkSettings modem = *LinkSettings::serial(model.device(SatelliteModem::Ground), QStringLiteral("9600"));
    modem.dialNumber = QStringLiteral("881612345678");
    modem.modemInit = QStringLiteral("ATE0V1&C1&D2S12=5");
    window.connectWith(modem);
    QTRY_VERIFY_WITH_TIMEOUT(window.statistics().framesReceived >= 2, 4 * kLinkTimeoutMs);
    QTRY_VERIFY_WITH_TIMEOUT(window.windowTitle().endsWith(QStringLiteral(" \u2014 Connected")), kLinkTimeoutMs);
    QVERIFY2(!window.windowTitle().contains(QStringLiteral("dialling")), qPrintable(window.windowTitle()));
    QVERIFY2(window.windowTitle().contains(QStringLiteral("phone 881612345678")), qPrintable(window.windowTitle()));

    ErrorBanner* banner = window.alerts()->errorBanner();
    const auto redialShown = [&] {
        return banner->currentText().contains(QStringLiteral("; redialling in "));
    };
    const int before = banner->count();
    model.dropCall();
    QTRY_VERIFY_WITH_TIMEOUT(redialShown(), kLinkTimeoutMs);
    QVERIFY2(banner->currentText().startsWith(QStringLiteral("call dropped (")), qPrintable(banner->currentText()));
    QVERIFY2(banner->currentText().endsWith(QStringLiteral("; redialling in 10 s, attempt 2 of 6")),
             qPrintable(banner->currentText()));
    const QString dropped = banner->currentText();
    // Redialled and frames again: the banner's error is gone, the log keeps it.
    QTRY_COMPARE_WITH_TIMEOUT(banner->count(), before, 4 * kLinkTimeoutMs);
    QTRY_COMPARE_WITH_TIMEOUT(window.statistics().state, LinkState::Connected, kLinkTimeoutMs);
    const EventLogModel* events = window.alerts()->model();
    QVERIFY(eventRow(events, dropped) >= 0);
    QVERIFY(eventRow(events, QStringLiteral("Off the banner, frames from the aircraft again: ") + dropped) >= 0);
    QTRY_VERIFY_WITH_TIMEOUT(window.windowTitle().endsWith(QStringLiteral(" \u2014 Connected")), kLinkTimeoutMs);

    // Dropped again, and hung up while it waits to redial.
    model.dropCall();
    QTRY_VERIFY_WITH_TIMEOUT(redialShown(), kLinkTimeoutMs);
    window.disconnectLink();
    QCOMPARE(banner->count(), before);
    QVERIFY(!redialShown());
    QVERIFY(!window.windowTitle().contains(QStringLiteral("phone")));
    uasim.terminate();
    QVERIFY(uasim.waitForFinished());
}

// A replay shows the log's link quality on the overview's plot and hides the
// live session's events, with the panels marked read only.
void TestMainWindow::replayShowsTheLogsPlotAndEvents()
{
    const QString path = m_dir.filePath(QStringLiteral("replay-plot.pcapng"));
    const qint64 start = 1795332720000000;  // 2026-11-22T07:32:00Z
    QVERIFY(writeStatusLog(path, 20, start));
    MainWindow window(options());
    window.show();
    auto* logDock = window.findChild<QDockWidget*>(QStringLiteral("frameLogDock"));
    logDock->setFloating(true);
    const QString live = QStringLiteral("A live event, before the replay");
    window.alerts()->info(EventSource::Console, live);
    const EventLogModel* events = window.alerts()->model();
    const int liveRow = eventRow(events, live);
    EventLogView* view = window.alerts()->eventView();
    QVERIFY(!view->table()->isRowHidden(liveRow));

    QSignalSpy finished(&window, &MainWindow::replayFinished);
    window.setReplaySpeed(10.0);
    window.openFrameLog(path);
    QTRY_VERIFY_WITH_TIMEOUT(view->isReplaying(), kLinkTimeoutMs);
    QCOMPARE(view->replayNoteText(), QStringLiteral("Replay: the live session's events are hidden until the replay "
                                                    "ends; these are the replay's own"));
    QVERIFY(view->table()->isRowHidden(liveRow));
    QVERIFY(view->hiddenRows() > liveRow);
    // The replay's own events show.
    QVERIFY(!view->table()->isRowHidden(events->rowCount() - 1));
    // Once the link starts, a timer's pass after the log was indexed (isReplaying()).
    QTRY_COMPARE_WITH_TIMEOUT(stripOf(logDock)->text(), QStringLiteral("Link: replay of a frame log, read only"),
                              kLinkTimeoutMs);
    auto* note = window.findChild<QLabel*>(QStringLiteral("readOnlyNote"));
    QVERIFY(note && note->isVisible());
    QCOMPARE(note->text(), QStringLiteral("Replay: the log's commands, read only"));
    QVERIFY(note->styleSheet().contains(QStringLiteral("#1565c0")));

    QTRY_COMPARE_WITH_TIMEOUT(finished.count(), 1, kLinkTimeoutMs);
    QTRY_COMPARE_WITH_TIMEOUT(window.statistics().framesReceived, quint64(20), kLinkTimeoutMs);
    // The plot's minutes are the log's: 07:32, twenty good frames.
    const auto& minutes = window.overview()->history().minutes();
    QVERIFY(!minutes.empty());
    for (const LinkQualityHistory::Minute& m : minutes)
        QCOMPARE(m.startUtcMicros, start);
    // Counted from the first sample on, as a live link's are: not the frames before it.
    QVERIFY(minutes.back().goodFrames >= 1 && minutes.back().goodFrames <= 20);

    // Ended: the live events again, the plot empty for the next link.
    window.disconnectLink();
    QVERIFY(!view->isReplaying());
    QVERIFY(!view->table()->isRowHidden(liveRow));
    QVERIFY(window.overview()->history().minutes().empty());
    QVERIFY(!note->isVisible());
}

// Issue 28: in a rehearsal, killing uasim showed "exit code 0", stopped the
// link and put the counters back to 0. An aircraft that falls silent is a
// link loss: the link stays, the alarm goes off, the counts stay.
void TestMainWindow::deadSimulatedAircraftIsALinkLoss()
{
    QVERIFY2(QFileInfo(QStringLiteral(RCM_BIN_DIR "/uasim")).isExecutable(), "build the uasim target first");
    MainWindow window(options());
    window.startRehearsalWith(QStringLiteral(RCM_BIN_DIR "/uasim"));
    QTRY_VERIFY_WITH_TIMEOUT(window.statistics().framesReceived >= 2, kLinkTimeoutMs);
    QTRY_COMPARE_WITH_TIMEOUT(window.statistics().state, LinkState::Connected, kLinkTimeoutMs);
    const qint64 pid = window.session()->rehearsalLauncher()->processId();
    QVERIFY(pid > 0);
    QSignalSpy attention(window.docks(), &ConsoleDocks::attentionRequested);
    QCOMPARE(::kill(pid_t(pid), SIGTERM), 0);  // as `kill <uasim's pid>` from a shell
    const EventLogModel* events = window.alerts()->model();
    const QString ended = QStringLiteral("The simulated aircraft ended (uasim ended with exit code 0): the link stays "
                                         "open, and is lost as a real aircraft's would be");
    QTRY_VERIFY_WITH_TIMEOUT(eventRow(events, ended) >= 0, kLinkTimeoutMs);
    QCOMPARE(events->event(eventRow(events, ended)).severity, EventSeverity::Warning);
    QTRY_VERIFY_WITH_TIMEOUT(window.alerts()->alarm()->isActive(), kLinkTimeoutMs);
    QVERIFY(window.isLinkRunning());
    QCOMPARE(window.statistics().state, LinkState::Lost);
    QVERIFY(window.statistics().framesReceived >= 2);
    QVERIFY(window.linkStatus()->alarmActive());
    QVERIFY(window.alerts()->alarmBanner()->text().startsWith(QStringLiteral("LINK LOST \u2014 no frame from the aircraft for ")));
    QCOMPARE(attention.count(), 1);
    QVERIFY(window.windowTitle().endsWith(QStringLiteral(" \u2014 Lost")));
    window.disconnectLink();
    QVERIFY(!window.alerts()->alarm()->isActive());
}

QTEST_MAIN(TestMainWindow)
void TestMainWindow::fitsASmallScreen()
{
    MainWindow window(options());
    window.resize(1366, 768);
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    QCOMPARE(window.size(), QSize(1366, 768));

    // Every tab shows, no panel scrolls sideways, the link pane is not squeezed.
    QTabWidget* panels = window.panels();
    QVERIFY(panels->tabBar()->width() >= panels->tabBar()->sizeHint().width());
    for (int i = 0; i < panels->count(); ++i) {
        if (panels->widget(i) == window.flightPlan())
            continue;  // the plan's table of ten columns scrolls sideways beside the map, as planners' tables do
        window.showPanel(i);
        QCoreApplication::processEvents();
        for (QScrollBar* bar : panels->currentWidget()->findChildren<QScrollBar*>())
            if (bar->orientation() == Qt::Horizontal)
                QVERIFY2(!bar->isVisible(), qPrintable(panels->tabText(i)));
    }
    QVERIFY(window.linkSettings()->width() >= window.linkSettings()->minimumSizeHint().width());

    // Issue 28: the overview shows every unit at once, its cards in a grid
    // that does not scroll.
    window.showPanel(0);
    QCoreApplication::processEvents();
    OverviewPage* overview = window.overview();
    auto* cardArea = overview->findChild<QScrollArea*>();
    QVERIFY(cardArea);
    const auto cards = overview->findChildren<QGroupBox*>();
    QCOMPARE(cards.size(), 12);
    QTRY_COMPARE(cardArea->verticalScrollBar()->maximum(), 0);
    for (QGroupBox* card : cards) {
        const QRect shown(card->mapTo(cardArea->viewport(), QPoint(0, 0)), card->size());
        QVERIFY2(cardArea->viewport()->rect().contains(shown),
                 qPrintable(card->objectName() + QStringLiteral(" at %1,%2 %3x%4")
                                                     .arg(shown.x())
                                                     .arg(shown.y())
                                                     .arg(shown.width())
                                                     .arg(shown.height())));
    }

    // Each reported value right beside its control, however wide the card:
    // the control column no wider than its widest control wants.
    int rows = 0;
    for (int i = 0; i < panels->count(); ++i) {
        window.showPanel(i);
        QCoreApplication::processEvents();
        for (auto* card : panels->currentWidget()->findChildren<QGroupBox*>()) {
            auto* grid = qobject_cast<QGridLayout*>(card->layout());
            int widest = 0;
            std::vector<std::pair<QLayoutItem*, QLayoutItem*>> pairs;
            for (int row = 0; grid && row < grid->rowCount(); ++row) {
                QLayoutItem* control = grid->itemAtPosition(row, 1);
                QLayoutItem* reported = grid->itemAtPosition(row, 2);
                if (!control || !reported || control == reported || !reported->widget()->isVisible())
                    continue;
                widest = std::max(widest, control->widget()->sizeHint().width());
                pairs.emplace_back(control, reported);
            }
            for (const auto& [control, reported] : pairs) {
                ++rows;
                const int column = reported->geometry().left() - control->geometry().left();
                QVERIFY2(column < widest + 40,
                         qPrintable(QStringLiteral("%1: %2 px for %3").arg(card->title()).arg(column).arg(widest)));
            }
        }
    }
    QVERIFY2(rows > 40, qPrintable(QString::number(rows)));

    // A 2,000-character error (an airframe file deep down) wraps: the window keeps its width.
    QString path = m_dir.path();
    for (int i = 0; i < 9; ++i)
        path += QLatin1Char('/') + QString(240, QLatin1Char('d'));
    path += QStringLiteral("/airframe.json");
    QVERIFY(path.size() > 2000);
    QString error;
    QVERIFY(!window.loadAirframe(path, &error));
    QVERIFY(error.contains(path));
    QVERIFY(!window.loadAirframe(path));  // shown: the banner and the event log
    QCoreApplication::processEvents();
    QCOMPARE(window.width(), 1366);
    QVERIFY(window.sizeHint().width() <= 1366);

    // A wheel turned over the link pane scrolls; it never switches the transport.
    auto* transport = window.linkSettings()->findChild<QComboBox*>();
    QVERIFY(transport);
    const int before = transport->currentIndex();
    QWheelEvent wheel(QPointF(5, 5), transport->mapToGlobal(QPointF(5, 5)), QPoint(), QPoint(0, -120), Qt::NoButton,
                      Qt::NoModifier, Qt::NoScrollPhase, false);
    QApplication::sendEvent(transport, &wheel);
    QCOMPARE(transport->currentIndex(), before);
    // Nor any number in it: bit rate, ports, the modem's cost a minute and delay.
    const LinkSettings settings = window.linkSettings()->settings();
    for (QAbstractSpinBox* box : window.linkSettings()->findChildren<QAbstractSpinBox*>()) {
        QWheelEvent up(QPointF(5, 5), box->mapToGlobal(QPointF(5, 5)), QPoint(), QPoint(0, 120), Qt::NoButton,
                       Qt::NoModifier, Qt::NoScrollPhase, false);
        QApplication::sendEvent(box, &up);
    }
    QVERIFY(window.linkSettings()->settings() == settings);
}

void TestMainWindow::resetLayoutRestoresTheDefault()
{
    MainWindow window(options());
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    const auto layout = [&] {
        QStringList places;
        for (QDockWidget* d : window.findChildren<QDockWidget*>())
            places << QStringLiteral("%1 area %2 floating %3 visible %4")
                          .arg(d->objectName())
                          .arg(window.dockWidgetArea(d))
                          .arg(d->isFloating())
                          .arg(d->isVisible());
        return places;
    };
    const QStringList first = layout();
    // The default size, or the window's least where the screen is smaller (offscreen: 800x800).
    const QSize defaultSize = window.size();
    QCOMPARE(defaultSize, window.defaultSize().expandedTo(defaultSize));

    // Moved about, saved, as a broken layout would be.
    auto* log = window.findChild<QDockWidget*>(QStringLiteral("frameLogDock"));
    auto* link = window.findChild<QDockWidget*>(QStringLiteral("linkDock"));
    log->setFloating(true);
    window.addDockWidget(Qt::RightDockWidgetArea, link);
    window.findChild<QDockWidget*>(QStringLiteral("voiceDock"))->hide();
    window.resize(700, 500);
    QVERIFY(layout() != first);
    {
        QSettings settings;
        settings.setValue(QStringLiteral("window/state"), window.saveState());
        settings.setValue(QStringLiteral("window/geometry"), window.saveGeometry());
    }

    window.resetLayout();
    QCoreApplication::processEvents();
    QCOMPARE(layout(), first);
    // The default size again, or the least the window takes (offscreen's
    // 800 px are less than the panels need).
    QCOMPARE(window.size(), window.defaultSize().expandedTo(window.layout()->minimumSize()));
    QVERIFY(window.size().height() <= defaultSize.height());
    QSettings settings;
    QVERIFY(!settings.contains(QStringLiteral("window/state")));
    QVERIFY(!settings.contains(QStringLiteral("window/geometry")));
}

void TestMainWindow::nightThemeIsKept()
{
    {
        MainWindow window(options());
        QCOMPARE(window.theme(), Theme::Kind::Day);
        auto* night = window.findChild<QAction*>();
        for (QAction* a : window.findChildren<QAction*>())
            if (a->text() == QStringLiteral("&Night theme"))
                night = a;
        QVERIFY(night->isCheckable());
        night->trigger();
        QCOMPARE(window.theme(), Theme::Kind::Night);
        QCOMPARE(qApp->palette().color(QPalette::Window), Theme::palette(Theme::Kind::Night).color(QPalette::Window));
        window.close();  // saves the settings
    }
    MainWindow::Options restoring = options();
    restoring.restoreSettings = true;
    MainWindow again(restoring);
    QCOMPARE(again.theme(), Theme::Kind::Night);
    QCOMPARE(qApp->palette().color(QPalette::Window), Theme::palette(Theme::Kind::Night).color(QPalette::Window));
    again.setTheme(Theme::Kind::Day);
    QCOMPARE(qApp->palette().color(QPalette::Window), Theme::palette(Theme::Kind::Day).color(QPalette::Window));
    QSettings().remove(QStringLiteral("theme"));
}

#include "tst_mainwindow.moc"
