#include "link/rehearsal/ScenarioRunner.h"

#include "codec/message/FlightPlanTransfer.h"
#include "codec/receive/LoggedFrameReading.h"
#include "codec/secure/SecureCodec.h"
#include "link/aircraft/AircraftResponder.h"
#include "link/aircraft/SimulatedAircraft.h"
#include "link/clock/VirtualClock.h"
#include "link/framelog/FrameLog.h"
#include "link/rehearsal/RehearsalProxy.h"
#include "link/satmodem/SatelliteModemThread.h"
#include "link/session/LinkWorker.h"
#include "link/session/RehearsalLauncher.h"
#include "link/transport/ModemLink.h"
#include "link/transport/SerialLink.h"
#include "link/transport/UdpLink.h"

#include <QRegularExpression>
#include <QTemporaryDir>
#include <QTimer>

#include <algorithm>
#include <chrono>
#include <cmath>

namespace {

QString transportName(Scenario::Transport transport)
{
    static const char* const names[] = {"udp", "serial", "modem"};
    return QLatin1String(names[int(transport)]);
}

// 2026-11-22 08:00:00 UTC: every run starts at the same instant, so that the
// same scenario gives the same frames.
constexpr std::int64_t kStartUtcMicros = 1'795'334'400'000'000;
// The faults' random numbers: fixed, for the same reason.
constexpr std::uint64_t kSeed = 0x5245484541525345;  // "REHEARSE"
// Scenario time moves in steps this long between judging expectations.
constexpr double kStepSeconds = 0.1;
// Link quality is judged over this window.
constexpr int kQualityWindow = 10;
// Passes over the plan before the upload gives up, as the console's.
constexpr int kUploadPasses = 5;
// A paced run catches up with the wall clock this often.
constexpr std::chrono::milliseconds kPaceInterval{20};

// The message in a frame as its sender sent it, read through the receive
// path for logged frames (with the sender's direction of the key on the
// secure link); nothing when that path refuses it.
std::optional<rcm::Message> sentMessage(const QByteArray& frame, const rcm::secure::SecureCodec* cipher)
{
    const auto* bytes = reinterpret_cast<const std::uint8_t*>(frame.constData());
    std::vector<const rcm::secure::SecureCodec*> codecs;
    if (cipher)
        codecs.push_back(cipher);
    rcm::LoggedFrameReading reading =
        rcm::readLoggedFrame(std::span(bytes, std::size_t(frame.size())), cipher != nullptr, codecs);
    if (!reading.read())
        return std::nullopt;
    return std::move(reading.decoded.message);
}

}  // namespace

// A timed expectation and what became of it.
struct ScenarioRunner::Pending {
    const ScenarioStep* step;
    bool decided = false;
    bool held = false;
    double measured = 0;
    double deadline() const { return *step->at + step->within; }
};

ScenarioRunner::ScenarioRunner(Scenario scenario, const QString& frameLogPath, QObject* parent,
                               std::shared_ptr<Clock> wallClock)
    : QObject(parent),
      m_scenario(std::move(scenario)),
      m_clock(std::make_shared<VirtualClock>(kStartUtcMicros)),
      m_time(m_clock),
      m_startUtcMicros(kStartUtcMicros),
      m_channel(m_scenario.transport != Scenario::Transport::Udp, kSeed),
      m_wall(wallClock ? std::move(wallClock) : std::make_shared<SystemClock>())
{
    m_report.scenarioName = m_scenario.name;
    m_report.scenarioPath = m_scenario.path;
    m_report.duration = m_scenario.duration;
    if (!frameLogPath.isEmpty()) {
        m_log = std::make_unique<FrameLog>();
        if (!m_log->open(frameLogPath, &m_frameLogError))
            m_log.reset();
    }
    if (m_scenario.key) {
        // A fresh key for each run, as the issue asks.
        m_psk = rcm::secure::generateKey();
        m_ciphers[RehearsalChannel::Console] =
            std::make_unique<rcm::secure::SecureCodec>(*m_psk, rcm::secure::Direction::GcsToUa);
        m_ciphers[RehearsalChannel::Aircraft] =
            std::make_unique<rcm::secure::SecureCodec>(*m_psk, rcm::secure::Direction::UaToGcs);
    }
    for (std::size_t i = 0; i < m_scenario.steps.size(); ++i) {
        const ScenarioStep& step = m_scenario.steps[i];
        if (step.at)
            m_order.push_back(i);
        if (step.at && step.isExpectation())
            m_pending.push_back(Pending{&step});
        if (step.kind == ScenarioStep::Kind::Set)
            m_report.latencies.push_back({step.number, step.text, std::nullopt});
    }
    std::stable_sort(m_order.begin(), m_order.end(), [this](std::size_t a, std::size_t b) {
        return *m_scenario.steps[a].at < *m_scenario.steps[b].at;
    });

    m_command = rcm::restingCommand(m_scenario.airframe);
}

