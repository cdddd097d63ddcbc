// The operator panels, driven as an operator drives them: mouse clicks on
// buttons, keys in spin boxes, sliders and combo boxes. Each action must
// change exactly the items it names in the next encoded frame and nothing
// else, so every check goes through the encoder and back: what the aircraft
// would read. Status frames come from SimulatedAircraft or are made by hand;
// no test waits on a clock.

#include "EventCounter.h"
#include "codec/message/Airframe.h"
#include "codec/message/MessageDecoder.h"
#include "codec/message/MessageEncoder.h"
#include "codec/message/TextFormat.h"
#include "link/aircraft/SimulatedAircraft.h"
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
#include "ui/panels/ItemText.h"
#include "ui/panels/LightsPanel.h"
#include "ui/panels/RadioPanel.h"
#include "ui/panels/ReportedLabel.h"
#include "ui/panels/ReportedState.h"
#include "ui/panels/StationEditor.h"
#include "ui/panels/SteadyGroupBox.h"
#include "ui/panels/SteadyLabel.h"
#include "ui/panels/UnitCard.h"

#include <QAbstractButton>
#include <QAbstractItemView>
#include <QAction>
#include <QApplication>
#include <QClipboard>
#include <QGuiApplication>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QImage>
#include <QComboBox>
#include <QLabel>
#include <QLineEdit>
#include <QMessageBox>
#include <QStyle>
#include <QStyleOptionFrame>
#include <QPushButton>
#include <QScrollArea>
#include <QSignalSpy>
#include <QSpinBox>
#include <QTest>
#include <QTimer>
#include <QVBoxLayout>

#include <chrono>
#include <functional>
#include <map>
#include <memory>

using namespace rcm;
using enum ItemId;

namespace {

const auto kT0 = std::chrono::sys_days{std::chrono::year{2026} / 5 / 14} + std::chrono::hours{12};

// The message as the aircraft would read it: encoded into both blocks and
// decoded again, every item under "unit item" ("engine 2 eng_prop_pitch").
std::map<QString, Value> wireItems(const Message& message)
{
    Diagnostics errors;
    const auto blocks = encodeBlocks(message, errors);
    if (!blocks) {
        qWarning() << "does not encode:" << QString::fromStdString(errors.empty() ? "" : errors.front().message);
        return {};
    }
    DecodedBlocks decoded;
    decoded.block1 = blocks->block1;
    decoded.block2 = blocks->block2;
    const DecodeResult result = decodeBlocks(decoded);
    std::map<QString, Value> items;
    result.message.forEachUnit([&](const Unit& unit) {
        for (const ItemValue& item : unit.items())
            items[QString::fromStdString(describeUnit(unit)) + QLatin1Char(' ') + ItemText::name(item.id)] = item.value;
    });
    return items;
}

// The items whose value on the wire differs between two commands, added and removed ones too.
QStringList changedItems(const Message& before, const Message& after)
{
    const auto a = wireItems(before);
    const auto b = wireItems(after);
    QStringList changed;
    for (const auto& [name, value] : a) {
        const auto it = b.find(name);
        if (it == b.end() || it->second != value)
            changed << name;
    }
    for (const auto& [name, value] : b)
        if (!a.count(name))
            changed << name;
    changed.sort();
    return changed;
}

// One field's code name as the command holds it.
QString fieldName(const Unit& unit, ItemId id, int field)
{
    const Value* v = unit.find(id);
    return v ? ItemText::fieldCodeName(id, field, fieldCode(static_cast<std::uint8_t>(v->number), field)) : QString();
}

// Chooses from a combo box's list as an operator does: Space opens it, the
// arrow keys move in it (Key_End to the last entry), Enter takes the entry.
void choose(QComboBox* combo, Qt::Key key, int times = 1)
{
    QTest::keyClick(combo, Qt::Key_Space);
    QTRY_VERIFY(combo->view()->isVisible());
    for (int i = 0; i < times; ++i)
        QTest::keyClick(combo->view(), key);
    QTest::keyClick(combo->view(), Qt::Key_Return);
}

// Steps a spin box with the arrow keys and sends the result with Enter.
void stepAndEnter(QAbstractSpinBox* spinBox, Qt::Key key)
{
    QTest::keyClick(spinBox, key);
    QTest::keyClick(spinBox, Qt::Key_Enter);
}

// Replaces a spin box's text by typing, then Enter: what an operator does.
void typeInto(QAbstractSpinBox* spinBox, const QString& text)
{
    QTest::keyClick(spinBox, Qt::Key_A, Qt::ControlModifier);
    QTest::keyClicks(spinBox, text);
    QTest::keyClick(spinBox, Qt::Key_Enter);
}

void typeInto(QLineEdit* edit, const QString& text)
{
    edit->setFocus();
    QTest::keyClick(edit, Qt::Key_A, Qt::ControlModifier);
    if (text.isEmpty())
        QTest::keyClick(edit, Qt::Key_Delete);
    else
        QTest::keyClicks(edit, text);
    QTest::keyClick(edit, Qt::Key_Enter);
}

template <typename T>
T* child(QObject* parent, const QString& name)
{
    T* found = parent->findChild<T*>(name);
    if (!found)
        qWarning() << "no" << T::staticMetaObject.className() << name << "in" << parent->objectName();
    return found;
}

QAbstractButton* codeButton(QWidget* within, const QString& field, const QString& code)
{
    auto* group = child<FieldButtonGroup>(within, field);
    return group ? child<QAbstractButton>(group, code) : nullptr;
}

// One engine, two radios, one camera: a small airframe unlike the default.
Airframe smallAirframe()
{
    Airframe a;
    a.name = "Small UA";
    a.engines = {{1, "Engine"}};
    a.radios = {{"VHF1", "VHF 1"}, {"UHF7", "UHF 7"}};
    a.cameras = {{"SNY", 4, "Nose camera"}};
    a.senseAndAvoid = false;
    return a;
}

class TestPanels : public QObject {
    Q_OBJECT

private:
    template <typename Panel>
    std::unique_ptr<Panel> shown()
    {
        auto panel = std::make_unique<Panel>(&m_command, &m_reported);
        panel->show();
        if (!QTest::qWaitForWindowExposed(panel.get()))
            qWarning() << "panel not exposed";
        return panel;
    }

    CommandState m_command;
    ReportedState m_reported{&m_command};
    // The large changes the panels asked about (CommandGate), and the answer they get.
    QStringList m_questions;
    bool m_answer = true;

private slots:
    void init()
    {
        m_command.setAirframe(Airframe::wellEquipped());
        m_command.replaceMessage(m_command.resting());  // another airframe carries values over
        m_command.editUnit({UnitKind::Header, 0}, [](Unit& header) { header = Unit(UnitKind::Header); });
        m_reported.clear();
        m_questions.clear();
        m_answer = true;
        CommandGate::of(&m_command)->setAsker([this](const Confirmation& question, QWidget*) {
            m_questions << question.text + QLatin1Char('\n') + question.informativeText;
            return m_answer;
        });
    }

    void cleanup() { CommandGate::of(&m_command)->setAsker({}); }

    void startsAtRestAndEncodes()
    {
        QCOMPARE(m_command.message(), restingCommand(Airframe::wellEquipped()));
        QVERIFY(!wireItems(m_command.message()).empty());
        QCOMPARE(m_command.unitCount(UnitKind::Engine), 3);
        QCOMPARE(m_command.unitCount(UnitKind::Radio), 3);
        QCOMPARE(m_command.unitCount(UnitKind::Camera), 2);
        QVERIFY(!m_command.unit({UnitKind::Engine, 3}));
    }

