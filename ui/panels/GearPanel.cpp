#include "ui/panels/GearPanel.h"

#include "ui/panels/CommandGate.h"
#include "ui/panels/CommandState.h"
#include "ui/panels/DeliberateInput.h"
#include "ui/panels/UnitCard.h"

#include <QHBoxLayout>
#include <QPushButton>
#include <QVBoxLayout>

namespace {

constexpr rcm::ItemId kItem = rcm::ItemId::land_wheels;
const UnitRef kUnit{rcm::UnitKind::Settings, 0};

}  // namespace

GearPanel::GearPanel(CommandState* command, ReportedState* reported, QWidget* parent)
    : QWidget(parent), m_command(command)
{
    setObjectName(QStringLiteral("GearPanel"));
    UnitCard* card = UnitCard::ofFields(command, reported, kUnit, kItem, this);
    m_allUp = new QPushButton(tr("All up"));
    m_allUp->setObjectName(QStringLiteral("allUp"));
    m_allUp->setToolTip(tr("Retract every wheel: asks first, as each wheel's retraction does"));
    m_allDown = new QPushButton(tr("All down"));
    m_allDown->setObjectName(QStringLiteral("allDown"));
    m_allDown->setToolTip(tr("Every wheel out (down)"));
    for (QPushButton* b : {m_allUp, m_allDown}) {
        // As the field buttons: a stray key after a click presses nothing again.
        b->setFocusPolicy(Qt::NoFocus);
        DeliberateInput::protect(b);
    }
    connect(m_allUp, &QPushButton::clicked, this, [this] { setAll(rcm::code::kRetracted); });
    connect(m_allDown, &QPushButton::clicked, this, [this] { setAll(rcm::code::kOut); });
    auto* all = new QHBoxLayout;
    all->addWidget(m_allDown);
    all->addWidget(m_allUp);
    all->addStretch(1);
    auto* column = new QVBoxLayout;
    column->setContentsMargins(0, 0, 0, 0);
    column->addWidget(card);
    column->addLayout(all);
    auto* layout = new QHBoxLayout(this);
    layout->addLayout(column);
    refresh();
    connect(command, &CommandState::changed, this, &GearPanel::refresh);
}

bool GearPanel::setAll(unsigned code)
{
    const rcm::Unit* unit = m_command->unit(kUnit);
    if (!unit || !unit->find(kItem))
        return false;
    rcm::Unit changed = *unit;
    for (int field = 0; field < static_cast<int>(rcm::itemInfo(kItem).fields.size()); ++field)
        changed.setFieldCode(kItem, field, code);
    const rcm::Value to = *changed.find(kItem);
    if (to == *unit->find(kItem))
        return true;
    // Retraction goes through the item table's rule like a single wheel's,
    // one question for all of them; lowering never asks.
    return CommandGate::of(m_command)->setItem(code == rcm::code::kRetracted ? m_allUp : m_allDown, kUnit, kItem, to,
                                               {}, tr("Retract all wheels"));
}

void GearPanel::refresh()
{
    const rcm::Value* value = m_command->value(kUnit, kItem);
    const auto every = [&](unsigned code) {
        for (int field = 0; value && field < static_cast<int>(rcm::itemInfo(kItem).fields.size()); ++field)
            if (m_command->fieldCode(kUnit, kItem, field) != code)
                return false;
        return value != nullptr;
    };
    m_allUp->setEnabled(value && !every(rcm::code::kRetracted));
    m_allDown->setEnabled(value && !every(rcm::code::kOut));
}
