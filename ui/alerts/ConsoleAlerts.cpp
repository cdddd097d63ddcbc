#include "ui/alerts/ConsoleAlerts.h"

#include "link/eventlog/EventLog.h"
#include "link/session/LinkController.h"
#include "ui/alerts/ErrorBanner.h"
#include "ui/alerts/LinkAlarm.h"
#include "ui/alerts/LinkAlarmBanner.h"
#include "ui/alerts/LinkStateStrip.h"
#include "ui/alerts/RefusalDigest.h"
#include "ui/alerts/ToneAlarmSound.h"
#include "ui/eventlog/EventLogModel.h"
#include "ui/eventlog/EventLogView.h"

#include <QDateTime>
#include <QDir>
#include <QVBoxLayout>

ConsoleAlerts::ConsoleAlerts(AlarmSound* sound, QObject* parent)
    : QObject(parent),
      m_events(new EventLog(this)),
      m_model(new EventLogModel(m_events, this)),
      m_sound(sound),
      m_refusals(new RefusalDigest(m_events, this))
{
    if (!m_sound) {
        auto* tone = new ToneAlarmSound(this);
        connect(tone, &ToneAlarmSound::unavailable, this,
                [this](const QString& reason) { warning(EventSource::Alarm, reason); });
        m_sound = tone;
    }
    m_alarm = new LinkAlarm(m_sound, m_events, this);
}

ConsoleAlerts::~ConsoleAlerts()
{
    // The sound may be ours (a child QObject); the alarm must not touch it after.
    m_sound->stop();
}

bool ConsoleAlerts::keepIn(const QString& directory)
{
    const QString path = QDir(directory).filePath(EventLog::sessionFileName(QDateTime::currentDateTimeUtc()));
    QString reason;
    if (m_events->openFile(path, &reason)) {
        if (m_view)
            m_view->setFilePath(path);
        return true;
    }
    warning(EventSource::Console, tr("Events are not kept in a file: %1").arg(reason));
    return false;
}

QWidget* ConsoleAlerts::banners()
{
    if (!m_banners) {
        m_banners = new QWidget;
        auto* layout = new QVBoxLayout(m_banners);
        layout->setContentsMargins(0, 0, 0, 0);
        layout->setSpacing(2);
        m_alarmBanner = new LinkAlarmBanner(m_alarm);
        m_errorBanner = new ErrorBanner;
        m_errorBanner->follow(m_events);
        layout->addWidget(m_alarmBanner);
        layout->addWidget(m_errorBanner);
    }
    return m_banners;
}

EventLogView* ConsoleAlerts::eventView()
{
    if (!m_view) {
        m_view = new EventLogView(m_model);
        m_view->setFilePath(m_events->filePath());
    }
    return m_view;
}

LinkStateStrip* ConsoleAlerts::newLinkStrip()
{
    auto* strip = new LinkStateStrip(m_alarm);
    strip->setStatistics(m_statistics);
    strip->setReplay(m_replay);
    connect(this, &ConsoleAlerts::statisticsChanged, strip, &LinkStateStrip::setStatistics);
    connect(this, &ConsoleAlerts::replayChanged, strip, &LinkStateStrip::setReplay);
    return strip;
}

QString ConsoleAlerts::noSoundText()
{
    return tr("No sound card: the link-loss alarm will be shown but not heard");
}

bool ConsoleAlerts::checkSound(bool soundCardPresent)
{
    if (soundCardPresent)
        return true;
    // An error, so that the banner says it before any link is lost.
    error(EventSource::Console, noSoundText());
    return false;
}

void ConsoleAlerts::follow(const LinkEvents* link)
{
    connect(link, &LinkEvents::errorOccurred, this, [this](const QString& message) { error(EventSource::Link, message); });
    connect(link, &LinkEvents::statisticsChanged, this, &ConsoleAlerts::setStatistics);
    connect(link, &LinkEvents::frameRejected, m_refusals, &RefusalDigest::refused);
    // The counts of the last minute belong to this link's session.
    connect(link, &QObject::destroyed, m_refusals, &RefusalDigest::flush);
}

void ConsoleAlerts::info(EventSource source, const QString& text)
{
    m_events->info(source, text);
}

void ConsoleAlerts::warning(EventSource source, const QString& text)
{
    m_events->warning(source, text);
}

void ConsoleAlerts::error(EventSource source, const QString& text)
{
    m_events->error(source, text);
}

void ConsoleAlerts::withdraw(const QString& message, const QString& reason)
{
    if (m_errorBanner && m_errorBanner->withdraw(message))
        m_events->info(EventSource::Console, tr("Off the banner, %1: %2").arg(reason, message));
}

void ConsoleAlerts::setStatistics(const LinkStatistics& statistics)
{
    m_alarm->setStatistics(statistics);
    const bool stateChanged = statistics.state != m_statistics.state;
    m_statistics = statistics;
    if (stateChanged)
        emit statisticsChanged(statistics);
}

void ConsoleAlerts::setReplay(bool replay)
{
    m_alarm->setEnabled(!replay);
    m_replay = replay;
    // The Events dock hides the live session's events meanwhile: they are not the log's.
    if (m_view) {
        if (replay)
            m_view->beginReplay();
        else
            m_view->endReplay();
    }
    emit replayChanged(replay);
}
