// The cameras: the three sense-and-avoid zooms (when the airframe has sense
// and avoid), and one card per payload camera with its ID (read-only: the key
// that names it), compass bearing, elevation, zoom, where its imagery goes,
// and a button that takes one photograph. The photograph is a one-shot
// command: TAKE goes out in one frame and CommandState::frameSent() puts it
// back to NONE, so one click is one photograph. The cards are rebuilt when
// CommandState's airframe changes.
#pragma once

#include "ui/panels/CardPanel.h"

class CommandState;
class ReportedState;
class QPushButton;
class UnitCard;

class CameraPanel : public CardPanel {
    Q_OBJECT

public:
    CameraPanel(CommandState* command, ReportedState* reported, QWidget* parent = nullptr);

private:
    void addCards() override;
    QPushButton* addPhotoButton(UnitCard* card);
};