// The console's worker on `link`, keyed as the scenario says, on m_time.
// The console's side of the modem transport: it dials uasim's modem, with
// the modem model's short guard time, and redials a dropped call.
std::unique_ptr<Link> ScenarioRunner::consoleModem(const QString& device)
{
    ModemLink::Options options;
    options.number = QStringLiteral("881600000001");
    options.initString = "ATE0V1&C1&D2S12=5";
    options.guardTime = std::chrono::milliseconds(150);
    options.clock = m_time;  // the run's clock: real time, as the modem model keeps
    options.redialDelay = std::chrono::milliseconds(qint64((Scenario::kCallDropOutage - Scenario::kModemCallSetupSeconds) * 1000));
    auto link = std::make_unique<ModemLink>(
        std::make_unique<SerialLink>(device, SerialLink::kDefaultBaudRate, SerialLink::FlowControl::RtsCts), options);
    connect(link.get(), &Link::statusChanged, this, [this](const QString& status) {
        if (!m_finished)
            note(QStringLiteral("event"), QStringLiteral("console's modem: ") + status);
    });
    return link;
}

void ScenarioRunner::makeConsole(std::unique_ptr<Link> link)
{
    LinkWorker::Options consoleOptions;
    consoleOptions.clock = m_time;
    if (m_psk) {
        rcm::secure::SecureEndpoint::Options options;
        options.persistState = false;  // its state in memory only
        options.clock = [clock = m_time] { return clock->utcMicros() / 1'000'000; };
        std::string error;
        consoleOptions.secure =
            rcm::secure::SecureEndpoint::fromKey(*m_psk, rcm::secure::Direction::GcsToUa, {}, error, options);
    }
    consoleOptions.block2Source = [this]() -> std::optional<rcm::FlightPlanSection> {
        return m_upload ? m_upload->next() : std::nullopt;
    };
    consoleOptions.block2Reply = [this](const rcm::FlightPlanSection& reply) {
        if (!m_upload || m_upload->state() != rcm::FlightPlanUploader::State::Sending || !m_upload->handleReply(reply))
            return;
        note(QStringLiteral("event"), QStringLiteral("flight plan %1 acknowledged")
                                          .arg(QString::fromStdString(rcm::planIdText(m_upload->planId()))));
        for (Pending& p : m_pending)
            if (!p.decided && p.step->kind == ScenarioStep::Kind::ExpectPlan && now() >= *p.step->at &&
                now() <= p.deadline())
                p.decided = p.held = true, p.measured = now() - *p.step->at;
    };
    m_console = std::make_unique<LinkWorker>(std::move(link), std::move(m_log), std::move(consoleOptions));
    connect(m_console.get(), &LinkWorker::frameSent, this, [this](quint32 id) {
        ++m_sentUp;
        m_sentIds.push_back(id);
        if (m_sentIds.size() > 32)
            m_sentIds.pop_front();
    });
    connect(m_console.get(), &LinkWorker::messageReceived, this, [this](const ReceivedMessage& r) {
        received(RehearsalChannel::Aircraft, r.message);
        statusReceived(r.message);
    });
    connect(m_console.get(), &LinkWorker::linkLost, this, [this] { alarm(QStringLiteral("link-lost")); });
    connect(m_console.get(), &LinkWorker::linkRegained, this, [this] { alarm(QStringLiteral("link-regained")); });
    connect(m_console.get(), &LinkWorker::errorOccurred, this,
            [this](const QString& message) { note(QStringLiteral("event"), message); });
    connect(m_console.get(), &LinkWorker::commandRejected, this, [this](const QString& reasons) {
        note(QStringLiteral("event"), QStringLiteral("command refused: ") + reasons);
    });
}

