// The flight plan tab: plan files with a geofence and rally points, edits on
// the map that leave the upload alone, the warning before a long upload, the
// progress and time left, and what the aircraft (uasim, a real process) says
// it holds.

#include "codec/message/FlightPlanTransfer.h"
#include "codec/plan/PlanContents.h"
#include "link/plan/PlanFile.h"
#include "ui/look/NoteLabel.h"
#include "ui/plan/FlightPlanUpload.h"
#include "ui/plan/FlightPlanWidget.h"
#include "ui/plan/PlanMapView.h"
#include "ui/window/MainWindow.h"

#include "ResumeCommanding.h"

#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QLabel>
#include <QProgressBar>
#include <QPushButton>
#include <QRegularExpression>
#include <QSettings>
#include <QTabWidget>
#include <QSignalSpy>
#include <QSplitter>
#include <QTableWidget>
#include <QTemporaryDir>
#include <QtTest>

#include <cmath>

namespace {

const QString kSamplePlan = QStringLiteral(RCM_SOURCE_DIR "/resources/plans/sample.plan");
const QString kFencedPlan = QStringLiteral(RCM_SOURCE_DIR "/resources/plans/fenced.plan");
constexpr int kLinkTimeoutMs = 30000;

// Every section of the upload, as the link would take them for one pass.
std::vector<rcm::FlightPlanSection> onePass(FlightPlanUpload& upload)
{
    std::vector<rcm::FlightPlanSection> sections;
    const int total = upload.progress().total;
    for (int i = 0; i < total; ++i)
        if (auto s = upload.next())
            sections.push_back(*s);
    return sections;
}

// The plan bytes the aircraft would put together from `sections`.
QByteArray assembled(const std::vector<rcm::FlightPlanSection>& sections, rcm::FlightPlanAssembler& aircraft)
{
    for (const auto& s : sections) {
        const auto r = aircraft.add(s);
        if (r.kind == rcm::FlightPlanAssembler::Result::Kind::Complete)
            return QByteArray(reinterpret_cast<const char*>(r.plan.data()), qsizetype(r.plan.size()));
    }
    return {};
}

}  // namespace

class TestPlanWidget : public QObject {
    Q_OBJECT

private slots:
    void initTestCase();
    void fencedPlanSummary();
    void editsLeaveTheUploadAlone();
    void mapAndTableAgree();
    void editsFromTheMap();
    void altitudeTypedInTheTable();
    void longUploadAsksFirst();
    void progressSaysWhatIsLeft();
    void reportThatDiffersIsAnError();
    void savedPlanReadsBack();
    void fenceForbidsAWaypoint();
    void cancelledUploadIsSaid();
    void openingAnotherPlanAsksFirst();
    void fenceOnlyPlanCanBeSent();
    void strayKeysAfterAClickPressNothing();
    void aircraftReportsFenceAndRally();
    void tableSpeaksAsThePlannersDo();
    void oneSectionIsOneSection();
    void mapHasThePage();
    void uploadNeedsAPlanAndALink();

private:
    QTemporaryDir m_dir;
};

void TestPlanWidget::initTestCase()
{
    QVERIFY(m_dir.isValid());
    QCoreApplication::setOrganizationName(QStringLiteral("rcm-tests"));
    QSettings::setDefaultFormat(QSettings::IniFormat);
    QSettings::setPath(QSettings::IniFormat, QSettings::UserScope, m_dir.filePath(QStringLiteral("settings")));
}

void TestPlanWidget::fencedPlanSummary()
{
    FlightPlanUpload upload;
    FlightPlanWidget widget(&upload);
    QString error;
    QVERIFY2(widget.loadPlan(kFencedPlan, &error), qPrintable(error));
    const MissionPlan& plan = *widget.plan();
    QCOMPARE(plan.fencePolygons.size(), 1);
    QCOMPARE(plan.fencePolygons[0].vertices.size(), 4);
    QVERIFY(plan.fencePolygons[0].inclusion);
    QCOMPARE(plan.fenceCircles.size(), 1);
    QCOMPARE(plan.fenceCircles[0].radius, 250.0);
    QVERIFY(!plan.fenceCircles[0].inclusion);
    QCOMPARE(plan.rallyPoints.size(), 2);
    QCOMPARE(plan.rallyPoints[1].altitude, 80.0);
    // 322 bytes of mission, 38 of polygon, 16 of circle, 26 of rally points: format 2.
    QCOMPARE(plan.toBytes().size(), 402);
    QCOMPARE(plan.format(), 2);
    QCOMPARE(widget.summary(), QStringLiteral("9 mission items, fence 1 polygon (4 vertices) and 1 circle, 2 rally "
                                              "points, 402 bytes, 2 BLOCK 2 sections, 2 s a pass"));
    // Before an upload the bar already counts the plan's sections.
    auto* bar = widget.findChild<QProgressBar*>();
    QVERIFY(bar);
    QCOMPARE(bar->maximum(), 2);
    QCOMPARE(bar->value(), 0);

    // The sample has neither: format 1, its bytes as before.
    QVERIFY(widget.loadPlan(kSamplePlan));
    QCOMPARE(widget.plan()->format(), 1);
    QCOMPARE(widget.summary(), QStringLiteral("9 mission items, 322 bytes, 2 BLOCK 2 sections, 2 s a pass"));
}

