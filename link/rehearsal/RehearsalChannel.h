#pragma once

// The radio path of a rehearsal run in process: two Link ends, the console's
// and the aircraft's, and between them the scenario's faults (Scenario.h says
// what each does). What one end writes the other receives within the write(),
// as one datagram (UDP) or one stream piece (serial), so a run on a
// VirtualClock is deterministic: the same scenario damages the same bits.
//
// It keeps the frames each end sent, undamaged, so that the run can tell a
// frame delivered right from a wrong one, and counts what it carried.

#include "link/rehearsal/Scenario.h"
#include "link/transport/Link.h"

#include <QByteArray>

#include <array>
#include <deque>
#include <memory>
#include <random>

class RehearsalChannel {
public:
    enum End { Console = 0, Aircraft = 1 };

    struct Counters {
        qint64 framesSent = 0;      // written by this end
        qint64 framesInOutage = 0;  // of those, lost to an outage
        qint64 framesDamaged = 0;   // delivered with at least one byte changed
    };

    RehearsalChannel(bool stream, std::uint64_t seed);
    ~RehearsalChannel();

    // Each end, to be owned by its LinkWorker; the channel must outlive both.
    std::unique_ptr<Link> takeEnd(End end);

    // From now on; an outage starts now. Clear ends every fault.
    void apply(const FaultSpec& fault, double nowSeconds);
    void setTime(double nowSeconds) { m_now = nowSeconds; }
    bool inOutage(End sender) const;

    const Counters& counters(End sender) const { return m_counters[sender]; }
    // The last frames `sender` wrote, undamaged, newest last.
    const std::deque<QByteArray>& recentFrames(End sender) const { return m_recent[sender]; }

private:
    class EndLink;
    struct Faults {
        double ber = 0;
        double slip = 0;
        double burst = 0;
        double outageUntil = -1;
    };
    friend class EndLink;
    void carry(End sender, QByteArray bytes);
    void damage(Faults& faults, QByteArray& bytes, Counters& counters);

    bool m_stream;
    std::mt19937_64 m_rng;
    double m_now = 0;
    std::array<EndLink*, 2> m_ends{};
    std::array<Faults, 2> m_faults;  // by sender: up is what the console sends
    std::array<Counters, 2> m_counters;
    std::array<std::deque<QByteArray>, 2> m_recent;
};
