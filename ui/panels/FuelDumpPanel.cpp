#include "ui/panels/FuelDumpPanel.h"

#include "ui/panels/CommandState.h"
#include "ui/panels/FieldButtonGroup.h"
#include "ui/panels/ItemText.h"
#include "ui/panels/UnitCard.h"

#include <QHBoxLayout>

namespace {

constexpr rcm::ItemId kItem = rcm::ItemId::ENABLE_fuel_dump;
constexpr int kFacilityField = 0;

}  // namespace

FuelDumpPanel::FuelDumpPanel(CommandState* command, ReportedState* reported, QWidget* parent)
    : QWidget(parent), m_command(command)
{
    setObjectName(QStringLiteral("FuelDumpPanel"));
    const UnitRef unit{rcm::UnitKind::FcuGeneral, 0};
    auto* card = new UnitCard(command, reported, unit, ItemText::label(kItem), this);
    const int fields = static_cast<int>(rcm::itemInfo(kItem).fields.size());
    for (int field = 0; field < fields; ++field)
        card->addButtons(kItem, field)->setDetail([this, field](unsigned code) { return consequence(field, code); });
    auto* layout = new QHBoxLayout(this);
    layout->addWidget(card);
}

QString FuelDumpPanel::consequence(int field, unsigned code) const
{
    const rcm::Unit& resting = m_command->resting().fuelDump;
    if (code == resting.fieldCode(kItem, field))
        return {};
    const UnitRef unit{rcm::UnitKind::FcuGeneral, 0};
    if (field == kFacilityField) {
        QStringList dumping;
        for (int tank = 1; tank < static_cast<int>(rcm::itemInfo(kItem).fields.size()); ++tank)
            if (m_command->fieldCode(unit, kItem, tank) != resting.fieldCode(kItem, tank))
                dumping << ItemText::label(kItem, tank);
        return dumping.isEmpty() ? QString()
                                 : tr("Dumping starts at once: %1.").arg(dumping.join(QStringLiteral(", ")));
    }
    const unsigned facilityAtRest = resting.fieldCode(kItem, kFacilityField);
    if (m_command->fieldCode(unit, kItem, kFacilityField) == facilityAtRest)
        return tr("%1 is %2 now; the tank dumps as soon as that changes.")
            .arg(ItemText::label(kItem, kFacilityField),
                 ItemText::fieldCodeWord(kItem, kFacilityField, facilityAtRest));
    return tr("Dumping starts at once.");
}
