#pragma once

// The command between the panels and the link: every change of it to the
// session and the next-frame preview (the header alone while it is held),
// each frame sent and report received to the preview and the journal, the
// aircraft's report adopted into the panels, control between stations in
// the header panel, and every change of the hold in the event log.

#include "ui/window/ConsoleNotices.h"

#include <QObject>
#include <QStringList>

class CommandHoldBar;
class CommandJournal;
class CommandPreview;
class CommandState;
class ConsoleSession;
class FlightPlanWidget;
class ReadOnlyPanels;
class ReportedState;
class StationControlWidget;
struct ReceivedMessage;

class CommandBinding : public QObject {
    Q_OBJECT

public:
    struct Parts {
        CommandState* command;
        ReportedState* reported;
        ConsoleSession* session;
        CommandPreview* preview;
        CommandHoldBar* holdBar;
        StationControlWidget* stationControl;
        FlightPlanWidget* flightPlan;
        const ReadOnlyPanels* readOnly;
    };
    CommandBinding(const Parts& parts, const ConsoleNotices& notices, QObject* parent = nullptr);

    // What the next frame carries, to the preview and the session.
    void commandChanged();
    // From the running link.
    void messageReceived(const ReceivedMessage& received);
    void frameSent(quint32 messageId);
    void linkEnded();

private:
    void bindStationControl();
    void bindHold();

    Parts m_parts;
    ConsoleNotices m_notices;
    CommandJournal* m_journal;
    QStringList m_controlAlarms;  // said since the last change of role
    QStringList m_offerAlarms;    // on the banner while control is offered to this station
};
