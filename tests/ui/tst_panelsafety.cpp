// The command panels' hazards, one test each: a slip of the hand (the mouse
// wheel, a stray key, a half-typed value or station ID) must not change what
// the aircraft is told, and reported values must not look current once the
// status frames stop. Every check compares the BLOCK 1 bytes the encoder
// makes of the command, byte for byte: what would go out in the next frame.
// Time is a clock the test moves; no test waits on a real one.

#include "codec/message/Airframe.h"
#include "codec/message/MessageEncoder.h"
#include "link/session/LinkWorker.h"
#include "ui/panels/CameraPanel.h"
#include "ui/panels/CommandGate.h"
#include "ui/panels/CommandState.h"
#include "ui/panels/EnginePanel.h"
#include "ui/panels/FieldButtonGroup.h"
#include "ui/panels/FieldComboBox.h"
#include "ui/panels/FlapsPanel.h"
#include "ui/panels/FuelDumpPanel.h"
#include "ui/panels/GearPanel.h"
#include "ui/panels/HeaderPanel.h"
#include "ui/panels/ItemSlider.h"
#include "ui/panels/ItemSpinBox.h"
#include "ui/panels/LightsPanel.h"
#include "ui/panels/RadioPanel.h"
#include "ui/panels/ReportedLabel.h"
#include "ui/panels/ReportedState.h"
#include "ui/panels/StationEditor.h"
#include "ui/window/Theme.h"

#include <QAbstractButton>
#include <QApplication>
#include <QLineEdit>
#include <QPushButton>
#include <QScrollArea>
#include <QScrollBar>
#include <QStyle>
#include <QSignalSpy>
#include <QTest>
#include <QVBoxLayout>
#include <QWheelEvent>

#include <chrono>
#include <memory>

using namespace rcm;
using enum ItemId;

namespace {

// BLOCK 1 as the encoder makes it of the command (ID_msg, time and date as the link would stamp them).
QByteArray block1(const Message& command)
{
    Message stamped = command;
    stamped.header.set(ID_msg, 7);
    stamped.header.set(time_UTC, 120000);
    stamped.header.set(date_UTC, 260514);
    Diagnostics errors;
    const auto blocks = encodeBlocks(stamped, errors);
    if (!blocks)
        return QByteArray("does not encode");
    return QByteArray(reinterpret_cast<const char*>(blocks->block1.data()), qsizetype(blocks->block1.size()));
}

// A wheel turned over the middle of `widget`. Returns whether the widget
// took it: one that does not, QApplication hands to its parent, and so on up
// to the scroll area around the panel, which scrolls. (QtTest cannot make the
// window system's spontaneous event, the only kind QApplication passes up.)
bool turnWheel(QWidget* widget, QPoint angleDelta)
{
    const QPointF at = QPointF(widget->rect().center());
    QWheelEvent event(at, QPointF(widget->mapToGlobal(at.toPoint())), QPoint(), angleDelta, Qt::NoButton,
                      Qt::NoModifier, Qt::NoScrollPhase, false);
    QApplication::sendEvent(widget, &event);
    return event.isAccepted();
}

// Every command panel of the main window, one under the other in a scroll
// area smaller than they are, as the operator sees them in their tabs.
struct AllPanels {
    explicit AllPanels(CommandState* command, ReportedState* reported)
    {
        auto* content = new QWidget;
        auto* layout = new QVBoxLayout(content);
        layout->addWidget(new HeaderPanel(command, reported));
        layout->addWidget(new EnginePanel(command, reported));
        layout->addWidget(new FlapsPanel(command, reported));
        layout->addWidget(new GearPanel(command, reported));
        layout->addWidget(new LightsPanel(command, reported));
        layout->addWidget(new FuelDumpPanel(command, reported));
        layout->addWidget(new RadioPanel(command, reported));
        layout->addWidget(new CameraPanel(command, reported));
        area.setWidget(content);
        area.setWidgetResizable(true);
        area.resize(900, 400);
        area.show();
    }
    template <typename T>
    QList<T*> all() const
    {
        return area.widget()->findChildren<T*>();
    }
    // Every widget an operator changes the command with.
    QList<QWidget*> commandControls() const
    {
        QList<QWidget*> controls;
        for (auto* w : all<ItemSpinBox>())
            controls << w;
        for (auto* w : all<ItemSlider>())
            controls << w;
        for (auto* w : all<FieldComboBox>())
            controls << w;
        for (auto* w : all<StationEditor>())
            controls << w->countryEdit() << w->unitEdit();
        for (auto* group : all<FieldButtonGroup>())
            for (auto* w : group->findChildren<QAbstractButton*>())
                controls << w;
        for (auto* w : area.widget()->findChildren<QPushButton*>(QStringLiteral("take_one_photo")))
            controls << w;
        return controls;
    }
    QScrollArea area;
};

class TestPanelSafety : public QObject {
    Q_OBJECT

private:
    CommandState m_command;
    ReportedState m_reported{&m_command};
    int m_asked = 0;  // large changes the panels asked about, all confirmed

