#include "ui/panels/HeaderPanel.h"

#include "ui/panels/UnitCard.h"

#include <QHBoxLayout>

HeaderPanel::HeaderPanel(CommandState* command, ReportedState* reported, QWidget* parent) : QWidget(parent)
{
    setObjectName(QStringLiteral("HeaderPanel"));
    using enum rcm::ItemId;
    auto* card = new UnitCard(command, reported, {rcm::UnitKind::Header, 0},
                              QString::fromUtf8(rcm::unitLabel(rcm::UnitKind::Header).data()), this);
    for (rcm::ItemId id : {ID_UA_source, ID_GCS_destination, ID_GCS_backup})
        card->addStation(id);
    auto* layout = new QHBoxLayout(this);
    layout->addWidget(card);
}
