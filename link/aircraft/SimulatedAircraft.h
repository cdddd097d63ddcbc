// The aircraft end of the link, without the aircraft: keeps the state a
// command sets, moves the slow parts (landing gear, control surfaces) at a
// finite rate, and reports the state it actually has in a status message of
// the command's own format. No I/O and no clock of its own: the caller feeds
// commands, advances time and asks for status frames, so tests drive it
// frame by frame.
//
// Status message contents (the same Remote Control Message format):
//   header   ID_msg counting the status frames from 0; ID_UA_source the
//            aircraft's identity; time_UTC and date_UTC of the frame; the last
//            commanded ID_BLK12_format, ID_GCS_destination and ID_GCS_backup,
//            echoed once a command carried them.
//   units    every unit the airframe has, every item set: what the aircraft
//            does, not what it was told. The differences from the last command:
//            - land_wheels: each wheel reports its locked position (OUT or
//              RETRACTED) until it has finished moving, kGearTransit later;
//            - F_*_set: the surface's present angle, slewing toward the
//              command at kSurfaceRate (kFlapRate for lift flaps and airbrake);
//            - ENABLE_fuel_dump: a tank dumps only while the facility is
//              enabled; otherwise its field reads NO_DUMP;
//            - take_one_photo: TAKE in the first status frame after the camera
//              took a photograph, NONE otherwise.
//   BLOCK 2  empty until a flight plan has been received complete; then the
//            acknowledgement of the last complete plan (section ID 0xFFFF,
//            see codec/message/FlightPlanTransfer.h) in every status frame,
//            with the report of its contents (codec/plan/PlanContents.h)
//            when it is a format 2 plan: mission items, fence, rally points.
//
// Slave codes (eng_status, FLAP_status) and control sources are kept and
// reported but do not change how the simulated parts move.
#pragma once

#include "codec/message/Airframe.h"
#include "codec/message/FlightPlanTransfer.h"
#include "codec/message/Message.h"
#include "link/session/MessageMetaType.h"

#include <array>
#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

class SimulatedAircraft {
public:
    // More than two status frames, so that the console's "mismatch persists"
    // highlight shows for every gear movement.
    static constexpr std::chrono::milliseconds kGearTransit{3500};
    static constexpr double kSurfaceRate = 40.0;  // degrees per second: ailerons, rudder, elevator
    static constexpr double kFlapRate = 10.0;     // lift flaps and airbrake
    // The seed's example aircraft, GB 133: the identity until one is set or adopted.
    static constexpr rcm::StationId kDefaultIdentity{44, 133};

    // With no identity, the aircraft adopts the ID_UA_source of the first
    // command that carries one.
    explicit SimulatedAircraft(rcm::Airframe airframe = rcm::Airframe::wellEquipped(),
                               std::optional<rcm::StationId> identity = std::nullopt);

    // What one command did, for the operator of the simulator.
    struct ApplyReport {
        std::vector<std::string> ignored;             // fields, values and units not acted on, and why
        std::vector<std::string> events;              // photographs taken, gear moving, flight plan complete ...
        rcm::FlightPlanAssembler::Result flightPlan;  // what BLOCK 2 did
    };

    // Acts on the valid fields of a decoded command. Items absent from the
    // command leave their state as it was.
    ApplyReport apply(const rcm::Message& command);

    // Moves the gear and the surfaces on by `elapsed`.
    void advance(std::chrono::milliseconds elapsed);

    // The next status frame's message. It stays the same until the state
    // changes or statusSent() is called, so it can be handed to a sender
    // again after every command without counting a frame each time.
    rcm::Message status(std::chrono::system_clock::time_point utc) const;
    // The status frame went out: counts it (ID_msg) and ends the one-frame
    // indications (take_one_photo TAKE).
    void statusSent();

    const rcm::Airframe& airframe() const { return m_airframe; }
    rcm::StationId identity() const { return m_identity.value_or(kDefaultIdentity); }
    std::uint32_t statusFrames() const { return m_statusFrames; }
    // Photographs taken by the airframe's camera `index`.
    int photoCount(std::size_t index) const { return m_cameras.at(index).photos; }
    bool gearMoving() const;
    // The last flight plan received complete; empty with ID 0 before that.
    std::uint32_t flightPlanId() const { return m_flightPlanId; }
    const std::vector<std::uint8_t>& flightPlan() const { return m_flightPlan; }

private:
    struct Wheel {
        double extension = 1.0;  // 1 out, 0 retracted
        unsigned locked = 1;     // the land_wheels code of the last end position reached
        unsigned target = 1;
    };
    struct Camera {
        unsigned lastPhotoCode = rcm::code::kNone;
        int photos = 0;
        bool photoSinceStatus = false;
    };

    void mergeUnit(rcm::Unit& into, const rcm::Unit& command, ApplyReport& report);
    void applyHeader(const rcm::Unit& header);
    void applySurfaces(ApplyReport& report);
    void applyGear(ApplyReport& report);
    void applyPhotos(const rcm::Message& command, ApplyReport& report);

    rcm::Airframe m_airframe;
    std::optional<rcm::StationId> m_identity;
    // Every item as last validly commanded; the status starts from it.
    rcm::Message m_commanded;
    std::array<double, 6> m_surfaceAngle{};  // in the order of kSurfaces
    std::array<Wheel, 4> m_wheels{};
    std::vector<Camera> m_cameras;
    rcm::FlightPlanAssembler m_assembler;
    std::uint32_t m_flightPlanId = 0;
    std::vector<std::uint8_t> m_flightPlan;
    std::vector<std::uint8_t> m_flightPlanReport;  // what the acknowledgement says of its contents
    std::uint32_t m_statusFrames = 0;
};