    // The window focus can move in: key focus and focus-out need an active window.
    static bool activate(QWidget* window)
    {
        window->activateWindow();
        return QTest::qWaitForWindowActive(window);
    }

private slots:
    void init()
    {
        m_command.setAirframe(Airframe::wellEquipped());
        m_command.editUnit({UnitKind::Header, 0}, [](Unit& header) {
            header = Unit(UnitKind::Header);
            header.set(ID_UA_source, Value::station({44, 133}));
        });
        m_reported.clear();
        m_asked = 0;
        CommandGate::of(&m_command)->setAsker([this](const Confirmation&, QWidget*) {
            ++m_asked;
            return true;
        });
    }

    void cleanup() { CommandGate::of(&m_command)->setAsker({}); }

    // Issue 11: scrolling over Flaps set the right aileron to -6 degrees,
    // over Engines it changed a carburettor setting and a master/slave mode.
    void wheelOverEveryControlChangesNothing()
    {
        AllPanels panels(&m_command, &m_reported);
        QVERIFY(QTest::qWaitForWindowExposed(&panels.area));
        // Not an empty test: the well-equipped airframe's controls are all there.
        QCOMPARE(panels.all<ItemSlider>().size(), 6);
        QCOMPARE(panels.all<ItemSpinBox>().size(), 6 + 3 * 2 + 3 * 3 + 3 + 2 * 3);
        QCOMPARE(panels.all<FieldComboBox>().size(), 3 * 2 + 2);
        QCOMPARE(panels.all<StationEditor>().size(), 3 + 2 * 2);
        QCOMPARE(panels.all<FieldButtonGroup>().size(), 4 + 4 + 4 + 2 * 3);

        const QByteArray before = block1(m_command.message());
        QSignalSpy changed(&m_command, &CommandState::changed);
        int turned = 0;
        for (QWidget* widget : panels.all<QWidget>()) {
            if (!widget->isVisible())
                continue;
            for (const QPoint delta :
                 {QPoint(0, 120), QPoint(0, -120), QPoint(0, -360), QPoint(120, 0), QPoint(-240, 0), QPoint(0, 15)})
                turnWheel(widget, delta);
            ++turned;
        }
        QCOMPARE_GT(turned, 200);
        QCOMPARE(changed.count(), 0);
        QCOMPARE(block1(m_command.message()), before);
        for (ItemSpinBox* spinBox : panels.all<ItemSpinBox>())
            QVERIFY2(!spinBox->edited(), qPrintable(spinBox->objectName()));  // not even the shown text moved
    }

    // The wheel is left to the scroll area: every command control, and every
    // part of one (a spin box's line edit), leaves the event unaccepted.
    void wheelIsLeftToTheScrollArea()
    {
        AllPanels panels(&m_command, &m_reported);
        QVERIFY(QTest::qWaitForWindowExposed(&panels.area));
        const QList<QWidget*> controls = panels.commandControls();
        QCOMPARE(controls.size(), 30 + 6 + 8 + 7 * 2 + 18 * 2 + 2);
        for (QWidget* control : controls)
            for (QWidget* w : QList<QWidget*>{control} + control->findChildren<QWidget*>())
                for (const QPoint delta : {QPoint(0, 120), QPoint(0, -120), QPoint(120, 0)})
                    QVERIFY2(!turnWheel(w, delta), qPrintable(control->objectName()));

        // And the area does scroll with an event nobody below it took.
        QScrollBar* scroll = panels.area.verticalScrollBar();
        QCOMPARE_GT(scroll->maximum(), 0);
        QCOMPARE(scroll->value(), 0);
        QVERIFY(turnWheel(panels.area.viewport(), QPoint(0, -120)));
        QCOMPARE_GT(scroll->value(), 0);
    }

