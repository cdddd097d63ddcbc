// The flaps and control surfaces: control source, slave aileron mode, and the
// six surfaces in degrees, each with a slider and a spin box that follow the
// command (and so each other).
#pragma once

#include <QWidget>

class CommandState;
class ReportedState;

class FlapsPanel : public QWidget {
    Q_OBJECT

public:
    FlapsPanel(CommandState* command, ReportedState* reported, QWidget* parent = nullptr);
};
