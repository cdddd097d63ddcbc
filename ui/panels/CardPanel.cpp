#include "ui/panels/CardPanel.h"

#include "ui/panels/CardGrid.h"
#include "ui/panels/CommandState.h"
#include "ui/panels/UnitCard.h"

CardPanel::CardPanel(CommandState* command, ReportedState* reported, const QString& objectName, QWidget* parent)
    : QWidget(parent), m_command(command), m_reported(reported), m_layout(new QGridLayout(this))
{
    setObjectName(objectName);
    connect(command, &CommandState::airframeChanged, this, &CardPanel::rebuild);
}

void CardPanel::rebuild()
{
    // Deleted at once, not later: the old cards name units the command no longer has.
    qDeleteAll(findChildren<UnitCard*>(Qt::FindDirectChildrenOnly));
    addCards();
}

void CardPanel::place(UnitCard* card)
{
    CardGrid::add(m_layout, card);
}

UnitCard* CardPanel::newUnitCard(UnitRef ref, const QString& title)
{
    auto* card = new UnitCard(m_command, m_reported, ref, title, this);
    card->addKey();
    return card;
}