void TestPlanWidget::editsLeaveTheUploadAlone()
{
    FlightPlanUpload upload;
    FlightPlanWidget widget(&upload);
    QVERIFY(widget.loadPlan(kSamplePlan));
    widget.setLinkReady(true);
    const QByteArray original = widget.plan()->toBytes();
    widget.uploadPlan();
    QCOMPARE(upload.progress().state, FlightPlanUpload::State::Sending);
    QVERIFY(!widget.isEdited());

    // The operator moves waypoint 1 and deletes waypoint 3 while the upload runs.
    const double before = *widget.plan()->items[1].latitude;
    widget.moveItem(1, {52.22, 0.125});
    widget.deleteItem(3);
    QVERIFY(widget.isEdited());
    QCOMPARE(*widget.plan()->items[1].latitude, 52.22);
    QCOMPARE(widget.plan()->items.size(), 8);
    QCOMPARE(widget.plan()->items[3].seq, quint16(3));
    QVERIFY(widget.plan()->toBytes() != original);
    QVERIFY(before != 52.22);

    // Every section still carries the plan as it was when Upload was pressed.
    rcm::FlightPlanAssembler aircraft;
    QCOMPARE(assembled(onePass(upload), aircraft), original);
    const auto edits = widget.findChildren<QLabel*>();
    QVERIFY(std::any_of(edits.begin(), edits.end(), [](const QLabel* l) {
        return l->text().contains(QStringLiteral("the upload in progress sends the plan as it was before"));
    }));
}

void TestPlanWidget::mapAndTableAgree()
{
    FlightPlanUpload upload;
    FlightPlanWidget widget(&upload);
    QVERIFY(widget.loadPlan(kSamplePlan));
    widget.table()->setCurrentCell(4, 0);
    QCOMPARE(widget.map()->selectedItem(), 4);
    emit widget.map()->itemSelected(6);
    QCOMPARE(widget.table()->currentRow(), 6);
    QCOMPARE(widget.map()->selectedItem(), 6);
}

void TestPlanWidget::editsFromTheMap()
{
    FlightPlanUpload upload;
    FlightPlanWidget widget(&upload);
    QVERIFY(widget.loadPlan(kSamplePlan));
    QSignalSpy problems(&widget, &FlightPlanWidget::problem);
    // After item 2 (DO_CHANGE_SPEED, no position): a waypoint at the altitude
    // and in the frame of the positioned item before it, item 1 at 120 m above home.
    widget.table()->setCurrentCell(2, 0);
    emit widget.map()->addRequested({52.2101, 0.1402});
    QCOMPARE(widget.plan()->items.size(), 10);
    const MissionItem& added = widget.plan()->items[3];
    QCOMPARE(added.seq, quint16(3));
    QCOMPARE(added.command, quint16(16));
    QCOMPARE(added.frame, quint8(3));
    QCOMPARE(*added.altitude, 120.0);
    QCOMPARE(*added.latitude, 52.2101);
    QCOMPARE(*added.longitude, 0.1402);
    QCOMPARE(widget.table()->rowCount(), 10);
    QCOMPARE(widget.table()->item(3, FlightPlanWidget::LatitudeColumn)->text(), QStringLiteral("52.2101000"));
    QCOMPARE(widget.table()->currentRow(), 3);
    QCOMPARE(widget.plan()->items[9].seq, quint16(9));

    emit widget.map()->moveRequested(3, GeoPoint{52.2111, 0.1412});
    QCOMPARE(*widget.plan()->items[3].latitude, 52.2111);
    emit widget.map()->deleteRequested(3);
    QCOMPARE(widget.plan()->items.size(), 9);
    QCOMPARE(widget.plan()->items[3].command, quint16(16));
    QCOMPARE(*widget.plan()->items[3].latitude, 52.2236903);
    // A mission item without a position cannot be moved.
    emit widget.map()->moveRequested(2, GeoPoint{52.0, 0.1});
    QVERIFY(!widget.plan()->items[2].latitude || *widget.plan()->items[2].latitude == 0);
    QCOMPARE(problems.count(), 0);
}