    void commandRefusesWhatWouldNotEncode()
    {
        const Message before = m_command.message();
        QSignalSpy changed(&m_command, &CommandState::changed);
        QSignalSpy rejected(&m_command, &CommandState::rejected);
        QVERIFY(!m_command.setNumber({UnitKind::Engine, 0}, eng_prop_pitch, 256));
        QVERIFY(!m_command.setNumber({UnitKind::Flaps, 0}, F_rudder_set, -128));
        QVERIFY(!m_command.setFieldCode({UnitKind::Flaps, 0}, FLAP_status, 1, 3));  // 11: corrupt for slave_aileron
        QVERIFY(!m_command.setNumber({UnitKind::Engine, 1}, eng_ID, 9));            // keys come from the airframe
        QVERIFY(!m_command.setNumber({UnitKind::Engine, 7}, eng_prop_pitch, 1));    // no such engine
        QCOMPARE(rejected.count(), 5);
        QVERIFY(rejected.at(0).at(0).toString().contains(QStringLiteral("above the maximum 255 by 1")));
        QCOMPARE(changed.count(), 0);
        QCOMPARE(m_command.message(), before);
        // The same value again is no change.
        QVERIFY(m_command.setNumber({UnitKind::Engine, 0}, eng_prop_pitch, 0));
        QCOMPARE(changed.count(), 0);
    }

    void controlsTakeTheirTextFromTheItemTable()
    {
        auto panel = shown<EnginePanel>();
        auto* card = child<UnitCard>(panel.get(), QStringLiteral("engine 1"));
        QVERIFY(card);
        auto* pitch = child<ItemSpinBox>(card, QStringLiteral("eng_prop_pitch"));
        QVERIFY(pitch);
        // The item's range first, then how the box sends and the item table's large-change rule.
        QCOMPARE(
            pitch->toolTip(),
            QStringLiteral("Propeller pitch, 0.0..100.0 %\n"
                           "Enter sends a typed or stepped value; leaving the field does not.\n"
                           "Setting 0.0 % or 100.0 %, or a change of more than 20.0 % in one action, asks first."));
        QCOMPARE(pitch->suffix(), QStringLiteral(" %"));
        QCOMPARE(pitch->minimum(), 0.0);
        QCOMPARE(pitch->maximum(), 255.0);
        auto* control = child<FieldComboBox>(card, QStringLiteral("eng_status.control"));
        QVERIFY(control);
        QCOMPARE(control->count(), 3);
        QCOMPARE(control->itemText(0), QStringLiteral("Automatic"));
        QCOMPARE(control->itemText(1), QStringLiteral("Ground station"));
        QCOMPARE(control->itemText(2), QStringLiteral("RC transmitter"));
        QCOMPARE(control->currentText(), QStringLiteral("Automatic"));

        auto camera = shown<CameraPanel>();
        auto* compass = child<ItemSpinBox>(camera.get(), QStringLiteral("cam_mag_compass"));
        QVERIFY(compass);
        QCOMPARE(compass->toolTip().section(QLatin1Char('\n'), 0, 0),
                 QStringLiteral("Compass bearing, 0.00..359.99\u00b0"));
        QCOMPARE(compass->maximum(), 35999.0);  // hundredths of a degree, as on the wire
        QCOMPARE(compass->suffix(), QStringLiteral("\u00b0"));

        // Frequencies in MHz, kHz on the wire; transmit power within what a real set gives.
        auto radios = shown<RadioPanel>();
        auto* rx = child<ItemSpinBox>(radios.get(), QStringLiteral("Rx_freq"));
        QCOMPARE(rx->suffix(), QStringLiteral(" MHz"));
        QCOMPARE(rx->textFromValue(127712), QStringLiteral("127.712"));
        auto* power = child<ItemSpinBox>(radios.get(), QStringLiteral("Tx_OP_power"));
        QCOMPARE(power->toolTip().section(QLatin1Char('\n'), 0, 0), QStringLiteral("Transmit power, 0..50 dBm"));
        QCOMPARE(power->maximum(), 50.0);
    }

    // Panels show words and units for people; the wire, the text format and
    // the encoder keep the profile's codes, units and ranges.
    void wordsAndUnitsForPeopleTheWireUnchanged()
    {
        for (const ItemInfo& item : itemTable())
            for (int field = 0; field < static_cast<int>(item.fields.size()); ++field)
                for (unsigned code : ItemText::validFieldCodes(item.id, field))
                    QVERIFY2(
                        ItemText::fieldCodeWord(item.id, field, code) != ItemText::fieldCodeName(item.id, field, code),
                        qPrintable(ItemText::fieldCodeName(item.id, field, code)));
        QCOMPARE(ItemText::fieldCodeWord(eng_status, 1, 2), QStringLiteral("Engine 1 master, engine 3 slave"));
        QCOMPARE(ItemText::fieldCodeWord(FLAP_status, 1, 2), QStringLiteral("Master and slave"));
        QCOMPARE(ItemText::fieldCodeWord(ENABLE_fuel_dump, 1, 1), QStringLiteral("Keep fuel"));
        QCOMPARE(ItemText::fieldCodeWord(eng_status, 1, 3), QStringLiteral("corrupt (11)"));

        // Percent of a 0..255 setting: every value shows apart and reads back as itself.
        for (ItemId id :
             {eng_prop_pitch, eng_carb_SET, SA_zoom_LHS_cam, SA_zoom_FWD_cam, SA_zoom_RHS_cam, cam_zoom_set})
            for (std::int64_t wire = 0; wire <= 255; ++wire)
                QCOMPARE(ItemText::parseNumber(id, ItemText::number(id, wire)), std::optional<std::int64_t>(wire));
        QCOMPARE(ItemText::value(eng_prop_pitch, Value::of(128)), QStringLiteral("50.2 %"));
        QCOMPARE(ItemText::value(eng_prop_pitch, Value::of(255)), QStringLiteral("100.0 %"));
        QCOMPARE(ItemText::parseNumber(eng_prop_pitch, QStringLiteral("50 %")), std::optional<std::int64_t>(128));
        QCOMPARE(ItemText::parseNumber(eng_prop_pitch, QStringLiteral("100.1")), std::nullopt);
        // MHz for kHz, to the kHz and no finer.
        QCOMPARE(ItemText::value(Rx_freq, Value::of(127712)), QStringLiteral("127.712 MHz"));
        QCOMPARE(ItemText::parseNumber(Tx_freq, QStringLiteral("127.712 MHz")), std::optional<std::int64_t>(127712));
        QCOMPARE(ItemText::parseNumber(Tx_freq, QStringLiteral("127.7125")), std::nullopt);
        QCOMPARE(ItemText::value(cam_elev, Value::of(-5464)), QStringLiteral("-54.64\u00b0"));
        // Transmit power: the console offers 0..50 dBm (1 mW..100 W).
        QCOMPARE(ItemText::parseNumber(Tx_OP_power, QStringLiteral("50")), std::optional<std::int64_t>(50));
        QCOMPARE(ItemText::parseNumber(Tx_OP_power, QStringLiteral("51 dBm")), std::nullopt);
        QCOMPARE(ItemText::parseNumber(Tx_OP_power, QStringLiteral("170")), std::nullopt);

        // What the panels do not change: the text format and the encoder, in kHz, 0..255 dBm, codes.
        Message m = m_command.message();
        m.radios[0].set(Rx_freq, 127712);
        m.radios[0].set(Tx_OP_power, 170);
        const std::string text = formatMessage(m);
        QVERIFY(text.find("Rx_freq 127712\n") != std::string::npos);
        QVERIFY(text.find("Tx_OP_power 170\n") != std::string::npos);
        QVERIFY(text.find("slave=NO_SLAVE") != std::string::npos);
        QVERIFY(parseMessage(text).ok());
        QVERIFY(!wireItems(m).empty());  // encodes
    }

