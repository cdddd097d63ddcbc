#pragma once

// The panels while a replay plays or an observation runs: they show what
// the log, or the observed station, commanded (ConsoleSession::loggedCommand)
// and take no clicks or keys; tabs and scroll bars still move, to look
// around. The console's own command is kept aside and comes back after. A
// note beside the tabs says so; the reports age in the log's time meanwhile,
// so that a pause or the log's end is not a silence of the aircraft.

#include "codec/message/Message.h"

#include <QObject>

#include <chrono>
#include <optional>

class CommandState;
class QLabel;
class QTabWidget;
class ReportedState;

class ReadOnlyPanels : public QObject {
    Q_OBJECT

public:
    // A page of the tabs with this property true keeps its clicks and keys
    // (the flight plan: planning goes on while a log plays).
    static constexpr const char* kKeepsInput = "keepsInputInReplay";

    ReadOnlyPanels(CommandState* command, QObject* parent = nullptr);

    // Once: the reports to clear at each change, the tabs to make read only
    // (its corner holds the note).
    void attach(ReportedState* reported, QTabWidget* panels);

    // The reports' clock: the log's time while read only, else steady_clock's.
    std::chrono::steady_clock::time_point now() const;
    bool isActive() const { return m_ownCommand.has_value(); }

    // The note alone, while a log is being opened; hidden by withdraw() or end().
    void announce(const QString& note);
    // Hides a note announced, unless the panels are read only already.
    void withdraw();
    // Read only from `startMicros` (the log's time) on, saying `note`.
    void begin(qint64 startMicros, const QString& note);
    // The console's own command back, and the panels editable.
    void end();

    // A frame's time and what it commanded, when it was a command; ignored
    // unless read only.
    void show(qint64 utcMicros, const std::optional<rcm::Message>& commanded);

    // "Replay: the log's commands, read only".
    static QString replayNote();

private:
    CommandState* m_command;
    ReportedState* m_reported = nullptr;
    QTabWidget* m_panels = nullptr;
    QLabel* m_note = nullptr;
    QObject* m_filter = nullptr;  // an application event filter, while read only
    std::optional<rcm::Message> m_ownCommand;
    qint64 m_micros = 0;
};
