#include "link/replay/ReplayLink.h"

#include "codec/frame/Frame.h"

#include <QFileInfo>

#include <algorithm>
#include <cmath>

namespace {

// Records due at the same moment are played this many at a time, so a dense
// stretch of log cannot starve the event loop (and the worker's own timers).
constexpr int kBatch = 64;

}  // namespace

ReplayLink::ReplayLink(const QString& pcapngPath, QObject* parent) : ReplayLink(pcapngPath, nullptr, parent) {}

ReplayLink::ReplayLink(const QString& pcapngPath, std::shared_ptr<Clock> clock, QObject* parent)
    : Link(parent),
      m_path(pcapngPath),
      m_clock(clock ? std::move(clock) : std::make_shared<SystemClock>()),
      m_timer(m_clock->createTimer(this, Qt::PreciseTimer))
{
    connect(m_timer, &ClockTimer::timeout, this, &ReplayLink::playDue);
}

ReplayLink::~ReplayLink() = default;

QString ReplayLink::description() const
{
    return QStringLiteral("replay %1 at %2x").arg(QFileInfo(m_path).fileName()).arg(m_speed);
}

qint64 ReplayLink::startMicros() const
{
    return m_reader.count() ? m_reader.index().first().utcMicros : 0;
}

qint64 ReplayLink::positionMicros() const
{
    if (m_state != State::Playing)
        return m_anchorMicros;
    return m_anchorMicros + qint64(double(m_clock->steadyMicros() - m_anchorSteadyMicros) * m_speed);
}

qint64 ReplayLink::dueMicros(int index) const
{
    return std::max(m_reader.index()[index].utcMicros, m_floorMicros);
}

void ReplayLink::restartClock(qint64 logMicros)
{
    m_anchorMicros = logMicros;
    m_anchorSteadyMicros = m_clock->steadyMicros();
}

void ReplayLink::open()
{
    if (m_open)
        return;
    const bool complete = m_reader.open(m_path);
    if (!complete && m_reader.count() == 0) {
        emit errorOccurred(QStringLiteral("cannot replay %1: %2").arg(m_path, m_reader.errorString()));
        m_reader.close();
        return;
    }
    m_open = true;
    m_endMicros = startMicros();
    for (const FrameIndexEntry& e : m_reader.index())
        m_endMicros = std::max(m_endMicros, e.utcMicros);
    m_next = 0;
    m_floorMicros = startMicros();
    restartClock(m_floorMicros);
    ++m_epoch;
    emit opened();
    if (!complete)
        emit errorOccurred(QStringLiteral("replaying the %1 frames before a fault in %2: %3")
                               .arg(m_reader.count())
                               .arg(m_path, m_reader.errorString()));
    emit positionChanged(m_floorMicros, m_next);
    updateState();
    schedule();
}

void ReplayLink::close()
{
    if (!m_open)
        return;
    m_timer->stop();
    m_reader.close();
    m_open = false;
    m_next = 0;
    ++m_epoch;
    updateState();
    emit closed();
}

bool ReplayLink::write(const QByteArray& bytes)
{
    Q_UNUSED(bytes);
    return false;
}

void ReplayLink::setPaused(bool paused)
{
    if (paused == m_paused)
        return;
    // Freeze or restart log time where it stands now, before the state changes what "now" means.
    const qint64 position = positionMicros();
    m_paused = paused;
    ++m_epoch;
    restartClock(position);
    updateState();
    schedule();
}

void ReplayLink::setSpeed(double speed)
{
    if (std::isnan(speed))
        return;
    speed = std::clamp(speed, kMinSpeed, kMaxSpeed);
    if (speed == m_speed)
        return;
    restartClock(positionMicros());
    m_speed = speed;
    ++m_epoch;
    emit speedChanged(m_speed);
    schedule();
}

void ReplayLink::seek(qint64 utcMicros)
{
    if (!m_open)
        return;
    // Before the first record, waiting for it in log time would only be a pause.
    const qint64 target = std::max(utcMicros, startMicros());
    m_next = m_reader.indexAtOrAfter(target);
    m_floorMicros = target;
    restartClock(target);
    ++m_epoch;
    emit positionChanged(target, m_next);
    updateState();
    schedule();
}

void ReplayLink::updateState()
{
    State state = State::Playing;
    if (!m_open)
        state = State::Closed;
    else if (m_next >= m_reader.count())
        state = State::Finished;
    else if (m_paused)
        state = State::Paused;
    if (state == m_state)
        return;
    m_state = state;
    emit stateChanged(state);
    if (state == State::Finished)
        emit endOfLog();
}

void ReplayLink::schedule()
{
    if (m_state != State::Playing) {
        m_timer->stop();
        return;
    }
    // Rounded up, here and to milliseconds: woken before the record is due,
    // playDue() would find nothing to play and wait again for nothing.
    const qint64 waitMicros = qint64(std::ceil(double(dueMicros(m_next) - positionMicros()) / m_speed));
    m_timer->start(std::chrono::milliseconds(std::clamp<qint64>((waitMicros + 999) / 1000, 0, 24 * 3600 * 1000)));
}

void ReplayLink::playDue()
{
    if (m_state != State::Playing)
        return;
    const quint64 epoch = m_epoch;
    const qint64 now = positionMicros();
    int played = 0;
    while (m_next < m_reader.count() && played < kBatch && dueMicros(m_next) <= now) {
        const FrameRecord record = m_reader.recordAt(m_next);
        m_floorMicros = std::max(m_floorMicros, record.utcMicros);
        ++m_next;
        ++played;
        emit frameReplayed(record);
        if (epoch != m_epoch)
            return;  // a slot paused, sought or closed: that call has rescheduled
        if (record.direction == FrameDirection::Received) {
            const bool serialFrame = std::size_t(record.bytes.size()) == rcm::kFrameSize;
            emit datagramReceived(serialFrame ? record.bytes.mid(qsizetype(rcm::kPreambleSize)) : record.bytes);
            if (epoch != m_epoch)
                return;
        }
    }
    if (played > 0) {
        emit positionChanged(m_floorMicros, m_next);
        if (epoch != m_epoch)
            return;
    }
    if (m_next >= m_reader.count())
        restartClock(m_floorMicros);  // the position stays on the last record, not running on
    updateState();
    schedule();
}
