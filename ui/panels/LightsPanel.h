// The lights (right wing, left wing, tail) and the wheel brake, each OFF or ON.
#pragma once

#include <QWidget>

class CommandState;
class ReportedState;

class LightsPanel : public QWidget {
    Q_OBJECT

public:
    LightsPanel(CommandState* command, ReportedState* reported, QWidget* parent = nullptr);
};