    void commandControlsNeverTakeFocusFromTheWheel()
    {
        AllPanels panels(&m_command, &m_reported);
        // Tab and clicks, never the wheel: a slider too, whose arrow keys are single steps.
        for (QWidget* w : panels.commandControls())
            QVERIFY2(w->focusPolicy() == Qt::StrongFocus, qPrintable(w->objectName()));
    }

    // A key pressed by mistake on a focused control: nothing goes out.
    void strayKeysChangeNothing()
    {
        AllPanels panels(&m_command, &m_reported);
        QVERIFY(activate(&panels.area));
        const QByteArray before = block1(m_command.message());
        QSignalSpy changed(&m_command, &CommandState::changed);
        const Qt::Key moves[] = {Qt::Key_Up,       Qt::Key_Down, Qt::Key_Left, Qt::Key_Right, Qt::Key_PageUp,
                                 Qt::Key_PageDown, Qt::Key_Home, Qt::Key_End,  Qt::Key_R,     Qt::Key_G};
        for (FieldComboBox* combo : panels.all<FieldComboBox>()) {
            combo->setFocus();
            for (Qt::Key key : moves)
                QTest::keyClick(combo, key);
        }
        // A slider's arrow key is a deliberate single step (tst_commandcontrols); no other key moves it.
        for (ItemSlider* slider : panels.all<ItemSlider>()) {
            slider->setFocus();
            for (Qt::Key key : moves)
                if (key != Qt::Key_Up && key != Qt::Key_Down && key != Qt::Key_Left && key != Qt::Key_Right)
                    QTest::keyClick(slider, key);
        }
        for (FieldButtonGroup* group : panels.all<FieldButtonGroup>()) {
            for (QAbstractButton* button : group->findChildren<QAbstractButton*>()) {
                button->setFocus();
                for (Qt::Key key : {Qt::Key_Up, Qt::Key_Down, Qt::Key_Left, Qt::Key_Right})
                    QTest::keyClick(button, key);
            }
        }
        QCOMPARE(changed.count(), 0);
        QCOMPARE(block1(m_command.message()), before);

        // An arrow key in a spin box steps the text, marked as not sent; Esc takes it back.
        auto* carb = panels.area.widget()->findChild<ItemSpinBox*>(QStringLiteral("eng_carb_SET"));
        carb->setFocus();
        QTest::keyClick(carb, Qt::Key_Up);
        QCOMPARE(carb->text(), QStringLiteral("0.4 %"));
        QVERIFY(carb->edited());
        QVERIFY(carb->toolTip().startsWith(QStringLiteral("Not sent yet")));
        QCOMPARE(block1(m_command.message()), before);
        QTest::keyClick(carb, Qt::Key_Escape);
        QVERIFY(!carb->edited());
        QCOMPARE(carb->text(), QStringLiteral("0.0 %"));
        QCOMPARE(block1(m_command.message()), before);

        // Deliberate input still works: Space on a button, a choice from the list.
        auto* wheels = panels.area.widget()->findChild<FieldButtonGroup*>(QStringLiteral("land_wheels.NOSE"));
        wheels->button(2)->setFocus();
        QTest::keyClick(wheels->button(2), Qt::Key_Space);
        QCOMPARE(m_asked, 1);  // retracting is confirmed first
        QCOMPARE(m_command.fieldCode({UnitKind::Settings, 0}, land_wheels, 2), 2u);
    }

