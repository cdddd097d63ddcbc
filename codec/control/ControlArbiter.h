// The aircraft's side of control between ground stations (docs/protocol.md
// section 10): which station's commands it acts on, which station takes over
// from it, and when control moves by handover or failover. Plain C++, no
// clock of its own: the caller says when each frame was delivered and ticks
// it at least once a second, in UTC microseconds, so that tests drive it
// frame by frame.
//
// It judges only frames the receive path delivered (section 8), each with
// the station whose channel it came on: on the secure link only that
// station's key opens the channel, so the sender is known, never read from
// the frame.
//
// With fewer than two stations (one channel, or none configured) it is the
// single-station aircraft: every delivered frame is acted on, and the
// station in control and the backup are whatever the last frame named.
#pragma once

#include "codec/message/Message.h"

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace rcm {

class ControlArbiter {
public:
    static constexpr std::chrono::microseconds kDefaultFailover{5'000'000};

    struct Event {
        enum class Kind {
            TakenUp,        // the station in control claimed control (isClaim): its commands are acted on
            Handover,       // the station in control gave control to the backup
            Failover,       // the station in control fell silent; the backup has control
            BackupChanged,  // the station in control named another backup
            NotInControl,   // a station not in control named itself destination (said once per change of control)
            Lapsed,         // control given was not taken up within the failover time; back to the backup
        };
        Kind kind;
        std::string text;  // one line for people, e.g. "failover: nothing from GB_30226 for 5 s; ..."
        friend bool operator==(const Event&, const Event&) = default;
    };

    struct Decision {
        bool act = false;           // hand the frame's commands (BLOCK 1 and BLOCK 2) to the aircraft
        std::vector<Event> events;  // what the frame changed, in the order it happened
        std::string notActedOn;     // why not, for people ("not in control"); empty when acted on
    };

    // `stations`: those the aircraft has a channel for, the first in control
    // and the second its backup at start. Fewer than two: single-station.
    explicit ControlArbiter(std::vector<StationId> stations = {},
                            std::chrono::microseconds failover = kDefaultFailover);

    // A frame delivered on `sender`'s channel at `nowMicros`, naming
    // `destination` (ID_GCS_destination) and `backup` (ID_GCS_backup), each
    // absent when the frame does not carry it. In single-station mode the
    // sender is not looked at.
    Decision onFrame(StationId sender, std::optional<StationId> destination, std::optional<StationId> backup,
                     std::int64_t nowMicros);
    // Failover, when it is due at `nowMicros`: nothing delivered from the
    // station in control for at least the failover time, counted from when
    // it was given control at the earliest (at start, the first time the
    // arbiter is told of), and something from the backup less than the
    // failover time ago. Or control given by handover or failover that was
    // not taken up within the failover time: it lapses back to the backup,
    // if heard, so that a station that does not answer the offer does not
    // leave the aircraft acting on nobody.
    std::optional<Event> tick(std::int64_t nowMicros);

    // The frame a console sends once its operator confirmed Take control:
    // it names its sender both as ID_GCS_destination and as ID_GCS_backup
    // (docs/protocol.md section 10). No other frame a console sends names
    // one station twice, so only that action takes control up.
    static bool isClaim(StationId sender, std::optional<StationId> destination, std::optional<StationId> backup);

    bool singleStation() const { return m_stations.size() < 2; }
    const std::vector<StationId>& stations() const { return m_stations; }
    std::chrono::microseconds failover() const { return m_failover; }
    // C and K: what each status frame names as ID_GCS_destination and
    // ID_GCS_backup. Always set with two stations or more; single-station,
    // what the last frame named, none before.
    std::optional<StationId> controller() const { return m_controller; }
    std::optional<StationId> backup() const { return m_backup; }
    // Whether the station in control has taken up control: its commands are
    // acted on. Always true single-station.
    bool takenUp() const { return singleStation() || m_takenUp; }
    // Frames from `station` that named it destination (commands) while it
    // was not in control, not acted on. A backup's frames naming the station
    // in control are not counted: that is what a backup sends.
    std::uint64_t notInControlCount(StationId station) const;

private:
    struct Heard {
        StationId station;
        std::optional<std::int64_t> lastMicros;  // the last frame delivered from it
        std::uint64_t notInControl = 0;
        bool notInControlSaid = false;  // since control last changed
    };

    Heard* find(StationId station);
    const Heard* find(StationId station) const;
    bool isStation(std::optional<StationId> station) const;
    // Control moved, or the backup did: a station not in control is told of again.
    void controlChanged();
    Decision single(std::optional<StationId> destination, std::optional<StationId> backup);

    std::vector<StationId> m_stations;
    std::chrono::microseconds m_failover;
    std::vector<Heard> m_heard;  // one per station, in m_stations' order
    std::optional<StationId> m_controller;
    std::optional<StationId> m_backup;
    bool m_takenUp = false;
    // Control was given (handover, failover, lapse), not configured at start:
    // it lapses when not taken up in time.
    bool m_offered = false;
    // When the station in control was given control: its silence counts from
    // then at the earliest, so that a station just given control has the
    // whole failover time to be heard. The first time the arbiter is told of.
    std::optional<std::int64_t> m_controlSinceMicros;
};

}  // namespace rcm
