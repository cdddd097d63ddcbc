// The landing gear: each of the four wheels OUT or RETRACTED, and All down /
// All up for the whole gear at once. Retracting (one wheel or all) is asked
// first, by the item table's rule through CommandGate; lowering never is.
// The aircraft takes seconds to move a wheel, so its reported position lags
// the command for a few status frames on every movement.
#pragma once

#include <QWidget>

class CommandState;
class QPushButton;
class ReportedState;

class GearPanel : public QWidget {
    Q_OBJECT

public:
    GearPanel(CommandState* command, ReportedState* reported, QWidget* parent = nullptr);

    // Every wheel to `code` (rcm::code::kOut or kRetracted) in one change;
    // false when the operator cancels the question or the command refuses.
    bool setAll(unsigned code);

private:
    void refresh();

    CommandState* m_command;
    QPushButton* m_allUp;
    QPushButton* m_allDown;
};
