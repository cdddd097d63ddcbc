#include "link/simulation/SimulatorSession.h"

#include "codec/message/ItemTable.h"
#include "codec/secure/SecureCodec.h"
#include "link/framelog/FrameLog.h"
#include "link/session/LinkWorker.h"
#include "link/simulation/FaultOptions.h"
#include "link/simulation/FaultyLink.h"
#include "link/simulation/SimulatedAircraft.h"
#include "link/transport/ModemLink.h"
#include "link/transport/UdpLink.h"
#include "link/voice/VoiceDecoderSink.h"
#include "link/voice/VoiceEncoderSource.h"
#include "link/voice/WithVoice.h"

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
                     .arg(m.flightPlan.planId)
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

}  // namespace

SimulatorSession::SimulatorSession(Settings settings, Say say, QObject* parent)
    : QObject(parent), m_settings(std::move(settings)), m_say(std::move(say))
{
}

SimulatorSession::~SimulatorSession() = default;

std::unique_ptr<Link> SimulatorSession::openLink()
{
    std::unique_ptr<Link> link;
    if (m_settings.udpPort) {
        auto udpLink = std::make_unique<UdpLink>(QHostAddress(QHostAddress::LocalHost), *m_settings.udpPort);
        udpLink->setReplyToSender(true);
        link = std::move(udpLink);
    } else if (m_settings.modem) {
        ModemLink::Options modem;
        modem.initString = m_settings.modemInit;
        link = std::make_unique<ModemLink>(std::make_unique<SerialLink>(m_settings.serialDevice, m_settings.baudRate,
                                                                        SerialLink::FlowControl::RtsCts),
                                           modem);
    } else {
        link = std::make_unique<SerialLink>(m_settings.serialDevice, m_settings.baudRate);
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
            sink = std::make_shared<VoiceDecoderSink>(
                [this](std::span<const std::int16_t> pcm) { m_voiceRecord.append(pcm); });
        }
        link = withVoice(std::move(link), m_settings.voiceSource, std::move(sink));
    }
    if (m_settings.faults.any()) {
        auto faulty = std::make_unique<FaultyLink>(std::move(link), m_settings.faults);
        m_faultyLink = faulty.get();
        link = std::move(faulty);
    }
    return link;
}

bool SimulatorSession::start()
{
    std::unique_ptr<Link> link = openLink();
    if (!link)
        return false;
    std::unique_ptr<FrameLog> frameLog;
    if (!m_settings.logFile.isEmpty()) {
        frameLog = std::make_unique<FrameLog>();
        QString error;
        if (!frameLog->open(m_settings.logFile, &error)) {
            m_say(QStringLiteral("cannot open the log: %1").arg(error));
            return false;
        }
    }
    LinkWorker::Options workerOptions;
    if (!m_settings.keyFile.isEmpty()) {
        std::string error;
        workerOptions.secure =
            secure::SecureEndpoint::open(m_settings.keyFile.toStdString(), secure::Direction::UaToGcs, error);
        if (!workerOptions.secure) {
            m_say(QString::fromStdString(error));
            return false;
        }
    }

    m_aircraft = std::make_unique<SimulatedAircraft>(m_settings.airframe, m_settings.identity);
    m_worker = std::make_unique<LinkWorker>(std::move(link), std::move(frameLog), workerOptions);
    m_simulationClock.start();
    LinkWorker* worker = m_worker.get();
    connect(worker, &LinkWorker::messageReceived, this, [this](const ReceivedMessage& received) {
        const auto report = m_aircraft->apply(received.message);
        if (m_settings.verbose)
            m_say(commandSummary(received, *m_aircraft, report));
        offerStatus();
    });
    connect(worker, &LinkWorker::frameSent, this, [this](quint32) {
        m_aircraft->statusSent();
        m_aircraft->advance(std::chrono::milliseconds(m_simulationClock.restart()));
        offerStatus();
    });
    connect(worker, &LinkWorker::errorOccurred, this, [this](const QString& message) { m_say(message); });
    // An error is said once; the status that repeats it is not said again.
    connect(worker, &LinkWorker::errorOccurred, this, [this](const QString& message) { m_lastError = message; });
    if (m_settings.verbose)
        connect(worker, &LinkWorker::transportStatusChanged, this, [this](const QString& status) {
            if (status != m_lastError)
                m_say(status);
        });
    if (m_settings.verbose || m_settings.modem) {
        // A dropped call, the port gone or silence: the aircraft flies on its
        // last commands, and whoever runs it should know.
        connect(worker, &LinkWorker::linkLost, this, [this] { m_say(QStringLiteral("link lost")); });
        connect(worker, &LinkWorker::linkRegained, this, [this] { m_say(QStringLiteral("link regained")); });
    }
    // Every rejection when verbose; otherwise the first of each kind, then
    // only the counts when the session stops: a forger must not flood the
    // terminal.
    connect(worker, &LinkWorker::frameRejected, this, [this](const QString& reason) {
        const QString kind = reason.section(QLatin1Char(':'), 0, 0);
        if (m_settings.verbose || !m_rejectionKinds.contains(kind))
            m_say(QStringLiteral("command rejected: ") + reason);
        m_rejectionKinds.insert(kind);
    });
    connect(worker, &LinkWorker::commandRejected, this, [this](const QString& reasons) {
        m_say(QStringLiteral("status frame refused by the encoder: ") + reasons);
    });

    offerStatus();
    worker->start();
    if (m_settings.udpPort && !worker->link()->isOpen())
        return false;  // the worker said why
    if (m_settings.verbose)
        m_say(QStringLiteral("%1 on %2")
                  .arg(QString::fromStdString(m_settings.airframe.name), worker->link()->description()));
    if (workerOptions.secure)
        m_say(QStringLiteral("secure link: encrypted and authenticated, key fingerprint %1")
                  .arg(QString::fromStdString(workerOptions.secure->fingerprint)));
    return true;
}

void SimulatorSession::stop()
{
    if (!m_worker)
        return;
    m_worker->stop();
    if (const LinkStatistics& s = m_worker->statistics(); s.secure)
        m_say(QStringLiteral("rejected commands: %1 forged, %2 replayed, %3 stale time, %4 plaintext")
                  .arg(s.refusedFor(rcm::Refusal::Forged))
                  .arg(s.refusedFor(rcm::Refusal::Replayed))
                  .arg(s.refusedFor(rcm::Refusal::TimeWindow))
                  .arg(s.refusedFor(rcm::Refusal::Plaintext)));
    if (m_settings.verbose && m_faultyLink)
        m_say(FaultOptions::countersText(m_faultyLink->faults().counters()));
}

void SimulatorSession::offerStatus()
{
    m_worker->setCommand(m_aircraft->status(std::chrono::system_clock::now()));
}
