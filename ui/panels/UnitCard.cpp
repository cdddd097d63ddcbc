#include "ui/panels/UnitCard.h"

#include "ui/panels/CommandState.h"
#include "ui/panels/FieldButtonGroup.h"
#include "ui/panels/FieldComboBox.h"
#include "ui/panels/ItemSpinBox.h"
#include "ui/panels/ItemText.h"
#include "ui/panels/ReportedLabel.h"
#include "ui/panels/StationEditor.h"

#include <QGridLayout>
#include <QLabel>

namespace {

enum Column { LabelColumn, ControlColumn, ReportedColumn, SpareColumn };

}  // namespace

UnitCard::UnitCard(CommandState* command, ReportedState* reported, UnitRef ref, const QString& title, QWidget* parent)
    : SteadyGroupBox(title, parent), m_command(command), m_reported(reported), m_ref(ref), m_grid(new QGridLayout(this))
{
    if (const rcm::Unit* unit = command->unit(ref))
        setObjectName(QString::fromStdString(rcm::describeUnit(*unit)));
    // Controls at their own width and the reported value right beside each;
    // the spare width goes after them, not between a control and its report.
    m_grid->setColumnStretch(SpareColumn, 1);
    // What the operator sets and what the aircraft says, headed as such: a
    // heading, told from the values by its shape (italic) rather than a faint colour.
    QFont headingFont = font();
    headingFont.setItalic(true);
    for (const auto& [column, text] : {std::pair{ControlColumn, tr("Commanded")}, std::pair{ReportedColumn, tr("Reported")}}) {
        auto* heading = new QLabel(text, this);
        heading->setObjectName(QStringLiteral("heading:") + text);
        heading->setFont(headingFont);
        m_grid->addWidget(heading, m_rows, column);
    }
    ++m_rows;
}

UnitCard* UnitCard::ofFields(CommandState* command, ReportedState* reported, UnitRef ref, rcm::ItemId id,
                             QWidget* parent)
{
    auto* card = new UnitCard(command, reported, ref, ItemText::label(id), parent);
    for (int field = 0; field < static_cast<int>(rcm::itemInfo(id).fields.size()); ++field)
        card->addButtons(id, field);
    return card;
}

ReportedLabel* UnitCard::addRow(QWidget* control, rcm::ItemId id, int field)
{
    auto* label = new QLabel(ItemText::label(id, field), this);
    label->setBuddy(control);
    auto* reported = new ReportedLabel(m_command, m_reported, m_ref, id, field, this);
    m_grid->addWidget(label, m_rows, LabelColumn);
    m_grid->addWidget(control, m_rows, ControlColumn);
    m_grid->addWidget(reported, m_rows, ReportedColumn);
    ++m_rows;
    return reported;
}

ItemSpinBox* UnitCard::addSpinBox(rcm::ItemId id)
{
    auto* spinBox = new ItemSpinBox(m_command, m_ref, id, this);
    addRow(spinBox, id);
    return spinBox;
}

FieldComboBox* UnitCard::addComboBox(rcm::ItemId id, int field)
{
    auto* comboBox = new FieldComboBox(m_command, m_ref, id, field, this);
    addRow(comboBox, id, field);
    return comboBox;
}

FieldButtonGroup* UnitCard::addButtons(rcm::ItemId id, int field)
{
    auto* buttons = new FieldButtonGroup(m_command, m_ref, id, field, this);
    addRow(buttons, id, field);
    return buttons;
}

StationEditor* UnitCard::addStation(rcm::ItemId id)
{
    auto* editor = new StationEditor(m_command, m_ref, id, this);
    addRow(editor, id);
    return editor;
}

void UnitCard::addKey()
{
    const auto key = rcm::unitKey(m_ref.kind);
    if (!key)
        return;
    const rcm::Value* v = m_command->value(m_ref, *key);
    auto* value = new QLabel(v ? ItemText::value(*key, *v) : QString(), this);
    value->setObjectName(ItemText::name(*key));
    value->setToolTip(ItemText::toolTip(*key) + tr(" (from the airframe)"));
    value->setTextInteractionFlags(Qt::TextSelectableByMouse);
    // The key names the unit in the command and in the report alike: nothing to compare.
    m_grid->addWidget(new QLabel(ItemText::label(*key), this), m_rows, LabelColumn);
    m_grid->addWidget(value, m_rows, ControlColumn, 1, 2);
    ++m_rows;
}
