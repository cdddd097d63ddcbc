#pragma once

// Runs a scenario: the console's LinkWorker, commanding what the steps set,
// and the simulated aircraft, joined by a RehearsalChannel that applies the
// faults.
//
// Faster than real time (and runToEnd()) it all runs in process: the
// aircraft behind its own LinkWorker (as uasim flies it), on one
// VirtualClock, so that nothing in a run depends on the wall clock. At speed
// 1 it runs the real programs: uasim as a process on a loopback port or a
// pseudo-terminal, the console's link on a real socket or serial device, and
// a RehearsalProxy between them with the channel's faults, on the wall
// clock (the SystemClock unless the runner is given another).
//
// Every expectation is judged as the run goes, and what it found is the
// RehearsalReport; the console's frames both ways go to a frame log.

#include "codec/secure/SecureCodec.h"
#include "link/rehearsal/RehearsalChannel.h"
#include "link/rehearsal/RehearsalReport.h"
#include "link/rehearsal/Scenario.h"

#include <QObject>

#include <deque>
#include <memory>
#include <optional>

class AircraftResponder;
class Clock;
class ClockTimer;
class FrameLog;
class Link;
class LinkWorker;
class QTemporaryDir;
class RehearsalLauncher;
class RehearsalProxy;
class SatelliteModemThread;
class SimulatedAircraft;
class VirtualClock;
namespace rcm {
class FlightPlanUploader;
namespace secure {
class SecureCodec;
}
}  // namespace rcm

class ScenarioRunner : public QObject {
    Q_OBJECT

public:
    // `frameLogPath`: the run's frame log (pcapng); empty for none.
    // `wallClock` paces a run and is the time of one at speed 1; null: the SystemClock.
    ScenarioRunner(Scenario scenario, const QString& frameLogPath, QObject* parent = nullptr,
                   std::shared_ptr<Clock> wallClock = nullptr);
    ~ScenarioRunner() override;

    // Paced: `speed` scenario seconds per wall-clock second (the scenario's
    // own when 0 or less); returns at once, progress() as it goes, finished()
    // at the end. At speed 1, against `uasimProgram` (beside this program
    // when empty) as a process.
    void start(double speed = 0, const QString& uasimProgram = QString());
    // Whether this run is against the real programs (known once started).
    bool realPrograms() const { return m_real; }
    // As fast as it goes, without an event loop; finished() before it returns.
    void runToEnd();
    bool isFinished() const { return m_finished; }

    const Scenario& scenario() const { return m_scenario; }
    const RehearsalReport& report() const { return m_report; }
    // Why the frame log could not be written; empty when it was.
    QString frameLogError() const { return m_frameLogError; }

signals:
    void progress(double scenarioSeconds, double duration);
    // Each step, fault, alarm and event as it goes into the report's timeline.
    void noted(double scenarioSeconds, const QString& kind, const QString& text);
    void finished();

private:
    struct Pending;
    double now() const;
    void advanceTo(double seconds);
    void applyStep(const ScenarioStep& step);
    void received(RehearsalChannel::End sender, const rcm::Message& message);
    void statusReceived(const rcm::Message& status);
    void alarm(const QString& name);
    void recordFault(const ScenarioStep& step);
    void note(const QString& kind, const QString& text);
    void judgeDeadlines();
    void sampleQuality();
    void finish();
    void paceTick();
    void buildInProcess();
    void startReal(const QString& uasimProgram);
    void uasimSaid(const QString& line);
    void makeConsole(std::unique_ptr<Link> link);
    std::unique_ptr<Link> consoleModem(const QString& device);
    void beginPacing();

    Scenario m_scenario;
    QString m_frameLogError;
    std::unique_ptr<FrameLog> m_log;  // until the console's worker takes it
    std::optional<rcm::secure::SecretKey> m_psk;
    bool m_real = false;
    bool m_built = false;
    std::shared_ptr<VirtualClock> m_clock;  // in process
    std::shared_ptr<Clock> m_time;          // what the run's time is read from: m_clock, or m_wall
    std::unique_ptr<QTemporaryDir> m_keyDir;  // real programs, keyed: uasim's key file
    RehearsalLauncher* m_launcher = nullptr;
    std::unique_ptr<RehearsalProxy> m_proxy;
    std::unique_ptr<SatelliteModemThread> m_modem;  // the modem transport's pair of modems
    std::deque<quint32> m_sentIds;                   // the modem transport: ID_msg of the console's last frames
    qint64 m_sentUp = 0;                             // the modem transport: frames the console sent
    std::int64_t m_startUtcMicros;
    RehearsalChannel m_channel;
    std::unique_ptr<SimulatedAircraft> m_aircraft;
    std::unique_ptr<LinkWorker> m_aircraftWorker;
    std::unique_ptr<AircraftResponder> m_responder;
    std::unique_ptr<LinkWorker> m_console;
    std::unique_ptr<rcm::FlightPlanUploader> m_upload;
    // Secure link: each sender's cipher, to read what it sent.
    std::array<std::unique_ptr<rcm::secure::SecureCodec>, 2> m_ciphers;
    rcm::Message m_command;
    std::vector<Pending> m_pending;  // one per timed expectation
    // A fault acting now: its period in the report ends when it does.
    struct OpenFault {
        FaultSpec::Kind kind;
        FaultDirection direction;
        std::size_t index;  // into m_report.faults
    };
    std::vector<OpenFault> m_openFaults;
    std::size_t m_nextStep = 0;      // steps are applied in order of "at"
    std::vector<std::size_t> m_order;
    std::array<qint64, 2> m_goodReceived{};          // by sender
    std::vector<std::array<qint64, 4>> m_perSecond;  // cumulative sent up/down, received up/down
    RehearsalReport m_report;
    std::shared_ptr<Clock> m_wall;
    ClockTimer* m_paceTimer = nullptr;
    qint64 m_paceStartSteadyMicros = 0;  // on m_wall
    double m_speed = 1;
    double m_done = 0;
    bool m_started = false;
    bool m_finished = false;
};
