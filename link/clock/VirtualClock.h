#pragma once

// Simulated time for tests: stands still until advance() moves it, then
// fires the timers that fall due on the way, each at its own instant, in the
// order they fall due (those due together in the order they were started).
// A session on it runs its 1 Hz cadence, silence timeout and replay pace as
// fast as the test can step, and a test asserts exact times and counts.
//
// Timers may be started and stopped from any thread; one whose parent lives
// in another thread (a worker under LinkController) fires there, and
// advance() waits for it to finish.

#include "link/clock/Clock.h"

#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>

class VirtualClock : public Clock {
public:
    explicit VirtualClock(std::int64_t startUtcMicros);
    ~VirtualClock() override;

    std::int64_t utcMicros() const override;
    // The same reading: virtual time never steps back.
    std::int64_t steadyMicros() const override { return utcMicros(); }
    ClockTimer* createTimer(QObject* parent, Qt::TimerType type = Qt::CoarseTimer) override;

    // Moves time on by `step`, firing what falls due, including timers the
    // fired ones start within the step.
    void advance(std::chrono::microseconds step);
    // Moves to the earliest armed timer and fires what is due then; false,
    // and time stands, when no timer is armed.
    bool advanceToNextTimer();
    int activeTimers() const;
    // When the earliest armed timer falls due (UTC microseconds); none when
    // no timer is armed. For a test that settles what one timer set going
    // (queued to other threads) before the next one fires.
    std::optional<std::int64_t> nextDueUtcMicros() const;

    struct Schedule;  // shared with the timers, which may outlive the clock

private:
    // Fires the earliest timer due at or before `limit`, first moving time
    // to when it is due; false when none is.
    bool fireNext(std::int64_t limit);

    std::shared_ptr<Schedule> m_schedule;
};