void TestPlanWidget::altitudeTypedInTheTable()
{
    FlightPlanUpload upload;
    FlightPlanWidget widget(&upload);
    QVERIFY(widget.loadPlan(kSamplePlan));
    QSignalSpy problems(&widget, &FlightPlanWidget::problem);
    // Not while editing is off: a double-click on the table changes nothing.
    QVERIFY(!widget.isEditing());
    QVERIFY(!(widget.table()->item(4, FlightPlanWidget::AltitudeColumn)->flags() & Qt::ItemIsEditable));
    widget.setEditing(true);
    QTableWidgetItem* altitude = widget.table()->item(4, FlightPlanWidget::AltitudeColumn);
    QVERIFY(altitude->flags() & Qt::ItemIsEditable);
    // Nothing else in the row is.
    QVERIFY(!(widget.table()->item(4, FlightPlanWidget::LatitudeColumn)->flags() & Qt::ItemIsEditable));
    QVERIFY(!(widget.table()->item(2, FlightPlanWidget::AltitudeColumn)->flags() & Qt::ItemIsEditable));
    altitude->setText(QStringLiteral("135.5"));
    QCOMPARE(*widget.plan()->items[4].altitude, 135.5);
    QVERIFY(widget.isEdited());
    widget.table()->item(4, FlightPlanWidget::AltitudeColumn)->setText(QStringLiteral("12o"));
    QCOMPARE(*widget.plan()->items[4].altitude, 135.5);
    QCOMPARE(problems.count(), 1);
    QCOMPARE(problems.at(0).at(0).toString(),
             QStringLiteral("Mission item 5: altitude \"12o\" is not a number of metres from -500 to 20000; it "
                            "stays 135.5 m"));
    QCOMPARE(widget.table()->item(4, FlightPlanWidget::AltitudeColumn)->text(), QStringLiteral("135.5"));
}

void TestPlanWidget::longUploadAsksFirst()
{
    // 10,000 waypoints: 340,016 bytes, 1,582 sections of 215 bytes.
    QJsonArray items;
    for (int i = 0; i < 10000; ++i)
        items.append(
            QJsonObject{{QStringLiteral("type"), QStringLiteral("SimpleItem")},
                        {QStringLiteral("command"), 16},
                        {QStringLiteral("frame"), 3},
                        {QStringLiteral("autoContinue"), true},
                        {QStringLiteral("params"), QJsonArray{0, 0, 0, QJsonValue(), 52.0 + i * 1e-5, 0.1, 100}}});
    const QJsonObject root{{QStringLiteral("fileType"), QStringLiteral("Plan")},
                           {QStringLiteral("version"), 1},
                           {QStringLiteral("mission"), QJsonObject{{QStringLiteral("items"), items}}}};
    const QString path = m_dir.filePath(QStringLiteral("long.plan"));
    QFile file(path);
    QVERIFY(file.open(QIODevice::WriteOnly));
    file.write(QJsonDocument(root).toJson());
    file.close();

    FlightPlanUpload upload;
    FlightPlanWidget widget(&upload);
    QString error;
    QVERIFY2(widget.loadPlan(path, &error), qPrintable(error));
    QVERIFY(widget.summary().endsWith(QStringLiteral("340016 bytes, 1582 BLOCK 2 sections, 26 min 22 s a pass")));
    widget.setLinkReady(true);
    QStringList asked;
    bool answer = false;
    widget.setConfirm([&](const QString& text, const QString&) {
        asked << text;
        return answer;
    });
    widget.uploadPlan();
    QCOMPARE(asked.size(), 1);
    QCOMPARE(asked[0], QStringLiteral("This plan is 1582 BLOCK 2 sections: one pass takes about 26 min 22 s at 1.0 s "
                                      "a section, and up to 2 h 12 min if frames are lost and all 5 passes are "
                                      "needed. Upload it?"));
    QCOMPARE(upload.progress().state, FlightPlanUpload::State::Idle);
    answer = true;
    widget.uploadPlan();
    QCOMPARE(asked.size(), 2);
    QCOMPARE(upload.progress().state, FlightPlanUpload::State::Sending);
    QCOMPARE(upload.progress().total, 1582);

    // A short plan goes without a question.
    upload.cancel();
    QVERIFY(widget.loadPlan(kSamplePlan));
    widget.uploadPlan();
    QCOMPARE(asked.size(), 2);
    QCOMPARE(upload.progress().state, FlightPlanUpload::State::Sending);
}

