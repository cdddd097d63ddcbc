#pragma once

// Errors where the operator is looking: a band across the top of the command
// panels that shows the newest error not yet dismissed, how many wait behind
// it, and stays until dismissed. Long messages wrap; the banner never makes
// the window wider. The same message again does not queue a copy, it counts
// ("3 times").
//
// Fed by EventLog: every event of severity Error appears here, so an error
// shown is always also an error recorded; all but the link-loss alarm's,
// which LinkAlarmBanner shows until the link is back.

#include "link/eventlog/ConsoleEvent.h"

#include <QFrame>
#include <QList>

class EventLog;
class QLabel;
class QPushButton;

class ErrorBanner : public QFrame {
    Q_OBJECT

public:
    explicit ErrorBanner(QWidget* parent = nullptr);

    // Shows every Error event `log` records from now on, but the alarm's.
    void follow(EventLog* log);

    // Errors waiting to be dismissed, the shown one included.
    int count() const { return int(m_errors.size()); }
    // The message shown (the newest); empty when none.
    QString currentText() const;
    // "1 of 3 errors", "error, 2 times"... what the counter label says.
    QString countText() const;

public slots:
    void showError(const QString& message);
    // The one shown; the next older one comes up.
    void dismiss();
    void dismissAll();
    // Its cause cleared (a call redialled, control taken): `message` goes,
    // however many times it came; the event log keeps it. False when not shown.
    bool withdraw(const QString& message);

signals:
    void countChanged(int count);

private:
    struct Error {
        QString message;
        int times = 1;
    };
    // The newest `n` go (all there are, when fewer); the next older one comes up.
    void dismissNewest(qsizetype n);
    void refresh();

    QList<Error> m_errors;  // oldest first
    QLabel* m_icon;
    QLabel* m_message;
    QLabel* m_count;
    QPushButton* m_dismiss;
    QPushButton* m_dismissAll;
};
