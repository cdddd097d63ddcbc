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
    using enum rcm::ItemId;
    const auto& engines = m_command->airframe().engines;
    for (int i = 0; i < static_cast<int>(engines.size()); ++i) {
        const auto& spec = engines[static_cast<std::size_t>(i)];
        const QString title = spec.name.empty() ? tr("Engine %1").arg(spec.id) : QString::fromStdString(spec.name);
        auto* card = new UnitCard(m_command, m_reported, {rcm::UnitKind::Engine, i}, title, this);
        card->addKey();
        card->addComboBox(eng_status, 0);
        card->addComboBox(eng_status, 1);
        card->addSpinBox(eng_prop_pitch);
        card->addSpinBox(eng_carb_SET);
        place(card);
    }
}
