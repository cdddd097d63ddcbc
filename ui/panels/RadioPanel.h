// The VHF radios: one card per set of the airframe, each with receiver and
// transmitter on/off, its system ID (read-only: it is the key that names the
// set), receive and transmit frequencies and output power. The cards are
// rebuilt when CommandState's airframe changes.
#pragma once

#include "ui/panels/CardPanel.h"

class CommandState;
class ReportedState;

class RadioPanel : public CardPanel {
    Q_OBJECT

public:
    RadioPanel(CommandState* command, ReportedState* reported, QWidget* parent = nullptr);

private:
    void addCards() override;
};
