#include "ui/alerts/RefusalDigest.h"

#include "link/eventlog/EventLog.h"

RefusalDigest::RefusalDigest(EventLog* log, QObject* parent) : QObject(parent), m_log(log)
{
    m_timer.setInterval(1000);
    connect(&m_timer, &QTimer::timeout, this, &RefusalDigest::tick);
    m_timer.start();
}

namespace {

const QString kFrame = QStringLiteral("frame:");
const QString kBroker = QStringLiteral("broker:");

}  // namespace

void RefusalDigest::refused(const QString& reasonAndDetail)
{
    record(false, reasonAndDetail);
}

void RefusalDigest::refusedBrokerMessage(const QString& reasonAndDetail)
{
    record(true, reasonAndDetail);
}

void RefusalDigest::record(bool broker, const QString& reasonAndDetail)
{
    const QString key = (broker ? kBroker : kFrame) + reasonAndDetail.section(QStringLiteral(": "), 0, 0);
    const qint64 now = m_log->now();
    auto it = m_windows.find(key);
    if (it != m_windows.end() && now - it->startMicros < kWindowMicros) {
        ++it->more;
        it->last = reasonAndDetail;
        return;
    }
    if (it != m_windows.end() && it->more > 0) {
        // Refused all through the minute: its count, and this one opens the next.
        recordMore(key, *it, now);
        it->more = 1;
        it->last = reasonAndDetail;
        return;
    }
    m_log->warning(EventSource::Link, broker ? tr("A broker message was refused: %1").arg(reasonAndDetail)
                                             : tr("A frame was refused: %1").arg(reasonAndDetail));
    m_windows.insert(key, Window{now, 0, QString()});
}

void RefusalDigest::tick()
{
    const qint64 now = m_log->now();
    for (auto it = m_windows.begin(); it != m_windows.end(); ++it)
        if (it->more > 0 && now - it->startMicros >= kWindowMicros)
            recordMore(it.key(), *it, now);
}

void RefusalDigest::flush()
{
    const qint64 now = m_log->now();
    for (auto it = m_windows.begin(); it != m_windows.end(); ++it)
        if (it->more > 0)
            recordMore(it.key(), *it, now);
    m_windows.clear();
}

void RefusalDigest::recordMore(const QString& key, Window& window, qint64 now)
{
    const bool broker = key.startsWith(kBroker);
    const QString reason = key.mid((broker ? kBroker : kFrame).size());
    const qint64 seconds = (now - window.startMicros + 500'000) / 1'000'000;
    const QString what = broker ? (window.more == 1 ? tr("broker message") : tr("broker messages"))
                                : (window.more == 1 ? tr("frame") : tr("frames"));
    const QString text =
        window.more == 1 ? tr("1 more %1 refused as %2 in the last %3 s; the last: %4").arg(what, reason).arg(seconds)
                         : tr("%1 more %2 refused as %3 in the last %4 s; the last: %5")
                               .arg(window.more)
                               .arg(what, reason)
                               .arg(seconds);
    m_log->warning(EventSource::Link, text.arg(window.last));
    window.startMicros = now;
    window.more = 0;
    window.last.clear();
}
