// The engines: one card per engine of the airframe, each with its control
// source, master/slave mode, propeller pitch and carburettor setting. The
// cards are rebuilt when CommandState's airframe changes.
#pragma once

#include "ui/panels/CardPanel.h"

class CommandState;
class ReportedState;

class EnginePanel : public CardPanel {
    Q_OBJECT

public:
    EnginePanel(CommandState* command, ReportedState* reported, QWidget* parent = nullptr);

private:
    void addCards() override;
};
