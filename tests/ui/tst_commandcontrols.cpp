// Issue 24, the command controls: a control changes the command only by an
// action the operator meant, once per action. A click or a held button on a
// slider's track, a half-typed or stepped value left behind by a Tab, a tab
// switch or another window, a valid prefix of a station ID: none of them
// reaches the command. A drag is sent once, on release; an arrow key on a
// slider is one step. A large change in one action (the item table's rule)
// asks first with the console's Confirmation, and Cancel leaves the command
// exactly as it was. Every check is on CommandState, what the next frame
// carries, and its changed() signal; no test waits on a clock.

#include "AnswerBox.h"
#include "codec/message/Airframe.h"
#include "codec/message/ValueCodec.h"
#include "ui/panels/CommandGate.h"
#include "ui/panels/CommandState.h"
#include "ui/panels/EnginePanel.h"
#include "ui/panels/FieldButtonGroup.h"
#include "ui/panels/FlapsPanel.h"
#include "ui/panels/FuelDumpPanel.h"
#include "ui/panels/GearPanel.h"
#include "ui/panels/HeaderPanel.h"
#include "ui/panels/ItemSlider.h"
#include "ui/panels/ItemSpinBox.h"
#include "ui/panels/RadioPanel.h"
#include "ui/panels/ReportedState.h"
#include "ui/panels/StationEditor.h"
#include "ui/panels/UnitCard.h"

#include <QAbstractButton>
#include <QApplication>
#include <QKeyEvent>
#include <QLineEdit>
#include <QSignalSpy>
#include <QStyle>
#include <QStyleOptionSlider>
#include <QTabWidget>
#include <QTest>
#include <QVBoxLayout>

#include <map>
#include <memory>

using namespace rcm;
using enum ItemId;

namespace {

// An ItemSlider that lets the test see whether QAbstractSlider would repeat
// an action while a button is held: the auto-repeat that drove an aileron
// to -84 degrees in 2 s.
class SliderProbe : public ItemSlider {
public:
    using ItemSlider::ItemSlider;
    using QAbstractSlider::repeatAction;
};

QRect handleRect(const QSlider* slider)
{
    QStyleOptionSlider option;
    option.initFrom(slider);
    option.subControls = QStyle::SC_None;
    option.activeSubControls = QStyle::SC_None;
    option.orientation = slider->orientation();
    option.maximum = slider->maximum();
    option.minimum = slider->minimum();
    option.tickPosition = slider->tickPosition();
    option.tickInterval = slider->tickInterval();
    option.upsideDown = slider->invertedAppearance();
    option.direction = slider->layoutDirection();
    option.sliderPosition = slider->sliderPosition();
    option.sliderValue = slider->value();
    option.singleStep = slider->singleStep();
    option.pageStep = slider->pageStep();
    return slider->style()->subControlRect(QStyle::CC_Slider, &option, QStyle::SC_SliderHandle, slider);
}

// Drags the handle from its centre, a pixel at a time, until the slider's
// position is `target`; returns whether it got there. The button stays down.
bool dragTo(ItemSlider* slider, int target)
{
    QPoint at = handleRect(slider).center();
    QTest::mousePress(slider, Qt::LeftButton, {}, at);
    const int direction = target > slider->sliderPosition() ? 1 : -1;
    for (int i = 0; i < slider->width() && slider->sliderPosition() != target; ++i) {
        at += QPoint(direction, 0);
        QTest::mouseMove(slider, at);
    }
    return slider->sliderPosition() == target;
}

void releaseAt(ItemSlider* slider)
{
    QTest::mouseRelease(slider, Qt::LeftButton, {}, handleRect(slider).center());
}

// The window focus can move in: key focus and focus-out need an active window.
bool activate(QWidget* window)
{
    window->show();
    window->activateWindow();
    return QTest::qWaitForWindowActive(window);
}

void typeText(QAbstractSpinBox* spinBox, const QString& text)
{
    spinBox->setFocus();
    QTest::keyClick(spinBox, Qt::Key_A, Qt::ControlModifier);
    QTest::keyClicks(spinBox, text);
}

struct Asked {
    QString text;
    QString informativeText;
    QString action;
};

class TestCommandControls : public QObject {
    Q_OBJECT

private:
    CommandState m_command;
    ReportedState m_reported{&m_command};
    QList<Asked> m_asked;
    bool m_answer = false;

    CommandGate* gate() { return CommandGate::of(&m_command); }

    // A panel in a window of its own beside a field to move the focus to.
    struct Shown {
        QWidget window;
        QLineEdit* elsewhere = nullptr;
    };
    template <typename Panel>
    Panel* show(Shown& shown)
    {
        auto* layout = new QVBoxLayout(&shown.window);
        auto* panel = new Panel(&m_command, &m_reported);
        layout->addWidget(panel);
        shown.elsewhere = new QLineEdit(&shown.window);
        shown.elsewhere->setObjectName(QStringLiteral("elsewhere"));
        layout->addWidget(shown.elsewhere);
        if (!activate(&shown.window))
            qWarning() << "window not active";
        return panel;
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
        m_asked.clear();
        m_answer = false;
        gate()->setAsker([this](const Confirmation& question, QWidget*) {
            m_asked << Asked{question.text, question.informativeText, question.action};
            return m_answer;
        });
    }

    void cleanup() { gate()->setAsker({}); }

