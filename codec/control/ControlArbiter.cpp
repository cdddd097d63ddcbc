#include "codec/control/ControlArbiter.h"

#include "codec/message/TextFormat.h"

#include <algorithm>

namespace rcm {

namespace {

std::string name(StationId station)
{
    return formatStation(station);
}

// "5 s", "2.5 s", "0.25 s": as long as it takes and no longer.
std::string seconds(std::chrono::microseconds time)
{
    const std::int64_t micros = time.count();
    std::string out = std::to_string(micros / 1'000'000);
    std::int64_t fraction = micros % 1'000'000;
    if (fraction != 0) {
        std::string digits = std::to_string(fraction);
        digits.insert(0, 6 - digits.size(), '0');
        digits.erase(digits.find_last_not_of('0') + 1);
        out += '.' + digits;
    }
    return out + " s";
}

}  // namespace

bool ControlArbiter::isClaim(StationId sender, std::optional<StationId> destination, std::optional<StationId> backup)
{
    return destination == sender && backup == sender;
}

ControlArbiter::ControlArbiter(std::vector<StationId> stations, std::chrono::microseconds failover)
    : m_failover(failover)
{
    // A station named twice would be its own backup.
    for (StationId s : stations)
        if (std::find(m_stations.begin(), m_stations.end(), s) == m_stations.end())
            m_stations.push_back(s);
    for (StationId s : m_stations)
        m_heard.push_back(Heard{s, std::nullopt, 0, false});
    if (!singleStation()) {
        m_controller = m_stations[0];
        m_backup = m_stations[1];
    }
}

ControlArbiter::Heard* ControlArbiter::find(StationId station)
{
    const auto it = std::find_if(m_heard.begin(), m_heard.end(), [&](const Heard& h) { return h.station == station; });
    return it == m_heard.end() ? nullptr : &*it;
}

const ControlArbiter::Heard* ControlArbiter::find(StationId station) const
{
    return const_cast<ControlArbiter*>(this)->find(station);
}

bool ControlArbiter::isStation(std::optional<StationId> station) const
{
    return station && find(*station);
}

std::uint64_t ControlArbiter::notInControlCount(StationId station) const
{
    const Heard* heard = find(station);
    return heard ? heard->notInControl : 0;
}

void ControlArbiter::controlChanged()
{
    for (Heard& h : m_heard)
        h.notInControlSaid = false;
}

ControlArbiter::Decision ControlArbiter::single(std::optional<StationId> destination, std::optional<StationId> backup)
{
    // As before there were several stations: the frame says who commands.
    if (destination)
        m_controller = destination;
    // A take-control claim names its sender twice: the backup stays as it was.
    if (backup && backup != destination)
        m_backup = backup;
    return Decision{true, {}, {}};
}

ControlArbiter::Decision ControlArbiter::onFrame(StationId sender, std::optional<StationId> destination,
                                                 std::optional<StationId> backup, std::int64_t nowMicros)
{
    if (singleStation())
        return single(destination, backup);
    if (!m_controlSinceMicros)
        m_controlSinceMicros = nowMicros;
    Heard* heard = find(sender);
    if (!heard)
        return Decision{false, {}, "no channel of this aircraft's"};
    heard->lastMicros = nowMicros;

    Decision decision;
    if (sender != *m_controller) {
        decision.notActedOn = "not in control";
        if (destination != sender)
            return decision;  // a backup's frame, naming the station in control
        ++heard->notInControl;
        if (!heard->notInControlSaid) {
            heard->notInControlSaid = true;
            decision.events.push_back({Event::Kind::NotInControl, "not in control: " + name(sender) +
                                                                      "'s frames are not acted on; " +
                                                                      name(*m_controller) + " in control"});
        }
        return decision;
    }
    if (destination == sender && !m_takenUp && !isClaim(sender, destination, backup)) {
        // Naming itself is what any frame of a station that thinks it is in
        // control does, a console just restarted among them: only its
        // operator's confirmed Take control, the claim, takes control up.
        decision.notActedOn =
            "control not yet taken up (" + name(sender) + " in control, waiting for its operator's Take control)";
        return decision;
    }
    if (destination == sender) {
        decision.act = true;
        if (!m_takenUp) {
            m_takenUp = true;
            m_offered = false;
            controlChanged();
            decision.events.push_back(
                {Event::Kind::TakenUp, "taken up: " + name(sender) + " in control, " + name(*m_backup) + " backup"});
        }
        if (backup && *backup != sender && *backup != *m_backup && isStation(backup)) {
            const StationId was = *m_backup;
            m_backup = backup;
            controlChanged();
            decision.events.push_back({Event::Kind::BackupChanged, "backup changed: " + name(*backup) + ", named by " +
                                                                       name(sender) + " in control (was " + name(was) +
                                                                       ")"});
        }
        return decision;
    }
    if (m_takenUp && destination == m_backup) {
        std::swap(m_controller, m_backup);
        m_takenUp = false;
        m_offered = true;
        m_controlSinceMicros = nowMicros;
        controlChanged();
        decision.events.push_back({Event::Kind::Handover, "handover: " + name(sender) + " hands control to " +
                                                              name(*m_controller) + ", not yet taken up"});
        decision.notActedOn = "a handover";
        return decision;
    }
    // Not yet taken up and naming another station (it has not seen that it
    // is in control), or naming a station that is neither: not a command.
    const std::string named = destination ? "names " + name(*destination) : std::string("names no station");
    decision.notActedOn =
        m_takenUp ? named + " as destination, not itself" : "control not yet taken up (" + named + " as destination)";
    return decision;
}

std::optional<ControlArbiter::Event> ControlArbiter::tick(std::int64_t nowMicros)
{
    if (singleStation())
        return std::nullopt;
    if (!m_controlSinceMicros)
        m_controlSinceMicros = nowMicros;
    const std::int64_t failover = m_failover.count();
    const Heard& controller = *find(*m_controller);
    const Heard& backup = *find(*m_backup);
    const std::int64_t controllerSince =
        std::max(controller.lastMicros.value_or(*m_controlSinceMicros), *m_controlSinceMicros);
    const bool silent = nowMicros - controllerSince >= failover;
    const bool lapsed = m_offered && !m_takenUp && nowMicros - *m_controlSinceMicros >= failover;
    if (!silent && !lapsed)
        return std::nullopt;
    // Control does not go to a station that is not there.
    if (!backup.lastMicros || nowMicros - *backup.lastMicros >= failover)
        return std::nullopt;
    const StationId was = *m_controller;
    std::swap(m_controller, m_backup);
    m_takenUp = false;
    m_offered = true;
    m_controlSinceMicros = nowMicros;
    controlChanged();
    if (silent)
        return Event{Event::Kind::Failover, "failover: nothing from " + name(was) + " for " + seconds(m_failover) +
                                                "; " + name(*m_controller) + " in control, not yet taken up"};
    return Event{Event::Kind::Lapsed, "not taken up: " + name(was) + " did not take control within " +
                                          seconds(m_failover) + "; " + name(*m_controller) +
                                          " in control, not yet taken up"};
}

}  // namespace rcm
