#pragma once

// One thing that happened at the console and that the operator (or whoever
// reads the session afterwards) must be able to find again: a link opened or
// refused, a key file refused, a flight plan sent, the link lost and
// regained, an error. EventLog records them; its file holds one per line.

#include <QMetaType>
#include <QString>
#include <QtGlobal>

#include <optional>

enum class EventSeverity : quint8 {
    Info,     // what the operator did or the link did as expected
    Warning,  // worth knowing, nothing failed: no frame yet, a damaged log replayed in part
    Error,    // something the operator asked for did not happen, or the link is lost
};

enum class EventSource : quint8 {
    Link,     // transports, the frame log, replay
    Key,      // the secure link's key file
    Plan,     // the flight plan and its upload
    Alarm,    // the link-loss alarm: lost, silenced, regained
    Console,  // the rest: airframe files, exports
    Control,  // control between stations: taken, handed over, failover
    Command,  // the command: each change, sent, confirmed or not by the aircraft; held and resumed
};
inline constexpr EventSource kEventSources[] = {EventSource::Link,    EventSource::Key,     EventSource::Plan,
                                                EventSource::Alarm,   EventSource::Console, EventSource::Control,
                                                EventSource::Command};

struct ConsoleEvent {
    qint64 utcMicros = 0;  // microseconds since 1970-01-01T00:00:00Z
    EventSeverity severity = EventSeverity::Info;
    EventSource source = EventSource::Console;
    QString text;  // for people, with its reason: "udp: cannot bind 0.0.0.0:5600: ..."

    friend bool operator==(const ConsoleEvent&, const ConsoleEvent&) = default;
};

QString eventSeverityName(EventSeverity severity);  // "info", "warning", "error"
QString eventSourceName(EventSource source);        // "link", "key", "plan", "alarm", "console", "control", "command"

// One line of the event log file, without its newline:
// "2026-11-23T17:45:20.123Z<TAB>error<TAB>link<TAB>text", the text's
// backslashes, tabs and line breaks written as \\, \t and \n so that every
// event is one line.
QString eventLine(const ConsoleEvent& event);
// The exact inverse of eventLine(); nothing when the line is not one.
std::optional<ConsoleEvent> parseEventLine(const QString& line);

Q_DECLARE_METATYPE(ConsoleEvent)
