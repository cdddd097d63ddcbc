// The console and a simulated aircraft talking in one process on simulated
// time: a LinkWorker on the ground side, the SimulatedAircraft behind its own
// LinkWorker (as uasim flies it) on the other, joined by an InProcessLink
// pair and driven by one VirtualClock. A test steps the clock and the
// session runs its 1 Hz cadence, gear transits and silence timeouts without
// waiting on a wall-clock second; what it asserts happens at an exact time.
#pragma once

#include "InProcessLink.h"

#include "codec/secure/SecureCodec.h"
#include "link/aircraft/AircraftResponder.h"
#include "link/aircraft/SimulatedAircraft.h"
#include "link/clock/VirtualClock.h"
#include "link/session/LinkWorker.h"

#include <chrono>
#include <memory>
#include <optional>

namespace rcm::test {

// 2026-11-22 07:32:00.250 UTC: a quarter second before a tick.
inline constexpr std::int64_t kFixtureStartUtcMicros =
    std::chrono::duration_cast<std::chrono::microseconds>(
        std::chrono::sys_days{std::chrono::year{2026} / 11 / 22}.time_since_epoch() + std::chrono::hours(7) +
        std::chrono::minutes(32) + std::chrono::milliseconds(250))
        .count();

// UTC seconds of `clock`, for the secure codec's time window.
inline rcm::secure::UtcClock utcSecondsOf(const std::shared_ptr<Clock>& clock)
{
    return [clock] { return clock->utcMicros() / 1'000'000; };
}

struct AircraftFixture {
    struct Options {
        // Null: a new one at kFixtureStartUtcMicros. Given, when what is
        // built before the fixture (a secure endpoint) needs it too.
        std::shared_ptr<VirtualClock> clock;
        rcm::Airframe airframe = rcm::Airframe::wellEquipped();
        std::optional<rcm::StationId> identity;
        InProcessLink::Kind kind = InProcessLink::Kind::Datagrams;
        LinkWorker::Options console;   // the clock is set here
        LinkWorker::Options aircraft;  // likewise
        std::unique_ptr<FrameLog> consoleLog;
    };

    AircraftFixture() : AircraftFixture(Options{}) {}
    explicit AircraftFixture(Options options)
        : clock(options.clock ? options.clock : std::make_shared<VirtualClock>(kFixtureStartUtcMicros)),
          aircraft(options.airframe, options.identity)
    {
        auto [consoleEnd, aircraftEnd] = InProcessLink::pair(options.kind);
        options.console.clock = clock;
        options.aircraft.clock = clock;
        aircraftWorker =
            std::make_unique<LinkWorker>(std::move(aircraftEnd), nullptr, std::move(options.aircraft));
        responder = std::make_unique<AircraftResponder>(aircraft, *aircraftWorker);
        console =
            std::make_unique<LinkWorker>(std::move(consoleEnd), std::move(options.consoleLog), std::move(options.console));
    }

    // The aircraft first: listening before the console's first frame.
    void start()
    {
        aircraftWorker->start();
        console->start();
    }

    // Simulated time on; every frame, timeout and gear movement due in it happens.
    void run(std::chrono::microseconds duration) { clock->advance(duration); }

    std::shared_ptr<VirtualClock> clock;
    SimulatedAircraft aircraft;
    std::unique_ptr<LinkWorker> aircraftWorker;
    std::unique_ptr<AircraftResponder> responder;
    std::unique_ptr<LinkWorker> console;
};

}  // namespace rcm::test
