#include "ui/panels/CameraPanel.h"

#include "ui/panels/CommandGate.h"
#include "ui/panels/CommandState.h"
#include "ui/panels/ItemText.h"
#include "ui/panels/UnitCard.h"

#include <QPushButton>

namespace {

constexpr rcm::ItemId kPhoto = rcm::ItemId::take_one_photo;

}  // namespace

CameraPanel::CameraPanel(CommandState* command, ReportedState* reported, QWidget* parent)
    : CardPanel(command, reported, QStringLiteral("CameraPanel"), parent)
{
    rebuild();
}

void CameraPanel::addCards()
{
    using enum rcm::ItemId;
    if (m_command->airframe().senseAndAvoid) {
        auto* sense = new UnitCard(m_command, m_reported, {rcm::UnitKind::Sense, 0},
                                   QString::fromUtf8(rcm::unitLabel(rcm::UnitKind::Sense).data()), this);
        for (rcm::ItemId id : rcm::kSenseAndAvoidZooms)
            sense->addSpinBox(id);
        place(sense);
    }
    const auto title = [](const rcm::CameraSpec& camera) {
        return camera.name.empty()
                   ? QStringLiteral("%1 %2").arg(QString::fromStdString(camera.maker)).arg(camera.number)
                   : QString::fromStdString(camera.name);
    };
    addUnitCards(rcm::UnitKind::Camera, m_command->airframe().cameras, title, [this](UnitCard* card) {
        card->addSpinBox(cam_mag_compass);
        card->addSpinBox(cam_elev);
        card->addSpinBox(cam_zoom_set);
        addPhotoButton(card);
        card->addStation(cam_GCS_destination);
        card->addStation(cam_GCS_backup);
    });
}

QPushButton* CameraPanel::addPhotoButton(UnitCard* card)
{
    const UnitRef ref = card->unitRef();
    auto* button = new QPushButton(ItemText::label(kPhoto), card);
    button->setObjectName(ItemText::name(kPhoto));
    button->setToolTip(ItemText::fieldToolTip(kPhoto, 0));
    card->addRow(button, kPhoto, 0);
    // The code that is not the resting one (NONE) is the command (TAKE).
    const unsigned none = m_command->resting().cameras.at(static_cast<std::size_t>(ref.index)).fieldCode(kPhoto, 0);
    unsigned take = none;
    for (unsigned code : ItemText::validFieldCodes(kPhoto, 0))
        if (code != none)
            take = code;
    connect(button, &QPushButton::clicked, this,
            [this, button, ref, take] { CommandGate::of(m_command)->setFieldCode(button, ref, kPhoto, 0, take); });
    // While a photograph waits for its frame, a second click would not be a second photograph.
    auto refresh = [this, button, ref, none] {
        const bool pending = m_command->unit(ref) && m_command->fieldCode(ref, kPhoto, 0) != none;
        button->setEnabled(!pending && m_command->unit(ref));
        button->setText(pending ? tr("Photograph in the next frame") : ItemText::label(kPhoto));
    };
    refresh();
    connect(m_command, &CommandState::changed, button, refresh);
    return button;
}
