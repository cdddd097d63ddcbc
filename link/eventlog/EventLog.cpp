#include "link/eventlog/EventLog.h"

#include "link/framelog/FrameLog.h"

#include <QDir>
#include <QFileInfo>

EventLog::EventLog(QObject* parent) : QObject(parent), m_clock(std::make_shared<SystemClock>())
{
    qRegisterMetaType<ConsoleEvent>();
}

EventLog::~EventLog() = default;

void EventLog::setClock(std::shared_ptr<const Clock> clock)
{
    m_clock = clock ? std::move(clock) : std::make_shared<SystemClock>();
}

QString EventLog::sessionFileName(const QDateTime& utc)
{
    return QFileInfo(FrameLog::sessionFileName(utc)).completeBaseName() + QStringLiteral(".events.txt");
}

bool EventLog::openFile(const QString& path, QString* error)
{
    m_file.close();
    const QFileInfo info(path);
    QString reason;
    if (!QDir().mkpath(info.absolutePath())) {
        reason = tr("cannot create directory %1").arg(QDir::toNativeSeparators(info.absolutePath()));
    } else {
        m_file.setFileName(path);
        // Unbuffered: each line goes to write(2) at once and survives our process.
        if (!m_file.open(QIODevice::WriteOnly | QIODevice::Append | QIODevice::Unbuffered))
            reason = tr("cannot open event log %1: %2").arg(QDir::toNativeSeparators(path), m_file.errorString());
    }
    if (reason.isEmpty())
        return true;
    m_file.setFileName(QString());
    if (error)
        *error = reason;
    return false;
}

void EventLog::record(EventSeverity severity, EventSource source, const QString& text)
{
    const ConsoleEvent event{now(), severity, source, text};
    if (m_file.isOpen()) {
        // One write per line, so the file never holds half an event.
        const QByteArray line = eventLine(event).toUtf8() + '\n';
        if (m_file.write(line) != line.size()) {
            const QString reason = tr("the event log %1 cannot be written: %2; events are only shown from now on")
                                       .arg(QDir::toNativeSeparators(m_file.fileName()), m_file.errorString());
            m_file.close();
            m_file.setFileName(QString());
            emit recorded(event);
            record(EventSeverity::Error, EventSource::Console, reason);
            return;
        }
    }
    emit recorded(event);
}
