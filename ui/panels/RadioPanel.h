// The VHF radios: one card per set of the airframe, each with receiver and
// transmitter on/off, its system ID (read-only: it is the key that names the
// set), receive and transmit frequencies and output power. The cards are
// rebuilt when CommandState's airframe changes.
#pragma once

#include <QWidget>

class CommandState;
class ReportedState;
class QGridLayout;

class RadioPanel : public QWidget {
    Q_OBJECT

public:
    RadioPanel(CommandState* command, ReportedState* reported, QWidget* parent = nullptr);

private:
    void rebuild();

    CommandState* m_command;
    ReportedState* m_reported;
    QGridLayout* m_layout;
};
