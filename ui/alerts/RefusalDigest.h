#pragma once

// Refused frames in the event log without drowning it: a forger, or a link
// at the edge of its range, can have a frame refused every second for hours,
// and a row a second would bury the loss of the link under them. The first
// refusal of each reason is recorded whole, with its detail; the next ones
// of that reason within a minute are counted, and when the minute is up one
// line says how many more there were and what the last one was. Nothing is
// hidden meanwhile: the status bar counts every refusal by reason as it
// happens, and the frame log keeps every frame with its status.
//
// Time is the event log's clock (a virtual one in tests); tick() ends the
// minutes that are over, and a timer calls it every second.
//
// Messages refused on a broker (forged, unsigned, replayed, too large ...)
// are digested the same way, apart from frames and said as messages.

#include <QMap>
#include <QObject>
#include <QString>
#include <QTimer>

class EventLog;

class RefusalDigest : public QObject {
    Q_OBJECT

public:
    static constexpr qint64 kWindowMicros = 60'000'000;

    explicit RefusalDigest(EventLog* log, QObject* parent = nullptr);

    // As the link worker says it: "reason: detail".
    void refused(const QString& reasonAndDetail);
    // A broker message, as BrokerTrust says it: "forged: ...".
    void refusedBrokerMessage(const QString& reasonAndDetail);
    // Records the counts of the minutes that are over.
    void tick();
    // Records every count now, over or not: the link has stopped.
    void flush();

private:
    struct Window {
        qint64 startMicros = 0;
        int more = 0;        // refused after the one recorded, within the window
        QString last;        // the last of them, whole
    };
    void record(bool broker, const QString& reasonAndDetail);
    void recordMore(const QString& key, Window& window, qint64 now);

    EventLog* m_log;
    // By "frame:REASON" or "broker:REASON", so that a tick records them in one order.
    QMap<QString, Window> m_windows;
    QTimer m_timer;
};
