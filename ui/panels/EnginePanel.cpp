#include "ui/panels/EnginePanel.h"

#include "ui/panels/CommandState.h"
#include "ui/panels/UnitCard.h"

EnginePanel::EnginePanel(CommandState* command, ReportedState* reported, QWidget* parent)
    : CardPanel(command, reported, QStringLiteral("EnginePanel"), parent)
{
    rebuild();
}

void EnginePanel::addCards()
{
    const auto title = [](const rcm::EngineSpec& engine) {
        return engine.name.empty() ? tr("Engine %1").arg(engine.id) : QString::fromStdString(engine.name);
    };
    addUnitCards(rcm::UnitKind::Engine, m_command->airframe().engines, title, [](UnitCard* card) {
        using enum rcm::ItemId;
        card->addComboBox(eng_status, 0);
        card->addComboBox(eng_status, 1);
        card->addSpinBox(eng_prop_pitch);
        card->addSpinBox(eng_carb_SET);
    });
}
