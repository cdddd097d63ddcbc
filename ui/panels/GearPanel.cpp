#include "ui/panels/GearPanel.h"

#include "ui/panels/UnitCard.h"

#include <QHBoxLayout>

GearPanel::GearPanel(CommandState* command, ReportedState* reported, QWidget* parent) : QWidget(parent)
{
    setObjectName(QStringLiteral("GearPanel"));
    auto* layout = new QHBoxLayout(this);
    layout->addWidget(
        UnitCard::ofFields(command, reported, {rcm::UnitKind::Settings, 0}, rcm::ItemId::land_wheels, this));
}