void TestPlanWidget::progressSaysWhatIsLeft()
{
    FlightPlanUpload upload;
    FlightPlanWidget widget(&upload);
    QVERIFY(widget.loadPlan(kSamplePlan));
    widget.setLinkReady(true);
    widget.uploadPlan();
    QCOMPARE(widget.uploadState(), QStringLiteral("Flight plan %1: waiting for the next frame")
                                       .arg(QString::fromStdString(rcm::planIdText(upload.progress().planId))));
    QVERIFY(upload.next());
    QCOMPARE(widget.uploadState(),
             QStringLiteral("Pass 1 of 5: 1 of 2 sections, 1 s left in this pass (a section a frame)"));
    auto* bar = widget.findChild<QProgressBar*>();
    QCOMPARE(bar->maximum(), 2);
    QCOMPARE(bar->value(), 1);
    QVERIFY(upload.next());
    QCOMPARE(widget.uploadState(), QStringLiteral("Pass 1 of 5 sent: waiting for the aircraft's acknowledgement"));
    QVERIFY(upload.next());
    QVERIFY(widget.uploadState().startsWith(QStringLiteral("Pass 2 of 5: 1 of 2 sections, ")));
    QVERIFY(upload.progress().rateMeasured);  // measured from the frames, no longer the nominal rate
    QVERIFY(widget.uploadState().contains(QStringLiteral(" s a section)")));
}

void TestPlanWidget::reportThatDiffersIsAnError()
{
    FlightPlanUpload upload;
    FlightPlanWidget widget(&upload);
    QVERIFY(widget.loadPlan(kFencedPlan));
    widget.setLinkReady(true);
    QSignalSpy problems(&widget, &FlightPlanWidget::problem);
    QSignalSpy messages(&widget, &FlightPlanWidget::message);
    widget.show();
    QVERIFY(QTest::qWaitForWindowExposed(&widget));
    const int width = widget.minimumSizeHint().width();

    widget.uploadPlan();
    rcm::FlightPlanAssembler aircraft;
    QVERIFY(!assembled(onePass(upload), aircraft).isEmpty());
    rcm::FlightPlanAcknowledgement ack = *aircraft.lastComplete();
    // An aircraft that lost a rally point on the way says so.
    rcm::plan::Report held{2, 9, 1, 4, 1, 1};
    ack.report = held.toBytes();
    upload.handleReply(ack.toSection());
    QCOMPARE(upload.progress().state, FlightPlanUpload::State::Acknowledged);
    QCOMPARE(problems.count(), 1);
    QCOMPARE(problems.at(0).at(0).toString(),
             QStringLiteral("The aircraft acknowledged the flight plan but holds 9 mission items, fence 1 polygon (4 "
                            "vertices) and 1 circle, 1 rally point; 9 mission items, fence 1 polygon (4 vertices) and "
                            "1 circle, 2 rally points were sent"));
    // A long state wraps; it never widens the tab (and so the window).
    QCoreApplication::sendPostedEvents(nullptr, QEvent::LayoutRequest);
    QCOMPARE(widget.minimumSizeHint().width(), width);

    // One that says nothing of a format 2 plan may have dropped the fence.
    widget.uploadPlan();
    rcm::FlightPlanAssembler older;
    QVERIFY(!assembled(onePass(upload), older).isEmpty());
    upload.handleReply(older.lastComplete()->toSection());
    QCOMPARE(problems.count(), 2);
    QVERIFY(problems.at(1).at(0).toString().contains(QStringLiteral("did not say it holds the geofence")));

    // The same report as sent: acknowledged, and said.
    widget.uploadPlan();
    rcm::FlightPlanAssembler right;
    QVERIFY(!assembled(onePass(upload), right).isEmpty());
    ack = *right.lastComplete();
    ack.report = rcm::plan::Report{2, 9, 1, 4, 1, 2}.toBytes();
    upload.handleReply(ack.toSection());
    QCOMPARE(problems.count(), 2);
    QCOMPARE(messages.constLast().at(0).toString(),
             QStringLiteral("Flight plan acknowledged by the aircraft: it holds 9 mission items, fence 1 polygon (4 "
                            "vertices) and 1 circle, 2 rally points"));
}

