#pragma once

// File > Rehearse scenario...: runs a scenario (link/rehearsal/) in the
// console at its own speed, showing scenario time on a progress bar, each
// step, fault, alarm and event as it happens, and the verdict, with the
// report written to a folder of its own. The run is in process on a virtual
// clock paced by a timer, so the GUI thread never waits on it.

#include <QDialog>

#include <memory>

class QLabel;
class QPlainTextEdit;
class QProgressBar;
class QPushButton;
class ScenarioRunner;

class RehearsalDialog : public QDialog {
    Q_OBJECT

public:
    explicit RehearsalDialog(QWidget* parent = nullptr);
    ~RehearsalDialog() override;

    // Asks for a scenario file and runs it in a new dialog, its report in
    // the application data folder under rehearsals/.
    static void chooseAndRun(QWidget* parent);

    // Reads `scenarioPath` and starts it; false, the reason shown, when the
    // scenario is wrong. `speed` 0: the scenario's own.
    bool run(const QString& scenarioPath, const QString& reportDirectory, double speed = 0);

    QString verdict() const;
    QString timeline() const;
    int progressValue() const;
    int progressMaximum() const;

signals:
    // The run ended and its report was written (or could not be: the verdict says so).
    void finished();

private:
    void runFinished();

    std::unique_ptr<ScenarioRunner> m_runner;
    QString m_reportDirectory;
    QLabel* m_title;
    QProgressBar* m_progress;
    QPlainTextEdit* m_timeline;
    QLabel* m_verdict;
    QPushButton* m_openReport;
};
