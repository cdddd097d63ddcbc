// The console's side of issue 24, in the window, against the real uasim:
// the amber band that says the command is held and why, the one confirmed
// action that resumes (listing what the panels would change), another
// airframe on a live link (asked for, carried over unit by unit, the units
// left said), the next-frame preview of a held frame, and a row in the
// event log for every change of the command with its confirmation. Every
// wait is QSignalSpy or QTRY_*; the timeouts only bound a broken build.

#include "AnswerBox.h"

#include "codec/message/Airframe.h"
#include "codec/message/CommandChanges.h"
#include "link/airframe/AirframeLoader.h"
#include "link/session/ConsoleSession.h"
#include "ui/alerts/ConsoleAlerts.h"
#include "ui/control/CommandHoldBar.h"
#include "ui/eventlog/EventLogModel.h"
#include "ui/panels/CommandJournal.h"
#include "ui/panels/CommandState.h"
#include "ui/window/MainWindow.h"

#include <QPushButton>
#include <QSettings>
#include <QSignalSpy>
#include <QTemporaryDir>
#include <QTest>

using namespace rcm;
using test::answerNextBox;
using test::SeenBox;

namespace {

constexpr int kPatienceMs = 30000;
const QString kUasim = QStringLiteral(RCM_BIN_DIR "/uasim");
const UnitRef kEngine1{UnitKind::Engine, 0};
const UnitRef kFlaps{UnitKind::Flaps, 0};

QStringList eventTexts(const MainWindow& window, EventSource source)
{
    QStringList texts;
    const EventLogModel* model = window.alerts()->model();
    for (int row = 0; row < model->rowCount(); ++row)
        if (model->event(row).source == source)
            texts << model->event(row).text;
    return texts;
}

bool anyStartsWith(const QStringList& texts, const QString& start)
{
    return std::any_of(texts.begin(), texts.end(), [&](const QString& t) { return t.startsWith(start); });
}

}  // namespace

class TestCommandIntent : public QObject {
    Q_OBJECT

private slots:
    void initTestCase()
    {
        QVERIFY(m_dir.isValid());
        QVERIFY2(QFileInfo(kUasim).isExecutable(), "build the uasim target first");
        QCoreApplication::setOrganizationName(QStringLiteral("rcm-test-commandintent"));
        QSettings().clear();
    }

    // Started: held, the band says so and why, the report comes into the
    // panels; Resume asks, listing what the panels would change; Cancel
    // leaves it held, the action resumes.
    void heldUntilTheOperatorResumes()
    {
        MainWindow window(options());
        window.show();
        // Panels the operator set before the link: engine 1 at 50 %.
        QVERIFY(window.command()->setNumber(kEngine1, ItemId::eng_prop_pitch, 128));
        window.startRehearsalWith(kUasim);
        QTRY_VERIFY_WITH_TIMEOUT(window.isLinkRunning(), kPatienceMs);
        CommandHoldBar* bar = window.commandHold();
        QTRY_VERIFY_WITH_TIMEOUT(bar->isVisible(), kPatienceMs);
        QVERIFY(bar->text().startsWith(QStringLiteral("Commands held: a new link.")));
        QCOMPARE(bar->resumeButton()->text(), QStringLiteral("Resume commanding\u2026"));
        QCOMPARE(bar->resumeButton()->focusPolicy(), Qt::NoFocus);

        // The aircraft's report, engine 1 at rest, replaces the panels' 50 %.
        QTRY_VERIFY_WITH_TIMEOUT(window.session()->commandHold()->reportHeard(), kPatienceMs);
        QCOMPARE(window.command()->value(kEngine1, ItemId::eng_prop_pitch)->number, 0);
        QVERIFY2(bar->text().contains(QStringLiteral("Engine 1, Propeller pitch: was 50.2 %, the aircraft reports 0.0 %")),
                 qPrintable(bar->text()));
        QVERIFY(anyStartsWith(eventTexts(window, EventSource::Command),
                              QStringLiteral("The aircraft's report is in the panels: 1 item(s) differed")));

        // Changed meanwhile: not sent, and the question says what would change.
        QVERIFY(window.command()->setNumber(kFlaps, ItemId::F_elev_set, 4));
        SeenBox seen;
        answerNextBox(&seen, true);
        bar->resumeButton()->click();
        QVERIFY(seen.shown);
        QVERIFY(seen.cancelIsDefault);
        QCOMPARE(seen.text, QStringLiteral("Command the aircraft from this console's panels again?"));
        QVERIFY2(seen.informativeText.contains(QStringLiteral("They differ from its report in 1 item(s):\n"
                                                              "Flaps, Elevator: the aircraft reports 0\u00b0, the "
                                                              "panels say 4\u00b0")),
                 qPrintable(seen.informativeText));
        QVERIFY(!window.session()->commanding());
        QVERIFY(bar->isVisible());

        answerNextBox(&seen, false);
        bar->resumeButton()->click();
        QVERIFY(window.session()->commanding());
        QVERIFY(!bar->isVisible());
        QVERIFY(anyStartsWith(eventTexts(window, EventSource::Command), QStringLiteral("Commanding resumed")));
        // The change made while held goes out and is confirmed.
        QTRY_VERIFY_WITH_TIMEOUT(
            anyStartsWith(eventTexts(window, EventSource::Command),
                          QStringLiteral("Command confirmed: Flaps, Elevator 4\u00b0, sent in frame ")),
            kPatienceMs);
    }