void TestPlanWidget::savedPlanReadsBack()
{
    FlightPlanUpload upload;
    FlightPlanWidget widget(&upload);
    QVERIFY(widget.loadPlan(kFencedPlan));
    widget.moveItem(4, {52.219, 0.171});
    const QString path = m_dir.filePath(QStringLiteral("saved.plan"));
    QString error;
    QVERIFY2(widget.savePlan(path, &error), qPrintable(error));
    const auto back = PlanFile::load(path, &error);
    QVERIFY2(back, qPrintable(error));
    QCOMPARE(back->toBytes(), widget.plan()->toBytes());
    QCOMPARE(*back->items[4].latitude, 52.219);
    QCOMPARE(back->rallyPoints.size(), 2);
}

void TestPlanWidget::fenceForbidsAWaypoint()
{
    FlightPlanUpload upload;
    FlightPlanWidget widget(&upload);
    QVERIFY(widget.loadPlan(kFencedPlan));
    widget.setLinkReady(true);
    QVERIFY(widget.plan()->fenceViolations().isEmpty());
    // Into the exclusion circle (250 m about 52.2105 N 0.1560 E), and out of the square.
    widget.moveItem(4, {52.2110, 0.1565});
    widget.moveItem(3, {52.2300, 0.1468});
    QCOMPARE(widget.plan()->fenceViolations(),
             (QStringList{QStringLiteral("mission item 4 is outside every inclusion area"),
                          QStringLiteral("mission item 5 is inside exclusion circle 1")}));
    QStringList asked;
    widget.setConfirm([&](const QString& text, const QString&) {
        asked << text;
        return false;
    });
    widget.uploadPlan();
    QCOMPARE(asked, QStringList{QStringLiteral("The plan's own fence forbids where it goes: mission item 4 is outside "
                                               "every inclusion area; mission item 5 is inside exclusion circle 1. "
                                               "Upload it anyway?")});
    QCOMPARE(upload.progress().state, FlightPlanUpload::State::Idle);
    auto* fenceNote = widget.findChild<NoteLabel*>(QStringLiteral("planEdits"));
    QVERIFY(fenceNote);
    QCOMPARE(fenceNote->note(), QStringLiteral("Fence: mission item 4 is outside every inclusion area; mission item 5 "
                                               "is inside exclusion circle 1"));
    QCOMPARE(fenceNote->severity(), SeverityColours::Severity::Error);

    // 0 N 0 E is "no position" (Mission Planner writes it for DO_LAND_START): not on the map, not a violation.
    MissionItem land;
    land.command = 189;
    land.frame = 0;
    land.latitude = 0.0;
    land.longitude = 0.0;
    QVERIFY(!land.hasPosition());
}

void TestPlanWidget::cancelledUploadIsSaid()
{
    FlightPlanUpload upload;
    FlightPlanWidget widget(&upload);
    QVERIFY(widget.loadPlan(kSamplePlan));
    widget.setLinkReady(true);
    QSignalSpy messages(&widget, &FlightPlanWidget::message);
    widget.uploadPlan();
    QVERIFY(messages.constLast().at(0).toString().startsWith(QStringLiteral("Uploading flight plan ")));
    QVERIFY(upload.next());
    widget.cancelUpload();
    QCOMPARE(upload.progress().state, FlightPlanUpload::State::Cancelled);
    QCOMPARE(messages.constLast().at(0).toString(),
             QStringLiteral("Flight plan upload cancelled: the aircraft holds the plan it last acknowledged"));
    const auto labels = widget.findChildren<QLabel*>();
    QVERIFY(std::any_of(labels.begin(), labels.end(), [](const QLabel* l) {
        return l->text().contains(QStringLiteral("Not on the aircraft: the upload did not finish"));
    }));
}

void TestPlanWidget::openingAnotherPlanAsksFirst()
{
    FlightPlanUpload upload;
    FlightPlanWidget widget(&upload);
    QVERIFY(widget.loadPlan(kSamplePlan));
    widget.setEditing(true);
    widget.moveItem(1, {52.22, 0.125});
    QStringList asked;
    bool answer = false;
    widget.setConfirm([&](const QString& text, const QString&) {
        asked << text;
        return answer;
    });
    QString error;
    QVERIFY(!widget.loadPlan(kFencedPlan, &error));
    QCOMPARE(asked, QStringList{QStringLiteral("The plan shown has edits that are neither uploaded nor saved. Open "
                                               "fenced.plan and drop them?")});
    QCOMPARE(*widget.plan()->items[1].latitude, 52.22);
    answer = true;
    QVERIFY(widget.loadPlan(kFencedPlan, &error));
    QCOMPARE(widget.plan()->rallyPoints.size(), 2);
    // Editing is off again for the plan just opened.
    QVERIFY(!widget.isEditing());
    QVERIFY(!widget.map()->isEditable());
    // Nothing to ask about an unedited plan.
    QVERIFY(widget.loadPlan(kSamplePlan));
    QCOMPARE(asked.size(), 2);
}

