#include "link/aircraft/AircraftResponder.h"

AircraftResponder::AircraftResponder(SimulatedAircraft& aircraft, LinkWorker& worker, QObject* parent)
    : QObject(parent), m_aircraft(aircraft), m_worker(worker), m_lastSteadyMicros(worker.clock().steadyMicros())
{
    connect(&worker, &LinkWorker::messageReceived, this, [this](const ReceivedMessage& received) {
        const SimulatedAircraft::ApplyReport report = m_aircraft.apply(received.message);
        emit commandApplied(received, report);
        offerStatus();
    });
    connect(&worker, &LinkWorker::frameSent, this, [this] {
        m_aircraft.statusSent();
        // Whole milliseconds; the remainder is carried to the next frame.
        const auto elapsed = std::chrono::duration_cast<std::chrono::milliseconds>(
            std::chrono::microseconds(m_worker.clock().steadyMicros() - m_lastSteadyMicros));
        m_aircraft.advance(elapsed);
        m_lastSteadyMicros += std::chrono::microseconds(elapsed).count();
        offerStatus();
    });
    offerStatus();
}

void AircraftResponder::offerStatus()
{
    const std::chrono::sys_time<std::chrono::microseconds> utc{std::chrono::microseconds(m_worker.clock().utcMicros())};
    m_worker.setCommand(m_aircraft.status(utc));
}
