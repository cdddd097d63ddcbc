// uasim in the test's own process, on simulated time: the SimulatorSession
// that uasim runs, on a VirtualClock, each of its channels (the one link, or
// one a ground station) joined to the console by an InProcessLink pair
// instead of a UDP port. A ConsoleSession on the same clock connects to
// consoleEnd(); the test steps simulated time with run() and runUntil(),
// which settle what each timer set going (frames queued to the console's
// link thread, its reports queued back) before the next timer fires
// (SimulatedTime). The
// 1 Hz cadence, silence timeouts and failover take no wall-clock time, and
// what the aircraft says is collected as uasim's standard error is.
#pragma once

#include "InProcessLink.h"
#include "SimulatedTime.h"

#include "link/aircraft/SimulatorSession.h"
#include "link/clock/VirtualClock.h"

#include <QByteArray>

#include <chrono>
#include <functional>
#include <memory>
#include <vector>

namespace rcm::test {

class InProcessUasim {
public:
    // GB_30226 in control and GB_41251 its backup, each a channel of its own
    // (as UasimProcess's kTwoStations, without ports or keys).
    static std::vector<SimulatorSession::Station> twoStations()
    {
        return {{rcm::StationId{44, 30226}, 0, {}}, {rcm::StationId{44, 41251}, 0, {}}};
    }

    explicit InProcessUasim(SimulatorSession::Settings settings = {})
        : time(std::dynamic_pointer_cast<VirtualClock>(settings.clock)), clock(time.clock)
    {
        settings.clock = clock;
        settings.verbose = true;
        settings.transport = [this](const SimulatorSession::Station*) -> std::unique_ptr<Link> {
            auto [consoleEnd, aircraftEnd] = InProcessLink::pair(InProcessLink::Kind::Datagrams);
            m_aircraftEnds.push_back(aircraftEnd.get());
            time.watch(aircraftEnd.get());
            m_firstConsoleEnds.push_back(std::move(consoleEnd));
            return std::move(aircraftEnd);
        };
        session = std::make_unique<SimulatorSession>(std::move(settings), [this](const QString& line) {
            m_said += line.toUtf8() + '\n';
        });
    }
    ~InProcessUasim() { session->stop(); }
    InProcessUasim(const InProcessUasim&) = delete;
    InProcessUasim& operator=(const InProcessUasim&) = delete;

    // The aircraft listens on every channel.
    bool start() { return session->start(); }

    // The console's end of `channel`'s link, for ConsoleSession::connectLink()
    // or a LinkWorker: a new one each call, the one before cut off (another
    // sender on the same port, a console restarted).
    std::unique_ptr<Link> consoleEnd(std::size_t channel = 0)
    {
        if (m_firstConsoleEnds.at(channel))
            return std::move(m_firstConsoleEnds[channel]);
        return InProcessLink::replug(*m_aircraftEnds.at(channel));
    }
    // Cut (false) and joined again: the aircraft hears nothing and is not heard.
    void setConnected(bool connected, std::size_t channel = 0) { m_aircraftEnds.at(channel)->setConnected(connected); }

    // Simulated time on, settled after each timer (SimulatedTime).
    void run(std::chrono::microseconds duration) { time.run(duration); }
    bool runUntil(const std::function<bool()>& done, std::chrono::microseconds limit = std::chrono::seconds(60))
    {
        return time.runUntil(done, limit);
    }

    // What the aircraft said, as uasim --verbose says it on standard error.
    const QByteArray& stderrText() const { return m_said; }
    bool said(const char* text) const { return m_said.contains(text); }

    SimulatedTime time;
    std::shared_ptr<VirtualClock> clock;
    std::unique_ptr<SimulatorSession> session;

private:
    std::vector<InProcessLink*> m_aircraftEnds;  // owned by the session's workers
    std::vector<std::unique_ptr<Link>> m_firstConsoleEnds;
    QByteArray m_said;
};

}  // namespace rcm::test