    void enginePanel()
    {
        auto panel = shown<EnginePanel>();
        QCOMPARE(panel->findChildren<UnitCard*>().size(), 3);
        auto* card = child<UnitCard>(panel.get(), QStringLiteral("engine 2"));
        QVERIFY(card);
        QCOMPARE(child<QLabel>(card, QStringLiteral("eng_ID"))->text(), QStringLiteral("2"));

        Message before = m_command.message();
        auto* control = child<FieldComboBox>(card, QStringLiteral("eng_status.control"));
        choose(control, Qt::Key_Down);
        QCOMPARE(changedItems(before, m_command.message()), QStringList{QStringLiteral("engine 2 eng_status")});
        QCOMPARE(fieldName(m_command.message().engines[1], eng_status, 0), QStringLiteral("GCS"));
        QCOMPARE(fieldName(m_command.message().engines[1], eng_status, 1), QStringLiteral("NO_SLAVE"));
        choose(control, Qt::Key_End);
        QCOMPARE(fieldName(m_command.message().engines[1], eng_status, 0), QStringLiteral("RC"));

        before = m_command.message();
        choose(child<FieldComboBox>(card, QStringLiteral("eng_status.slave")), Qt::Key_Down);
        QCOMPARE(changedItems(before, m_command.message()), QStringList{QStringLiteral("engine 2 eng_status")});
        QCOMPARE(fieldName(m_command.message().engines[1], eng_status, 1), QStringLiteral("MASTER_SLAVE"));
        QCOMPARE(fieldName(m_command.message().engines[1], eng_status, 0), QStringLiteral("RC"));

        before = m_command.message();
        typeInto(child<ItemSpinBox>(card, QStringLiteral("eng_prop_pitch")), QStringLiteral("47.1"));
        QCOMPARE(changedItems(before, m_command.message()), QStringList{QStringLiteral("engine 2 eng_prop_pitch")});
        QCOMPARE(m_command.message().engines[1].number(eng_prop_pitch), 120);  // 47.1 % of 255

        before = m_command.message();
        stepAndEnter(child<ItemSpinBox>(card, QStringLiteral("eng_carb_SET")), Qt::Key_Up);
        QCOMPARE(changedItems(before, m_command.message()), QStringList{QStringLiteral("engine 2 eng_carb_SET")});
        QCOMPARE(m_command.message().engines[1].number(eng_carb_SET), 1);

        // Typing does not command each digit on the way: one change for "78.4" (200).
        QSignalSpy changed(&m_command, &CommandState::changed);
        auto* carb = child<ItemSpinBox>(card, QStringLiteral("eng_carb_SET"));
        QTest::keyClick(carb, Qt::Key_A, Qt::ControlModifier);
        QTest::keyClicks(carb, QStringLiteral("78.4"));
        QCOMPARE(changed.count(), 0);
        QTest::keyClick(carb, Qt::Key_Enter);
        QCOMPARE(changed.count(), 1);
        QCOMPARE(m_command.message().engines[1].number(eng_carb_SET), 200);
    }

    void flapsPanelSliderAndSpinBoxFollowEachOther()
    {
        auto panel = shown<FlapsPanel>();
        auto* rudderSlider = child<ItemSlider>(panel.get(), QStringLiteral("F_rudder_set.slider"));
        auto* rudderSpin = child<ItemSpinBox>(panel.get(), QStringLiteral("F_rudder_set"));
        QVERIFY(rudderSlider && rudderSpin);
        QCOMPARE(rudderSlider->minimum(), -127);
        QCOMPARE(rudderSlider->maximum(), 127);
        QCOMPARE(rudderSpin->toolTip().section(QLatin1Char('\n'), 0, 0), QStringLiteral("Rudder, -127..127\u00b0"));

        // The handle dragged to the right.
        Message before = m_command.message();
        const QPoint middle(rudderSlider->width() / 2, rudderSlider->height() / 2);
        QTest::mousePress(rudderSlider, Qt::LeftButton, {}, middle);
        QTest::mouseMove(rudderSlider, middle + QPoint(10, 0));
        QTest::mouseRelease(rudderSlider, Qt::LeftButton, {}, middle + QPoint(10, 0));
        QCOMPARE(changedItems(before, m_command.message()), QStringList{QStringLiteral("flaps F_rudder_set")});
        QCOMPARE_GT(m_command.message().flaps.number(F_rudder_set), 0);
        QCOMPARE(m_command.message().flaps.number(F_rudder_set), rudderSlider->value());
        QCOMPARE(rudderSpin->value(), double(rudderSlider->value()));

        before = m_command.message();
        auto* elevatorSpin = child<ItemSpinBox>(panel.get(), QStringLiteral("F_elev_set"));
        typeInto(elevatorSpin, QStringLiteral("-20"));
        QCOMPARE(changedItems(before, m_command.message()), QStringList{QStringLiteral("flaps F_elev_set")});
        QCOMPARE(m_command.message().flaps.number(F_elev_set), -20);
        QCOMPARE(child<ItemSlider>(panel.get(), QStringLiteral("F_elev_set.slider"))->value(), -20);

        // -128 is not a valid angle: shown as invalid, not sent, left for correction.
        typeInto(elevatorSpin, QStringLiteral("-128"));
        QCOMPARE(m_command.message().flaps.number(F_elev_set), -20);
        QVERIFY(elevatorSpin->invalid());
        QTest::keyClick(elevatorSpin, Qt::Key_Escape);
        QVERIFY(!elevatorSpin->invalid());
        QCOMPARE(elevatorSpin->text(), QStringLiteral("-20\u00b0"));

        before = m_command.message();
        auto* aileron = child<ItemSpinBox>(panel.get(), QStringLiteral("F_aileron_LHS_set"));
        stepAndEnter(aileron, Qt::Key_Down);
        QCOMPARE(changedItems(before, m_command.message()), QStringList{QStringLiteral("flaps F_aileron_LHS_set")});
        QCOMPARE(m_command.message().flaps.number(F_aileron_LHS_set), -1);
        QCOMPARE(child<ItemSlider>(panel.get(), QStringLiteral("F_aileron_LHS_set.slider"))->value(), -1);

        before = m_command.message();
        choose(child<FieldComboBox>(panel.get(), QStringLiteral("FLAP_status.slave_aileron")), Qt::Key_Down);
        QCOMPARE(changedItems(before, m_command.message()), QStringList{QStringLiteral("flaps FLAP_status")});
        QCOMPARE(fieldName(m_command.message().flaps, FLAP_status, 1), QStringLiteral("MASTER_SLAVE"));
        QCOMPARE(fieldName(m_command.message().flaps, FLAP_status, 0), QStringLiteral("AUTO"));

        before = m_command.message();
        choose(child<FieldComboBox>(panel.get(), QStringLiteral("FLAP_status.control")), Qt::Key_Down);
        QCOMPARE(changedItems(before, m_command.message()), QStringList{QStringLiteral("flaps FLAP_status")});
        QCOMPARE(fieldName(m_command.message().flaps, FLAP_status, 0), QStringLiteral("GCS"));
    }

    void gearPanel()
    {
        auto panel = shown<GearPanel>();
        auto* retracted = codeButton(panel.get(), QStringLiteral("land_wheels.NOSE"), QStringLiteral("RETRACTED"));
        QVERIFY(retracted);
        QVERIFY(codeButton(panel.get(), QStringLiteral("land_wheels.NOSE"), QStringLiteral("OUT"))->isChecked());
        const Message before = m_command.message();
        QTest::mouseClick(retracted, Qt::LeftButton);
        QCOMPARE(m_questions.size(), 1);  // retracting asks first (tst_commandcontrols)
        QCOMPARE(changedItems(before, m_command.message()), QStringList{QStringLiteral("SETTINGS land_wheels")});
        const Unit& settings = m_command.message().settings;
        QCOMPARE(fieldName(settings, land_wheels, 2), QStringLiteral("RETRACTED"));
        for (int wheel : {0, 1, 3})
            QCOMPARE(fieldName(settings, land_wheels, wheel), QStringLiteral("OUT"));
        QVERIFY(retracted->isChecked());
        // Clicking the position the wheel is already commanded to is no change.
        QSignalSpy changed(&m_command, &CommandState::changed);
        QTest::mouseClick(retracted, Qt::LeftButton);
        QCOMPARE(changed.count(), 0);
    }

    void lightsPanel()
    {
        auto panel = shown<LightsPanel>();
        const Message before = m_command.message();
        QTest::mouseClick(codeButton(panel.get(), QStringLiteral("lights.wheel_brake"), QStringLiteral("ON")),
                          Qt::LeftButton);
        QCOMPARE(changedItems(before, m_command.message()), QStringList{QStringLiteral("SETTINGS lights")});
        const Unit& settings = m_command.message().settings;
        QCOMPARE(fieldName(settings, lights, 3), QStringLiteral("ON"));
        for (int light : {0, 1, 2})
            QCOMPARE(fieldName(settings, lights, light), QStringLiteral("OFF"));

        const Message beforeTail = m_command.message();
        QTest::mouseClick(codeButton(panel.get(), QStringLiteral("lights.tail"), QStringLiteral("ON")), Qt::LeftButton);
        QCOMPARE(changedItems(beforeTail, m_command.message()), QStringList{QStringLiteral("SETTINGS lights")});
        QCOMPARE(fieldName(m_command.message().settings, lights, 2), QStringLiteral("ON"));
        QCOMPARE(fieldName(m_command.message().settings, lights, 3), QStringLiteral("ON"));
    }

