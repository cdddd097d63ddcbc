#include "link/aircraft/SimulatorSession.h"

#include "codec/message/FlightPlanTransfer.h"
#include "codec/message/ItemTable.h"
#include "codec/message/TextFormat.h"
#include "codec/secure/SecureCodec.h"
#include "link/aircraft/FaultOptions.h"
#include "link/aircraft/FaultyLink.h"
#include "link/aircraft/SimulatedAircraft.h"
#include "link/framelog/FrameLog.h"
#include "link/session/LinkWorker.h"
#include "link/transport/ModemLink.h"
#include "link/transport/UdpLink.h"
#include "link/voice/VoiceDecoderSink.h"
#include "link/voice/VoiceEncoderSource.h"
#include "link/voice/WithVoice.h"

#include <QFileInfo>

#include <algorithm>
#include <QStringList>

using namespace rcm;

namespace {

// "OUT/OUT/RETRACTED/OUT": a Fields item's codes by name; "?" for a corrupt field.
QString fieldsText(const Unit& unit, ItemId id)
{
    if (!unit.has(id))
        return QStringLiteral("-");
    const ItemInfo& info = itemInfo(id);
    QStringList codes;
    for (int f = 0; f < static_cast<int>(info.fields.size()); ++f) {
        const std::string_view name = info.fields[static_cast<std::size_t>(f)].codes[unit.fieldCode(id, f)];
        codes << (name.empty() ? QStringLiteral("?") : QString::fromLatin1(name.data(), qsizetype(name.size())));
    }
    return codes.join(QLatin1Char('/'));
}

// One line per command, when verbose.
QString commandSummary(const ReceivedMessage& received, const SimulatedAircraft& aircraft,
                       const SimulatedAircraft::ApplyReport& report)
{
    const Message& m = received.message;
    QStringList parts;
    parts << QStringLiteral("command %1 (RS %2+%3)")
                 .arg(m.header.has(ItemId::ID_msg) ? QString::number(m.header.number(ItemId::ID_msg))
                                                   : QStringLiteral("?"))
                 .arg(received.corrected.block1)
                 .arg(received.corrected.block2);
    parts << QStringLiteral("gear %1").arg(fieldsText(m.settings, ItemId::land_wheels));
    parts << QStringLiteral("lights %1").arg(fieldsText(m.settings, ItemId::lights));
    QStringList engines;
    for (const Unit& e : m.engines)
        engines << QStringLiteral("%1:%2 pitch %3 carb %4")
                       .arg(e.number(ItemId::eng_ID))
                       .arg(fieldsText(e, ItemId::eng_status))
                       .arg(e.number(ItemId::eng_prop_pitch))
                       .arg(e.number(ItemId::eng_carb_SET));
    if (!engines.isEmpty())
        parts << QStringLiteral("engines ") + engines.join(QStringLiteral(", "));
    QStringList photos;
    for (std::size_t i = 0; i < aircraft.airframe().cameras.size(); ++i)
        photos << QString::number(aircraft.photoCount(i));
    if (!photos.isEmpty())
        parts << QStringLiteral("photos taken %1").arg(photos.join(QLatin1Char('/')));
    if (!m.flightPlan.empty())
        parts << QStringLiteral("flight plan %1 section %2 (%3 bytes): %4/%5")
                     .arg(QString::fromStdString(rcm::planIdText(m.flightPlan.planId)))
                     .arg(m.flightPlan.sectionId)
                     .arg(m.flightPlan.data.size())
                     .arg(report.flightPlan.received)
                     .arg(report.flightPlan.total);
    for (const std::string& e : report.events)
        parts << QString::fromStdString(e);
    for (const std::string& e : report.ignored)
        parts << QStringLiteral("IGNORED ") + QString::fromStdString(e);
    return parts.join(QStringLiteral("; "));
}

QString stationName(StationId station)
{
    return QString::fromStdString(formatStation(station));
}

std::optional<StationId> stationIn(const Unit& header, ItemId id)
{
    const Value* v = header.find(id);
    if (!v)
        return std::nullopt;
    return StationId{static_cast<std::uint16_t>(v->number), static_cast<std::uint16_t>(v->second)};
}

std::vector<StationId> idsOf(const std::vector<SimulatorSession::Station>& stations)
{
    std::vector<StationId> ids;
    for (const SimulatorSession::Station& s : stations)
        ids.push_back(s.id);
    return ids;
}

}  // namespace