void TestPlanWidget::fenceOnlyPlanCanBeSent()
{
    FlightPlanUpload upload;
    FlightPlanWidget widget(&upload);
    QString error;
    QVERIFY2(widget.loadPlan(QStringLiteral(RCM_SOURCE_DIR "/tests/data/plans/ce_geofence_rd_2.plan"), &error),
             qPrintable(error));
    QVERIFY(widget.plan()->items.isEmpty());
    QVERIFY(widget.plan()->hasFence());
    widget.setLinkReady(true);
    widget.uploadPlan();
    QCOMPARE(upload.progress().state, FlightPlanUpload::State::Sending);
}

void TestPlanWidget::strayKeysAfterAClickPressNothing()
{
    FlightPlanUpload upload;
    FlightPlanWidget widget(&upload);
    QVERIFY(widget.loadPlan(kSamplePlan));
    widget.setLinkReady(true);
    widget.show();
    QVERIFY(QTest::qWaitForWindowExposed(&widget));
    widget.activateWindow();
    QPushButton* send = nullptr;
    QPushButton* cancel = nullptr;
    QPushButton* edit = nullptr;
    for (QPushButton* b : widget.findChildren<QPushButton*>()) {
        if (b->text() == QStringLiteral("Upload to aircraft"))
            send = b;
        else if (b->text() == QStringLiteral("Cancel upload"))
            cancel = b;
        else if (b->text() == QStringLiteral("Edit plan"))
            edit = b;
    }
    QVERIFY(send && cancel && edit);
    widget.table()->setFocus();

    // Edit plan, clicked on and off: Space and Enter afterwards switch nothing.
    QTest::mouseClick(edit, Qt::LeftButton);
    QVERIFY(widget.isEditing());
    QTest::mouseClick(edit, Qt::LeftButton);
    QVERIFY(!widget.isEditing());
    QVERIFY(QApplication::focusWidget() != edit);
    QTest::keyClick(QApplication::focusWidget(), Qt::Key_Space);
    QTest::keyClick(QApplication::focusWidget(), Qt::Key_Return);
    QVERIFY(!widget.isEditing());

    // Upload, then Cancel: a Space after each starts or cancels nothing more.
    QTest::mouseClick(send, Qt::LeftButton);
    QCOMPARE(upload.progress().state, FlightPlanUpload::State::Sending);
    QTest::mouseClick(cancel, Qt::LeftButton);
    QCOMPARE(upload.progress().state, FlightPlanUpload::State::Cancelled);
    QVERIFY(QApplication::focusWidget() != send && QApplication::focusWidget() != cancel);
    QTest::keyClick(QApplication::focusWidget(), Qt::Key_Space);
    QCOMPARE(upload.progress().state, FlightPlanUpload::State::Cancelled);
    QCOMPARE(widget.plan()->toBytes(), PlanFile::load(kSamplePlan)->toBytes());
}

void TestPlanWidget::aircraftReportsFenceAndRally()
{
    QVERIFY2(QFileInfo(QStringLiteral(RCM_BIN_DIR "/uasim")).isExecutable(), "build the uasim target first");
    MainWindow::Options options;
    options.restoreSettings = false;
    options.frameLogDirectory = m_dir.filePath(QStringLiteral("framelogs"));
    MainWindow window(options);
    window.show();
    QVERIFY(window.flightPlan()->loadPlan(kFencedPlan));
    window.startRehearsalWith(QStringLiteral(RCM_BIN_DIR "/uasim"));
    QTRY_VERIFY_WITH_TIMEOUT(window.isLinkRunning(), kLinkTimeoutMs);
    QVERIFY(rcm::test::resumeCommanding(window, kLinkTimeoutMs));
    auto* upload = window.findChild<FlightPlanUpload*>();
    QVERIFY(upload);
    QSignalSpy problems(window.flightPlan(), &FlightPlanWidget::problem);
    window.flightPlan()->uploadPlan();
    QTRY_COMPARE_WITH_TIMEOUT(upload->progress().state, FlightPlanUpload::State::Acknowledged, kLinkTimeoutMs);
    QCOMPARE(upload->progress().report.toHex(), QByteArray("0200090001000400010002"));
    // The widget hears of it through the queued signal from the link thread.
    QTRY_VERIFY_WITH_TIMEOUT(
        window.flightPlan()->uploadState().contains(
            QStringLiteral("it holds 9 mission items, fence 1 polygon (4 vertices) and 1 circle, 2 rally points")),
        kLinkTimeoutMs);
    QCOMPARE(problems.count(), 0);
    window.disconnectLink();
}