    // The rules, stated once in the item table, read back exactly.
    void itemTableStatesLargeChanges()
    {
        const std::map<ItemId, std::string_view> surfaces{{F_aileron_LHS_set, "Move left aileron"},
                                                          {F_aileron_RHS_set, "Move right aileron"},
                                                          {F_lift_set, "Move lift flaps"},
                                                          {F_rudder_set, "Move rudder"},
                                                          {F_elev_set, "Move elevator"},
                                                          {F_airbrake_set, "Move airbrake"}};
        const std::map<ItemId, std::string_view> engine{{eng_prop_pitch, "Set propeller pitch"},
                                                        {eng_carb_SET, "Set carburettor"}};
        int withRule = 0;
        for (const ItemInfo& info : itemTable()) {
            const LargeChange& rule = info.largeChange;
            if (surfaces.count(info.id)) {
                QCOMPARE(rule.step, std::int64_t{5});
                QCOMPARE(rule.extremes, false);
                QCOMPARE(rule.action, surfaces.at(info.id));
            } else if (engine.count(info.id)) {
                QCOMPARE(rule.step, std::int64_t{51});  // 20.0 % of 0..255
                QCOMPARE(rule.extremes, true);
                QCOMPARE(rule.action, engine.at(info.id));
            } else {
                QCOMPARE(rule.step, kAnyStep);
                QCOMPARE(rule.extremes, false);
            }
            bool fieldRule = false;
            for (const FieldConfirmation& field : rule.fields)
                fieldRule = fieldRule || field.code != 0;
            QCOMPARE(fieldRule, info.id == land_wheels || info.id == ENABLE_fuel_dump || info.id == receiver_control);
            withRule += fieldRule || rule.step != kAnyStep || rule.extremes;
        }
        QCOMPARE(withRule, 6 + 2 + 3);

        const auto& wheels = itemInfo(land_wheels).largeChange.fields;
        const std::string_view wheelActions[] = {"Retract left wheel", "Retract right wheel", "Retract nose wheel",
                                                 "Retract tail wheel"};
        for (int f = 0; f < 4; ++f) {
            QCOMPARE(unsigned{wheels[f].code}, code::kRetracted);
            QCOMPARE(wheels[f].action, wheelActions[f]);
        }
        const auto& dump = itemInfo(ENABLE_fuel_dump).largeChange.fields;
        QCOMPARE(unsigned{dump[0].code}, code::kEnabled);
        QCOMPARE(dump[0].action, std::string_view("Enable fuel dump"));
        for (int tank = 1; tank <= 3; ++tank) {
            QCOMPARE(unsigned{dump[tank].code}, code::kDump);
            QCOMPARE(std::string(dump[tank].action), std::string("Dump tank ") + char('0' + tank));
        }
        const auto& radio = itemInfo(receiver_control).largeChange.fields;
        QCOMPARE(unsigned{radio[0].code}, 0u);  // the receiver: never asks
        QCOMPARE(unsigned{radio[1].code}, code::kOn);
        QCOMPARE(radio[1].action, std::string_view("Switch transmitter on"));
        QCOMPARE(itemInfo(ENABLE_fuel_dump).largeChange.note, std::string_view("Dumped fuel cannot be recovered."));

        // Applied to the value in force.
        using Rule = LargeChangeFound::Rule;
        const ItemInfo& rudder = itemInfo(F_rudder_set);
        const Value zero = Value::of(0);
        QVERIFY(!findLargeChange(rudder, &zero, Value::of(5)));
        QVERIFY(!findLargeChange(rudder, &zero, Value::of(-5)));
        QCOMPARE(findLargeChange(rudder, &zero, Value::of(6))->rule, Rule::Step);
        const Value minusThree = Value::of(-3);
        QCOMPARE(findLargeChange(rudder, &minusThree, Value::of(3))->rule, Rule::Step);
        QCOMPARE(findLargeChange(rudder, &minusThree, Value::of(3))->action, std::string_view("Move rudder"));
        QVERIFY(!findLargeChange(rudder, &zero, zero));
        const ItemInfo& pitch = itemInfo(eng_prop_pitch);
        QVERIFY(!findLargeChange(pitch, &zero, Value::of(51)));
        const Value ten = Value::of(10);
        QCOMPARE(findLargeChange(pitch, &ten, Value::of(0))->rule, Rule::Extreme);
        const Value high = Value::of(250);
        QCOMPARE(findLargeChange(pitch, &high, Value::of(255))->rule, Rule::Extreme);
        const Value hundred = Value::of(100);
        QCOMPARE(findLargeChange(pitch, &hundred, Value::of(152))->rule, Rule::Step);
        QVERIFY(!findLargeChange(pitch, &hundred, Value::of(151)));
        const Value allOut = Value::of(withEveryFieldCode(code::kOut));
        const Value noseUp = Value::of(withFieldCode(allOut.number, 2, code::kRetracted));
        const auto retract = findLargeChange(itemInfo(land_wheels), &allOut, noseUp);
        QVERIFY(retract);
        QCOMPARE(retract->rule, Rule::FieldCode);
        QCOMPARE(retract->field, 2);
        QCOMPARE(retract->action, std::string_view("Retract nose wheel"));
        QVERIFY(!findLargeChange(itemInfo(land_wheels), &noseUp, allOut));  // lowering never asks
        QVERIFY(!findLargeChange(itemInfo(lights), &allOut, Value::of(withEveryFieldCode(code::kOn))));
    }