SimulatorSession::SimulatorSession(Settings settings, Say say, QObject* parent)
    : QObject(parent),
      m_settings(std::move(settings)),
      m_say(std::move(say)),
      m_arbiter(idsOf(m_settings.stations), m_settings.failover),
      m_clock(m_settings.clock ? m_settings.clock : std::make_shared<SystemClock>())
{
}

SimulatorSession::~SimulatorSession() = default;

// What the radio heard goes back as it came, a radio check: speech is said
// again, silence ends the talk. The first 100 ms of a talk are held before
// any goes, so that the echo, paced by the line as the speech came, never
// runs dry in the middle of it and splits it.
void SimulatorSession::echo(VoiceEncoderSource& source, std::span<const std::int16_t> pcm)
{
    constexpr std::size_t kHeld = 5 * voice::kFrameSamples;
    for (std::size_t at = 0; at < pcm.size(); at += voice::kFrameSamples) {
        const auto slot = pcm.subspan(at, std::min(voice::kFrameSamples, pcm.size() - at));
        if (std::all_of(slot.begin(), slot.end(), [](std::int16_t s) { return s == 0; })) {
            if (!m_echoHeld.empty())
                source.pushPcm(m_echoHeld);
            if (m_echoTalking || !m_echoHeld.empty())
                source.endTalk();
            m_echoHeld.clear();
            m_echoTalking = false;
        } else if (m_echoTalking) {
            source.pushPcm(slot);
        } else {
            m_echoHeld.insert(m_echoHeld.end(), slot.begin(), slot.end());
            if (m_echoHeld.size() >= kHeld) {
                source.pushPcm(m_echoHeld);
                m_echoHeld.clear();
                m_echoTalking = true;
            }
        }
    }
}

QString SimulatorSession::logFileFor(const QString& logFile, StationId station)
{
    const QString fileName = QFileInfo(logFile).fileName();
    const QString folder = logFile.left(logFile.size() - fileName.size());
    const qsizetype dot = fileName.lastIndexOf(QLatin1Char('.'));
    const QString tag = QLatin1Char('-') + stationName(station);
    if (dot <= 0)
        return folder + fileName + tag;
    return folder + fileName.left(dot) + tag + fileName.mid(dot);
}

std::unique_ptr<Link> SimulatorSession::openLink(const Station* station, Channel& channel,
                                                const secure::SecureEndpoint* key)
{
    std::unique_ptr<Link> link;
    if (m_settings.transport) {
        link = m_settings.transport(station);
    } else if (station || m_settings.udpPort) {
        auto udpLink = std::make_unique<UdpLink>(QHostAddress(QHostAddress::LocalHost),
                                                 station ? station->udpPort : *m_settings.udpPort);
        udpLink->setReplyToSender(true);
        link = std::move(udpLink);
    } else if (m_settings.modem) {
        ModemLink::Options modem;
        modem.initString = m_settings.modemInit;
        modem.clock = m_clock;
        link = std::make_unique<ModemLink>(std::make_unique<SerialLink>(m_settings.serialDevice, m_settings.baudRate,
                                                                        SerialLink::FlowControl::RtsCts, nullptr, m_clock),
                                           modem);
    } else {
        link = std::make_unique<SerialLink>(m_settings.serialDevice, m_settings.baudRate, nullptr, m_clock);
    }
    // Voice goes inside the faults, which spoil whole status frames.
    if (m_settings.voiceSource) {
        std::shared_ptr<VoiceDecoderSink> sink;
        if (!m_settings.voiceOutFile.isEmpty()) {
            std::string error;
            if (!m_voiceRecord.create(m_settings.voiceOutFile.toStdString(), voice::kSampleRate, error)) {
                m_say(QStringLiteral("cannot write the voice: %1").arg(QString::fromStdString(error)));
                return nullptr;
            }
        }
        if (!m_settings.voiceOutFile.isEmpty() || m_settings.voiceEcho) {
            sink = std::make_shared<VoiceDecoderSink>(
                [this, source = m_settings.voiceSource](std::span<const std::int16_t> pcm) {
                    if (!m_settings.voiceOutFile.isEmpty())
                        m_voiceRecord.append(pcm);
                    if (m_settings.voiceEcho)
                        echo(*source, pcm);
                });
        }
        VoiceSecurity security;
        if (key) {
            security.send = key->voiceSend;
            security.receive = key->voiceReceive;
            security.refused = [this, prefix = channel.prefix](std::uint64_t forged, std::uint64_t replayed) {
                m_say(prefix + QStringLiteral("voice refused, never played: %1 forged, %2 replayed")
                                   .arg(forged)
                                   .arg(replayed));
            };
        }
        link = withVoice(std::move(link), m_settings.voiceSource, std::move(sink), security);
    }
    if (m_settings.faults.any()) {
        auto faulty = std::make_unique<FaultyLink>(std::move(link), m_settings.faults, m_clock);
        channel.faultyLink = faulty.get();
        link = std::move(faulty);
    }
    return link;
}

