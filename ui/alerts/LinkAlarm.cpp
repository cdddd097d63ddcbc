#include "ui/alerts/LinkAlarm.h"

#include "link/eventlog/EventLog.h"
#include "ui/alerts/AlarmSound.h"

#include <QDateTime>
#include <QLocale>

LinkAlarm::LinkAlarm(AlarmSound* sound, EventLog* log, QObject* parent) : QObject(parent), m_sound(sound), m_log(log)
{
}

QString LinkAlarm::durationText(qint64 micros)
{
    const qint64 seconds = (std::max<qint64>(micros, 0) + 500'000) / 1'000'000;
    if (seconds < 60)
        return tr("%1 s").arg(seconds);
    if (seconds < 3600)
        return seconds % 60 ? tr("%1 min %2 s").arg(seconds / 60).arg(seconds % 60) : tr("%1 min").arg(seconds / 60);
    const qint64 minutes = seconds / 60;
    return minutes % 60 ? tr("%1 h %2 min").arg(minutes / 60).arg(minutes % 60) : tr("%1 h").arg(minutes / 60);
}

qint64 LinkAlarm::now() const
{
    return m_log ? m_log->now() : QDateTime::currentMSecsSinceEpoch() * 1000;
}

qint64 LinkAlarm::silentMicros() const
{
    if (!m_active)
        return 0;
    return now() - (m_lastFrameMicros ? m_lastFrameMicros : m_lostAtMicros);
}

void LinkAlarm::record(EventSeverity severity, const QString& text)
{
    if (m_log)
        m_log->record(severity, EventSource::Alarm, text);
}

void LinkAlarm::setEnabled(bool enabled)
{
    if (enabled == m_enabled)
        return;
    m_enabled = enabled;
    if (!enabled && m_active) {
        if (m_sound)
            m_sound->stop();
        m_active = false;
        m_acknowledged = false;
    }
    m_warnedNoFrame = false;
    emit changed();
}

void LinkAlarm::setStatistics(const LinkStatistics& statistics)
{
    const LinkState before = m_last.state;
    const LinkState after = statistics.state;
    const LinkStatistics previous = m_last;
    m_last = statistics;
    if (!m_enabled || before == after)
        return;
    switch (after) {
    case LinkState::Connected:
        if (m_active)
            regain(statistics);
        // Frames counted from the last snapshot that was not connected.
        m_connectedSinceMicros = statistics.lastGoodFrameUtcMicros ? statistics.lastGoodFrameUtcMicros : now();
        m_framesAtConnect = previous.framesReceived;
        break;
    case LinkState::Lost:
        if (before == LinkState::Connected) {
            lose(statistics);
        } else if (before == LinkState::Waiting && !m_warnedNoFrame) {
            m_warnedNoFrame = true;
            record(EventSeverity::Warning, tr("No frame from the aircraft since the link opened"));
        }
        break;
    case LinkState::Closed:
    case LinkState::Waiting:
        // Closed by the operator, or opened anew: nothing is lost any more.
        clear();
        m_warnedNoFrame = false;
        break;
    }
}

void LinkAlarm::acknowledge()
{
    if (!m_active || m_acknowledged)
        return;
    m_acknowledged = true;
    if (m_sound)
        m_sound->stop();
    record(EventSeverity::Info, tr("Link-loss alarm silenced by the operator, %1 without a frame")
                                    .arg(durationText(silentMicros())));
    emit changed();
}

void LinkAlarm::lose(const LinkStatistics& statistics)
{
    m_active = true;
    m_acknowledged = false;
    m_lostAtMicros = now();
    m_lastFrameMicros = statistics.lastGoodFrameUtcMicros;
    if (m_sound)
        m_sound->start();
    const quint64 frames = statistics.framesReceived - std::min(statistics.framesReceived, m_framesAtConnect);
    const qint64 spell = m_lastFrameMicros && m_connectedSinceMicros ? m_lastFrameMicros - m_connectedSinceMicros : 0;
    record(EventSeverity::Error, tr("Link lost: no good frame for %1, after %2 in %3")
                                     .arg(durationText(silentMicros()),
                                          frames == 1 ? tr("1 frame") : tr("%1 frames").arg(QLocale().toString(frames)),
                                          durationText(spell)));
    emit changed();
}

void LinkAlarm::regain(const LinkStatistics& statistics)
{
    const qint64 gap = m_lastFrameMicros && statistics.lastGoodFrameUtcMicros
                           ? statistics.lastGoodFrameUtcMicros - m_lastFrameMicros
                           : silentMicros();
    clear();
    record(EventSeverity::Info, tr("Link regained after %1 without a frame").arg(durationText(gap)));
}

void LinkAlarm::clear()
{
    if (!m_active)
        return;
    if (m_sound)
        m_sound->stop();
    m_active = false;
    m_acknowledged = false;
    emit changed();
}
