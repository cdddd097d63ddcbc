#include "ui/panels/FieldComboBox.h"

#include "ui/panels/CommandGate.h"
#include "ui/panels/CommandState.h"
#include "ui/panels/DeliberateInput.h"
#include "ui/panels/ItemText.h"

#include <QKeyEvent>
#include <QSignalBlocker>

FieldComboBox::FieldComboBox(CommandState* command, UnitRef ref, rcm::ItemId id, int field, QWidget* parent)
    : QComboBox(parent), m_command(command), m_ref(ref), m_id(id), m_field(field)
{
    setObjectName(ItemText::name(id, field));
    for (unsigned code : ItemText::validFieldCodes(id, field))
        addItem(ItemText::fieldCodeWord(id, field, code, command->unit(ref)), code);
    const QString rule = CommandGate::ruleText(id, field);
    setToolTip(ItemText::fieldToolTip(id, field) + (rule.isEmpty() ? QString() : QLatin1Char('\n') + rule));
    setAccessibleName(ItemText::label(id, field));
    DeliberateInput::protect(this);
    refresh();
    connect(this, &QComboBox::currentIndexChanged, this, &FieldComboBox::commit);
    connect(command, &CommandState::changed, this, &FieldComboBox::refresh);
}

void FieldComboBox::refresh()
{
    const bool commanded = m_command->value(m_ref, m_id) != nullptr;
    setEnabled(commanded);
    // A code not in the list (nothing commanded yet) shows as no selection.
    const int index = commanded ? findData(m_command->fieldCode(m_ref, m_id, m_field)) : -1;
    if (index != currentIndex()) {
        const QSignalBlocker block(this);
        setCurrentIndex(index);
    }
}

void FieldComboBox::commit(int index)
{
    if (index < 0 || !CommandGate::of(m_command)->setFieldCode(this, m_ref, m_id, m_field, itemData(index).toUInt()))
        refresh();
}

void FieldComboBox::keyPressEvent(QKeyEvent* event)
{
    // Keys that open the list go through; the arrows, Home, End and letters
    // that would change the selection in place are not the combo box's.
    const bool alt = event->modifiers() & Qt::AltModifier;
    const int key = event->key();
    if (key == Qt::Key_Space || key == Qt::Key_F4 || (alt && (key == Qt::Key_Down || key == Qt::Key_Up)))
        QComboBox::keyPressEvent(event);
    else
        event->ignore();
}