    void fuelDumpNeedsConfirmation()
    {
        auto panel = shown<FuelDumpPanel>();
        QStringList& questions = m_questions;
        bool& answer = m_answer;
        answer = false;
        auto* dump2 = codeButton(panel.get(), QStringLiteral("ENABLE_fuel_dump.tank2"), QStringLiteral("DUMP"));
        auto* keep2 = codeButton(panel.get(), QStringLiteral("ENABLE_fuel_dump.tank2"), QStringLiteral("NO_DUMP"));
        QVERIFY(dump2 && keep2);

        // Cancelled: nothing changes, so the next frame is the same.
        QSignalSpy changed(&m_command, &CommandState::changed);
        Message before = m_command.message();
        QTest::mouseClick(dump2, Qt::LeftButton);
        QCOMPARE(questions.size(), 1);
        QVERIFY2(questions.last().startsWith(QStringLiteral("Dump tank 2 from Keep fuel to Dump?")),
                 qPrintable(questions.last()));
        QCOMPARE(changed.count(), 0);
        QCOMPARE(changedItems(before, m_command.message()), QStringList{});
        QVERIFY(keep2->isChecked());
        QVERIFY(!dump2->isChecked());

        answer = true;
        QTest::mouseClick(dump2, Qt::LeftButton);
        QCOMPARE(questions.size(), 2);
        QCOMPARE(changedItems(before, m_command.message()),
                 QStringList{QStringLiteral("FCU_general ENABLE_fuel_dump")});
        QCOMPARE(fieldName(m_command.message().fuelDump, ENABLE_fuel_dump, 2), QStringLiteral("DUMP"));
        QCOMPARE(fieldName(m_command.message().fuelDump, ENABLE_fuel_dump, 0), QStringLiteral("DISABLED"));

        before = m_command.message();
        auto* enable = codeButton(panel.get(), QStringLiteral("ENABLE_fuel_dump.facility"), QStringLiteral("ENABLED"));
        QTest::mouseClick(enable, Qt::LeftButton);
        QCOMPARE(questions.size(), 3);
        QVERIFY2(questions.last().contains(QStringLiteral("Dump tank 2")), qPrintable(questions.last()));
        QCOMPARE(changedItems(before, m_command.message()),
                 QStringList{QStringLiteral("FCU_general ENABLE_fuel_dump")});
        QCOMPARE(fieldName(m_command.message().fuelDump, ENABLE_fuel_dump, 0), QStringLiteral("ENABLED"));

        // Back to the safe state without a question.
        before = m_command.message();
        QTest::mouseClick(
            codeButton(panel.get(), QStringLiteral("ENABLE_fuel_dump.facility"), QStringLiteral("DISABLED")),
            Qt::LeftButton);
        QCOMPARE(questions.size(), 3);
        QCOMPARE(fieldName(m_command.message().fuelDump, ENABLE_fuel_dump, 0), QStringLiteral("DISABLED"));
        QCOMPARE(changedItems(before, m_command.message()),
                 QStringList{QStringLiteral("FCU_general ENABLE_fuel_dump")});
    }

    // Issue 28: the question is named by its verb, and behind it the panel
    // shows what is commanded, not the box the click would tick.
    void fuelDumpQuestionShowsTheCommand()
    {
        auto panel = shown<FuelDumpPanel>();
        auto* dump1 = codeButton(panel.get(), QStringLiteral("ENABLE_fuel_dump.tank1"), QStringLiteral("DUMP"));
        auto* keep1 = codeButton(panel.get(), QStringLiteral("ENABLE_fuel_dump.tank1"), QStringLiteral("NO_DUMP"));
        QVERIFY(dump1 && keep1);
        QStringList actions;
        bool dumpTickedWhileAsked = true;
        bool keepTickedWhileAsked = false;
        CommandGate::of(&m_command)->setAsker([&](const Confirmation& question, QWidget*) {
            actions << question.action;
            dumpTickedWhileAsked = dump1->isChecked();
            keepTickedWhileAsked = keep1->isChecked();
            return false;
        });
        QTest::mouseClick(dump1, Qt::LeftButton);
        QCOMPARE(actions, QStringList{QStringLiteral("Dump tank 1")});
        QVERIFY(!dumpTickedWhileAsked);
        QVERIFY(keepTickedWhileAsked);
        QVERIFY(keep1->isChecked());
        QCOMPARE(fieldName(m_command.message().fuelDump, ENABLE_fuel_dump, 1), QStringLiteral("NO_DUMP"));
    }

    // The dialog itself: the action button says the verb, the other Cancel,
    // and Cancel is the default.
    void confirmationButtonsNamedByTheirVerb()
    {
        auto panel = shown<FuelDumpPanel>();
        CommandGate::of(&m_command)->setAsker({});
        QStringList buttons;
        QString defaultButton;
        // Answered from the dialog's own event loop, once it is up.
        std::function<void()> answer = [&] {
            auto* box = qobject_cast<QMessageBox*>(QApplication::activeModalWidget());
            if (!box) {
                QTimer::singleShot(0, this, answer);
                return;
            }
            for (QAbstractButton* b : box->buttons())
                buttons << b->text().remove(QLatin1Char('&'));
            defaultButton = box->defaultButton()->text().remove(QLatin1Char('&'));
            box->reject();
        };
        QTimer::singleShot(0, this, answer);
        QTest::mouseClick(codeButton(panel.get(), QStringLiteral("ENABLE_fuel_dump.tank3"), QStringLiteral("DUMP")),
                          Qt::LeftButton);
        buttons.sort();
        QCOMPARE(buttons, (QStringList{QStringLiteral("Cancel"), QStringLiteral("Dump tank 3")}));
        QCOMPARE(defaultButton, QStringLiteral("Cancel"));
        QCOMPARE(fieldName(m_command.message().fuelDump, ENABLE_fuel_dump, 3), QStringLiteral("NO_DUMP"));
    }

    // Issue 28: All down and All up; retracting them all is one question, named by its verb.
    void gearAllUpAllDown()
    {
        auto panel = shown<GearPanel>();
        auto* up = child<QPushButton>(panel.get(), QStringLiteral("allUp"));
        auto* down = child<QPushButton>(panel.get(), QStringLiteral("allDown"));
        QVERIFY(up && down);
        QCOMPARE(up->text(), QStringLiteral("All up"));
        QCOMPARE(down->text(), QStringLiteral("All down"));
        QVERIFY(up->isEnabled());
        QVERIFY(!down->isEnabled());  // all out already
        QStringList actions;
        CommandGate::of(&m_command)->setAsker([&](const Confirmation& question, QWidget*) {
            actions << question.action;
            m_questions << question.text + QLatin1Char('\n') + question.informativeText;
            return m_answer;
        });
        const Message before = m_command.message();
        m_answer = false;
        QTest::mouseClick(up, Qt::LeftButton);
        QCOMPARE(actions, QStringList{QStringLiteral("Retract all wheels")});
        QCOMPARE(m_questions.last(), QStringLiteral("Retract all wheels?\n"
                                                    "Left wheel: Out (down) to Retracted\n"
                                                    "Right wheel: Out (down) to Retracted\n"
                                                    "Nose wheel: Out (down) to Retracted\n"
                                                    "Tail wheel: Out (down) to Retracted\n"
                                                    "A retracted wheel cannot carry the aircraft on the ground.\n"
                                                    "Cancel keeps the landing gear as it is."));
        QCOMPARE(m_command.message(), before);

        m_answer = true;
        QTest::mouseClick(up, Qt::LeftButton);
        QCOMPARE(actions.size(), 2);
        QCOMPARE(changedItems(before, m_command.message()), QStringList{QStringLiteral("SETTINGS land_wheels")});
        for (int wheel = 0; wheel < 4; ++wheel)
            QCOMPARE(fieldName(m_command.message().settings, land_wheels, wheel), QStringLiteral("RETRACTED"));
        QVERIFY(!up->isEnabled());
        QVERIFY(down->isEnabled());

        // Lowering asks nothing.
        QTest::mouseClick(down, Qt::LeftButton);
        QCOMPARE(actions.size(), 2);
        for (int wheel = 0; wheel < 4; ++wheel)
            QCOMPARE(fieldName(m_command.message().settings, land_wheels, wheel), QStringLiteral("OUT"));

        // One wheel up, then All up: the question names the three still out.
        QVERIFY(m_command.setFieldCode({UnitKind::Settings, 0}, land_wheels, 2, code::kRetracted));
        QTest::mouseClick(up, Qt::LeftButton);
        QCOMPARE(actions.size(), 3);
        QVERIFY(!m_questions.last().contains(QStringLiteral("Nose wheel")));
        QVERIFY(m_questions.last().contains(QStringLiteral("Tail wheel: Out (down) to Retracted")));
    }

