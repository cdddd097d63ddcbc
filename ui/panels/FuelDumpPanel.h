// The fuel dump: the facility and the three tanks. Dumped fuel cannot be put
// back, so a change away from the safe resting state (facility enabled, a
// tank to dump) is commanded only once the operator confirms it: the item
// table's large-change rule, asked through CommandGate like every other; this
// panel adds to the question what the change would start. Cancelling leaves
// the command, and so the next frame, as it was. Going back to the safe state
// is never held up by a question.
#pragma once

#include <QWidget>

class CommandState;
class ReportedState;

class FuelDumpPanel : public QWidget {
    Q_OBJECT

public:
    FuelDumpPanel(CommandState* command, ReportedState* reported, QWidget* parent = nullptr);

private:
    // What commanding `code` in `field` would start, for the question.
    QString consequence(int field, unsigned code) const;

    CommandState* m_command;
};
