#pragma once

// The console's record of events (ConsoleEvent): stamps each with the time,
// appends it to the session's event log file as one complete line the moment
// it happens, and hands it on to whoever shows it (recorded()). It keeps no
// list itself; the file is the record, the views keep what they show.
//
// The file is opened for appending without a buffer of our own, and each
// line reaches the kernel in one write, so a killed console loses nothing it
// recorded.

#include "link/clock/Clock.h"
#include "link/eventlog/ConsoleEvent.h"

#include <QDateTime>
#include <QFile>
#include <QObject>

#include <memory>

class EventLog : public QObject {
    Q_OBJECT

public:
    explicit EventLog(QObject* parent = nullptr);
    ~EventLog() override;

    // What events are stamped by: the session's clock (null: the
    // SystemClock); tests pass a VirtualClock.
    void setClock(std::shared_ptr<const Clock> clock);
    // Microseconds since the epoch, UTC, in whole milliseconds (what the file keeps).
    qint64 now() const { return m_clock->utcMicros() / 1000 * 1000; }

    // The event log of a session that starts at `utc`, named after the frame
    // log it sits beside: "rcm-2026-11-22T07-32-00Z.events.txt".
    static QString sessionFileName(const QDateTime& utc);

    // Appends every event from now on to `path` as well (creating it and its
    // directories when missing). False, with the reason, when it cannot be
    // opened; the events are then only shown.
    bool openFile(const QString& path, QString* error = nullptr);
    QString filePath() const { return m_file.fileName(); }
    bool isFileOpen() const { return m_file.isOpen(); }

public slots:
    void record(EventSeverity severity, EventSource source, const QString& text);
    void info(EventSource source, const QString& text) { record(EventSeverity::Info, source, text); }
    void warning(EventSource source, const QString& text) { record(EventSeverity::Warning, source, text); }
    void error(EventSource source, const QString& text) { record(EventSeverity::Error, source, text); }

signals:
    void recorded(const ConsoleEvent& event);

private:
    std::shared_ptr<const Clock> m_clock;
    QFile m_file;
};
