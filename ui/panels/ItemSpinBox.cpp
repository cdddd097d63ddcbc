#include "ui/panels/ItemSpinBox.h"

#include "ui/panels/CommandGate.h"
#include "ui/panels/CommandState.h"
#include "ui/panels/DeliberateInput.h"
#include "ui/panels/ItemText.h"

#include <QFocusEvent>
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
        m_notSent.clear();
        showState();
    });
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
    m_notSent.clear();
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
            QDoubleSpinBox::keyPressEvent(event);  // takes the text as the value
            commit();
            return;
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

QString ItemSpinBox::defaultToolTip() const
{
    QString tip = ItemText::toolTip(m_id) + QLatin1Char('\n') +
                  tr("Enter sends a typed or stepped value; leaving the field does not.");
    if (const QString rule = CommandGate::ruleText(m_id); !rule.isEmpty())
        tip += QLatin1Char('\n') + rule;
    return tip;
}

void ItemSpinBox::focusOutEvent(QFocusEvent* event)
{
    // A context menu over the text is still this field; a question the gate
    // asks on Enter is that Enter's, not the operator leaving.
    if (m_edited && event->reason() != Qt::PopupFocusReason && !CommandGate::of(m_command)->asking()) {
        const QString left = lineEdit()->text().trimmed();
        const auto typed = ItemText::parseNumber(m_id, left);
        const rcm::Value* v = m_command->value(m_ref, m_id);
        m_edited = false;
        if (!typed || !v || v->number != *typed)
            restoreUnsent(left);
        else
            refresh();
    }
    QDoubleSpinBox::focusOutEvent(event);
}

void ItemSpinBox::restoreUnsent(const QString& left)
{
    const rcm::Value* v = m_command->value(m_ref, m_id);
    m_edited = false;
    m_notSent = tr("Not sent: '%1' was left unsent; the command stays %2")
                    .arg(left, v ? ItemText::value(m_id, *v) : tr("nothing"));
    refresh();
    CommandGate::of(m_command)->tellNotSent(m_ref, m_id, m_notSent);
}

void ItemSpinBox::commit()
{
    const QString typedText = lineEdit()->text().trimmed();
    const auto typed = ItemText::parseNumber(m_id, typedText);
    if (!typed)
        return;
    const bool edited = m_edited;
    m_edited = false;
    m_notSent.clear();
    if (CommandGate::of(m_command)->setNumber(this, m_ref, m_id, *typed)) {
        showState();
        return;
    }
    // Cancelled or refused: the command as it was, and the box says so.
    const rcm::Value* v = m_command->value(m_ref, m_id);
    if (edited && (!v || v->number != *typed))
        m_notSent =
            tr("Not sent: '%1'; the command stays %2").arg(typedText, v ? ItemText::value(m_id, *v) : tr("nothing"));
    refresh();
}

void ItemSpinBox::showState()
{
    const auto typed = ItemText::parseNumber(m_id, lineEdit()->text());
    const bool invalid = !typed;
    const rcm::Value* v = m_command->value(m_ref, m_id);
    const bool edited = !invalid && m_edited && v && v->number != *typed;
    if (invalid != property("invalid").toBool() || edited != property("edited").toBool()) {
        setProperty("invalid", invalid);
        setProperty("edited", edited);
        setStyleSheet(invalid  ? DeliberateInput::invalidStyle("QDoubleSpinBox")
                      : edited ? DeliberateInput::editedStyle("QDoubleSpinBox")
                               : QString());
    }
    const QString commanded = v ? ItemText::value(m_id, *v) : tr("nothing");
    QString tip;
    if (invalid)
        tip = tr("Not a valid %1 (%2): not sent; the command stays %3")
                  .arg(ItemText::label(m_id), ItemText::toolTip(m_id), commanded);
    else if (edited)
        tip = tr("Not sent yet: Enter sends it, Esc or leaving the field goes back to the command (%1)").arg(commanded);
    else if (!m_notSent.isEmpty())
        tip = m_notSent;
    else
        tip = defaultToolTip();
    if (tip != toolTip())
        setToolTip(tip);
}
