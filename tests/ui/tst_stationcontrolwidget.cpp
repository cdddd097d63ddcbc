// The link pane's control part (ui/control/StationControlWidget.h): what it
// shows for each role, that Hand over and Take control ask first with Cancel
// as the default and hold no focus, and that a mistyped station is refused
// with its reason. The aircraft's side is tst_control, the whole story
// tst_stations.
#include "AnswerBox.h"
#include "codec/message/ItemTable.h"
#include "link/session/StationControl.h"
#include "ui/control/StationControlWidget.h"

#include <QLabel>
#include <QLineEdit>
#include <QPushButton>
#include <QSignalSpy>
#include <QTest>
#include <QVBoxLayout>

using namespace rcm;
using Role = StationControl::Role;
using test::answerNextBox;
using test::SeenBox;

namespace {

const StationId kPrimary{44, 30226};
const StationId kBackup{44, 41251};

Message status(StationId control, StationId backup)
{
    Message m;
    m.header.set(ItemId::ID_GCS_destination, Value::station(control));
    m.header.set(ItemId::ID_GCS_backup, Value::station(backup));
    return m;
}

}  // namespace

class TestStationControlWidget : public QObject {
    Q_OBJECT

private slots:
    // Neither button ever takes the focus (as Connect and Disconnect), so a
    // stray Space or Enter after a click cannot press it again.
    void withoutAStationNothingShows()
    {
        StationControl control;
        StationControlWidget widget(&control);
        widget.show();
        QVERIFY(!widget.roleLabel()->isVisible());
        QVERIFY(!widget.handOverButton()->isEnabled());
        QVERIFY(!widget.takeControlButton()->isEnabled());
        QCOMPARE(widget.handOverButton()->focusPolicy(), Qt::NoFocus);
        QCOMPARE(widget.takeControlButton()->focusPolicy(), Qt::NoFocus);
    }

    void aMistypedStationIsRefused()
    {
        StationControl control;
        StationControlWidget widget(&control);
        QSignalSpy refused(&widget, &StationControlWidget::stationRefused);
        widget.setStationText(QStringLiteral("GB_30226"));
        QCOMPARE(control.station(), std::optional<StationId>(kPrimary));
        widget.setStationText(QStringLiteral("GB 41251"));
        QCOMPARE(refused.count(), 1);
        QCOMPARE(refused.at(0).at(0).toString(),
                 QStringLiteral("This station: expected a station COUNTRY_UNIT such as GB_133, got 'GB 41251'"));
        // The station stays what it was.
        QCOMPARE(control.station(), std::optional<StationId>(kPrimary));
        widget.setStationText(QString());
        QCOMPARE(control.station(), std::nullopt);
    }

    void handOverAsksAndCancelKeepsControl()
    {
        StationControl control;
        StationControlWidget widget(&control);
        widget.show();
        widget.setStationText(QStringLiteral("GB_30226"));
        control.statusReceived(status(kPrimary, kBackup));
        control.takeControl();
        QCOMPARE(widget.roleLabel()->text(), QStringLiteral("GB_30226: in control, backup GB_41251"));
        QVERIFY(widget.handOverButton()->isEnabled());
        QVERIFY(!widget.takeControlButton()->isEnabled());

        SeenBox seen;
        answerNextBox(&seen, true);
        widget.handOverButton()->click();
        QVERIFY(seen.shown);
        QCOMPARE(seen.text, QStringLiteral("Hand control of the aircraft to GB_41251?"));
        QVERIFY(seen.cancelIsDefault);
        QVERIFY(seen.cancelHasFocus);
        QCOMPARE(control.role(), Role::InControl);

        answerNextBox(&seen, false);
        widget.handOverButton()->click();
        QCOMPARE(control.role(), Role::HandingOver);
        QCOMPARE(widget.roleLabel()->text(), QStringLiteral("GB_30226: handing over to GB_41251"));
        QVERIFY(!widget.handOverButton()->isEnabled());
    }

    // Take control resumes commanding: the console asks where it holds the
    // command (CommandHoldBar, tst_mainwindow), so the button only asks for it.
    void takeControlOnlyWhenGivenControl()
    {
        StationControl control;
        StationControlWidget widget(&control);
        widget.show();
        QSignalSpy requested(&widget, &StationControlWidget::takeControlRequested);
        widget.setStationText(QStringLiteral("GB_41251"));
        control.statusReceived(status(kPrimary, kBackup));
        QCOMPARE(widget.roleLabel()->text(), QStringLiteral("GB_41251: backup, GB_30226 in control"));
        QVERIFY(!widget.takeControlButton()->isEnabled());

        control.statusReceived(status(kBackup, kPrimary));  // failover
        QCOMPARE(widget.roleLabel()->text(),
                 QStringLiteral("GB_41251: given control, not taken: Take control to command"));
        QVERIFY(widget.takeControlButton()->isEnabled());

        widget.takeControlButton()->click();
        QCOMPARE(requested.count(), 1);
        QCOMPARE(control.role(), Role::Offered);  // nothing taken by the click alone

        control.takeControl();
        QCOMPARE(control.role(), Role::InControl);
        QVERIFY(!widget.takeControlButton()->isEnabled());
    }

    // Typed and left without Enter (GB_30 of GB_30226): not applied, the
    // field shows the station in force again and says so.
    void stationAppliedOnEnterOnly()
    {
        StationControl control;
        QWidget window;
        auto* widget = new StationControlWidget(&control, &window);
        auto* elsewhere = new QLineEdit(&window);
        auto* layout = new QVBoxLayout(&window);
        layout->addWidget(widget);
        layout->addWidget(elsewhere);
        window.show();
        window.activateWindow();
        QVERIFY(QTest::qWaitForWindowActive(&window));
        widget->setStationText(QStringLiteral("GB_30226"));
        auto* field = widget->findChild<QLineEdit*>();
        field->setFocus();
        field->selectAll();
        QTest::keyClicks(field, QStringLiteral("GB_30"));
        elsewhere->setFocus();
        QTRY_VERIFY(!field->hasFocus());
        QCOMPARE(control.station(), std::optional<StationId>(kPrimary));
        QCOMPARE(field->text(), QStringLiteral("GB_30226"));
        QCOMPARE(field->toolTip(),
                 QStringLiteral("Not applied: 'GB_30' was left without Enter; this station stays GB_30226"));

        field->setFocus();
        field->selectAll();
        QTest::keyClicks(field, QStringLiteral("GB_41251"));
        QTest::keyClick(field, Qt::Key_Return);
        QCOMPARE(control.station(), std::optional<StationId>(kBackup));
    }

    void stationNotEditableWhileALinkRuns()
    {
        StationControl control;
        StationControlWidget widget(&control);
        widget.setStationEditable(false);
        QVERIFY(!widget.findChild<QLineEdit*>()->isEnabled());
        widget.setStationEditable(true);
        QVERIFY(widget.findChild<QLineEdit*>()->isEnabled());
    }
};

QTEST_MAIN(TestStationControlWidget)
#include "tst_stationcontrolwidget.moc"
