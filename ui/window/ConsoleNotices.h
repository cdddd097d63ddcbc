#pragma once

// What the window's parts say to the operator, said the same way by each:
// briefly in the status bar, and in the event log (errors on the banner
// too). A small value over the window's status bar and its alerts. The
// status bar's message is StatusBarWidget's, never QStatusBar's own, which
// QStatusBar would paint over the link state.

#include "link/eventlog/ConsoleEvent.h"

class ConsoleAlerts;
class StatusBarWidget;
class QString;

class ConsoleNotices {
public:
    ConsoleNotices(StatusBarWidget* bar, ConsoleAlerts* alerts) : m_bar(bar), m_alerts(alerts) {}

    ConsoleAlerts* alerts() const { return m_alerts; }
    // In the status bar only: what may come many times a second (a refused
    // frame) is counted in the event log by others, never said there each time.
    void flash(const QString& text) const;
    // In the status bar and, as information, in the event log.
    void info(EventSource source, const QString& text) const;
    // On the error banner and in the event log (and, briefly, the status bar).
    void error(const QString& message, EventSource source = EventSource::Console) const;

private:
    StatusBarWidget* m_bar;
    ConsoleAlerts* m_alerts;
};
