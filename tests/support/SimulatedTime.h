// Simulated time for a console whose link runs in a thread of its own (a
// ConsoleSession's LinkController) against an aircraft in this thread,
// joined by InProcessLink pairs: run() and runUntil() step a VirtualClock
// from timer to timer and, after each, settle what the timer set going
// (frames queued to the link thread, its reports queued back here, the
// console's answers) before the next one fires. Nothing waits on the wall
// clock; what a test asserts happens at an exact simulated time.
#pragma once

#include "AircraftFixture.h"
#include "InProcessLink.h"

#include "link/clock/VirtualClock.h"

#include <QCoreApplication>

#include <chrono>
#include <functional>
#include <memory>
#include <vector>

namespace rcm::test {

class SimulatedTime {
public:
    explicit SimulatedTime(std::shared_ptr<VirtualClock> clock = nullptr)
        : clock(clock ? std::move(clock) : std::make_shared<VirtualClock>(kFixtureStartUtcMicros))
    {
    }

    // An end in this thread whose other end may live in the link thread:
    // settled after each timer. It must outlive this, or be forgotten first.
    void watch(InProcessLink* end) { m_ends.push_back(end); }
    void forget(InProcessLink* end) { std::erase(m_ends, end); }

    // Simulated time on by `duration`, every timer in it fired at its own
    // instant, and what each set going settled before the next.
    void run(std::chrono::microseconds duration)
    {
        const std::int64_t end = clock->utcMicros() + duration.count();
        runUntil([] { return false; }, duration);
        clock->advance(std::chrono::microseconds(end - clock->utcMicros()));
        settle();
    }
    // Simulated time on until `done` holds, checked after each timer; false
    // when `limit` of simulated time passed first.
    bool runUntil(const std::function<bool()>& done, std::chrono::microseconds limit = std::chrono::seconds(60))
    {
        const std::int64_t end = clock->utcMicros() + limit.count();
        settle();
        while (!done()) {
            const std::optional<std::int64_t> due = clock->nextDueUtcMicros();
            if (!due || *due > end)
                return false;
            clock->advance(std::chrono::microseconds(*due - clock->utcMicros()));
            settle();
        }
        return true;
    }
    // What was queued between the threads, run: frames to the console's
    // link thread, its reports to this one, the console's answers back.
    void settle()
    {
        for (int pass = 0; pass < 3; ++pass) {
            for (InProcessLink* end : m_ends)
                end->settleOtherEnd();
            QCoreApplication::processEvents();
        }
    }

    std::shared_ptr<VirtualClock> clock;

private:
    std::vector<InProcessLink*> m_ends;
};

}  // namespace rcm::test