void ScenarioRunner::buildInProcess()
{
    m_built = true;
    m_report.transport =
        QStringLiteral("%1 (in process)%2")
            .arg(transportName(m_scenario.transport), m_scenario.key ? QStringLiteral(", secure link") : QString());
    m_aircraft = std::make_unique<SimulatedAircraft>(m_scenario.airframe);
    LinkWorker::Options aircraftOptions;
    aircraftOptions.clock = m_clock;
    if (m_psk) {
        rcm::secure::SecureEndpoint::Options options;
        options.persistState = false;
        options.clock = [clock = m_clock] { return clock->utcMicros() / 1'000'000; };
        std::string error;
        aircraftOptions.secure =
            rcm::secure::SecureEndpoint::fromKey(*m_psk, rcm::secure::Direction::UaToGcs, {}, error, options);
    }
    m_aircraftWorker = std::make_unique<LinkWorker>(m_channel.takeEnd(RehearsalChannel::Aircraft), nullptr,
                                                    std::move(aircraftOptions));
    m_responder = std::make_unique<AircraftResponder>(*m_aircraft, *m_aircraftWorker);
    makeConsole(m_channel.takeEnd(RehearsalChannel::Console));
    connect(m_aircraftWorker.get(), &LinkWorker::messageReceived, this,
            [this](const ReceivedMessage& r) { received(RehearsalChannel::Console, r.message); });
    connect(m_responder.get(), &AircraftResponder::commandApplied, this,
            [this](const ReceivedMessage&, const SimulatedAircraft::ApplyReport& report) {
                for (const std::string& event : report.events)
                    note(QStringLiteral("event"), QStringLiteral("aircraft: ") + QString::fromStdString(event));
            });
}

ScenarioRunner::~ScenarioRunner()
{
    // The responder and workers refer to each other and to the channel: end them first.
    m_responder.reset();
    m_console.reset();
    m_aircraftWorker.reset();
    m_proxy.reset();
}

double ScenarioRunner::now() const
{
    return double(m_time->utcMicros() - m_startUtcMicros) / 1e6;
}

void ScenarioRunner::note(const QString& kind, const QString& text)
{
    m_report.timeline.push_back({now(), kind, text});
    emit noted(now(), kind, text);
}

void ScenarioRunner::applyStep(const ScenarioStep& step)
{
    switch (step.kind) {
        case ScenarioStep::Kind::Set:
            applyItems(m_command, step.items);
            m_console->setCommand(m_command);
            note(QStringLiteral("step"), step.describe());
            break;
        case ScenarioStep::Kind::Fault:
            if (m_modem && step.fault.kind == FaultSpec::Kind::CallDrop)
                m_modem->dropCall();
            else
                m_channel.apply(step.fault, now());
            recordFault(step);
            note(QStringLiteral("fault"), step.describe());
            break;
        case ScenarioStep::Kind::Upload:
            m_upload = std::make_unique<rcm::FlightPlanUploader>(
                0x52450000u + std::uint32_t(step.number),
                std::span(reinterpret_cast<const std::uint8_t*>(step.plan.constData()), std::size_t(step.plan.size())),
                m_scenario.key ? rcm::secure::kMaxFlightPlanData : rcm::FlightPlanSection::kMaxData, kUploadPasses);
            note(QStringLiteral("step"),
                 step.describe() + QStringLiteral(" (flight plan %1, %2 %3)")
                                       .arg(QString::fromStdString(rcm::planIdText(m_upload->planId())))
                                       .arg(m_upload->sections().size())
                                       .arg(m_upload->sections().size() == 1 ? QStringLiteral("section")
                                                                             : QStringLiteral("sections")));
            break;
        default:
            note(QStringLiteral("step"), step.describe());
            break;
    }
}

void ScenarioRunner::received(RehearsalChannel::End sender, const rcm::Message& message)
{
    ++m_goodReceived[sender];
    if (m_modem)
        return;  // what uasim sent through the modem model is not seen here: counted, not judged
    const auto& recent = m_channel.recentFrames(sender);
    const bool sent = std::any_of(recent.rbegin(), recent.rend(), [&](const QByteArray& f) {
        return sentMessage(f, m_ciphers[sender].get()) == message;
    });
    if (!sent) {
        ++m_report.frames.wrong;
        note(QStringLiteral("event"), sender == RehearsalChannel::Console
                                          ? QStringLiteral("wrong frame delivered to the aircraft")
                                          : QStringLiteral("wrong frame delivered to the console"));
    }
}