    // Issue 28: each card heads its columns, and an engine's master/slave
    // mode says what it means on that engine.
    void headingsAndEngineWords()
    {
        auto panel = shown<EnginePanel>();
        for (const QString& name : {QStringLiteral("engine 1"), QStringLiteral("engine 2"), QStringLiteral("engine 3")}) {
            auto* card = child<UnitCard>(panel.get(), name);
            QVERIFY(card);
            QCOMPARE(child<QLabel>(card, QStringLiteral("heading:Commanded"))->text(), QStringLiteral("Commanded"));
            QCOMPARE(child<QLabel>(card, QStringLiteral("heading:Reported"))->text(), QStringLiteral("Reported"));
            for (QLabel* label : card->findChildren<QLabel*>())
                QVERIFY2(!label->text().contains(QStringLiteral("slave engine 3")), qPrintable(label->text()));
        }
        const auto words = [&](const QString& card) {
            auto* box = child<FieldComboBox>(child<UnitCard>(panel.get(), card), QStringLiteral("eng_status.slave"));
            QStringList items;
            for (int i = 0; i < box->count(); ++i)
                items << box->itemText(i);
            return items;
        };
        QCOMPARE(words(QStringLiteral("engine 1")), (QStringList{QStringLiteral("Independent"), QStringLiteral("Master of engine 3")}));
        QCOMPARE(words(QStringLiteral("engine 2")),
                 (QStringList{QStringLiteral("Independent"), QStringLiteral("Engine 1 master, engine 3 slave")}));
        QCOMPARE(words(QStringLiteral("engine 3")), (QStringList{QStringLiteral("Independent"), QStringLiteral("Slave of engine 1")}));
        QCOMPARE(ItemText::label(eng_status, 1), QStringLiteral("Master/slave mode"));

        // The reported value says it the same way.
        Message status = m_command.message();
        status.engines[2].setFieldCode(eng_status, 1, code::kMasterSlave);
        m_reported.onStatus(status);
        QCOMPARE(child<ReportedLabel>(child<UnitCard>(panel.get(), QStringLiteral("engine 3")),
                                      QStringLiteral("reported:eng_status.slave"))
                     ->text(),
                 QStringLiteral("Slave of engine 1"));
        auto gear = shown<GearPanel>();
        QVERIFY(child<QLabel>(gear.get(), QStringLiteral("heading:Reported")));
    }

    void radioPanel()
    {
        auto panel = shown<RadioPanel>();
        QCOMPARE(panel->findChildren<UnitCard*>().size(), 3);
        auto* card = child<UnitCard>(panel.get(), QStringLiteral("radio VHF2"));
        QVERIFY(card);
        // The system ID is the key: shown, not editable.
        auto* systemId = child<QLabel>(card, QStringLiteral("system_ID"));
        QCOMPARE(systemId->text(), QStringLiteral("VHF2"));
        QVERIFY(!card->findChild<QLineEdit*>(QStringLiteral("system_ID")));

        Message before = m_command.message();
        QTest::mouseClick(codeButton(card, QStringLiteral("receiver_control.receiver"), QStringLiteral("ON")),
                          Qt::LeftButton);
        QCOMPARE(changedItems(before, m_command.message()), QStringList{QStringLiteral("radio VHF2 receiver_control")});
        QCOMPARE(fieldName(m_command.message().radios[1], receiver_control, 0), QStringLiteral("ON"));
        QCOMPARE(fieldName(m_command.message().radios[1], receiver_control, 1), QStringLiteral("OFF"));

        before = m_command.message();
        auto* rx = child<ItemSpinBox>(card, QStringLiteral("Rx_freq"));
        QCOMPARE(rx->suffix(), QStringLiteral(" MHz"));
        typeInto(rx, QStringLiteral("127.712"));
        QCOMPARE(changedItems(before, m_command.message()), QStringList{QStringLiteral("radio VHF2 Rx_freq")});
        QCOMPARE(m_command.message().radios[1].number(Rx_freq), 127712);

        // Frequencies are 32-bit: beyond what an int spin box holds.
        before = m_command.message();
        typeInto(child<ItemSpinBox>(card, QStringLiteral("Tx_freq")), QStringLiteral("4000000.000"));
        QCOMPARE(changedItems(before, m_command.message()), QStringList{QStringLiteral("radio VHF2 Tx_freq")});
        QCOMPARE(m_command.message().radios[1].number(Tx_freq), 4000000000LL);

        before = m_command.message();
        typeInto(child<ItemSpinBox>(card, QStringLiteral("Tx_OP_power")), QStringLiteral("37"));
        QCOMPARE(changedItems(before, m_command.message()), QStringList{QStringLiteral("radio VHF2 Tx_OP_power")});
        QCOMPARE(m_command.message().radios[1].number(Tx_OP_power), 37);
    }

    void cameraPanel()
    {
        auto panel = shown<CameraPanel>();
        auto* sense = child<UnitCard>(panel.get(), QStringLiteral("SENSE"));
        QVERIFY(sense);
        Message before = m_command.message();
        typeInto(child<ItemSpinBox>(sense, QStringLiteral("SA_zoom_FWD_cam")), QStringLiteral("41.2"));
        QCOMPARE(changedItems(before, m_command.message()), QStringList{QStringLiteral("SENSE SA_zoom_FWD_cam")});
        QCOMPARE(m_command.message().sense.number(SA_zoom_FWD_cam), 105);

        auto* card = child<UnitCard>(panel.get(), QStringLiteral("camera NIK 2"));
        QVERIFY(card);
        QCOMPARE(child<QLabel>(card, QStringLiteral("cam_ID"))->text(), QStringLiteral("NIK 2"));

        before = m_command.message();
        typeInto(child<ItemSpinBox>(card, QStringLiteral("cam_mag_compass")), QStringLiteral("264.95"));
        QCOMPARE(changedItems(before, m_command.message()),
                 QStringList{QStringLiteral("camera NIK 2 cam_mag_compass")});
        QCOMPARE(m_command.message().cameras[1].number(cam_mag_compass), 26495);

        before = m_command.message();
        typeInto(child<ItemSpinBox>(card, QStringLiteral("cam_elev")), QStringLiteral("-54.64"));
        QCOMPARE(changedItems(before, m_command.message()), QStringList{QStringLiteral("camera NIK 2 cam_elev")});
        QCOMPARE(m_command.message().cameras[1].number(cam_elev), -5464);

        before = m_command.message();
        stepAndEnter(child<ItemSpinBox>(card, QStringLiteral("cam_zoom_set")), Qt::Key_Up);
        QCOMPARE(changedItems(before, m_command.message()), QStringList{QStringLiteral("camera NIK 2 cam_zoom_set")});

        before = m_command.message();
        auto* destination = child<StationEditor>(card, QStringLiteral("ID_GCS_destination"));
        typeInto(destination->countryEdit(), QStringLiteral("GB"));
        typeInto(destination->unitEdit(), QStringLiteral("30226"));
        QCOMPARE(changedItems(before, m_command.message()),
                 QStringList{QStringLiteral("camera NIK 2 ID_GCS_destination")});
        QCOMPARE(*m_command.message().cameras[1].find(cam_GCS_destination), Value::station({44, 30226}));
    }

