#include "ui/panels/RadioPanel.h"

#include "ui/panels/CommandState.h"
#include "ui/panels/UnitCard.h"

RadioPanel::RadioPanel(CommandState* command, ReportedState* reported, QWidget* parent)
    : CardPanel(command, reported, QStringLiteral("RadioPanel"), parent)
{
    rebuild();
}

void RadioPanel::addCards()
{
    using enum rcm::ItemId;
    const auto& radios = m_command->airframe().radios;
    for (int i = 0; i < static_cast<int>(radios.size()); ++i) {
        const auto& spec = radios[static_cast<std::size_t>(i)];
        const QString title = QString::fromStdString(spec.name.empty() ? spec.systemId : spec.name);
        auto* card = new UnitCard(m_command, m_reported, {rcm::UnitKind::Radio, i}, title, this);
        card->addKey();
        card->addButtons(receiver_control, 0);
        card->addButtons(receiver_control, 1);
        card->addSpinBox(Rx_freq);
        card->addSpinBox(Tx_freq);
        card->addSpinBox(Tx_OP_power);
        place(card);
    }
}