void ScenarioRunner::statusReceived(const rcm::Message& status)
{
    const double t = now();
    for (Pending& p : m_pending)
        if (!p.decided && p.step->kind == ScenarioStep::Kind::ExpectReported && t >= *p.step->at && t <= p.deadline() &&
            reportsItems(status, p.step->items))
            p.decided = p.held = true, p.measured = t - *p.step->at;
    for (RehearsalReport::Latency& latency : m_report.latencies) {
        const auto it = std::find_if(m_scenario.steps.begin(), m_scenario.steps.end(),
                                     [&](const ScenarioStep& s) { return s.number == latency.step; });
        if (!latency.seconds && t >= *it->at && reportsItems(status, it->items))
            latency.seconds = t - *it->at;
    }
}

void ScenarioRunner::recordFault(const ScenarioStep& step)
{
    const double t = now();
    const FaultSpec& fault = step.fault;
    const auto overlaps = [](FaultDirection a, FaultDirection b) {
        return a == FaultDirection::Both || b == FaultDirection::Both || a == b;
    };
    // As RehearsalChannel::apply: clear ends every fault, an outage too; a
    // fault of the same kind replaces one acting the same way.
    for (OpenFault& open : m_openFaults) {
        const bool replaced = open.kind == fault.kind && fault.kind != FaultSpec::Kind::Outage &&
                              fault.kind != FaultSpec::Kind::CallDrop && overlaps(open.direction, fault.direction);
        if (fault.kind == FaultSpec::Kind::Clear || replaced)
            m_report.faults[open.index].end = std::min(m_report.faults[open.index].end, t);
    }
    std::erase_if(m_openFaults, [&](const OpenFault& open) { return m_report.faults[open.index].end <= t; });
    if (fault.kind == FaultSpec::Kind::Clear ||
        (fault.kind != FaultSpec::Kind::Outage && fault.kind != FaultSpec::Kind::CallDrop && fault.value <= 0))
        return;
    const double seconds = fault.kind == FaultSpec::Kind::Outage     ? fault.value
                           : fault.kind == FaultSpec::Kind::CallDrop ? Scenario::kCallDropOutage
                                                                     : m_scenario.duration - t;
    QString text = step.describe();
    text = text.mid(text.indexOf(QStringLiteral(": ")) + 2);  // without "step 5 at 40 s: "
    m_report.faults.push_back({t, std::min(t + seconds, m_scenario.duration), text});
    m_openFaults.push_back({fault.kind, fault.direction, m_report.faults.size() - 1});
}

void ScenarioRunner::alarm(const QString& name)
{
    const double t = now();
    // Expected by the first step that expects this alarm around now, else
    // by one that allows link losses over the whole run (which fails when
    // they are more than it allows).
    int expectedBy = 0;
    for (const ScenarioStep& step : m_scenario.steps)
        if (step.kind == ScenarioStep::Kind::ExpectAlarm && step.text == name && t >= *step.at - 1e-9 &&
            t <= *step.at + step.within + 1e-9) {
            expectedBy = step.number;
            break;
        }
    for (const ScenarioStep& step : m_scenario.steps)
        if (expectedBy == 0 && step.kind == ScenarioStep::Kind::ExpectLinkLostAtMost &&
            name == QLatin1String("link-lost"))
            expectedBy = step.number;
    const RehearsalReport::Alarm raised{t, name, expectedBy};
    m_report.alarms.push_back(raised);
    note(QStringLiteral("alarm"), raised.unexpected() ? name + QStringLiteral(": no step expected it") : name);
    for (Pending& p : m_pending)
        if (!p.decided && p.step->kind == ScenarioStep::Kind::ExpectAlarm && p.step->text == name && t >= *p.step->at &&
            t <= p.deadline())
            p.decided = p.held = true, p.measured = t - *p.step->at;
}

void ScenarioRunner::judgeDeadlines()
{
    for (Pending& p : m_pending)
        if (!p.decided && now() > p.deadline() + 1e-9)
            p.decided = true;
}