bool SimulatorSession::openChannel(const Station* station)
{
    auto channel = std::make_unique<Channel>();
    if (station) {
        channel->station = station->id;
        channel->prefix = stationName(station->id) + QStringLiteral(": ");
    }
    LinkWorker::Options workerOptions;
    workerOptions.clock = m_clock;
    const QString keyFile = station ? station->keyFile : m_settings.keyFile;
    if (!keyFile.isEmpty()) {
        std::string error;
        secure::SecureEndpoint::Options keyOptions;
        keyOptions.clock = [clock = m_clock] { return clock->utcMicros() / 1'000'000; };
        workerOptions.secure =
            secure::SecureEndpoint::open(keyFile.toStdString(), secure::Direction::UaToGcs, error, keyOptions);
        if (!workerOptions.secure) {
            m_say(channel->prefix + QString::fromStdString(error));
            return false;
        }
    }
    std::unique_ptr<Link> link = openLink(station, *channel, workerOptions.secure.get());
    if (!link)
        return false;
    std::unique_ptr<FrameLog> frameLog;
    if (!m_settings.logFile.isEmpty()) {
        frameLog = std::make_unique<FrameLog>();
        const QString path = station ? logFileFor(m_settings.logFile, station->id) : m_settings.logFile;
        QString error;
        if (!frameLog->open(path, &error)) {
            m_say(channel->prefix + QStringLiteral("cannot open the log: %1").arg(error));
            return false;
        }
    }
    channel->worker = std::make_unique<LinkWorker>(std::move(link), std::move(frameLog), workerOptions);
    connectChannel(*channel);
    m_channels.push_back(std::move(channel));
    return true;
}

void SimulatorSession::connectChannel(Channel& channel)
{
    Channel* c = &channel;  // held by pointer in m_channels: it does not move
    LinkWorker* worker = c->worker.get();
    connect(worker, &LinkWorker::messageReceived, this,
            [this, c](const ReceivedMessage& received) { commandReceived(*c, received); });
    connect(worker, &LinkWorker::frameSent, this, [this, c](quint32) { statusFrameSent(*c); });
    // An error is said once; the status that repeats it is not said again.
    connect(worker, &LinkWorker::errorOccurred, this, [this, c](const QString& message) {
        m_say(c->prefix + message);
        c->lastError = message;
    });
    if (m_settings.verbose)
        connect(worker, &LinkWorker::transportStatusChanged, this, [this, c](const QString& status) {
            if (status != c->lastError)
                m_say(c->prefix + status);
        });
    if (m_settings.verbose || m_settings.modem) {
        // A dropped call, the port gone or silence: the aircraft flies on its
        // last commands, and whoever runs it should know.
        connect(worker, &LinkWorker::linkLost, this, [this, c] { m_say(c->prefix + QStringLiteral("link lost")); });
        connect(worker, &LinkWorker::linkRegained, this,
                [this, c] { m_say(c->prefix + QStringLiteral("link regained")); });
    }
    // Every rejection when verbose; otherwise the first of each kind, then
    // only the counts when the session stops: a forger must not flood the
    // terminal.
    connect(worker, &LinkWorker::frameRejected, this, [this, c](const QString& reason) {
        const QString kind = reason.section(QLatin1Char(':'), 0, 0);
        if (m_settings.verbose || !c->rejectionKinds.contains(kind))
            m_say(c->prefix + QStringLiteral("command rejected: ") + reason);
        c->rejectionKinds.insert(kind);
    });
    connect(worker, &LinkWorker::commandRejected, this, [this, c](const QString& reasons) {
        m_say(c->prefix + QStringLiteral("status frame refused by the encoder: ") + reasons);
    });
}