    void takeOnePhotoIsOneShot()
    {
        auto panel = shown<CameraPanel>();
        auto* card = child<UnitCard>(panel.get(), QStringLiteral("camera NIK 1"));
        auto* photo = child<QPushButton>(card, QStringLiteral("take_one_photo"));
        QVERIFY(photo);
        QVERIFY(photo->isEnabled());

        const Message atRest = m_command.message();
        QTest::mouseClick(photo, Qt::LeftButton);
        QCOMPARE(changedItems(atRest, m_command.message()), QStringList{QStringLiteral("camera NIK 1 take_one_photo")});
        QCOMPARE(fieldName(m_command.message().cameras[0], take_one_photo, 0), QStringLiteral("TAKE"));
        QVERIFY(m_command.oneShotPending());
        QVERIFY(!photo->isEnabled());  // one photograph per frame

        QSignalSpy changed(&m_command, &CommandState::changed);
        m_command.frameSent();
        QCOMPARE(changed.count(), 1);
        QCOMPARE(fieldName(m_command.message().cameras[0], take_one_photo, 0), QStringLiteral("NONE"));
        QCOMPARE(changedItems(atRest, m_command.message()), QStringList{});
        QVERIFY(!m_command.oneShotPending());
        QVERIFY(photo->isEnabled());

        // The next frame sent changes nothing more.
        m_command.frameSent();
        QCOMPARE(changed.count(), 1);

        // The simulated aircraft takes exactly one photograph for the click.
        SimulatedAircraft aircraft;
        QTest::mouseClick(photo, Qt::LeftButton);
        aircraft.apply(m_command.message());
        m_command.frameSent();
        aircraft.apply(m_command.message());
        aircraft.apply(m_command.message());
        QCOMPARE(aircraft.photoCount(0), 1);
        QCOMPARE(aircraft.photoCount(1), 0);
    }

    void headerPanel()
    {
        auto panel = shown<HeaderPanel>();
        auto* source = child<StationEditor>(panel.get(), QStringLiteral("ID_UA_source"));
        QVERIFY(source);
        QVERIFY(!m_command.message().header.has(ID_UA_source));
        // The field shows its placeholder, "GB" and a four-digit code such as 1929 whole.
        const QLineEdit* country = source->countryEdit();
        QStyleOptionFrame frame;
        frame.initFrom(country);
        frame.lineWidth = country->style()->pixelMetric(QStyle::PM_DefaultFrameWidth, &frame, country);
        // Where QLineEdit draws text: the style's contents rectangle, less its 2 px inner margin each side.
        const QRect text = country->style()
                               ->subElementRect(QStyle::SE_LineEditContents, &frame, country)
                               .marginsRemoved(country->textMargins())
                               .adjusted(2, 0, -2, 0);
        for (const QString& sample : {country->placeholderText(), QStringLiteral("GB"), QStringLiteral("1929")})
            QVERIFY2(country->fontMetrics().horizontalAdvance(sample) <= text.width(), qPrintable(sample));

        Message before = m_command.message();
        typeInto(source->countryEdit(), QStringLiteral("gb"));
        typeInto(source->unitEdit(), QStringLiteral("133"));
        QCOMPARE(changedItems(before, m_command.message()), QStringList{QStringLiteral("HEADER ID_UA_source")});
        QCOMPARE(*m_command.message().header.find(ID_UA_source), Value::station({44, 133}));
        QCOMPARE(source->countryEdit()->text(), QStringLiteral("GB"));

        // A dialling code is as good as the two letters.
        before = m_command.message();
        auto* backup = child<StationEditor>(panel.get(), QStringLiteral("ID_GCS_backup"));
        typeInto(backup->unitEdit(), QStringLiteral("41251"));
        QCOMPARE(changedItems(before, m_command.message()), QStringList{});  // no country yet: not sent
        typeInto(backup->countryEdit(), QStringLiteral("49"));
        QCOMPARE(changedItems(before, m_command.message()), QStringList{QStringLiteral("HEADER ID_GCS_backup")});
        QCOMPARE(*m_command.message().header.find(ID_GCS_backup), Value::station({49, 41251}));
        QCOMPARE(backup->countryEdit()->text(), QStringLiteral("DE"));

        // No such country: refused where it was typed, the command keeps its value.
        before = m_command.message();
        QSignalSpy changed(&m_command, &CommandState::changed);
        typeInto(source->countryEdit(), QStringLiteral("XX"));
        QCOMPARE(changed.count(), 0);
        QVERIFY(source->countryEdit()->property("invalid").toBool());
        QCOMPARE(source->countryEdit()->text(), QStringLiteral("XX"));
        typeInto(source->countryEdit(), QStringLiteral("2000"));  // above the table's 1929
        QCOMPARE(changed.count(), 0);
        QCOMPARE(m_command.message(), before);

        // Country and unit both empty: the item is no longer sent.
        typeInto(source->countryEdit(), QString());
        QVERIFY(source->incomplete());  // a unit without a country is not a station
        QCOMPARE(m_command.message(), before);
        typeInto(source->unitEdit(), QString());
        QCOMPARE(changedItems(before, m_command.message()), QStringList{QStringLiteral("HEADER ID_UA_source")});
        QVERIFY(!m_command.message().header.has(ID_UA_source));
        QVERIFY(!source->countryEdit()->property("invalid").toBool());
        QVERIFY(!source->incomplete());
    }

    void statusFramesFillTheReportedValues()
    {
        auto engines = shown<EnginePanel>();
        auto radios = shown<RadioPanel>();
        auto header = shown<HeaderPanel>();
        auto* pitch = child<ReportedLabel>(child<UnitCard>(engines.get(), QStringLiteral("engine 3")),
                                           QStringLiteral("reported:eng_prop_pitch"));
        QVERIFY(pitch);
        QCOMPARE(pitch->text(), QStringLiteral("\u2014"));

        SimulatedAircraft aircraft;
        m_command.setNumber({UnitKind::Engine, 2}, eng_prop_pitch, 77);
        m_command.setNumber({UnitKind::Radio, 0}, Rx_freq, 127712);
        aircraft.apply(m_command.message());
        QSignalSpy updated(&m_reported, &ReportedState::updated);
        m_reported.onStatus(aircraft.status(kT0));
        QCOMPARE(updated.count(), 1);
        QCOMPARE(m_reported.statusFrames(), 1);
        QCOMPARE(pitch->text(), QStringLiteral("30.2 %"));  // 77 of 255
        QVERIFY(!pitch->mismatch());
        auto* rx = child<ReportedLabel>(child<UnitCard>(radios.get(), QStringLiteral("radio VHF1")),
                                        QStringLiteral("reported:Rx_freq"));
        QCOMPARE(rx->text(), QStringLiteral("127.712 MHz"));
        auto* receiver = child<ReportedLabel>(child<UnitCard>(radios.get(), QStringLiteral("radio VHF1")),
                                              QStringLiteral("reported:receiver_control.receiver"));
        QCOMPARE(receiver->text(), QStringLiteral("Off"));
        // The aircraft's identity, though the console has not commanded one.
        QCOMPARE(child<ReportedLabel>(header.get(), QStringLiteral("reported:ID_UA_source"))->text(),
                 QStringLiteral("GB_133"));
        QCOMPARE(*m_reported.value({UnitKind::Header, 0}, ID_msg), Value::of(0));
    }

    void unitsAreMatchedByKeyNotByPosition()
    {
        Message status = m_command.message();
        std::swap(status.radios[0], status.radios[2]);  // VHF3, VHF2, VHF1
        status.radios[0].set(Tx_OP_power, 33);          // VHF3
        m_reported.onStatus(status);
        QCOMPARE(*m_reported.value({UnitKind::Radio, 2}, Tx_OP_power), Value::of(33));
        QCOMPARE(*m_reported.value({UnitKind::Radio, 0}, Tx_OP_power), Value::of(0));
        QCOMPARE(m_reported.mismatchFrames({UnitKind::Radio, 2}, Tx_OP_power), 1);
        QCOMPARE(m_reported.mismatchFrames({UnitKind::Radio, 0}, Tx_OP_power), 0);
    }