void ScenarioRunner::sampleQuality()
{
    const auto& up = m_channel.counters(RehearsalChannel::Console);
    const auto& down = m_channel.counters(RehearsalChannel::Aircraft);
    m_perSecond.push_back({m_modem ? m_sentUp : up.framesSent,
                           m_modem ? m_goodReceived[RehearsalChannel::Aircraft] : down.framesSent,
                           m_goodReceived[RehearsalChannel::Console], m_goodReceived[RehearsalChannel::Aircraft]});
    const std::size_t last = m_perSecond.size() - 1;
    const auto& before = m_perSecond[last >= kQualityWindow ? last - kQualityWindow : 0];
    const auto& nowCounts = m_perSecond[last];
    const auto ratio = [](qint64 good, qint64 sent) {
        return sent > 0 ? std::min(1.0, double(good) / double(sent)) : 1.0;
    };
    m_report.quality.push_back({now(), ratio(nowCounts[2] - before[2], nowCounts[0] - before[0]),
                                ratio(nowCounts[3] - before[3], nowCounts[1] - before[1])});
}

void ScenarioRunner::advanceTo(double seconds)
{
    if (!m_built)
        buildInProcess();
    if (!m_started) {
        m_started = true;
        note(QStringLiteral("event"), QStringLiteral("run starts: %1").arg(m_scenario.name));
        m_console->setCommand(m_command);
        if (m_aircraftWorker)
            m_aircraftWorker->start();
        m_console->start();
        sampleQuality();
    }
    const double target = std::min(seconds, m_scenario.duration);
    while (m_done < target - 1e-9) {
        while (m_nextStep < m_order.size() && *m_scenario.steps[m_order[m_nextStep]].at <= m_done + 1e-9)
            applyStep(m_scenario.steps[m_order[m_nextStep++]]);
        const double next = std::min(target, std::floor(m_done / kStepSeconds + 1 + 1e-9) * kStepSeconds);
        if (!m_real)
            m_clock->advance(std::chrono::microseconds(std::llround((next - m_done) * 1e6)));
        m_done = next;
        m_channel.setTime(m_done);
        judgeDeadlines();
        if (std::floor(m_done + 1e-9) > double(m_perSecond.size() - 1))
            sampleQuality();
    }
    emit progress(m_done, m_scenario.duration);
    if (m_done >= m_scenario.duration - 1e-9 && !m_finished)
        finish();
}

void ScenarioRunner::finish()
{
    m_finished = true;
    if (m_paceTimer)
        m_paceTimer->stop();
    if (m_console)
        m_console->stop();
    if (m_aircraftWorker)
        m_aircraftWorker->stop();
    if (m_launcher)
        m_launcher->stop();

    auto& frames = m_report.frames;
    const auto& up = m_channel.counters(RehearsalChannel::Console);
    const auto& down = m_channel.counters(RehearsalChannel::Aircraft);
    frames.sentUp = up.framesSent;
    frames.sentDown = down.framesSent;
    if (m_modem) {
        // No channel in the path: the console says what it sent; what uasim
        // sent is not seen, so the frames down are those that came.
        frames.sentUp = m_sentUp;
        frames.sentDown = m_goodReceived[RehearsalChannel::Aircraft];
    }
    frames.receivedUp = m_goodReceived[RehearsalChannel::Console];
    frames.receivedDown = m_goodReceived[RehearsalChannel::Aircraft];
    frames.inOutage = up.framesInOutage + down.framesInOutage;
    frames.damaged = up.framesDamaged + down.framesDamaged;
    frames.lost = std::max<qint64>(
        0, frames.sentUp + frames.sentDown - frames.inOutage - frames.receivedUp - frames.receivedDown);

    const auto pendingOf = [this](const ScenarioStep& step) {
        return std::find_if(m_pending.begin(), m_pending.end(), [&](const Pending& p) { return p.step == &step; });
    };
    for (const ScenarioStep& step : m_scenario.steps) {
        if (!step.isExpectation())
            continue;
        RehearsalReport::Expectation e{step.number, step.describe(), false, std::nullopt, {}};
        if (step.kind == ScenarioStep::Kind::ExpectLinkLostAtMost) {
            const auto count = std::count_if(m_report.alarms.begin(), m_report.alarms.end(),
                                             [](const RehearsalReport::Alarm& a) { return a.raised(); });
            e.held = count <= step.count;
            e.measured = double(count);
            e.detail = QStringLiteral("raised %1 %2")
                           .arg(count)
                           .arg(count == 1 ? QStringLiteral("time") : QStringLiteral("times"));
        } else if (step.kind == ScenarioStep::Kind::ExpectWrongFrames ||
                   step.kind == ScenarioStep::Kind::ExpectFramesLost) {
            const qint64 count = step.kind == ScenarioStep::Kind::ExpectWrongFrames ? frames.wrong : frames.lost;
            e.held = step.kind == ScenarioStep::Kind::ExpectWrongFrames ? count == step.count : count <= step.count;
            e.measured = double(count);
            const QString frame = count == 1 ? QStringLiteral("frame") : QStringLiteral("frames");
            e.detail = step.kind == ScenarioStep::Kind::ExpectWrongFrames
                           ? QStringLiteral("%1 wrong %2").arg(count).arg(frame)
                           : QStringLiteral("%1 %2 lost").arg(count).arg(frame);
        } else {
            const Pending& p = *pendingOf(step);
            e.held = p.held;
            if (p.held) {
                e.measured = std::round(p.measured * 1000) / 1000;
                e.detail = QStringLiteral("after %1 s").arg(*e.measured);
            } else {
                e.detail = p.decided
                               ? QStringLiteral("not seen by %1 s").arg(p.deadline())
                               : QStringLiteral("the run ended at %1 s before the deadline").arg(m_scenario.duration);
            }
        }
        m_report.expectations.push_back(e);
    }
    for (const auto& e : m_report.expectations)
        if (!e.held)
            note(QStringLiteral("expectation"), QStringLiteral("failed: ") + e.description);
    m_openFaults.clear();
    std::stable_sort(m_report.timeline.begin(), m_report.timeline.end(),
                     [](const auto& a, const auto& b) { return a.time < b.time; });
    emit finished();
}

