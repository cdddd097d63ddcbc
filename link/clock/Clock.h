#pragma once

// The time a link session runs on: the UTC clock its frames are stamped
// with, a monotonic one for intervals, and single-shot timers on it. Passed
// in (LinkWorker::Options::clock, ReplayLink, the voice links; the secure
// codec takes UTC seconds as rcm::secure::UtcClock), so that tests run a
// session on a VirtualClock in simulated time instead of waiting on the
// wall clock. Null where a clock is passed means the SystemClock.

#include <QObject>

#include <chrono>
#include <cstdint>
#include <memory>

// A single-shot timer. Created by a Clock as a child of the object whose
// thread it fires in, so that moveToThread() takes it along.
class ClockTimer : public QObject {
    Q_OBJECT

public:
    using QObject::QObject;

    // Fires timeout() once, `delay` from now (a restart replaces the earlier start).
    virtual void start(std::chrono::milliseconds delay) = 0;
    virtual void stop() = 0;
    virtual bool isActive() const = 0;

signals:
    void timeout();
};

class Clock {
public:
    virtual ~Clock() = default;

    // Microseconds since 1970-01-01 UTC.
    virtual std::int64_t utcMicros() const = 0;
    // Microseconds on a clock that never steps, for intervals.
    virtual std::int64_t steadyMicros() const = 0;
    // Owned by `parent`. Precise timers are for cadences, coarse ones for timeouts.
    virtual ClockTimer* createTimer(QObject* parent, Qt::TimerType type = Qt::CoarseTimer) = 0;
};

// The system's clocks and QTimer: what the programs run on.
class SystemClock : public Clock {
public:
    std::int64_t utcMicros() const override;
    std::int64_t steadyMicros() const override;
    ClockTimer* createTimer(QObject* parent, Qt::TimerType type = Qt::CoarseTimer) override;
};
