#include "ui/panels/LightsPanel.h"

#include "ui/panels/UnitCard.h"

#include <QHBoxLayout>

LightsPanel::LightsPanel(CommandState* command, ReportedState* reported, QWidget* parent) : QWidget(parent)
{
    setObjectName(QStringLiteral("LightsPanel"));
    auto* layout = new QHBoxLayout(this);
    layout->addWidget(UnitCard::ofFields(command, reported, {rcm::UnitKind::Settings, 0}, rcm::ItemId::lights, this));
}