void ScenarioRunner::runToEnd()
{
    advanceTo(m_scenario.duration);
}

void ScenarioRunner::start(double speed, const QString& uasimProgram)
{
    m_speed = speed > 0 ? speed : m_scenario.speed;
    if (m_speed == 1 && !m_built) {
        startReal(uasimProgram.isEmpty() ? RehearsalLauncher::defaultProgram() : uasimProgram);
        return;
    }
    beginPacing();
}

void ScenarioRunner::beginPacing()
{
    m_paceTimer = m_wall->createTimer(this);
    connect(m_paceTimer, &ClockTimer::timeout, this, [this] {
        m_paceTimer->start(kPaceInterval);
        paceTick();
    });
    m_paceStartSteadyMicros = m_wall->steadyMicros();
    m_paceTimer->start(kPaceInterval);
    advanceTo(0);
}

// uasim on a loopback port (or a pseudo-terminal), the proxy between it and
// the console's link; the run starts once uasim says it listens (uasimSaid()).
void ScenarioRunner::startReal(const QString& uasimProgram)
{
    m_real = m_built = true;
    m_time = m_wall;
    const bool serial = m_scenario.transport == Scenario::Transport::Serial;
    const bool modem = m_scenario.transport == Scenario::Transport::Modem;
    static const char* const how[] = {"udp (uasim as a process, real sockets)",
                                      "serial (uasim as a process, pseudo-terminal pairs)",
                                      "modem (uasim --modem as a process, the satellite modem model)"};
    m_report.transport = QStringLiteral("%1%2").arg(QLatin1String(how[int(m_scenario.transport)]),
                                                    m_scenario.key ? QStringLiteral(", secure link") : QString());
    const auto cannot = [this](const QString& why) {
        m_startUtcMicros = m_time->utcMicros();
        note(QStringLiteral("event"), QStringLiteral("the run cannot start: ") + why);
        finish();
    };
    QString error;
    if (modem) {
        SatelliteModem::Options satellite;
        satellite.callSetupTime = std::chrono::milliseconds(qint64(Scenario::kModemCallSetupSeconds * 1000));
        satellite.clock = m_time;
        m_modem = std::make_unique<SatelliteModemThread>(satellite);
        if (!m_modem->open(&error))
            return cannot(error);
        connect(m_modem.get(), &SatelliteModemThread::hungUp, this, [this](int side, const QString& how) {
            if (!m_finished)
                note(QStringLiteral("event"), QStringLiteral("modem model: %1 hung up (%2)")
                                                  .arg(side == SatelliteModem::Ground ? QStringLiteral("the console")
                                                       : side == SatelliteModem::Aircraft ? QStringLiteral("uasim")
                                                                                          : QStringLiteral("the network"),
                                                       how));
        });
    } else {
        m_proxy = std::make_unique<RehearsalProxy>(m_channel);
        if (!(serial ? m_proxy->openSerial(&error) : m_proxy->open(&error)))
            return cannot(error);
    }
    QString keyPath;
    if (m_psk) {
        m_keyDir = std::make_unique<QTemporaryDir>();
        keyPath = m_keyDir->filePath(QStringLiteral("rehearsal.key"));
        std::string why;
        if (!m_keyDir->isValid() || !rcm::secure::writeKeyFile(keyPath.toStdString(), *m_psk, why))
            return cannot(QStringLiteral("cannot write uasim's key: %1").arg(QString::fromStdString(why)));
    }
    m_launcher = new RehearsalLauncher(this);
    m_launcher->setVerbose(true);
    if (serial)
        m_launcher->setSerialDevice(m_proxy->aircraftDevice());
    if (modem) {
        m_launcher->setSerialDevice(m_modem->device(SatelliteModem::Aircraft));
        m_launcher->setModem(true);
    }
    connect(m_launcher, &RehearsalLauncher::output, this, &ScenarioRunner::uasimSaid);
    connect(m_launcher, &RehearsalLauncher::failed, this, [this, cannot](const QString& why) {
        if (!m_started)
            cannot(why);
        else if (!m_finished)
            note(QStringLiteral("event"), QStringLiteral("uasim: ") + why);
    });
    m_launcher->start(m_scenario.airframe, uasimProgram, keyPath);
}