    // The defect: one click on the track moved a flap 10 degrees; a held
    // button drove the right aileron to -84 degrees, every step sent.
    void trackClickAndHeldButtonSendNothing()
    {
        Shown shown;
        auto* panel = show<FlapsPanel>(shown);
        auto* slider = panel->findChild<ItemSlider*>(QStringLiteral("F_aileron_RHS_set.slider"));
        QVERIFY(slider);
        const Message before = m_command.message();
        QSignalSpy changed(&m_command, &CommandState::changed);
        const QRect handle = handleRect(slider);
        QVERIFY(handle.width() > 0 && handle.left() > 10 && handle.right() < slider->width() - 10);
        const int y = handle.center().y();
        const QPoint track[] = {{2, y}, {slider->width() - 3, y}, {handle.left() - 3, y}, {handle.right() + 3, y}};
        for (const QPoint at : track) {
            QVERIFY(!handle.contains(at));
            for (Qt::MouseButton button : {Qt::LeftButton, Qt::MiddleButton, Qt::RightButton})
                QTest::mouseClick(slider, button, {}, at);
            QTest::mouseDClick(slider, Qt::LeftButton, {}, at);
        }
        QCOMPARE(changed.count(), 0);
        QCOMPARE(m_command.message(), before);
        QCOMPARE(slider->value(), 0);
        QCOMPARE(slider->sliderPosition(), 0);

        // Held on the track: no drag begins and nothing is set to repeat.
        SliderProbe probe(&m_command, {UnitKind::Flaps, 0}, F_aileron_RHS_set);
        probe.resize(slider->size());
        probe.show();
        QVERIFY(QTest::qWaitForWindowExposed(&probe));
        for (const QPoint at : {QPoint(2, y), QPoint(probe.width() - 3, y)}) {
            QTest::mousePress(&probe, Qt::LeftButton, {}, at);
            QCOMPARE(probe.repeatAction(), QAbstractSlider::SliderNoAction);
            QVERIFY(!probe.isSliderDown());
            QCOMPARE(probe.sliderPosition(), 0);
            QTest::mouseRelease(&probe, Qt::LeftButton, {}, at);
        }
        QCOMPARE(changed.count(), 0);
        QCOMPARE(m_command.message(), before);
        QVERIFY(m_asked.isEmpty());
        QVERIFY2(slider->toolTip().contains(QStringLiteral("A click on the track changes nothing")),
                 qPrintable(slider->toolTip()));
        QVERIFY2(slider->toolTip().contains(QStringLiteral("A change of more than 5\u00b0 in one action asks first.")),
                 qPrintable(slider->toolTip()));
    }

    void dragCommitsOnceOnRelease()
    {
        Shown shown;
        auto* panel = show<FlapsPanel>(shown);
        auto* slider = panel->findChild<ItemSlider*>(QStringLiteral("F_aileron_RHS_set.slider"));
        auto* spinBox = panel->findChild<ItemSpinBox*>(QStringLiteral("F_aileron_RHS_set"));
        const UnitRef flaps{UnitKind::Flaps, 0};
        const Message before = m_command.message();
        QSignalSpy changed(&m_command, &CommandState::changed);

        // Dragged through 1, 2, 3 to 4 degrees: shown as not sent until the release.
        QVERIFY(dragTo(slider, 4));
        QCOMPARE(changed.count(), 0);
        QCOMPARE(m_command.message(), before);
        QCOMPARE(slider->dragged(), std::optional<int>(4));
        QCOMPARE(slider->draggedText(), QStringLiteral("Right aileron 4\u00b0 not sent: release to send"));
        QCOMPARE(spinBox->value(), 0.0);
        releaseAt(slider);
        QCOMPARE(changed.count(), 1);
        QCOMPARE(m_command.value(flaps, F_aileron_RHS_set)->number, 4);
        QCOMPARE(slider->dragged(), std::nullopt);
        QCOMPARE(spinBox->value(), 4.0);
        QVERIFY(m_asked.isEmpty());

        // Dragged back where it started: no change, nothing sent.
        QVERIFY(dragTo(slider, 6));
        QVERIFY(dragTo(slider, 4));
        releaseAt(slider);
        QCOMPARE(changed.count(), 1);

        // Far in one drag: asked; Cancel leaves the command and puts the handle back.
        QVERIFY(dragTo(slider, 20));
        releaseAt(slider);
        QCOMPARE(m_asked.size(), 1);
        QCOMPARE(m_asked[0].text, QStringLiteral("Move right aileron from 4\u00b0 to 20\u00b0?"));
        QCOMPARE(m_asked[0].action, QStringLiteral("Move right aileron"));
        QVERIFY2(m_asked[0].informativeText.contains(
                     QStringLiteral("A change of more than 5\u00b0 in one action is confirmed first.")),
                 qPrintable(m_asked[0].informativeText));
        QCOMPARE(changed.count(), 1);
        QCOMPARE(m_command.value(flaps, F_aileron_RHS_set)->number, 4);
        QCOMPARE(slider->value(), 4);
        QCOMPARE(slider->sliderPosition(), 4);

        m_answer = true;
        QVERIFY(dragTo(slider, -20));
        releaseAt(slider);
        QCOMPARE(m_asked.size(), 2);
        QCOMPARE(changed.count(), 2);
        QCOMPARE(m_command.value(flaps, F_aileron_RHS_set)->number, -20);
        QCOMPARE(slider->value(), -20);
    }

