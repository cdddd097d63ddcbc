#pragma once

// Binds the console's widgets to whatever the session runs, a link of its
// own or an observation, and unbinds them when it ends: the link's events to
// the status bar, the overview, the alerts and the frame log view; its
// description, key and state to the Link dock's note and the event log; a
// replay or an observation shown read only in the panels.

#include "ui/window/ConsoleNotices.h"

#include <QObject>
#include <QString>
#include <QStringList>

class CommandBinding;
class CommandPreview;
class ConsoleSession;
class FlightPlanUpload;
class FlightPlanWidget;
class FrameLogModel;
class LinkController;
class LinkEvents;
class LinkPane;
class Observation;
class OverviewPage;
class ReadOnlyPanels;
class ReplayBinding;
class ReportedState;
class StatusBarWidget;

class SessionBinding : public QObject {
    Q_OBJECT

public:
    struct Parts {
        ConsoleSession* session;
        FrameLogModel* logModel;
        StatusBarWidget* status;
        OverviewPage* overview;
        ReportedState* reported;
        LinkPane* linkPane;
        CommandPreview* preview;
        FlightPlanWidget* flightPlan;
        FlightPlanUpload* upload;
        ReadOnlyPanels* readOnly;
        CommandBinding* commands;
        ReplayBinding* replay;
    };
    SessionBinding(const Parts& parts, const ConsoleNotices& notices, QObject* parent = nullptr);

signals:
    // What runs changed: the window's title and link controls follow.
    void changed();

private:
    void linkStarted(const LinkController* controller);
    void linkStopped();
    void observationStarted(const Observation* observation);
    void observationStopped();
    void failed(const QString& reason);
    // What a link or an observation says, to the status bar, overview, alerts and log view.
    void bindEvents(const LinkEvents* events, bool logRows);
    // What runs now, to the status bar and the event log.
    void showRunning(const QString& note);
    // Nothing runs: the status bar and the alarm say so.
    void showStopped();
    // The transport's errors off the banner: `why` their cause is gone.
    void withdrawTransportErrors(const QString& why);

    Parts m_parts;
    ConsoleNotices m_notices;
    QString m_lastLinkError;         // the link's last error, not logged again when its status repeats it
    // The transport's errors that were its state too ("call dropped ...;
    // redialling in 10 s"): off the banner once frames come again or the
    // link ends, since their cause is gone.
    QStringList m_transportErrors;
    bool m_modemRegistered = false;  // the satellite phone's registration, as last said
};
