// The fuel dump: the facility and the three tanks. Dumped fuel cannot be put
// back, so a change away from the safe resting state (facility enabled, a
// tank to dump) is commanded only once the operator confirms it; cancelling
// leaves the command, and so the next frame, as it was. Going back to the
// safe state is never held up by a question.
#pragma once

#include <QWidget>

#include <functional>

class CommandState;
class ReportedState;

class FuelDumpPanel : public QWidget {
    Q_OBJECT

public:
    // Asks the operator; true to go ahead. The default shows a QMessageBox;
    // tests put in one that answers without a modal loop.
    using Confirmer = std::function<bool(QWidget* parent, const QString& question)>;

    FuelDumpPanel(CommandState* command, ReportedState* reported, QWidget* parent = nullptr);

    void setConfirmer(Confirmer confirmer) { m_confirmer = std::move(confirmer); }
    static bool askWithMessageBox(QWidget* parent, const QString& question);

private:
    bool confirm(int field, unsigned code);

    CommandState* m_command;
    Confirmer m_confirmer = &FuelDumpPanel::askWithMessageBox;
};
