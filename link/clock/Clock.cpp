#include "link/clock/Clock.h"

#include <QTimer>

namespace {

class SystemTimer : public ClockTimer {
public:
    SystemTimer(QObject* parent, Qt::TimerType type) : ClockTimer(parent), m_timer(this)
    {
        m_timer.setSingleShot(true);
        m_timer.setTimerType(type);
        connect(&m_timer, &QTimer::timeout, this, &ClockTimer::timeout);
    }

    void start(std::chrono::milliseconds delay) override { m_timer.start(delay); }
    void stop() override { m_timer.stop(); }
    bool isActive() const override { return m_timer.isActive(); }

private:
    QTimer m_timer;
};

}  // namespace

std::int64_t SystemClock::utcMicros() const
{
    using namespace std::chrono;
    return duration_cast<microseconds>(system_clock::now().time_since_epoch()).count();
}

std::int64_t SystemClock::steadyMicros() const
{
    using namespace std::chrono;
    return duration_cast<microseconds>(steady_clock::now().time_since_epoch()).count();
}

ClockTimer* SystemClock::createTimer(QObject* parent, Qt::TimerType type)
{
    return new SystemTimer(parent, type);
}
