#include "ui/panels/LightsPanel.h"

#include "ui/panels/UnitCard.h"

#include <QHBoxLayout>

LightsPanel::LightsPanel(CommandState* command, ReportedState* reported, QWidget* parent) : QWidget(parent)
{
    setObjectName(QStringLiteral("LightsPanel"));
    const auto& lights = rcm::itemInfo(rcm::ItemId::lights);
    auto* card =
        new UnitCard(command, reported, {rcm::UnitKind::Settings, 0},
                     QString::fromUtf8(lights.label.data(), static_cast<qsizetype>(lights.label.size())), this);
    for (int field = 0; field < static_cast<int>(lights.fields.size()); ++field)
        card->addButtons(rcm::ItemId::lights, field);
    auto* layout = new QHBoxLayout(this);
    layout->addWidget(card);
}