// Items numbered from 1, commands by Mission Planner's names, a dash where a
// command has no position (RETURN_TO_LAUNCH, a TAKEOFF written at 0, 0) or
// no altitude.
void TestPlanWidget::tableSpeaksAsThePlannersDo()
{
    QTemporaryDir dir;
    const QString path = dir.filePath(QStringLiteral("mp.waypoints"));
    QFile file(path);
    QVERIFY(file.open(QIODevice::WriteOnly));
    file.write(
        "QGC WPL 110\n"
        "0\t1\t0\t16\t0\t0\t0\t0\t52.2076813\t0.1155201\t14.2\t1\n"
        "1\t0\t3\t22\t15\t0\t0\t0\t0\t0\t60\t1\n"
        "2\t0\t3\t16\t0\t0\t0\t0\t52.2151260\t0.1302118\t120\t1\n"
        "3\t0\t2\t205\t-45\t0\t90\t0\t0\t0\t0\t1\n"
        "4\t0\t3\t20\t0\t0\t0\t0\t0\t0\t0\t1\n");
    file.close();
    FlightPlanUpload upload;
    FlightPlanWidget widget(&upload);
    QString error;
    QVERIFY2(widget.loadPlan(path, &error), qPrintable(error));
    const auto row = [&](int r) {
        QStringList cells;
        for (int c = 0; c <= FlightPlanWidget::AltitudeColumn; ++c)
            cells << widget.table()->item(r, c)->text();
        return cells.join(QLatin1Char('|'));
    };
    QCOMPARE(row(0), QStringLiteral("1|TAKEOFF|above home|\u2014|\u2014|60.0"));
    QCOMPARE(row(1), QStringLiteral("2|WAYPOINT|above home|52.2151260|0.1302118|120.0"));
    QCOMPARE(row(2), QStringLiteral("3|DO_MOUNT_CONTROL|mission|\u2014|\u2014|\u2014"));
    QCOMPARE(row(3), QStringLiteral("4|RETURN_TO_LAUNCH|above home|\u2014|\u2014|\u2014"));
    QCOMPARE(widget.table()->item(2, FlightPlanWidget::CommandColumn)->toolTip(),
             QStringLiteral("MAV_CMD_DO_MOUNT_CONTROL (205)"));
    QCOMPARE(widget.table()->item(2, FlightPlanWidget::Param1Column)->text(), QStringLiteral("-45"));
    // The takeoff's altitude is the one field of its position that can be edited.
    widget.setEditing(true);
    QVERIFY(widget.table()->item(0, FlightPlanWidget::AltitudeColumn)->flags() & Qt::ItemIsEditable);
    QVERIFY(!(widget.table()->item(3, FlightPlanWidget::AltitudeColumn)->flags() & Qt::ItemIsEditable));
}

// "1 BLOCK 2 section", "0 of 1 section", and the plan ID one way (0x%08X)
// in the event log's lines and beside the progress bar.
void TestPlanWidget::oneSectionIsOneSection()
{
    QTemporaryDir dir;
    const QString path = dir.filePath(QStringLiteral("one.waypoints"));
    QFile file(path);
    QVERIFY(file.open(QIODevice::WriteOnly));
    file.write("QGC WPL 110\n1\t0\t3\t16\t0\t0\t0\t0\t52.2151260\t0.1302118\t120\t1\n");
    file.close();
    FlightPlanUpload upload;
    FlightPlanWidget widget(&upload);
    QSignalSpy messages(&widget, &FlightPlanWidget::message);
    QVERIFY(widget.loadPlan(path));
    QCOMPARE(widget.summary(), QStringLiteral("1 mission item, 50 bytes, 1 BLOCK 2 section, 1 s a pass"));
    auto* bar = widget.findChild<QProgressBar*>();
    QCOMPARE(bar->text(), QStringLiteral("0 of 1 section"));
    widget.setLinkReady(true);
    widget.uploadPlan();
    const QString id = QString::fromStdString(rcm::planIdText(upload.progress().planId));
    QVERIFY2(QRegularExpression(QStringLiteral("^0x[0-9A-F]{8}$")).match(id).hasMatch(), qPrintable(id));
    QCOMPARE(messages.constLast().at(0).toString(),
             QStringLiteral("Uploading flight plan %1 (one.waypoints): 1 BLOCK 2 section").arg(id));
    QCOMPARE(widget.uploadState(), QStringLiteral("Flight plan %1: waiting for the next frame").arg(id));
    QVERIFY(upload.next());
    QCOMPARE(widget.uploadState(), QStringLiteral("Pass 1 of 5 sent: waiting for the aircraft's acknowledgement"));
    QCOMPARE(bar->text(), QStringLiteral("1 of 1 section"));
}

