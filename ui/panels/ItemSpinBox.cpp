#include "ui/panels/ItemSpinBox.h"

#include "ui/panels/CommandState.h"
#include "ui/panels/DeliberateInput.h"
#include "ui/panels/ItemText.h"

#include <QKeyEvent>
#include <QLineEdit>
#include <QRegularExpression>
#include <QSignalBlocker>

#include <cmath>

ItemSpinBox::ItemSpinBox(CommandState* command, UnitRef ref, rcm::ItemId id, QWidget* parent)
    : QDoubleSpinBox(parent), m_command(command), m_ref(ref), m_id(id)
{
    const rcm::ItemInfo& info = rcm::itemInfo(id);
    const rcm::Presentation shown = rcm::presentation(info);
    setObjectName(ItemText::name(id));
    setDecimals(0);  // value() counts units on the wire; textFromValue() shows them
    setRange(static_cast<double>(shown.min), static_cast<double>(shown.max));
    setSingleStep(info.scale);  // hundredths of a degree step by whole degrees
    setSuffix(ItemText::unitSuffix(id));
    setToolTip(ItemText::toolTip(id));
    setAccessibleName(ItemText::label(id));
    setKeyboardTracking(false);
    setCorrectionMode(QAbstractSpinBox::CorrectToPreviousValue);
    setAlignment(Qt::AlignRight);
    setProperty("edited", false);
    setProperty("invalid", false);
    DeliberateInput::protect(this);
    refresh();
    connect(lineEdit(), &QLineEdit::textEdited, this, [this] {
        m_edited = true;
        showState();
    });
    connect(this, &QAbstractSpinBox::editingFinished, this, &ItemSpinBox::commit);
    connect(command, &CommandState::changed, this, &ItemSpinBox::refresh);
}

QValidator::State ItemSpinBox::validate(QString& text, int&) const
{
    if (ItemText::parseNumber(m_id, text))
        return QValidator::Acceptable;
    // On the way to a number, or a number outside the range: kept, marked, not sent.
    static const QRegularExpression kPartial(QStringLiteral("^[-+]?[0-9]*\\.?[0-9]*$"));
    QString number = text.trimmed();
    const QString unit = suffix().trimmed();
    if (!unit.isEmpty() && number.endsWith(unit))
        number = number.chopped(unit.size()).trimmed();
    return kPartial.match(number).hasMatch() ? QValidator::Intermediate : QValidator::Invalid;
}

QString ItemSpinBox::textFromValue(double wire) const
{
    return ItemText::number(m_id, std::llround(wire));
}

double ItemSpinBox::valueFromText(const QString& text) const
{
    const auto wire = ItemText::parseNumber(m_id, text);
    return wire ? static_cast<double>(*wire) : value();
}

void ItemSpinBox::stepBy(int steps)
{
    QDoubleSpinBox::stepBy(steps);
    m_edited = true;
    showState();
}

void ItemSpinBox::keyPressEvent(QKeyEvent* event)
{
    switch (event->key()) {
        case Qt::Key_Escape:
            if (m_edited) {
                m_edited = false;
                refresh();
                event->accept();
                return;
            }
            break;
        case Qt::Key_Enter:
        case Qt::Key_Return:
            if (!ItemText::parseNumber(m_id, lineEdit()->text())) {
                showState();  // left on show, marked, for the operator to correct
                event->accept();
                return;
            }
            break;
        default:
            break;
    }
    QDoubleSpinBox::keyPressEvent(event);
}

void ItemSpinBox::refresh()
{
    const rcm::Value* v = m_command->value(m_ref, m_id);
    setEnabled(v != nullptr);
    // Text being typed or stepped stays; otherwise the command, text and all.
    if (v && !m_edited) {
        const QSignalBlocker block(this);
        setValue(static_cast<double>(v->number));
    }
    showState();
}

void ItemSpinBox::commit()
{
    if (!ItemText::parseNumber(m_id, lineEdit()->text()))
        return;
    m_edited = false;
    if (!m_command->setNumber(m_ref, m_id, std::llround(value())))
        refresh();
    else
        showState();
}

void ItemSpinBox::showState()
{
    const auto typed = ItemText::parseNumber(m_id, lineEdit()->text());
    const bool invalid = !typed;
    const rcm::Value* v = m_command->value(m_ref, m_id);
    const bool edited = !invalid && m_edited && v && v->number != *typed;
    if (invalid == property("invalid").toBool() && edited == property("edited").toBool())
        return;
    setProperty("invalid", invalid);
    setProperty("edited", edited);
    setStyleSheet(invalid  ? DeliberateInput::invalidStyle("QDoubleSpinBox")
                  : edited ? DeliberateInput::editedStyle("QDoubleSpinBox")
                           : QString());
    const QString commanded = v ? ItemText::value(m_id, *v) : tr("nothing");
    if (invalid)
        setToolTip(tr("Not a valid %1 (%2): not sent; the command stays %3")
                       .arg(ItemText::label(m_id), ItemText::toolTip(m_id), commanded));
    else if (edited)
        setToolTip(tr("Not sent yet: Enter sends it, Esc goes back to the command (%1)").arg(commanded));
    else
        setToolTip(ItemText::toolTip(m_id));
}