    void keyboardMovesBySingleSteps()
    {
        Shown shown;
        auto* panel = show<FlapsPanel>(shown);
        auto* slider = panel->findChild<ItemSlider*>(QStringLiteral("F_rudder_set.slider"));
        const UnitRef flaps{UnitKind::Flaps, 0};
        QCOMPARE(slider->focusPolicy(), Qt::StrongFocus);
        slider->setFocus();
        QTRY_VERIFY(slider->hasFocus());
        QSignalSpy changed(&m_command, &CommandState::changed);

        QTest::keyClick(slider, Qt::Key_Right);
        QCOMPARE(changed.count(), 1);
        QCOMPARE(m_command.value(flaps, F_rudder_set)->number, 1);
        QTest::keyClick(slider, Qt::Key_Right);
        QTest::keyClick(slider, Qt::Key_Left);
        QTest::keyClick(slider, Qt::Key_Left);
        QTest::keyClick(slider, Qt::Key_Left);
        QCOMPARE(changed.count(), 5);  // each press a deliberate step, sent
        QCOMPARE(m_command.value(flaps, F_rudder_set)->number, -1);

        // No jumps: PageUp/PageDown, Home/End, modified arrows; a held key does not repeat.
        for (Qt::Key key : {Qt::Key_PageUp, Qt::Key_PageDown, Qt::Key_Home, Qt::Key_End})
            QTest::keyClick(slider, key);
        QTest::keyClick(slider, Qt::Key_Right, Qt::ControlModifier);
        QTest::keyClick(slider, Qt::Key_Right, Qt::ShiftModifier);
        for (int i = 0; i < 20; ++i) {
            QKeyEvent repeated(QEvent::KeyPress, Qt::Key_Left, Qt::NoModifier, QString(), true);
            QApplication::sendEvent(slider, &repeated);
        }
        const auto send = [slider](QEvent::Type type, Qt::Key key, ulong time) {
            QKeyEvent event(type, key, Qt::NoModifier);
            event.setTimestamp(time);
            QApplication::sendEvent(slider, &event);
        };
        send(QEvent::KeyRelease, Qt::Key_Left, 900);
        QCOMPARE(changed.count(), 5);
        // A held key as X11 often delivers it: a real press, then releases and
        // presses not flagged as repeats, each pair at one time; or presses alone.
        send(QEvent::KeyPress, Qt::Key_Left, 1000);
        for (ulong time = 1500; time < 2500; time += 40) {
            send(QEvent::KeyRelease, Qt::Key_Left, time);
            send(QEvent::KeyPress, Qt::Key_Left, time);
        }
        send(QEvent::KeyRelease, Qt::Key_Left, 2600);
        QCOMPARE(changed.count(), 6);  // the first press only
        QCOMPARE(m_command.value(flaps, F_rudder_set)->number, -2);
        send(QEvent::KeyPress, Qt::Key_Right, 3000);
        for (ulong time = 3500; time < 4500; time += 40)
            send(QEvent::KeyPress, Qt::Key_Right, time);
        send(QEvent::KeyRelease, Qt::Key_Right, 4600);
        QCOMPARE(changed.count(), 7);
        QCOMPARE(m_command.value(flaps, F_rudder_set)->number, -1);
        // Pressed again after the release: a new step.
        send(QEvent::KeyPress, Qt::Key_Right, 5000);
        send(QEvent::KeyRelease, Qt::Key_Right, 5100);
        QCOMPARE(changed.count(), 8);
        QCOMPARE(m_command.value(flaps, F_rudder_set)->number, 0);
        QTest::keyClick(slider, Qt::Key_Left);
        QCOMPARE(changed.count(), 9);
        QCOMPARE(m_command.value(flaps, F_rudder_set)->number, -1);
        QCOMPARE(slider->value(), -1);
        QVERIFY(m_asked.isEmpty());
    }

