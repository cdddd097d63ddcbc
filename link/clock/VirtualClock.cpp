#include "link/clock/VirtualClock.h"

#include <QMutex>
#include <QThread>

#include <algorithm>
#include <limits>
#include <vector>

namespace {

class VirtualTimer;

}  // namespace

struct VirtualClock::Schedule {
    struct Armed {
        std::int64_t due;
        std::uint64_t order;
        VirtualTimer* timer;
    };
    mutable QMutex mutex;
    std::int64_t now = 0;
    std::uint64_t started = 0;  // start() calls so far: the tie-break between equal due times
    std::vector<Armed> armed;

    // Under the mutex.
    void remove(const VirtualTimer* timer)
    {
        std::erase_if(armed, [timer](const Armed& a) { return a.timer == timer; });
    }
};

namespace {

class VirtualTimer : public ClockTimer {
public:
    VirtualTimer(QObject* parent, std::shared_ptr<VirtualClock::Schedule> schedule)
        : ClockTimer(parent), m_schedule(std::move(schedule))
    {
    }
    ~VirtualTimer() override { stop(); }

    void start(std::chrono::milliseconds delay) override
    {
        const QMutexLocker lock(&m_schedule->mutex);
        m_schedule->remove(this);
        const std::int64_t due = m_schedule->now + std::chrono::microseconds(std::max(delay, {})).count();
        m_schedule->armed.push_back({due, m_schedule->started++, this});
    }
    void stop() override
    {
        const QMutexLocker lock(&m_schedule->mutex);
        m_schedule->remove(this);
    }
    bool isActive() const override
    {
        const QMutexLocker lock(&m_schedule->mutex);
        return std::any_of(m_schedule->armed.begin(), m_schedule->armed.end(),
                           [this](const VirtualClock::Schedule::Armed& a) { return a.timer == this; });
    }

    void fire() { emit timeout(); }

private:
    std::shared_ptr<VirtualClock::Schedule> m_schedule;
};

}  // namespace

VirtualClock::VirtualClock(std::int64_t startUtcMicros) : m_schedule(std::make_shared<Schedule>())
{
    m_schedule->now = startUtcMicros;
}

VirtualClock::~VirtualClock() = default;

std::int64_t VirtualClock::utcMicros() const
{
    const QMutexLocker lock(&m_schedule->mutex);
    return m_schedule->now;
}

ClockTimer* VirtualClock::createTimer(QObject* parent, Qt::TimerType)
{
    return new VirtualTimer(parent, m_schedule);
}

int VirtualClock::activeTimers() const
{
    const QMutexLocker lock(&m_schedule->mutex);
    return int(m_schedule->armed.size());
}

std::optional<std::int64_t> VirtualClock::nextDueUtcMicros() const
{
    const QMutexLocker lock(&m_schedule->mutex);
    if (m_schedule->armed.empty())
        return std::nullopt;
    std::int64_t due = std::numeric_limits<std::int64_t>::max();
    for (const Schedule::Armed& a : m_schedule->armed)
        due = std::min(due, a.due);
    return due;
}

bool VirtualClock::fireNext(std::int64_t limit)
{
    VirtualTimer* timer = nullptr;
    {
        const QMutexLocker lock(&m_schedule->mutex);
        auto& armed = m_schedule->armed;
        const auto next = std::min_element(armed.begin(), armed.end(), [](const auto& a, const auto& b) {
            return a.due != b.due ? a.due < b.due : a.order < b.order;
        });
        if (next == armed.end() || next->due > limit)
            return false;
        m_schedule->now = std::max(m_schedule->now, next->due);
        timer = next->timer;
        armed.erase(next);
    }
    // Unlocked: what the timer's slots do may read the clock and start timers.
    if (timer->thread() == QThread::currentThread())
        timer->fire();
    else
        QMetaObject::invokeMethod(timer, [timer] { timer->fire(); }, Qt::BlockingQueuedConnection);
    return true;
}

void VirtualClock::advance(std::chrono::microseconds step)
{
    const std::int64_t target = utcMicros() + step.count();
    while (fireNext(target)) {
    }
    const QMutexLocker lock(&m_schedule->mutex);
    m_schedule->now = std::max(m_schedule->now, target);
}

bool VirtualClock::advanceToNextTimer()
{
    std::int64_t due = std::numeric_limits<std::int64_t>::max();
    {
        const QMutexLocker lock(&m_schedule->mutex);
        for (const Schedule::Armed& a : m_schedule->armed)
            due = std::min(due, a.due);
        if (m_schedule->armed.empty())
            return false;
    }
    while (fireNext(due)) {
    }
    return true;
}