    void spinBoxSendsOnlyCompleteValidValues()
    {
        AllPanels panels(&m_command, &m_reported);
        QVERIFY(activate(&panels.area));
        auto* rx = panels.area.widget()->findChild<ItemSpinBox*>(QStringLiteral("Rx_freq"));
        auto* tx = panels.area.widget()->findChild<ItemSpinBox*>(QStringLiteral("Tx_freq"));
        const UnitRef vhf1{UnitKind::Radio, 0};
        const QByteArray before = block1(m_command.message());
        QSignalSpy changed(&m_command, &CommandState::changed);

        // Partial: marked invalid, Enter leaves it on show, nothing sent.
        rx->setFocus();
        QTest::keyClick(rx, Qt::Key_A, Qt::ControlModifier);
        QTest::keyClicks(rx, QStringLiteral("127."));
        QVERIFY(!rx->invalid());  // "127." is 127.000 MHz: complete
        QVERIFY(rx->edited());
        QTest::keyClick(rx, Qt::Key_A, Qt::ControlModifier);
        QTest::keyClicks(rx, QStringLiteral("-"));
        QVERIFY(rx->invalid());
        QVERIFY2(rx->toolTip().contains(QStringLiteral("not sent")), qPrintable(rx->toolTip()));
        QTest::keyClick(rx, Qt::Key_Enter);
        QVERIFY(rx->invalid());
        QCOMPARE(rx->text(), QStringLiteral("- MHz"));
        // More decimals than the wire carries (kHz): not a value, not sent.
        QTest::keyClick(rx, Qt::Key_A, Qt::ControlModifier);
        QTest::keyClicks(rx, QStringLiteral("127.7125"));
        QVERIFY(rx->invalid());
        QTest::keyClick(rx, Qt::Key_Enter);
        QCOMPARE(changed.count(), 0);
        // Leaving the field with it: the command's value comes back.
        tx->setFocus();
        QTRY_VERIFY(!rx->hasFocus());
        QVERIFY(!rx->invalid());
        QCOMPARE(rx->text(), QStringLiteral("0.000 MHz"));
        QCOMPARE(changed.count(), 0);
        QCOMPARE(block1(m_command.message()), before);

        // Complete and valid: sent on Enter, and only on Enter.
        rx->setFocus();
        QTest::keyClick(rx, Qt::Key_A, Qt::ControlModifier);
        QTest::keyClicks(rx, QStringLiteral("127.712"));
        QCOMPARE(changed.count(), 0);
        QTest::keyClick(rx, Qt::Key_Enter);
        QCOMPARE(changed.count(), 1);
        QCOMPARE(m_command.value(vhf1, Rx_freq)->number, 127712);  // kHz on the wire
        QVERIFY(!rx->edited());
        tx->setFocus();
        QTest::keyClick(tx, Qt::Key_A, Qt::ControlModifier);
        QTest::keyClicks(tx, QStringLiteral("118.1"));
        rx->setFocus();
        QTRY_VERIFY(!tx->hasFocus());
        QCOMPARE(changed.count(), 1);
        QCOMPARE(m_command.value(vhf1, Tx_freq)->number, 0);
        QCOMPARE(tx->text(), QStringLiteral("0.000 MHz"));
        QCOMPARE(tx->notSentText(),
                 QStringLiteral("Not sent: '118.1 MHz' was left unsent; the command stays 0.000 MHz"));
    }

