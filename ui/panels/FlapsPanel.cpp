#include "ui/panels/FlapsPanel.h"

#include "ui/panels/ItemSlider.h"
#include "ui/panels/ItemSpinBox.h"
#include "ui/panels/ItemText.h"
#include "ui/panels/UnitCard.h"

#include <QHBoxLayout>

FlapsPanel::FlapsPanel(CommandState* command, ReportedState* reported, QWidget* parent) : QWidget(parent)
{
    setObjectName(QStringLiteral("FlapsPanel"));
    using enum rcm::ItemId;
    const UnitRef flaps{rcm::UnitKind::Flaps, 0};
    auto* card =
        new UnitCard(command, reported, flaps, QString::fromUtf8(rcm::unitLabel(rcm::UnitKind::Flaps).data()), this);
    card->addComboBox(FLAP_status, 0);
    card->addComboBox(FLAP_status, 1);
    for (rcm::ItemId id : rcm::kFlapSurfaces) {
        auto* control = new QWidget(card);
        control->setObjectName(ItemText::name(id) + QStringLiteral(".control"));
        auto* row = new QHBoxLayout(control);
        row->setContentsMargins(0, 0, 0, 0);
        row->addWidget(new ItemSlider(command, flaps, id, control), 1);
        row->addWidget(new ItemSpinBox(command, flaps, id, control));
        card->addRow(control, id);
    }
    auto* layout = new QHBoxLayout(this);
    layout->addWidget(card);
}
