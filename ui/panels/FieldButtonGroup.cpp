#include "ui/panels/FieldButtonGroup.h"

#include "ui/panels/CommandState.h"
#include "ui/panels/ItemText.h"

#include <QButtonGroup>
#include <QHBoxLayout>
#include <QRadioButton>

FieldButtonGroup::FieldButtonGroup(CommandState* command, UnitRef ref, rcm::ItemId id, int field, QWidget* parent)
    : QWidget(parent), m_command(command), m_ref(ref), m_id(id), m_field(field), m_group(new QButtonGroup(this))
{
    setObjectName(ItemText::name(id, field));
    setToolTip(ItemText::fieldToolTip(id, field));
    setAccessibleName(ItemText::label(id, field));
    auto* layout = new QHBoxLayout(this);
    layout->setContentsMargins(0, 0, 0, 0);
    for (unsigned code : ItemText::validFieldCodes(id, field)) {
        const QString name = ItemText::fieldCodeName(id, field, code);
        auto* button = new QRadioButton(name, this);
        button->setObjectName(name);
        m_group->addButton(button, static_cast<int>(code));
        layout->addWidget(button);
    }
    layout->addStretch();
    refresh();
    connect(m_group, &QButtonGroup::idClicked, this, &FieldButtonGroup::commit);
    connect(command, &CommandState::changed, this, &FieldButtonGroup::refresh);
}

QAbstractButton* FieldButtonGroup::button(unsigned code) const
{
    return m_group->button(static_cast<int>(code));
}

void FieldButtonGroup::refresh()
{
    const bool commanded = m_command->value(m_ref, m_id) != nullptr;
    setEnabled(commanded);
    QAbstractButton* shown = commanded ? button(m_command->fieldCode(m_ref, m_id, m_field)) : nullptr;
    if (shown) {
        shown->setChecked(true);
    } else if (QAbstractButton* checked = m_group->checkedButton()) {
        // An exclusive group will not uncheck its last button by itself.
        m_group->setExclusive(false);
        checked->setChecked(false);
        m_group->setExclusive(true);
    }
}

void FieldButtonGroup::commit(int code)
{
    const auto wanted = static_cast<unsigned>(code);
    if (wanted == m_command->fieldCode(m_ref, m_id, m_field))
        return;
    if ((m_guard && !m_guard(wanted)) || !m_command->setFieldCode(m_ref, m_id, m_field, wanted))
        refresh();
}