    // The defect: a value typed or stepped went out when the field lost the focus.
    void spinBoxSendsOnlyOnEnter()
    {
        Shown shown;
        auto* tabs = new QTabWidget;
        auto* engines = new EnginePanel(&m_command, &m_reported);
        tabs->addTab(engines, QStringLiteral("Engines"));
        auto* otherTab = new QLineEdit;
        tabs->addTab(otherTab, QStringLiteral("Other"));
        auto* layout = new QVBoxLayout(&shown.window);
        layout->addWidget(tabs);
        shown.elsewhere = new QLineEdit;
        layout->addWidget(shown.elsewhere);
        QVERIFY(activate(&shown.window));
        auto* card = engines->findChild<UnitCard*>(QStringLiteral("engine 1"));
        auto* carb = card->findChild<ItemSpinBox*>(QStringLiteral("eng_carb_SET"));
        const UnitRef engine1{UnitKind::Engine, 0};
        const Message before = m_command.message();
        QSignalSpy changed(&m_command, &CommandState::changed);
        QSignalSpy notSent(gate(), &CommandGate::notSent);
        const QString defaultTip = carb->toolTip();
        QVERIFY2(
            defaultTip.contains(QStringLiteral("Enter sends a typed or stepped value; leaving the field does not.")),
            qPrintable(defaultTip));

        // Typed, then Tab: not sent, the command shown again, and said.
        typeText(carb, QStringLiteral("10"));
        QVERIFY(carb->edited());
        QTest::keyClick(carb, Qt::Key_Tab);
        QTRY_VERIFY(!carb->hasFocus());
        QCOMPARE(changed.count(), 0);
        QCOMPARE(carb->text(), QStringLiteral("0.0 %"));
        QVERIFY(!carb->edited());
        const QString said = QStringLiteral("Not sent: '10 %' was left unsent; the command stays 0.0 %");
        QCOMPARE(carb->notSentText(), said);
        QCOMPARE(carb->toolTip(), said);
        QCOMPARE(notSent.count(), 1);
        QCOMPARE(notSent.last().at(0).toString(), QStringLiteral("Carburettor setting of engine 1: ") + said);

        // An arrow key and PageUp only step the text; a click elsewhere sends nothing.
        carb->setFocus();
        QTRY_VERIFY(carb->hasFocus());
        QTest::keyClick(carb, Qt::Key_Up);
        QTest::keyClick(carb, Qt::Key_PageUp);
        QCOMPARE(carb->text(), QStringLiteral("4.3 %"));  // 1 + 10 of 255
        QVERIFY(carb->edited());
        QCOMPARE(carb->toolTip().left(13), QStringLiteral("Not sent yet:"));
        shown.elsewhere->setFocus();
        QTRY_VERIFY(!carb->hasFocus());
        QCOMPARE(changed.count(), 0);
        QCOMPARE(carb->text(), QStringLiteral("0.0 %"));
        QCOMPARE(carb->notSentText(), QStringLiteral("Not sent: '4.3 %' was left unsent; the command stays 0.0 %"));
        QCOMPARE(notSent.count(), 2);

        // Stepped, then a tab switch.
        carb->setFocus();
        QTRY_VERIFY(carb->hasFocus());
        QTest::keyClick(carb, Qt::Key_PageUp);
        QVERIFY(carb->edited());
        tabs->setCurrentIndex(1);
        QTRY_VERIFY(!carb->hasFocus());
        QCOMPARE(changed.count(), 0);
        tabs->setCurrentIndex(0);
        QCOMPARE(carb->text(), QStringLiteral("0.0 %"));
        QCOMPARE(notSent.count(), 3);

        // Typed, then another window.
        carb->setFocus();
        QTRY_VERIFY(carb->hasFocus());
        typeText(carb, QStringLiteral("12.5"));
        QWidget other;
        QVERIFY(activate(&other));
        QTRY_VERIFY(!carb->hasFocus());
        QCOMPARE(changed.count(), 0);
        QCOMPARE(carb->text(), QStringLiteral("0.0 %"));
        QCOMPARE(notSent.count(), 4);
        QCOMPARE(m_command.message(), before);

        // Enter sends, once.
        QVERIFY(activate(&shown.window));
        typeText(carb, QStringLiteral("10"));
        QCOMPARE(changed.count(), 0);
        QTest::keyClick(carb, Qt::Key_Enter);
        QCOMPARE(changed.count(), 1);
        QCOMPARE(m_command.value(engine1, eng_carb_SET)->number, 26);  // 10 % of 255, to the nearest
        QVERIFY(!carb->edited());
        QCOMPARE(carb->toolTip(), defaultTip);
        QTest::keyClick(carb, Qt::Key_Up);
        QTest::keyClick(carb, Qt::Key_Enter);
        QCOMPARE(changed.count(), 2);
        QCOMPARE(m_command.value(engine1, eng_carb_SET)->number, 27);
        // Leaving it unedited says nothing.
        shown.elsewhere->setFocus();
        QTRY_VERIFY(!carb->hasFocus());
        QCOMPARE(notSent.count(), 4);
        QVERIFY(m_asked.isEmpty());
    }

