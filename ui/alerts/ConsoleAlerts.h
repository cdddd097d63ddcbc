#pragma once

// Everything that tells the operator what happened or what is wrong, as one
// part for the main window: the event log (and its file in the session's
// frame log directory), the Events table, the error banner, the link-loss
// alarm with its tone and its red banner. The window puts banners() above
// its panels and eventView() in a dock, and hands every link it runs to
// follow(); errors of its own it records with error().

#include "link/eventlog/ConsoleEvent.h"
#include "link/session/LinkStatistics.h"

#include <QObject>

class AlarmSound;
class ErrorBanner;
class EventLog;
class EventLogModel;
class EventLogView;
class LinkAlarm;
class LinkAlarmBanner;
class LinkEvents;
class LinkStateStrip;
class RefusalDigest;
class QWidget;

class ConsoleAlerts : public QObject {
    Q_OBJECT

public:
    // `sound` null: the link-loss tone on the sound card (ToneAlarmSound).
    explicit ConsoleAlerts(AlarmSound* sound = nullptr, QObject* parent = nullptr);
    ~ConsoleAlerts() override;

    // Keeps the events in `directory` too, in EventLog::sessionFileName(now);
    // false, and the reason recorded as a warning, when it cannot.
    bool keepIn(const QString& directory);

    EventLog* events() const { return m_events; }
    EventLogModel* model() const { return m_model; }
    LinkAlarm* alarm() const { return m_alarm; }
    // Created on first call, owned by whoever takes them into a layout.
    QWidget* banners();
    EventLogView* eventView();
    // The link's state and alarm in a line, for each window besides the
    // main one (a floating dock); owned by whoever lays it out.
    LinkStateStrip* newLinkStrip();

    // The start-up check of the sound card: without one, an error for the
    // log and the banner, at once rather than when the link is first lost.
    // False when there is none.
    bool checkSound(bool soundCardPresent);
    // What checkSound() says when there is no sound card.
    static QString noSoundText();
    ErrorBanner* errorBanner() const { return m_errorBanner; }
    LinkAlarmBanner* alarmBanner() const { return m_alarmBanner; }

    // The link's errors and statistics reach the event log, the banner and
    // the alarm, its refused frames the event log (RefusalDigest). The
    // connections end with the link (a LinkController, or an observation).
    void follow(const LinkEvents* link);
    RefusalDigest* refusals() const { return m_refusals; }

public slots:
    void info(EventSource source, const QString& text);
    void warning(EventSource source, const QString& text);
    // In the event log and on the banner.
    void error(EventSource source, const QString& text);
    void setStatistics(const LinkStatistics& statistics);
    // An error whose cause cleared leaves the banner, with a line in the
    // event log saying why: "Off the banner, <reason>: <message>".
    void withdraw(const QString& message, const QString& reason);
    // A replay: no link alarm; live again: armed again.
    void setReplay(bool replay);

signals:
    // The link's state changed (not each count): for the strips.
    void statisticsChanged(const LinkStatistics& statistics);
    void replayChanged(bool replay);

private:
    EventLog* m_events;
    EventLogModel* m_model;
    AlarmSound* m_sound;
    AlarmSound* m_ownSound = nullptr;
    LinkAlarm* m_alarm;
    QWidget* m_banners = nullptr;
    ErrorBanner* m_errorBanner = nullptr;
    LinkAlarmBanner* m_alarmBanner = nullptr;
    EventLogView* m_view = nullptr;
    RefusalDigest* m_refusals;
    LinkStatistics m_statistics;
    bool m_replay = false;
};