bool SimulatorSession::start()
{
    if (m_settings.voiceSource && !m_settings.stations.empty()) {
        m_say(QStringLiteral("voice is for one link, not for several stations"));
        return false;
    }
    m_aircraft = std::make_unique<SimulatedAircraft>(m_settings.airframe, m_settings.identity);
    if (m_settings.stations.empty()) {
        if (!openChannel(nullptr))
            return false;
    }
    for (const Station& station : m_settings.stations)
        if (!openChannel(&station))
            return false;
    m_lastAdvanceMicros = m_clock->steadyMicros();
    offerStatus();
    for (const std::unique_ptr<Channel>& c : m_channels) {
        LinkWorker* worker = c->worker.get();
        worker->start();
        if ((m_settings.udpPort || c->station) && !worker->link()->isOpen())
            return false;  // the worker said why
        if (m_settings.verbose)
            m_say(c->prefix +
                  QStringLiteral("%1 on %2")
                      .arg(QString::fromStdString(m_settings.airframe.name), worker->link()->description()));
        if (const auto& secure = worker->options().secure)
            m_say(c->prefix + QStringLiteral("secure link: encrypted and authenticated, key fingerprint %1")
                                  .arg(QString::fromStdString(secure->fingerprint)));
    }
    if (!m_arbiter.singleStation()) {
        QStringList roles;
        for (StationId s : m_arbiter.stations())
            roles << stationName(s) + (s == *m_arbiter.controller() ? QStringLiteral(" in control (not yet taken up)")
                                       : s == *m_arbiter.backup()   ? QStringLiteral(" backup")
                                                                    : QStringLiteral(" observing"));
        m_say(QStringLiteral("stations: %1; failover after %2 s")
                  .arg(roles.join(QStringLiteral(", ")))
                  .arg(double(m_settings.failover.count()) / 1000.0));
        m_controlTimer = m_clock->createTimer(this);
        connect(m_controlTimer, &ClockTimer::timeout, this, &SimulatorSession::checkControl);
        armControlTimer();
    }
    return true;
}

void SimulatorSession::stop()
{
    if (m_channels.empty())
        return;
    if (m_controlTimer)
        m_controlTimer->stop();
    for (const std::unique_ptr<Channel>& c : m_channels)
        c->worker->stop();
    for (const std::unique_ptr<Channel>& c : m_channels) {
        if (const LinkStatistics& s = c->worker->statistics(); s.secure)
            m_say(c->prefix + QStringLiteral("rejected commands: %1 forged, %2 replayed, %3 stale time, %4 plaintext")
                                  .arg(s.refusedFor(rcm::Refusal::Forged))
                                  .arg(s.refusedFor(rcm::Refusal::Replayed))
                                  .arg(s.refusedFor(rcm::Refusal::TimeWindow))
                                  .arg(s.refusedFor(rcm::Refusal::Plaintext)));
        if (m_settings.verbose && c->faultyLink)
            m_say(c->prefix + FaultOptions::countersText(c->faultyLink->faults().counters()));
    }
    if (!m_arbiter.singleStation()) {
        QStringList counts;
        for (StationId s : m_arbiter.stations())
            counts << QStringLiteral("%1 %2 frames").arg(stationName(s)).arg(m_arbiter.notInControlCount(s));
        m_say(QStringLiteral("not in control: ") + counts.join(QStringLiteral(", ")));
    }
}