    // Each change of the command: one row when made (station, unit, item,
    // old -> new), one when the aircraft's report confirms it.
    void everyChangeIsInTheEventLog()
    {
        MainWindow window(options());
        window.show();
        window.startRehearsalWith(kUasim);
        QTRY_VERIFY_WITH_TIMEOUT(window.session()->commandHold()->reportHeard(), kPatienceMs);
        SeenBox seen;
        answerNextBox(&seen, false);
        window.commandHold()->resumeButton()->click();
        QVERIFY(window.session()->commanding());

        QVERIFY(window.command()->setNumber(kEngine1, ItemId::eng_prop_pitch, 64));
        QVERIFY(window.command()->setFieldCode({UnitKind::Settings, 0}, ItemId::lights, 2, code::kOn));
        const QStringList made = eventTexts(window, EventSource::Command);
        QVERIFY(made.contains(QStringLiteral("Command changed: Engine 1, Propeller pitch: 0.0 % -> 25.1 %")));
        QVERIFY(made.contains(QStringLiteral("Command changed: Settings, Lights and wheel brake, Tail light: Off -> On")));
        QTRY_COMPARE_WITH_TIMEOUT(window.findChild<CommandJournal*>()->pending(), 0, kPatienceMs);
        const QStringList all = eventTexts(window, EventSource::Command);
        QVERIFY(anyStartsWith(all, QStringLiteral("Command confirmed: Engine 1, Propeller pitch 25.1 %, sent in frame ")));
        QVERIFY(anyStartsWith(all,
                              QStringLiteral("Command confirmed: Settings, Lights and wheel brake, Tail light On, sent "
                                             "in frame ")));
    }

    // File > Airframe on a live link asks; Cancel changes nothing. Loaded, the
    // command's engine 1 keeps its values, the engines and cameras the
    // trainer lacks are said, and the command is held until resumed.
    void airframeChangeAsksAndCarriesOver()
    {
        MainWindow window(options());
        window.show();
        window.startRehearsalWith(kUasim);
        QTRY_VERIFY_WITH_TIMEOUT(window.session()->commandHold()->reportHeard(), kPatienceMs);
        SeenBox seen;
        answerNextBox(&seen, false);
        window.commandHold()->resumeButton()->click();
        QVERIFY(window.session()->commanding());
        QVERIFY(window.command()->setNumber(kEngine1, ItemId::eng_prop_pitch, 2));  // 0.8 %
        const Message before = window.command()->message();

        const QString trainer = QStringLiteral(":/airframes/single-engine.json");
        answerNextBox(&seen, true);
        window.requestAirframe(trainer);
        QVERIFY(seen.shown);
        QCOMPARE(seen.text, QStringLiteral("Load the airframe Single-engine trainer while the link is live?"));
        QVERIFY2(seen.informativeText.contains(
                     QStringLiteral("Not in this airframe, so no longer commanded: Engine 2, Engine 3, Radio VHF2, "
                                    "Radio VHF3, Sense and avoid, Camera NIK 1, Camera NIK 2")),
                 qPrintable(seen.informativeText));
        QCOMPARE(window.command()->message(), before);
        QVERIFY(window.session()->commanding());

        answerNextBox(&seen, false);
        window.requestAirframe(trainer);
        QCOMPARE(window.command()->airframe().name, std::string("Single-engine trainer"));
        QCOMPARE(window.command()->value(kEngine1, ItemId::eng_prop_pitch)->number, 2);
        QVERIFY(!window.session()->commanding());
        QCOMPARE(window.session()->commandHold()->reason(), CommandHold::Reason::Airframe);
        const QStringList console = eventTexts(window, EventSource::Console);
        QVERIFY(console.contains(QStringLiteral("Not in airframe Single-engine trainer, so no longer commanded: Engine "
                                                "2, Engine 3, Radio VHF2, Radio VHF3, Sense and avoid, Camera NIK 1, "
                                                "Camera NIK 2")));
        QTRY_VERIFY_WITH_TIMEOUT(window.session()->commandHold()->reportHeard(), kPatienceMs);
        // The aircraft still has its three engines: the band says so.
        QVERIFY2(window.commandHold()->text().contains(QStringLiteral("Engine 2, Propeller pitch: was nothing")),
                 qPrintable(window.commandHold()->text()));
    }

private:
    MainWindow::Options options() const
    {
        MainWindow::Options o;
        o.restoreSettings = false;
        o.frameLogDirectory = m_dir.path();
        return o;
    }
    QTemporaryDir m_dir;
};

QTEST_MAIN(TestCommandIntent)
#include "tst_commandintent.moc"
