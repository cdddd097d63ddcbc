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
    const auto title = [](const rcm::RadioSpec& radio) {
        return QString::fromStdString(radio.name.empty() ? radio.systemId : radio.name);
    };
    addUnitCards(rcm::UnitKind::Radio, m_command->airframe().radios, title, [](UnitCard* card) {
        using enum rcm::ItemId;
        card->addButtons(receiver_control, 0);
        card->addButtons(receiver_control, 1);
        card->addSpinBox(Rx_freq);
        card->addSpinBox(Tx_freq);
        card->addSpinBox(Tx_OP_power);
    });
}