// uasim's --verbose lines: that it listens, and each command it took.
void ScenarioRunner::uasimSaid(const QString& line)
{
    // "uasim: Well-equipped UA on udp 127.0.0.1:50123 ...": it listens.
    static const QRegularExpression listening(QStringLiteral("^uasim: .+ on (udp|/dev/)"));
    if (!m_started && !m_console && listening.match(line).hasMatch()) {
        m_launcher->confirm();
        QString error;
        const bool serial = m_scenario.transport != Scenario::Transport::Udp;
        if (!serial && !m_proxy->connectAircraft(m_launcher->port(), &error)) {
            m_startUtcMicros = m_time->utcMicros();
            note(QStringLiteral("event"), QStringLiteral("the run cannot start: ") + error);
            finish();
            return;
        }
        m_startUtcMicros = m_time->utcMicros();
        if (m_modem)
            makeConsole(consoleModem(m_modem->device(SatelliteModem::Ground)));
        else if (serial)
            makeConsole(std::make_unique<SerialLink>(m_proxy->consoleDevice()));
        else
            makeConsole(std::make_unique<UdpLink>(QHostAddress(QHostAddress::LocalHost), 0,
                                                  QHostAddress(QHostAddress::LocalHost), m_proxy->consolePort()));
        beginPacing();
        return;
    }
    // "uasim: command 12 (RS 0+0); gear ...": a command uasim acted on. It was sent
    // if a frame the console sent lately carried that ID_msg.
    static const QRegularExpression command(QStringLiteral("^uasim: command (\\d+) \\(RS "));
    const QRegularExpressionMatch m = command.match(line);
    if (!m.hasMatch() || m_finished)
        return;
    ++m_goodReceived[RehearsalChannel::Console];
    const std::int64_t id = m.captured(1).toLongLong();
    const auto& recent = m_channel.recentFrames(RehearsalChannel::Console);
    const auto sentFrame = [&](const QByteArray& f) {
        const std::optional<rcm::Message> sent = sentMessage(f, m_ciphers[RehearsalChannel::Console].get());
        return sent && sent->header.has(rcm::ItemId::ID_msg) && sent->header.number(rcm::ItemId::ID_msg) == id;
    };
    // Through the modem model no channel sees the frames: the console's own word for what it sent.
    const bool sent = m_modem ? std::find(m_sentIds.begin(), m_sentIds.end(), quint32(id)) != m_sentIds.end()
                              : std::any_of(recent.rbegin(), recent.rend(), sentFrame);
    if (!sent) {
        ++m_report.frames.wrong;
        note(QStringLiteral("event"), QStringLiteral("wrong frame delivered to the aircraft"));
    }
}

void ScenarioRunner::paceTick()
{
    advanceTo(m_real ? now() : double(m_wall->steadyMicros() - m_paceStartSteadyMicros) / 1e6 * m_speed);
}
