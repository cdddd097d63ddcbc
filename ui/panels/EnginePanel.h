// The engines: one card per engine of the airframe, each with its control
// source, master/slave mode, propeller pitch and carburettor setting. The
// cards are rebuilt when CommandState's airframe changes.
#pragma once

#include <QWidget>

class CommandState;
class ReportedState;
class QGridLayout;

class EnginePanel : public QWidget {
    Q_OBJECT

public:
    EnginePanel(CommandState* command, ReportedState* reported, QWidget* parent = nullptr);

private:
    void rebuild();

    CommandState* m_command;
    ReportedState* m_reported;
    QGridLayout* m_layout;
};