    void largeChangesAsk()
    {
        Shown shown;
        auto* window = new QWidget(&shown.window);
        auto* layout = new QVBoxLayout(window);
        auto* flaps = new FlapsPanel(&m_command, &m_reported);
        auto* engines = new EnginePanel(&m_command, &m_reported);
        layout->addWidget(flaps);
        layout->addWidget(engines);
        auto* outer = new QVBoxLayout(&shown.window);
        outer->addWidget(window);
        QVERIFY(activate(&shown.window));
        QSignalSpy changed(&m_command, &CommandState::changed);
        QSignalSpy notSent(gate(), &CommandGate::notSent);

        // A surface by more than 5 degrees, typed: asked; Cancel keeps the command and shows it.
        auto* elevator = flaps->findChild<ItemSpinBox*>(QStringLiteral("F_elev_set"));
        const UnitRef flapsRef{UnitKind::Flaps, 0};
        const Message before = m_command.message();
        typeText(elevator, QStringLiteral("-20"));
        QTest::keyClick(elevator, Qt::Key_Enter);
        QCOMPARE(m_asked.size(), 1);
        QCOMPARE(m_asked[0].text, QStringLiteral("Move elevator from 0\u00b0 to -20\u00b0?"));
        QCOMPARE(m_asked[0].action, QStringLiteral("Move elevator"));
        QVERIFY2(m_asked[0].informativeText.endsWith(QStringLiteral("Cancel keeps 0\u00b0.")),
                 qPrintable(m_asked[0].informativeText));
        QCOMPARE(changed.count(), 0);
        QCOMPARE(m_command.message(), before);
        QCOMPARE(elevator->text(), QStringLiteral("0\u00b0"));
        QVERIFY(!elevator->edited());
        QCOMPARE(elevator->notSentText(), QStringLiteral("Not sent: '-20\u00b0'; the command stays 0\u00b0"));
        QCOMPARE(notSent.count(), 1);
        QCOMPARE(notSent.last().at(0).toString(),
                 QStringLiteral("Elevator: Not sent: Move elevator cancelled; the command stays 0\u00b0"));
        QCOMPARE(flaps->findChild<ItemSlider*>(QStringLiteral("F_elev_set.slider"))->value(), 0);
        // Within the rule: no question.
        typeText(elevator, QStringLiteral("-5"));
        QTest::keyClick(elevator, Qt::Key_Enter);
        QCOMPARE(m_asked.size(), 1);
        QCOMPARE(m_command.value(flapsRef, F_elev_set)->number, -5);
        m_answer = true;
        typeText(elevator, QStringLiteral("-20"));
        QTest::keyClick(elevator, Qt::Key_Enter);
        QCOMPARE(m_asked.size(), 2);
        QCOMPARE(m_asked[1].text, QStringLiteral("Move elevator from -5\u00b0 to -20\u00b0?"));
        QCOMPARE(m_command.value(flapsRef, F_elev_set)->number, -20);

        // An engine to an extreme, or by more than 20 %.
        m_answer = false;
        auto* pitch = engines->findChild<UnitCard*>(QStringLiteral("engine 2"))
                          ->findChild<ItemSpinBox*>(QStringLiteral("eng_prop_pitch"));
        const UnitRef engine2{UnitKind::Engine, 1};
        typeText(pitch, QStringLiteral("100"));
        QTest::keyClick(pitch, Qt::Key_Enter);
        QCOMPARE(m_asked.size(), 3);
        QCOMPARE(m_asked[2].text, QStringLiteral("Set propeller pitch of engine 2 from 0.0 % to 100.0 %?"));
        QVERIFY2(m_asked[2].informativeText.startsWith(
                     QStringLiteral("100.0 % is an end of the range (0.0..100.0 %): confirmed first.")),
                 qPrintable(m_asked[2].informativeText));
        QCOMPARE(m_command.value(engine2, eng_prop_pitch)->number, 0);
        QCOMPARE(pitch->text(), QStringLiteral("0.0 %"));
        for (const char* small : {"20", "40"}) {  // 51, then 102: 51 each
            typeText(pitch, QString::fromLatin1(small));
            QTest::keyClick(pitch, Qt::Key_Enter);
        }
        QCOMPARE(m_asked.size(), 3);
        QCOMPARE(m_command.value(engine2, eng_prop_pitch)->number, 102);
        typeText(pitch, QStringLiteral("60.8"));  // 155: 53 at once
        QTest::keyClick(pitch, Qt::Key_Enter);
        QCOMPARE(m_asked.size(), 4);
        QVERIFY2(m_asked[3].informativeText.startsWith(
                     QStringLiteral("A change of more than 20.0 % in one action is confirmed first.")),
                 qPrintable(m_asked[3].informativeText));
        QCOMPARE(m_command.value(engine2, eng_prop_pitch)->number, 102);
        // Stepped down to 0 with the arrow key and Enter: the extreme asks, however small the step.
        typeText(pitch, QStringLiteral("0.4"));
        QTest::keyClick(pitch, Qt::Key_Enter);
        QCOMPARE(m_asked.size(), 5);
        m_answer = true;
        typeText(pitch, QStringLiteral("0.4"));
        QTest::keyClick(pitch, Qt::Key_Enter);
        QCOMPARE(m_command.value(engine2, eng_prop_pitch)->number, 1);
        QTest::keyClick(pitch, Qt::Key_Down);
        QTest::keyClick(pitch, Qt::Key_Enter);
        QCOMPARE(m_asked.size(), 7);
        QCOMPARE(m_asked[6].text, QStringLiteral("Set propeller pitch of engine 2 from 0.4 % to 0.0 %?"));
        QCOMPARE(m_command.value(engine2, eng_prop_pitch)->number, 0);
    }