    // Issue 11: typing "GB" then Tab sent GB_0; the aircraft adopted it.
    void incompleteStationIsNeverSent()
    {
        AllPanels panels(&m_command, &m_reported);
        QVERIFY(activate(&panels.area));
        auto* header = panels.area.widget()->findChild<HeaderPanel*>();
        auto* destination = header->findChild<StationEditor*>(QStringLiteral("ID_GCS_destination"));
        auto* source = header->findChild<StationEditor*>(QStringLiteral("ID_UA_source"));
        const UnitRef headerRef{UnitKind::Header, 0};
        const QByteArray before = block1(m_command.message());
        QSignalSpy changed(&m_command, &CommandState::changed);

        destination->countryEdit()->setFocus();
        QTest::keyClicks(destination->countryEdit(), QStringLiteral("GB"));
        QTest::keyClick(destination->countryEdit(), Qt::Key_Tab);
        QTRY_VERIFY(destination->unitEdit()->hasFocus());
        QVERIFY(destination->incomplete());
        QVERIFY(destination->unitEdit()->property("invalid").toBool());
        QVERIFY2(destination->unitEdit()->toolTip().startsWith(QStringLiteral("No unit number for GB. Not sent")),
                 qPrintable(destination->unitEdit()->toolTip()));
        QCOMPARE(changed.count(), 0);
        QVERIFY(!m_command.message().header.has(ID_GCS_destination));
        QCOMPARE(block1(m_command.message()), before);
        // Enter on the empty unit is no more a station than Tab was.
        QTest::keyClick(destination->unitEdit(), Qt::Key_Enter);
        QCOMPARE(block1(m_command.message()), before);

        QTest::keyClicks(destination->unitEdit(), QStringLiteral("30226"));
        QCOMPARE(changed.count(), 0);
        QTest::keyClick(destination->unitEdit(), Qt::Key_Enter);
        QCOMPARE(changed.count(), 1);
        QCOMPARE(*m_command.value(headerRef, ID_GCS_destination), Value::station({44, 30226}));
        QVERIFY(!destination->incomplete());

        // Changing a station in use: the old one stays in the command until the new one is whole.
        const QByteArray withSource = block1(m_command.message());
        source->countryEdit()->setFocus();
        QTest::keyClick(source->countryEdit(), Qt::Key_A, Qt::ControlModifier);
        QTest::keyClicks(source->countryEdit(), QStringLiteral("DE"));
        source->unitEdit()->setFocus();
        QTest::keyClick(source->unitEdit(), Qt::Key_A, Qt::ControlModifier);
        QTest::keyClick(source->unitEdit(), Qt::Key_Delete);
        QTest::keyClick(source->unitEdit(), Qt::Key_Enter);
        QVERIFY(source->incomplete());
        QCOMPARE(*m_command.value(headerRef, ID_UA_source), Value::station({44, 133}));
        QVERIFY2(source->unitEdit()->toolTip().endsWith(QStringLiteral("the command keeps GB_133")),
                 qPrintable(source->unitEdit()->toolTip()));
        QTest::keyClicks(source->unitEdit(), QStringLiteral("99999"));  // above 65535
        QTest::keyClick(source->unitEdit(), Qt::Key_Enter);
        QVERIFY(source->incomplete());
        QCOMPARE(block1(m_command.message()), withSource);
        QTest::keyClick(source->unitEdit(), Qt::Key_A, Qt::ControlModifier);
        QTest::keyClicks(source->unitEdit(), QStringLiteral("7"));
        QTest::keyClick(source->unitEdit(), Qt::Key_Enter);
        QCOMPARE(*m_command.value(headerRef, ID_UA_source), Value::station({49, 7}));
        QCOMPARE(changed.count(), 2);
    }

    // Issue 11: the reported column stayed black and current-looking while no
    // status frame arrived, and a command given meanwhile showed no mismatch.
    void reportedValuesTurnStale()
    {
        std::chrono::steady_clock::time_point now{std::chrono::hours(1)};
        CommandState command;
        ReportedState reported(&command, nullptr, [&now] { return now; });
        // N, stated once: the link's own silence timeout.
        QCOMPARE(reported.staleAfter(), LinkWorker::Options{}.silenceTimeout);
        QCOMPARE(reported.staleAfter(), std::chrono::milliseconds(3000));
        FlapsPanel panel(&command, &reported);
        panel.show();
        auto* rudder = panel.findChild<ReportedLabel*>(QStringLiteral("reported:F_rudder_set"));
        auto* elevator = panel.findChild<ReportedLabel*>(QStringLiteral("reported:F_elev_set"));
        auto* slave = panel.findChild<ReportedLabel*>(QStringLiteral("reported:FLAP_status.slave_aileron"));
        QVERIFY(rudder && elevator && slave);

        reported.checkAge();
        QVERIFY(!reported.stale());  // nothing reported yet: nothing to be stale
        reported.onStatus(command.message());
        QCOMPARE(rudder->text(), QStringLiteral("0\u00b0"));
        QSignalSpy updated(&reported, &ReportedState::updated);

        now += std::chrono::milliseconds(2999);
        reported.checkAge();
        QCOMPARE(updated.count(), 0);
        QVERIFY(!rudder->stale());
        now += std::chrono::milliseconds(1);
        reported.checkAge();
        QCOMPARE(updated.count(), 1);
        QVERIFY(rudder->stale());
        QCOMPARE(rudder->text(), QStringLiteral("0\u00b0 (stale, 3 s)"));
        QVERIFY(!rudder->mismatch());
        QVERIFY2(rudder->toolTip().contains(QStringLiteral("3 s ago; no status frame since")),
                 qPrintable(rudder->toolTip()));
        now += std::chrono::milliseconds(500);
        reported.checkAge();
        QCOMPARE(updated.count(), 1);  // the same whole second: no repaint
        now += std::chrono::milliseconds(8500);
        reported.checkAge();
        QCOMPARE(updated.count(), 2);
        QCOMPARE(rudder->text(), QStringLiteral("0\u00b0 (stale, 12 s)"));
        QCOMPARE(slave->text(), QStringLiteral("Independent (stale, 12 s)"));

        // A command given during the outage: a mismatch at once, no frame needed to count it.
        command.setNumber({UnitKind::Flaps, 0}, F_rudder_set, 7);
        command.setFieldCode({UnitKind::Flaps, 0}, FLAP_status, 1, 2);
        QVERIFY(rudder->mismatch());
        QVERIFY(slave->mismatch());
        QVERIFY(!elevator->mismatch());
        QVERIFY2(rudder->toolTip().contains(QStringLiteral("commanded 7\u00b0, last reported 0\u00b0 12 s ago")),
                 qPrintable(rudder->toolTip()));
        QCOMPARE(reported.mismatchFrames({UnitKind::Flaps, 0}, F_rudder_set), 0);

        // Status frames again: fresh, and the mismatch is counted as usual.
        Message status = command.message();
        status.flaps.set(F_rudder_set, 0);
        reported.onStatus(status);
        QVERIFY(!rudder->stale());
        QCOMPARE(rudder->text(), QStringLiteral("0\u00b0"));
        QVERIFY(!rudder->mismatch());  // one frame off: a surface on its way
        QVERIFY(!slave->mismatch());   // the report agrees
        reported.onStatus(status);
        reported.onStatus(status);
        QVERIFY(rudder->mismatch());
    }

