#include "ui/panels/FuelDumpPanel.h"

#include "ui/panels/CommandState.h"
#include "ui/panels/FieldButtonGroup.h"
#include "ui/panels/ItemText.h"
#include "ui/panels/UnitCard.h"

#include <QHBoxLayout>
#include <QMessageBox>

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
        card->addButtons(kItem, field)->setGuard([this, field](unsigned code) { return confirm(field, code); });
    auto* layout = new QHBoxLayout(this);
    layout->addWidget(card);
}

bool FuelDumpPanel::askWithMessageBox(QWidget* parent, const QString& question)
{
    return QMessageBox::warning(parent, tr("Fuel dump"), question, QMessageBox::Yes | QMessageBox::Cancel,
                                QMessageBox::Cancel) == QMessageBox::Yes;
}

bool FuelDumpPanel::confirm(int field, unsigned code)
{
    const rcm::Unit& resting = m_command->resting().fuelDump;
    if (code == resting.fieldCode(kItem, field))
        return true;
    QString question =
        tr("Command %1: %2?").arg(ItemText::label(kItem, field), ItemText::fieldCodeWord(kItem, field, code));
    const UnitRef unit{rcm::UnitKind::FcuGeneral, 0};
    const bool facilityOff =
        m_command->fieldCode(unit, kItem, kFacilityField) == resting.fieldCode(kItem, kFacilityField);
    if (field == kFacilityField) {
        QStringList dumping;
        for (int tank = 1; tank < static_cast<int>(rcm::itemInfo(kItem).fields.size()); ++tank)
            if (m_command->fieldCode(unit, kItem, tank) != resting.fieldCode(kItem, tank))
                dumping << ItemText::label(kItem, tank);
        if (!dumping.isEmpty())
            question += QLatin1Char('\n') + tr("Dumping starts at once: %1.").arg(dumping.join(QStringLiteral(", ")));
    } else if (facilityOff) {
        question += QLatin1Char('\n') +
                    tr("%1 is %2 now; the tank dumps as soon as that changes.")
                        .arg(ItemText::label(kItem, kFacilityField),
                             ItemText::fieldCodeWord(kItem, kFacilityField, resting.fieldCode(kItem, kFacilityField)));
    }
    question += QLatin1Char('\n') + tr("Dumped fuel cannot be recovered.");
    return m_confirmer && m_confirmer(this, question);
}