    void gearTransmitterAndFuelDumpAsk()
    {
        Shown shown;
        auto* window = new QWidget(&shown.window);
        auto* layout = new QVBoxLayout(window);
        auto* gear = new GearPanel(&m_command, &m_reported);
        auto* radios = new RadioPanel(&m_command, &m_reported);
        auto* fuel = new FuelDumpPanel(&m_command, &m_reported);
        layout->addWidget(gear);
        layout->addWidget(radios);
        layout->addWidget(fuel);
        auto* outer = new QVBoxLayout(&shown.window);
        outer->addWidget(window);
        QVERIFY(activate(&shown.window));
        QSignalSpy changed(&m_command, &CommandState::changed);
        const UnitRef settings{UnitKind::Settings, 0};

        auto* nose = gear->findChild<FieldButtonGroup*>(QStringLiteral("land_wheels.NOSE"));
        QVERIFY2(nose->toolTip().endsWith(QStringLiteral("\nRetracted asks first.")), qPrintable(nose->toolTip()));
        const Message before = m_command.message();
        QTest::mouseClick(nose->button(code::kRetracted), Qt::LeftButton);
        QCOMPARE(m_asked.size(), 1);
        QCOMPARE(m_asked[0].text, QStringLiteral("Retract nose wheel from Out (down) to Retracted?"));
        QCOMPARE(m_asked[0].action, QStringLiteral("Retract nose wheel"));
        QVERIFY2(m_asked[0].informativeText.contains(QStringLiteral("Nose wheel to Retracted is confirmed first.")),
                 qPrintable(m_asked[0].informativeText));
        QCOMPARE(changed.count(), 0);
        QCOMPARE(m_command.message(), before);
        QVERIFY(nose->button(code::kOut)->isChecked());
        m_answer = true;
        QTest::mouseClick(nose->button(code::kRetracted), Qt::LeftButton);
        QCOMPARE(m_command.fieldCode(settings, land_wheels, 2), code::kRetracted);
        m_answer = false;
        QTest::mouseClick(nose->button(code::kOut), Qt::LeftButton);  // lowering: no question
        QCOMPARE(m_asked.size(), 2);
        QCOMPARE(m_command.fieldCode(settings, land_wheels, 2), code::kOut);

        // The receiver goes on without a question, the transmitter asks.
        auto* vhf1 = radios->findChild<UnitCard*>(QStringLiteral("radio VHF1"));
        auto* receiver = vhf1->findChild<FieldButtonGroup*>(QStringLiteral("receiver_control.receiver"));
        auto* transmitter = vhf1->findChild<FieldButtonGroup*>(QStringLiteral("receiver_control.transmitter"));
        const UnitRef radio1{UnitKind::Radio, 0};
        QTest::mouseClick(receiver->button(code::kOn), Qt::LeftButton);
        QCOMPARE(m_asked.size(), 2);
        QCOMPARE(m_command.fieldCode(radio1, receiver_control, 0), code::kOn);
        QTest::mouseClick(transmitter->button(code::kOn), Qt::LeftButton);
        QCOMPARE(m_asked.size(), 3);
        QCOMPARE(m_asked[2].text, QStringLiteral("Switch transmitter on of radio VHF1 from Off to On?"));
        QCOMPARE(m_command.fieldCode(radio1, receiver_control, 1), code::kOff);
        QVERIFY(transmitter->button(code::kOff)->isChecked());

        // The fuel dump: the same question, with what it would start.
        auto* tank2 = fuel->findChild<FieldButtonGroup*>(QStringLiteral("ENABLE_fuel_dump.tank2"));
        QTest::mouseClick(tank2->button(code::kDump), Qt::LeftButton);
        QCOMPARE(m_asked.size(), 4);
        QCOMPARE(m_asked[3].text, QStringLiteral("Dump tank 2 from Keep fuel to Dump?"));
        QCOMPARE(m_asked[3].informativeText,
                 QStringLiteral("Dump tank 2 to Dump is confirmed first.\n"
                                "Dumped fuel cannot be recovered.\n"
                                "Fuel dump facility is Disabled now; the tank dumps as soon as that changes.\n"
                                "Cancel keeps Keep fuel."));
        QVERIFY(tank2->button(code::kNoDump)->isChecked());
        m_answer = true;
        QTest::mouseClick(tank2->button(code::kDump), Qt::LeftButton);
        auto* facility = fuel->findChild<FieldButtonGroup*>(QStringLiteral("ENABLE_fuel_dump.facility"));
        QTest::mouseClick(facility->button(code::kEnabled), Qt::LeftButton);
        QCOMPARE(m_asked.size(), 6);
        QCOMPARE(m_asked[5].action, QStringLiteral("Enable fuel dump"));
        QVERIFY2(m_asked[5].informativeText.contains(QStringLiteral("Dumping starts at once: Dump tank 2.")),
                 qPrintable(m_asked[5].informativeText));
        QCOMPARE(m_command.fieldCode({UnitKind::FcuGeneral, 0}, ENABLE_fuel_dump, 0), code::kEnabled);
        // Back to safe: no question.
        QTest::mouseClick(facility->button(code::kDisabled), Qt::LeftButton);
        QCOMPARE(m_asked.size(), 6);
        QCOMPARE(m_command.fieldCode({UnitKind::FcuGeneral, 0}, ENABLE_fuel_dump, 0), code::kDisabled);
    }

    // The question is the console's one Confirmation: Cancel is the default
    // and holds the focus, the action button is named by its verb.
    void theQuestionIsTheConsoleConfirmation()
    {
        gate()->setAsker({});
        Shown shown;
        auto* gear = show<GearPanel>(shown);
        auto* nose = gear->findChild<FieldButtonGroup*>(QStringLiteral("land_wheels.NOSE"));
        const UnitRef settings{UnitKind::Settings, 0};
        const Message before = m_command.message();
        test::SeenBox seen;
        test::answerNextBox(&seen, true);
        QTest::mouseClick(nose->button(code::kRetracted), Qt::LeftButton);
        QVERIFY(seen.shown);
        QVERIFY(seen.cancelIsDefault);
        QVERIFY(seen.cancelHasFocus);
        QCOMPARE(seen.actionText, QStringLiteral("Retract nose wheel"));
        QCOMPARE(seen.text, QStringLiteral("Retract nose wheel from Out (down) to Retracted?"));
        QCOMPARE(m_command.message(), before);
        QVERIFY(nose->button(code::kOut)->isChecked());

        test::SeenBox confirmed;
        test::answerNextBox(&confirmed, false);
        QTest::mouseClick(nose->button(code::kRetracted), Qt::LeftButton);
        QVERIFY(confirmed.shown);
        QCOMPARE(m_command.fieldCode(settings, land_wheels, 2), code::kRetracted);

        // Asked on Enter in a spin box: the question's focus is not the operator leaving the field.
        Shown flapsShown;
        auto* flaps = show<FlapsPanel>(flapsShown);
        auto* rudder = flaps->findChild<ItemSpinBox*>(QStringLiteral("F_rudder_set"));
        QSignalSpy notSent(gate(), &CommandGate::notSent);
        typeText(rudder, QStringLiteral("30"));
        test::SeenBox moved;
        test::answerNextBox(&moved, false);
        QTest::keyClick(rudder, Qt::Key_Enter);
        QVERIFY(moved.shown);
        QCOMPARE(moved.actionText, QStringLiteral("Move rudder"));
        QCOMPARE(m_command.value({UnitKind::Flaps, 0}, F_rudder_set)->number, 30);
        QCOMPARE(notSent.count(), 0);
    }