    // Not selectable with the mouse (that costs a rich-text layout per new
    // value): its context menu copies it.
    void reportedValueCopiedFromItsMenu()
    {
        auto panel = shown<FlapsPanel>();
        auto* rudder = child<ReportedLabel>(panel.get(), QStringLiteral("reported:F_rudder_set"));
        QVERIFY(rudder);
        Message status = m_command.message();
        status.flaps.set(F_rudder_set, -7);
        m_reported.onStatus(status);
        QCOMPARE(rudder->text(), QStringLiteral("-7\u00b0"));
        QCOMPARE(rudder->contextMenuPolicy(), Qt::ActionsContextMenu);
        QCOMPARE(rudder->actions().size(), 1);
        QCOMPARE(rudder->actions().at(0)->text(), QStringLiteral("Copy"));
        QGuiApplication::clipboard()->clear();
        rudder->actions().at(0)->trigger();
        QCOMPARE(QGuiApplication::clipboard()->text(), QStringLiteral("-7\u00b0"));
    }

    // A new text that fits repaints the label alone: its layout is not asked
    // for room and its neighbour stays put. A longer one grows it, once, and
    // it is never left clipped.
    // A steady group box looks like a QGroupBox, and a value changing inside
    // it does not draw its frame again; a new size or title does.
    void steadyGroupBoxDrawsItsFrameOnce()
    {
        const auto card = [](QGroupBox* box, const QString& value) {
            auto* layout = new QHBoxLayout(box);
            auto* label = new QLabel(value);
            layout->addWidget(label);
            box->resize(240, 90);
            return label;
        };
        SteadyGroupBox steady(QStringLiteral("Engine 1"));
        QGroupBox plain(QStringLiteral("Engine 1"));
        QLabel* value = card(&steady, QStringLiteral("1,200 rpm"));
        card(&plain, QStringLiteral("1,200 rpm"));
        const QImage drawn = steady.grab().toImage().convertToFormat(QImage::Format_ARGB32);
        const QImage expected = plain.grab().toImage().convertToFormat(QImage::Format_ARGB32);
        QCOMPARE(drawn.size(), expected.size());
        int worst = 0;
        for (int y = 0; y < drawn.height(); ++y)
            for (int x = 0; x < drawn.width(); ++x) {
                const QRgb a = drawn.pixel(x, y), b = expected.pixel(x, y);
                worst = std::max({worst, std::abs(qRed(a) - qRed(b)), std::abs(qGreen(a) - qGreen(b)),
                                  std::abs(qBlue(a) - qBlue(b)), std::abs(qAlpha(a) - qAlpha(b))});
            }
        QVERIFY2(worst <= 2, qPrintable(QString::number(worst)));  // compositing rounds, no more
        QCOMPARE(steady.framesDrawn(), 1);

        steady.show();
        QVERIFY(QTest::qWaitForWindowExposed(&steady));
        QTRY_VERIFY(steady.framesDrawn() >= 1);
        const int drawnOnShow = steady.framesDrawn();
        for (const char* text : {"1,210 rpm", "1,220 rpm", "900 rpm"}) {
            value->setText(QLatin1String(text));
            steady.repaint();
        }
        QCOMPARE(steady.framesDrawn(), drawnOnShow);
        steady.resize(260, 90);
        steady.repaint();
        QCOMPARE(steady.framesDrawn(), drawnOnShow + 1);
        steady.setTitle(QStringLiteral("Engine 2"));
        steady.repaint();
        QCOMPARE(steady.framesDrawn(), drawnOnShow + 2);
    }

    // A label scrolled out of view is never painted; fitted when shown, a
    // new text of it still asks nothing of the layouts above it.
    void steadyLabelFittedOutOfView()
    {
        QScrollArea area;
        auto* page = new QWidget;
        auto* column = new QVBoxLayout(page);
        column->addSpacing(2000);
        auto* figure = new SteadyLabel(QStringLiteral("1,234"));
        column->addWidget(figure);
        area.setWidget(page);
        area.resize(300, 200);
        area.show();
        QVERIFY(QTest::qWaitForWindowExposed(&area));
        QTRY_COMPARE(figure->minimumSize(), figure->maximumSize());
        QVERIFY(figure->visibleRegion().isEmpty());  // never painted
        QCoreApplication::processEvents();
        EventCounter requests(page, QEvent::LayoutRequest);
        figure->setText(QStringLiteral("7"));
        QCoreApplication::processEvents();
        QCOMPARE(requests.count(), 0);
    }

    void steadyLabelKeepsItsSize()
    {
        QWidget row;
        auto* layout = new QHBoxLayout(&row);
        auto* figure = new SteadyLabel(QStringLiteral("1,234"));
        auto* neighbour = new QLabel(QStringLiteral("frames"));
        layout->addWidget(figure);
        layout->addWidget(neighbour);
        layout->addStretch(1);
        row.show();
        QVERIFY(QTest::qWaitForWindowExposed(&row));
        QTRY_COMPARE(figure->minimumSize(), figure->maximumSize());  // fixed once painted
        QTRY_COMPARE(figure->size(), figure->minimumSize());
        const QSize fitted = figure->size();
        QVERIFY(fitted.width() >= figure->sizeHint().width());
        const int neighbourX = neighbour->x();
        QCoreApplication::processEvents();  // the layout request of the fit itself
        EventCounter requests(&row, QEvent::LayoutRequest);

        figure->setText(QStringLiteral("7"));
        QCoreApplication::processEvents();
        QCoreApplication::processEvents();
        QCOMPARE(requests.count(), 0);
        QCOMPARE(figure->size(), fitted);
        QCOMPARE(neighbour->x(), neighbourX);

        figure->setText(QStringLiteral("123,456,789"));
        QTRY_VERIFY(figure->width() >= figure->sizeHint().width());
        QVERIFY(figure->width() > fitted.width());
        QTRY_VERIFY(neighbour->x() > neighbourX);
        QVERIFY(requests.count() > 0);

        // A new font is fitted anew: to the text it shows now.
        figure->setText(QStringLiteral("7"));
        QFont big = figure->font();
        big.setPointSizeF(big.pointSizeF() * 2);
        figure->setFont(big);
        QTRY_COMPARE(figure->size(), figure->sizeHint().expandedTo(figure->minimumSizeHint()));
    }

    void mismatchHighlightedOnlyWhenItPersists()
    {
        auto panel = shown<FlapsPanel>();
        auto* rudder = child<ReportedLabel>(panel.get(), QStringLiteral("reported:F_rudder_set"));
        QVERIFY(rudder);
        const UnitRef flaps{UnitKind::Flaps, 0};

        // One frame off (a surface on its way): not highlighted.
        Message status = m_command.message();
        status.flaps.set(F_rudder_set, 5);
        m_reported.onStatus(status);
        QCOMPARE(rudder->text(), QStringLiteral("5\u00b0"));
        QCOMPARE(m_reported.mismatchFrames(flaps, F_rudder_set), 1);
        QVERIFY(!rudder->mismatch());
        m_reported.onStatus(m_command.message());
        QCOMPARE(m_reported.mismatchFrames(flaps, F_rudder_set), 0);
        QVERIFY(!rudder->mismatch());

        // Three frames off: highlighted, with what was commanded and what is reported.
        for (int frame = 1; frame <= 3; ++frame) {
            m_reported.onStatus(status);
            QCOMPARE(rudder->mismatch(), frame == 3);
            QCOMPARE(m_reported.mismatchPersistent(flaps, F_rudder_set), frame == 3);
        }
        QVERIFY(rudder->styleSheet().contains(QStringLiteral("background")));
        QVERIFY2(rudder->toolTip().contains(QStringLiteral("commanded 0\u00b0, reported 5\u00b0")),
                 qPrintable(rudder->toolTip()));

        // A new command restarts the count: the aircraft has not had a frame to answer it.
        m_command.setNumber(flaps, F_rudder_set, 3);
        QVERIFY(!rudder->mismatch());
        QCOMPARE(m_reported.mismatchFrames(flaps, F_rudder_set), 0);
        // The report agrees: the highlight has gone.
        m_command.setNumber(flaps, F_rudder_set, 5);
        m_reported.onStatus(status);
        QVERIFY(!rudder->mismatch());
        QVERIFY(rudder->styleSheet().isEmpty());

        // A frame without the item ends the run.
        Message other = status;
        other.flaps.set(F_rudder_set, 9);
        m_reported.onStatus(other);
        m_reported.onStatus(other);
        other.flaps.erase(F_rudder_set);
        m_reported.onStatus(other);
        QCOMPARE(m_reported.mismatchFrames(flaps, F_rudder_set), 0);
        QCOMPARE(rudder->text(), QStringLiteral("9\u00b0"));  // still the last value reported
    }

