#include "ui/panels/FieldButtonGroup.h"

#include "ui/panels/CommandGate.h"
#include "ui/panels/CommandState.h"
#include "ui/panels/DeliberateInput.h"
#include "ui/panels/ItemText.h"

#include <QButtonGroup>
#include <QHBoxLayout>
#include <QKeyEvent>
#include <QRadioButton>

FieldButtonGroup::FieldButtonGroup(CommandState* command, UnitRef ref, rcm::ItemId id, int field, QWidget* parent)
    : QWidget(parent), m_command(command), m_ref(ref), m_id(id), m_field(field), m_group(new QButtonGroup(this))
{
    setObjectName(ItemText::name(id, field));
    const QString rule = CommandGate::ruleText(id, field);
    setToolTip(ItemText::fieldToolTip(id, field) + (rule.isEmpty() ? QString() : QLatin1Char('\n') + rule));
    setAccessibleName(ItemText::label(id, field));
    auto* layout = new QHBoxLayout(this);
    layout->setContentsMargins(0, 0, 0, 0);
    for (unsigned code : ItemText::validFieldCodes(id, field)) {
        auto* button = new QRadioButton(ItemText::fieldCodeWord(id, field, code), this);
        button->setObjectName(ItemText::fieldCodeName(id, field, code));
        DeliberateInput::protect(button);
        button->installEventFilter(this);
        m_group->addButton(button, static_cast<int>(code));
        layout->addWidget(button);
    }
    layout->addStretch();
    refresh();
    connect(m_group, &QButtonGroup::idClicked, this, &FieldButtonGroup::commit);
    connect(command, &CommandState::changed, this, &FieldButtonGroup::refresh);
}

bool FieldButtonGroup::eventFilter(QObject* watched, QEvent* event)
{
    // In an exclusive group an arrow key checks the next button: a stray key
    // would switch a light or a wheel. Space or a click on the button does.
    if (event->type() == QEvent::KeyPress) {
        switch (static_cast<QKeyEvent*>(event)->key()) {
            case Qt::Key_Left:
            case Qt::Key_Right:
            case Qt::Key_Up:
            case Qt::Key_Down:
                return true;
            default:
                break;
        }
    }
    return QWidget::eventFilter(watched, event);
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
    const QString detail = m_detail ? m_detail(wanted) : QString();
    // The click checked the button already: until the operator confirms, it
    // shows what is commanded, not what the question asks about.
    refresh();
    if (!CommandGate::of(m_command)->setFieldCode(this, m_ref, m_id, m_field, wanted, detail))
        refresh();
}
