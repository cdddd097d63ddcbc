// The landing gear: each of the four wheels OUT or RETRACTED. The aircraft
// takes seconds to move a wheel, so its reported position lags the command
// for a few status frames on every movement.
#pragma once

#include <QWidget>

class CommandState;
class ReportedState;

class GearPanel : public QWidget {
    Q_OBJECT

public:
    GearPanel(CommandState* command, ReportedState* reported, QWidget* parent = nullptr);
};