QTEST_MAIN(TestPlanWidget)
#include "tst_planwidget.moc"

// Issue 28: at 1366x768 the plan is a page of the window's middle, its map
// takes most of the page with the table beside it in a splitter, and a
// refused plan's long message keeps to its two lines (whole in the tool tip):
// the map keeps its size.
void TestPlanWidget::mapHasThePage()
{
    MainWindow::Options options;
    options.restoreSettings = false;
    options.frameLogDirectory = m_dir.filePath(QStringLiteral("framelogs"));
    MainWindow window(options);
    window.resize(1366, 768);
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    FlightPlanWidget* widget = window.flightPlan();
    QVERIFY(widget->loadPlan(kSamplePlan));
    QCOMPARE(window.panels()->currentWidget(), widget);
    auto* split = widget->findChild<QSplitter*>(QStringLiteral("planSplitter"));
    QVERIFY(split);
    QCOMPARE(split->orientation(), Qt::Horizontal);
    QCOMPARE(split->indexOf(widget->table()), 1);
    PlanMapView* map = widget->map();
    QTRY_VERIFY(map->isVisible());
    // About 375x170 when the plan was a dock under the panels.
    QVERIFY2(map->width() >= 560 && map->height() >= 280,
             qPrintable(QStringLiteral("%1x%2").arg(map->width()).arg(map->height())));
    QVERIFY(map->width() > widget->table()->width());
    window.close();

    // The page on its own (the window's error banner above the tabs takes its height from every page alike).
    FlightPlanUpload upload;
    FlightPlanWidget page(&upload);
    page.resize(1080, 480);
    page.show();
    QVERIFY(QTest::qWaitForWindowExposed(&page));
    QVERIFY(page.loadPlan(kSamplePlan));
    QCoreApplication::processEvents();
    map = page.map();
    widget = &page;
    const QSize before = map->size();

    const QString refused = m_dir.filePath(QStringLiteral("a-plan-file-whose-name-is-long-enough-to-wrap-twice-over-"
                                                          "in-the-state-line-of-the-flight-plan-page.plan"));
    QFile file(refused);
    QVERIFY(file.open(QIODevice::WriteOnly));
    file.write("{ this is not JSON at all, and the message that says so names the whole path }");
    file.close();
    QString error;
    QVERIFY(!widget->loadPlan(refused, &error));
    QVERIFY(error.size() > 120);
    auto* state = widget->findChild<NoteLabel*>(QStringLiteral("planState"));
    QVERIFY(state);
    QCOMPARE(state->note(), error);
    QCOMPARE(state->severity(), SeverityColours::Severity::Error);
    QTRY_VERIFY(state->isCut());
    QCOMPARE(state->toolTip(), error);
    QVERIFY(state->text().contains(QStringLiteral("\u2026")));
    QCoreApplication::processEvents();
    QVERIFY2(map->size() == before, qPrintable(QStringLiteral("%1x%2 then %3x%4, table %5")
                                                  .arg(before.width())
                                                  .arg(before.height())
                                                  .arg(map->width())
                                                  .arg(map->height())
                                                  .arg(widget->table()->width())));
}

// Upload is offered only with a plan that holds something and a link that can send it.
void TestPlanWidget::uploadNeedsAPlanAndALink()
{
    FlightPlanUpload upload;
    FlightPlanWidget widget(&upload);
    QPushButton* send = nullptr;
    for (QPushButton* b : widget.findChildren<QPushButton*>())
        if (b->text() == QStringLiteral("Upload to aircraft"))
            send = b;
    QVERIFY(send);
    QVERIFY(!send->isEnabled());
    QCOMPARE(send->toolTip(), QStringLiteral("Open a plan and connect a link first"));
    widget.setLinkReady(true);
    QVERIFY(!send->isEnabled());
    QCOMPARE(send->toolTip(), QStringLiteral("Open a plan first"));
    QVERIFY(widget.loadPlan(kSamplePlan));
    QVERIFY(send->isEnabled());
    QCOMPARE(send->toolTip(),
             QStringLiteral("Send the plan in BLOCK 2 sections, one per frame, until the aircraft acknowledges it"));
    widget.setLinkReady(false);
    QVERIFY(!send->isEnabled());
    QCOMPARE(send->toolTip(), QStringLiteral("Connect a link first"));
}
