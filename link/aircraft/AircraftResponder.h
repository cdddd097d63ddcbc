#pragma once

// A simulated aircraft at the far end of a LinkWorker, as uasim flies it:
// every command received is acted on at once, and every frame the worker
// sends is the status the aircraft has by then. Between two status frames
// the aircraft moves on by the time that passed on the worker's clock, and
// each status is stamped with that clock's UTC, so on a VirtualClock a test
// flies it in simulated seconds.
//
// Worker and aircraft stay in one thread, so every status frame is exactly
// the state after the commands received before it (a one-frame indication
// such as a photograph taken cannot be cleared by a frame that did not carry it).

#include "link/aircraft/SimulatedAircraft.h"
#include "link/session/LinkWorker.h"

#include <QObject>

class AircraftResponder : public QObject {
    Q_OBJECT

public:
    // Both must outlive the responder. Offers the first status at once.
    AircraftResponder(SimulatedAircraft& aircraft, LinkWorker& worker, QObject* parent = nullptr);

signals:
    // After each command was applied, with what it did.
    void commandApplied(const ReceivedMessage& received, const SimulatedAircraft::ApplyReport& report);

private:
    void offerStatus();

    SimulatedAircraft& m_aircraft;
    LinkWorker& m_worker;
    std::int64_t m_lastSteadyMicros;  // when the aircraft was last moved on
};
