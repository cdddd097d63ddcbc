#include "ui/panels/GearPanel.h"

#include "ui/panels/UnitCard.h"

#include <QHBoxLayout>

GearPanel::GearPanel(CommandState* command, ReportedState* reported, QWidget* parent) : QWidget(parent)
{
    setObjectName(QStringLiteral("GearPanel"));
    const auto& wheels = rcm::itemInfo(rcm::ItemId::land_wheels);
    auto* card =
        new UnitCard(command, reported, {rcm::UnitKind::Settings, 0},
                     QString::fromUtf8(wheels.label.data(), static_cast<qsizetype>(wheels.label.size())), this);
    for (int field = 0; field < static_cast<int>(wheels.fields.size()); ++field)
        card->addButtons(rcm::ItemId::land_wheels, field);
    auto* layout = new QHBoxLayout(this);
    layout->addWidget(card);
}