    void satelliteDelayIsNotAMismatch()
    {
        // A satellite's 1.5 s each way: status frames for three seconds after
        // a change still answer the command before it.
        auto now = std::chrono::steady_clock::time_point{};
        ReportedState reported(&m_command, nullptr, [&now] { return now; });
        reported.setLinkDelay(std::chrono::milliseconds(1500));
        const UnitRef flaps{UnitKind::Flaps, 0};
        reported.onStatus(m_command.message());
        const Message before = m_command.message();
        m_command.setNumber(flaps, F_rudder_set, 7);
        for (int frame = 0; frame < 3; ++frame) {  // at 0, 1 and 2 s after the change
            reported.onStatus(before);
            QCOMPARE(reported.mismatchFrames(flaps, F_rudder_set), 0);
            now += std::chrono::seconds(1);
        }
        // From 3 s on the aircraft has had the change: disagreeing frames count again.
        for (int frame = 1; frame <= 3; ++frame) {
            reported.onStatus(before);
            QCOMPARE(reported.mismatchFrames(flaps, F_rudder_set), frame);
            now += std::chrono::seconds(1);
        }
        QVERIFY(reported.mismatchPersistent(flaps, F_rudder_set));
        // Without the delay the same frames count from the first.
        ReportedState direct(&m_command, nullptr, [&now] { return now; });
        direct.onStatus(before);
        QCOMPARE(direct.mismatchFrames(flaps, F_rudder_set), 1);
    }

    void gearInTransitIsHighlightedPerWheel()
    {
        auto panel = shown<GearPanel>();
        const UnitRef settings{UnitKind::Settings, 0};
        auto* nose = child<ReportedLabel>(panel.get(), QStringLiteral("reported:land_wheels.NOSE"));
        auto* tail = child<ReportedLabel>(panel.get(), QStringLiteral("reported:land_wheels.TAIL"));
        QVERIFY(nose && tail);

        SimulatedAircraft aircraft;
        QTest::mouseClick(codeButton(panel.get(), QStringLiteral("land_wheels.NOSE"), QStringLiteral("RETRACTED")),
                          Qt::LeftButton);
        // A frame a second: the command goes out, the aircraft moves, its status comes back.
        auto frame = [&](int n) {
            aircraft.apply(m_command.message());
            m_command.frameSent();
            aircraft.advance(std::chrono::seconds(1));
            m_reported.onStatus(aircraft.status(kT0 + std::chrono::seconds(n)));
            aircraft.statusSent();
        };
        frame(1);
        QCOMPARE(nose->text(), QStringLiteral("Out (down)"));
        QVERIFY(!nose->mismatch());
        frame(2);
        QVERIFY(!nose->mismatch());
        frame(3);
        QVERIFY(aircraft.gearMoving());
        QVERIFY(nose->mismatch());
        QVERIFY(m_reported.mismatchPersistent(settings, land_wheels, 2));
        QVERIFY(m_reported.mismatchPersistent(settings, land_wheels));
        QVERIFY2(nose->toolTip().contains(QStringLiteral("commanded Retracted, reported Out (down)")),
                 qPrintable(nose->toolTip()));
        QVERIFY(!tail->mismatch());  // the other wheels agree
        QVERIFY(!m_reported.mismatchPersistent(settings, land_wheels, 3));
        frame(4);
        QVERIFY(!aircraft.gearMoving());
        QCOMPARE(nose->text(), QStringLiteral("Retracted"));
        QVERIFY(!nose->mismatch());
    }

    void panelsFollowTheAirframe()
    {
        auto engines = shown<EnginePanel>();
        auto radios = shown<RadioPanel>();
        auto cameras = shown<CameraPanel>();
        auto header = shown<HeaderPanel>();
        m_command.setNumber({UnitKind::Header, 0}, ID_UA_source, 0);  // refused: country 0
        m_command.setItem({UnitKind::Header, 0}, ID_UA_source, Value::station({44, 133}));
        SimulatedAircraft aircraft;
        aircraft.apply(m_command.message());
        m_reported.onStatus(aircraft.status(kT0));

        QSignalSpy airframeChanged(&m_command, &CommandState::airframeChanged);
        m_command.setAirframe(smallAirframe());
        QCOMPARE(airframeChanged.count(), 1);
        QCOMPARE(m_reported.statusFrames(), 0);  // another aircraft: nothing reported yet

        QCOMPARE(engines->findChildren<UnitCard*>().size(), 1);
        QCOMPARE(radios->findChildren<UnitCard*>().size(), 2);
        QCOMPARE(cameras->findChildren<UnitCard*>().size(), 1);  // no sense and avoid on this one
        QVERIFY(child<UnitCard>(radios.get(), QStringLiteral("radio UHF7")));
        QVERIFY(child<UnitCard>(cameras.get(), QStringLiteral("camera SNY 4")));
        QVERIFY(!cameras->findChild<UnitCard*>(QStringLiteral("SENSE")));
        QCOMPARE(m_command.message().engines.size(), std::size_t(1));
        // The header names who talks to whom, not what the aircraft carries: kept.
        QCOMPARE(*m_command.message().header.find(ID_UA_source), Value::station({44, 133}));

        // The new cards command the new airframe's units, once the layout has shown them.
        Message before = m_command.message();
        auto* uhf = child<UnitCard>(radios.get(), QStringLiteral("radio UHF7"));
        auto* transmitterOn = codeButton(uhf, QStringLiteral("receiver_control.transmitter"), QStringLiteral("ON"));
        QTRY_VERIFY(transmitterOn->isVisible() && !transmitterOn->rect().isEmpty());
        QTest::mouseClick(transmitterOn, Qt::LeftButton);
        QCOMPARE(changedItems(before, m_command.message()), QStringList{QStringLiteral("radio UHF7 receiver_control")});

        before = m_command.message();
        typeInto(child<ItemSpinBox>(engines.get(), QStringLiteral("eng_prop_pitch")), QStringLiteral("42"));  // %
        QCOMPARE(changedItems(before, m_command.message()), QStringList{QStringLiteral("engine 1 eng_prop_pitch")});

        before = m_command.message();
        auto* photo = child<QPushButton>(cameras.get(), QStringLiteral("take_one_photo"));
        QTRY_VERIFY(photo->isVisible() && !photo->rect().isEmpty());
        QTest::mouseClick(photo, Qt::LeftButton);
        QCOMPARE(changedItems(before, m_command.message()), QStringList{QStringLiteral("camera SNY 4 take_one_photo")});

        // And the reports of the new aircraft reach them.
        SimulatedAircraft small(smallAirframe());
        small.apply(m_command.message());
        m_reported.onStatus(small.status(kT0));
        QCOMPARE(child<ReportedLabel>(engines.get(), QStringLiteral("reported:eng_prop_pitch"))->text(),
                 QStringLiteral("42.0 %"));
        QCOMPARE(child<ReportedLabel>(uhf, QStringLiteral("reported:receiver_control.transmitter"))->text(),
                 QStringLiteral("On"));

        // Back to the big one: engine 1 keeps what it was commanded, units
        // the small one lacked come at rest, and none of the small one's is
        // left but its radio UHF7 and camera SNY 4.
        const std::vector<Unit> left = m_command.setAirframe(Airframe::wellEquipped());
        QCOMPARE(m_command.message().engines.at(0).number(eng_prop_pitch), 107);
        QCOMPARE(m_command.message().engines.at(1).number(eng_prop_pitch), 0);
        QCOMPARE(left.size(), std::size_t(2));
        QCOMPARE(describeUnit(left[0]), std::string("radio UHF7"));
        QCOMPARE(describeUnit(left[1]), std::string("camera SNY 4"));
        QCOMPARE(engines->findChildren<UnitCard*>().size(), 3);
        QCOMPARE(radios->findChildren<UnitCard*>().size(), 3);
        QCOMPARE(cameras->findChildren<UnitCard*>().size(), 3);
    }
};

}  // namespace

QTEST_MAIN(TestPanels)
#include "tst_panels.moc"