    // The defect: GB_30 of GB_30226 went out when the field lost the focus.
    void stationPrefixNeverSentByFocusLoss()
    {
        Shown shown;
        auto* header = show<HeaderPanel>(shown);
        const UnitRef headerRef{UnitKind::Header, 0};
        QVERIFY(m_command.setItem(headerRef, ID_GCS_destination, Value::station({44, 30226})));
        auto* destination = header->findChild<StationEditor*>(QStringLiteral("ID_GCS_destination"));
        QCOMPARE(destination->unitEdit()->text(), QStringLiteral("30226"));
        const Message before = m_command.message();
        QSignalSpy changed(&m_command, &CommandState::changed);
        QSignalSpy notSent(gate(), &CommandGate::notSent);

        // Backspaced to GB_30, then Tab out of the editor.
        destination->unitEdit()->setFocus();
        QTRY_VERIFY(destination->unitEdit()->hasFocus());
        QTest::keyClick(destination->unitEdit(), Qt::Key_End);
        for (int i = 0; i < 3; ++i)
            QTest::keyClick(destination->unitEdit(), Qt::Key_Backspace);
        QCOMPARE(destination->unitEdit()->text(), QStringLiteral("30"));
        QVERIFY(destination->edited());  // a whole station, marked as not sent while typed
        QVERIFY2(destination->unitEdit()->toolTip().startsWith(QStringLiteral("Not sent yet: Enter sends it")),
                 qPrintable(destination->unitEdit()->toolTip()));
        QTest::keyClick(destination->unitEdit(), Qt::Key_Tab);
        QTRY_VERIFY(!destination->unitEdit()->hasFocus());
        QVERIFY(!destination->isAncestorOf(QApplication::focusWidget()));
        QCOMPARE(changed.count(), 0);
        QCOMPARE(m_command.message(), before);
        QCOMPARE(destination->unitEdit()->text(), QStringLiteral("30226"));
        const QString said = QStringLiteral("Not sent: 'GB_30' was left unsent; the command stays GB_30226");
        QCOMPARE(destination->notSentText(), said);
        QVERIFY2(destination->unitEdit()->toolTip().startsWith(said), qPrintable(destination->unitEdit()->toolTip()));
        QVERIFY2(destination->countryEdit()->toolTip().startsWith(said),
                 qPrintable(destination->countryEdit()->toolTip()));
        QCOMPARE(notSent.count(), 1);
        QCOMPARE(notSent.last().at(0).toString(), QStringLiteral("GCS destination: ") + said);

        // Country changed, Tab to the unit (still typing it), then a click elsewhere.
        destination->countryEdit()->setFocus();
        QTRY_VERIFY(destination->countryEdit()->hasFocus());
        QTest::keyClick(destination->countryEdit(), Qt::Key_A, Qt::ControlModifier);
        QTest::keyClicks(destination->countryEdit(), QStringLiteral("DE"));
        QVERIFY(destination->notSentText().isEmpty());  // an edit: the old notice goes
        QTest::keyClick(destination->countryEdit(), Qt::Key_Tab);
        QTRY_VERIFY(destination->unitEdit()->hasFocus());
        QVERIFY(destination->edited());
        QCOMPARE(destination->countryEdit()->text(), QStringLiteral("DE"));
        shown.elsewhere->setFocus();
        QTRY_VERIFY(shown.elsewhere->hasFocus());
        QCOMPARE(changed.count(), 0);
        QCOMPARE(destination->countryEdit()->text(), QStringLiteral("GB"));
        QCOMPARE(destination->notSentText(),
                 QStringLiteral("Not sent: 'DE_30226' was left unsent; the command stays GB_30226"));

        // Another window: the same.
        destination->unitEdit()->setFocus();
        QTRY_VERIFY(destination->unitEdit()->hasFocus());
        QTest::keyClick(destination->unitEdit(), Qt::Key_Backspace);
        QWidget other;
        QVERIFY(activate(&other));
        QCOMPARE(changed.count(), 0);
        QCOMPARE(destination->unitEdit()->text(), QStringLiteral("30226"));
        QCOMPARE(notSent.count(), 3);
        QCOMPARE(m_command.message(), before);

        // Enter sends it.
        QVERIFY(activate(&shown.window));
        destination->unitEdit()->setFocus();
        QTRY_VERIFY(destination->unitEdit()->hasFocus());
        QTest::keyClick(destination->unitEdit(), Qt::Key_Backspace);
        QTest::keyClick(destination->unitEdit(), Qt::Key_Enter);
        QCOMPARE(changed.count(), 1);
        QCOMPARE(*m_command.value(headerRef, ID_GCS_destination), Value::station({44, 3022}));
        QVERIFY(destination->notSentText().isEmpty());
        QVERIFY(m_asked.isEmpty());
    }
};

}  // namespace

QTEST_MAIN(TestCommandControls)
#include "tst_commandcontrols.moc"
