#pragma once

// The band above the panels while the console holds its command back
// (link/session/CommandHold.h): why, whether the aircraft has been heard,
// how its report differed from the panels, and the one action that resumes
// commanding, "Resume commanding" or, when the aircraft names this station
// in control but its operator has not taken it, "Take control". The action
// asks first, listing every item where the panels differ from what the
// aircraft reports now, with Cancel as default.

#include <QFrame>

class CommandState;
class ConsoleSession;
class QLabel;
class QPushButton;

class CommandHoldBar : public QFrame {
    Q_OBJECT

public:
    // Both must outlive the bar.
    CommandHoldBar(ConsoleSession* session, const CommandState* command, QWidget* parent = nullptr);

    QPushButton* resumeButton() const { return m_resume; }
    QString text() const;

public slots:
    // Asks the operator, then resumes (or takes control); said in the
    // status bar and the event log through ConsoleSession::commandEvent.
    void requestResume();
    void refresh();

signals:
    // Resuming was refused: why, for the banner.
    void refused(const QString& reason);

private:
    // The panels against the aircraft's last report, one line each.
    QStringList differencesNow(int* count) const;

    ConsoleSession* m_session;
    const CommandState* m_command;
    QLabel* m_text;
    QPushButton* m_resume;
};
