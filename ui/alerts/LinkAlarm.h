#pragma once

// The link-loss alarm's logic: goes off when a link that was connected
// falls silent (LinkState Connected -> Lost), sounds until the operator
// silences it or the link comes back, stays on screen (LinkAlarmBanner)
// until the link comes back or is closed, and records loss, silencing and
// recovery with their durations in the event log:
//   "Link lost: no good frame for 3 s, after 1,234 frames in 20 min 34 s"
//   "Link regained after 14 s without a frame"
//
// A link that never connected does not sound it: that is a warning in the
// event log ("no frame from the aircraft since the link opened"), since an
// alarm that sounds before anything was there to lose teaches people to
// ignore it. Disabled (a replay), it neither sounds nor shows nor records.

#include "link/eventlog/ConsoleEvent.h"
#include "link/session/LinkStatistics.h"

#include <QObject>

class AlarmSound;
class EventLog;

class LinkAlarm : public QObject {
    Q_OBJECT

public:
    // `sound` and `log` must outlive the alarm; either may be null.
    LinkAlarm(AlarmSound* sound, EventLog* log, QObject* parent = nullptr);

    // On: the link is lost and the alarm shows.
    bool isActive() const { return m_active; }
    // Silenced by the operator while still active.
    bool isAcknowledged() const { return m_acknowledged; }
    bool isSounding() const { return m_active && !m_acknowledged; }
    bool isEnabled() const { return m_enabled; }
    // Microseconds since the last good frame (or since the loss, when no
    // frame time is known), by the event log's clock; 0 when not active.
    qint64 silentMicros() const;

    // "14 s", "2 min 5 s", "1 h 3 min": a duration as the event log writes it.
    static QString durationText(qint64 micros);

public slots:
    // Off for a replay: a log's silence is not the aircraft's. Turning it
    // off ends an active alarm quietly.
    void setEnabled(bool enabled);
    // LinkController::statisticsChanged: the state and the counters.
    void setStatistics(const LinkStatistics& statistics);
    // The operator heard it: the sound stops, the banner stays.
    void acknowledge();

signals:
    // Whenever active, acknowledged or enabled changes.
    void changed();

private:
    void lose(const LinkStatistics& statistics);
    void regain(const LinkStatistics& statistics);
    void clear();
    qint64 now() const;
    void record(EventSeverity severity, const QString& text);

    AlarmSound* m_sound;
    EventLog* m_log;
    LinkStatistics m_last;
    bool m_enabled = true;
    bool m_active = false;
    bool m_acknowledged = false;
    bool m_warnedNoFrame = false;
    qint64 m_lostAtMicros = 0;          // when the loss was declared
    qint64 m_lastFrameMicros = 0;       // the last good frame before the loss; 0: unknown
    qint64 m_connectedSinceMicros = 0;  // first good frame of this connected spell
    quint64 m_framesAtConnect = 0;      // framesReceived when this spell began
};