void SimulatorSession::commandReceived(Channel& channel, const ReceivedMessage& received)
{
    // Who sent it is the channel it came on, never what it says of itself.
    const Unit& header = received.message.header;
    const ControlArbiter::Decision decision =
        m_arbiter.onFrame(channel.station.value_or(StationId{}), stationIn(header, ItemId::ID_GCS_destination),
                          stationIn(header, ItemId::ID_GCS_backup), received.utcMicros);
    for (const ControlArbiter::Event& event : decision.events)
        sayControlEvent(event);
    if (!decision.act) {
        if (m_settings.verbose)
            m_say(channel.prefix + QStringLiteral("command %1 not acted on: %2")
                                       .arg(header.has(ItemId::ID_msg) ? QString::number(header.number(ItemId::ID_msg))
                                                                       : QStringLiteral("?"),
                                            QString::fromStdString(decision.notActedOn)));
        if (!decision.events.empty())
            offerStatus();  // who is in control, in the next status frame
        return;
    }
    const auto report = m_aircraft->apply(received.message);
    if (m_settings.verbose)
        m_say(channel.prefix + commandSummary(received, *m_aircraft, report));
    offerStatus();
}

void SimulatorSession::statusFrameSent(Channel& channel)
{
    // Every channel sends on the same second. The first to send ends the
    // frame: it counts, its one-frame indications are over and the state
    // moves on. A channel that has not sent yet keeps the frame it holds, so
    // that every station is sent the same one.
    const std::int64_t period = std::chrono::microseconds(channel.worker->options().interval).count();
    const std::int64_t second = m_clock->utcMicros() / period;
    if (second != m_statusSecond) {
        m_statusSecond = second;
        m_aircraft->statusSent();
        const auto step = std::chrono::duration_cast<std::chrono::milliseconds>(
            std::chrono::microseconds(m_clock->steadyMicros() - m_lastAdvanceMicros));
        m_aircraft->advance(step);
        m_lastAdvanceMicros += std::chrono::microseconds(step).count();  // the fraction left carries over
    }
    channel.worker->setCommand(status());
}

void SimulatorSession::armControlTimer()
{
    // Half way between the seconds the status frames go on: every channel
    // has sent the frame of the second before this hands them the next.
    const std::int64_t period = std::chrono::microseconds(m_channels.front()->worker->options().interval).count();
    const std::int64_t now = m_clock->utcMicros();
    std::int64_t next = now / period * period + period / 2;
    if (next <= now)
        next += period;
    m_controlTimer->start(std::chrono::milliseconds((next - now + 999) / 1000));
}

void SimulatorSession::checkControl()
{
    if (const std::optional<ControlArbiter::Event> event = m_arbiter.tick(m_clock->utcMicros()))
        sayControlEvent(*event);
    // Also to a channel that has sent nothing lately (no station on it yet).
    offerStatus();
    armControlTimer();
}

void SimulatorSession::sayControlEvent(const ControlArbiter::Event& event)
{
    m_say(QString::fromStdString(event.text));
}

Message SimulatorSession::status() const
{
    Message status = m_aircraft->status(
        std::chrono::system_clock::time_point(std::chrono::microseconds(m_clock->utcMicros())));
    // The aircraft decides who is in control, not the last command.
    if (!m_arbiter.singleStation()) {
        status.header.set(ItemId::ID_GCS_destination, Value::station(*m_arbiter.controller()));
        status.header.set(ItemId::ID_GCS_backup, Value::station(*m_arbiter.backup()));
    }
    return status;
}

void SimulatorSession::offerStatus()
{
    const Message next = status();
    for (const std::unique_ptr<Channel>& c : m_channels)
        c->worker->setCommand(next);
}