    // The night theme an operator can switch to: dark, and every text on its
    // own background at 7:1 or better (WCAG AAA), as in the day theme.
    void nightThemeIsReadable()
    {
        using R = QPalette::ColorRole;
        const std::pair<R, R> pairs[] = {{R::WindowText, R::Window},
                                         {R::Text, R::Base},
                                         {R::ButtonText, R::Button},
                                         {R::ToolTipText, R::ToolTipBase},
                                         {R::Text, R::AlternateBase}};
        for (Theme::Kind kind : {Theme::Kind::Day, Theme::Kind::Night}) {
            const QPalette palette = Theme::palette(kind);
            for (const auto& [text, background] : pairs) {
                const double ratio = Theme::contrast(palette.color(text), palette.color(background));
                QVERIFY2(ratio >= 7.0, qPrintable(QStringLiteral("%1: %2 on %3 is %4:1")
                                                      .arg(Theme::name(kind))
                                                      .arg(palette.color(text).name(), palette.color(background).name())
                                                      .arg(ratio)));
            }
        }
        const QPalette night = Theme::palette(Theme::Kind::Night);
        QCOMPARE_GE(Theme::contrast(night.color(R::HighlightedText), night.color(R::Highlight)), 4.5);
        QCOMPARE_GE(Theme::contrast(night.color(R::PlaceholderText), night.color(R::Base)), 4.5);
        QCOMPARE_GE(Theme::contrast(night.color(R::Mid), night.color(R::Window)), 4.5);
        QCOMPARE_LT(night.color(R::Window).lightness(), 48);  // dark: no large bright area
        QCOMPARE_LT(night.color(R::Base).lightness(), 48);
        QCOMPARE(Theme::contrast(Qt::black, Qt::white), 21.0);

        // Switched for the whole application, and back.
        Theme::apply(*qApp, Theme::Kind::Night);
        FlapsPanel panel(&m_command, &m_reported);
        QCOMPARE(panel.palette().color(R::Window), night.color(R::Window));
        QCOMPARE(QApplication::style()->name(), QStringLiteral("fusion"));
        Theme::apply(*qApp, Theme::Kind::Day);
        QCOMPARE(QApplication::palette().color(R::Window), Theme::palette(Theme::Kind::Day).color(R::Window));
        QCOMPARE(Theme::fromName(Theme::name(Theme::Kind::Night)), Theme::Kind::Night);
        QCOMPARE(Theme::fromName(QStringLiteral("dusk")), std::nullopt);
    }
};

}  // namespace

QTEST_MAIN(TestPanelSafety)
#include "tst_panelsafety.moc"
