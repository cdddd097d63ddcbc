// uasim: a simulated aircraft at the far end of the link, for rehearsals and
// tests. It answers each command with the state it actually has, once a
// second, through the same LinkWorker and transports as the console, and can
// spoil its own replies with rehearsal faults.
//
// The worker runs in the main thread: uasim has no GUI to keep responsive,
// and one thread makes every status frame exactly the state after the
// commands received before it (a one-frame indication such as a photograph
// taken cannot be cleared by a frame that did not carry it).
#include "codec/message/Airframe.h"
#include "link/simulation/AirframeLoader.h"
#include "codec/message/ItemTable.h"
#include "codec/secure/SecureCodec.h"
#include "codec/voice/WavFile.h"
#include "link/simulation/FaultInjector.h"
#include "link/framelog/FrameLog.h"
#include "link/session/LinkWorker.h"
#include "link/transport/SerialLink.h"
#include "link/simulation/SimulatedAircraft.h"
#include "link/transport/UdpLink.h"
#include "link/voice/VoiceDecoderSink.h"
#include "link/voice/VoiceEncoderSource.h"
#include "link/voice/WithVoice.h"

#include <QCommandLineParser>
#include <QCoreApplication>
#include <QElapsedTimer>
#include <QFile>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QSet>
#include <QSocketNotifier>
#include <QTimer>

#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <memory>
#include <optional>

using namespace rcm;

namespace {

// Exit codes.
constexpr int kUsageError = 2;
constexpr int kRunError = 1;

void say(const QString& line)
{
    std::fprintf(stderr, "uasim: %s\n", qPrintable(line));
}

// A transport with rehearsal faults on what it sends and an outage on what
// it receives; otherwise the transport it wraps.
class FaultyLink : public Link {
    Q_OBJECT

public:
    FaultyLink(std::unique_ptr<Link> inner, const FaultSettings& settings)
        : m_inner(inner.release()), m_faults(settings)
    {
        m_inner->setParent(this);
        m_clock.start();
        connect(m_inner, &Link::opened, this, &Link::opened);
        connect(m_inner, &Link::closed, this, &Link::closed);
        connect(m_inner, &Link::errorOccurred, this, &Link::errorOccurred);
        connect(m_inner, &Link::bytesReceived, this, [this](const QByteArray& bytes) {
            if (m_faults.incoming(elapsed()))
                emit bytesReceived(bytes);
        });
        connect(m_inner, &Link::datagramReceived, this, [this](const QByteArray& datagram) {
            if (m_faults.incoming(elapsed()))
                emit datagramReceived(datagram);
        });
    }

    FrameTransport transport() const override { return m_inner->transport(); }
    bool isStream() const override { return m_inner->isStream(); }
    bool isOpen() const override { return m_inner->isOpen(); }
    QString description() const override { return m_inner->description() + QStringLiteral(", rehearsal faults"); }
    const FaultInjector& faults() const { return m_faults; }

public slots:
    void open() override { m_inner->open(); }
    void close() override { m_inner->close(); }

    // A frame the faults swallow still counts as sent, as it would for an
    // aircraft whose radio path failed: the console sees the ID_msg gap.
    bool write(const QByteArray& bytes) override
    {
        QByteArray damaged = bytes;
        const auto outcome = m_faults.outgoing(
            {reinterpret_cast<std::uint8_t*>(damaged.data()), static_cast<std::size_t>(damaged.size())}, elapsed());
        if (!outcome.sent())
            return m_inner->isOpen();
        if (outcome.delay.count() == 0)
            return m_inner->write(damaged);
        QTimer::singleShot(outcome.delay, m_inner, [inner = m_inner, damaged] { inner->write(damaged); });
        return m_inner->isOpen();
    }

private:
    std::chrono::milliseconds elapsed() const { return std::chrono::milliseconds(m_clock.elapsed()); }

    Link* m_inner;  // a child
    FaultInjector m_faults;
    QElapsedTimer m_clock;
};

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

// One line per command for --verbose.
QString commandSummary(const ReceivedMessage& received, const SimulatedAircraft& aircraft,
                       const SimulatedAircraft::ApplyReport& report)
{
    const Message& m = received.message;
    QStringList parts;
    parts << QStringLiteral("command %1 (RS %2+%3)")
                 .arg(m.header.has(ItemId::ID_msg) ? QString::number(m.header.number(ItemId::ID_msg))
                                                   : QStringLiteral("?"))
                 .arg(received.corrected1)
                 .arg(received.corrected2);
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

// "A:B" with both numbers; false when not.
template <typename A, typename B>
bool parsePair(const QString& text, A* a, B* b)
{
    const QStringList p = text.split(QLatin1Char(':'));
    if (p.size() != 2)
        return false;
    bool okA = false, okB = false;
    const double x = p[0].toDouble(&okA);
    const double y = p[1].toDouble(&okB);
    *a = static_cast<A>(x);
    *b = static_cast<B>(y);
    return okA && okB && x >= 0 && y >= 0;
}

// SIGINT and SIGTERM reach the event loop through this pair: a handler may
// only write to a descriptor.
int g_signalPipe[2] = {-1, -1};

void onSignal(int)
{
    const char c = 1;
    [[maybe_unused]] const ssize_t n = ::write(g_signalPipe[0], &c, 1);
}

}  // namespace

int main(int argc, char* argv[])
{
    QCoreApplication app(argc, argv);
    QCoreApplication::setApplicationName(QStringLiteral("uasim"));

    QCommandLineParser parser;
    parser.setApplicationDescription(QStringLiteral(
        "A simulated aircraft: answers Remote Control Message commands, once a second, with a status frame in\n"
        "the same format reporting the state it actually has (gear and surfaces take time to move), and\n"
        "acknowledges flight plans uploaded in BLOCK 2 sections.\n"
        "\n"
        "Examples:\n"
        "  uasim --udp 5600 --verbose\n"
        "  uasim --serial /dev/pts/3 --baud 9600 --log uasim.pcapng --ber 1e-4 --drop 0.05 --outage 60:10\n"
        "  uasim --serial /dev/pts/3 --voice-out heard.wav --voice-in reply.wav"));
    parser.addHelpOption();
    const QCommandLineOption udp(QStringLiteral("udp"),
                                 QStringLiteral("Listen on 127.0.0.1:<port>; reply to whoever sent the last command."),
                                 QStringLiteral("port"));
    const QCommandLineOption serial(QStringLiteral("serial"),
                                    QStringLiteral("Use a serial device (a pseudo-terminal works)."),
                                    QStringLiteral("device"));
    const QCommandLineOption baud(QStringLiteral("baud"),
                                  QStringLiteral("Serial bit rate (default %1).").arg(SerialLink::kDefaultBaudRate),
                                  QStringLiteral("n"), QString::number(SerialLink::kDefaultBaudRate));
    const QCommandLineOption log(QStringLiteral("log"),
                                 QStringLiteral("Keep a pcapng log of every frame sent and received; the file must "
                                                "not exist."),
                                 QStringLiteral("file"));
    const QCommandLineOption airframe(
        QStringLiteral("airframe"),
        QStringLiteral("The aircraft's units, as JSON: {\"name\", \"engines\": [{\"id\", \"name\"}], \"radios\": "
                       "[{\"systemId\", \"name\"}], \"cameras\": [{\"maker\", \"number\", \"name\"}], "
                       "\"senseAndAvoid\"}. Default: three engines, three radios, sense and avoid, two cameras."),
        QStringLiteral("file"));
    const QCommandLineOption uaId(
        QStringLiteral("ua-id"),
        QStringLiteral("The aircraft's ID_UA_source, country:unit. Default: the first command's ID_UA_source."),
        QStringLiteral("country:unit"));
    const QCommandLineOption ber(QStringLiteral("ber"),
                                 QStringLiteral("Fault: flip each bit sent with probability <rate>."),
                                 QStringLiteral("rate"));
    const QCommandLineOption burst(
        QStringLiteral("burst"),
        QStringLiteral("Fault: error bursts <len> bits long, <rate> per frame on average (Poisson)."),
        QStringLiteral("len:rate"));
    const QCommandLineOption drop(QStringLiteral("drop"),
                                  QStringLiteral("Fault: lose each status frame with probability <p>."),
                                  QStringLiteral("p"));
    const QCommandLineOption delay(QStringLiteral("delay"),
                                   QStringLiteral("Fault: send each status frame <ms> milliseconds late."),
                                   QStringLiteral("ms"));
    const QCommandLineOption outage(QStringLiteral("outage"),
                                    QStringLiteral("Fault: <start> seconds after starting, for <duration> seconds, "
                                                   "send and receive nothing."),
                                    QStringLiteral("start:duration"));
    const QCommandLineOption silent(QStringLiteral("silent"),
                                    QStringLiteral("Fault: stop replying (commands are still received and acted on)."));
    const QCommandLineOption seed(QStringLiteral("seed"),
                                  QStringLiteral("Seed of the fault generator, so a rehearsal repeats (default 1)."),
                                  QStringLiteral("n"), QStringLiteral("1"));
    const QCommandLineOption verbose(QStringLiteral("verbose"),
                                     QStringLiteral("Print one line per command received to stderr."));
    const QCommandLineOption key(
        QStringLiteral("key"),
        QStringLiteral("The secure link (docs/security.md): the aircraft's key file, 64 hex digits, mode 0600. "
                       "Status frames are enciphered; a command that does not authenticate, repeats an earlier "
                       "ID_msg or is more than 30 s from this clock is rejected and counted. The replay state and "
                       "the send counter are kept beside the key file."),
        QStringLiteral("file"));
    const QCommandLineOption voiceOut(
        QStringLiteral("voice-out"),
        QStringLiteral("Voice (docs/protocol.md section 7): take the voice beside the commands, decode it and write "
                       "what the VHF radio would transmit to a WAV file (8 kHz, 16-bit mono), silence included."),
        QStringLiteral("file.wav"));
    const QCommandLineOption voiceIn(
        QStringLiteral("voice-in"),
        QStringLiteral("Voice: speak a WAV file (16-bit PCM, any rate) back to the console, from the start."),
        QStringLiteral("file.wav"));
    parser.addOptions({udp, serial, baud, log, airframe, uaId, ber, burst, drop, delay, outage, silent, seed, verbose,
                       key, voiceOut, voiceIn});
    parser.process(app);

    const auto usage = [&](const QString& message) {
        say(message);
        std::fprintf(stderr, "%s", qPrintable(parser.helpText()));
        return kUsageError;
    };
    if (parser.isSet(udp) == parser.isSet(serial))
        return usage(QStringLiteral("give either --udp PORT or --serial DEVICE"));
    if (!parser.positionalArguments().isEmpty())
        return usage(QStringLiteral("unexpected argument %1").arg(parser.positionalArguments().first()));

    FaultSettings faults;
    bool ok = true;
    if (parser.isSet(ber)) {
        faults.bitErrorRate = parser.value(ber).toDouble(&ok);
        if (!ok || faults.bitErrorRate < 0 || faults.bitErrorRate > 1)
            return usage(QStringLiteral("--ber wants a probability 0..1, not %1").arg(parser.value(ber)));
    }
    if (parser.isSet(burst) && !parsePair(parser.value(burst), &faults.burstLength, &faults.burstRate))
        return usage(QStringLiteral("--burst wants LEN:RATE, e.g. 32:0.5, not %1").arg(parser.value(burst)));
    if (parser.isSet(drop)) {
        faults.dropProbability = parser.value(drop).toDouble(&ok);
        if (!ok || faults.dropProbability < 0 || faults.dropProbability > 1)
            return usage(QStringLiteral("--drop wants a probability 0..1, not %1").arg(parser.value(drop)));
    }
    if (parser.isSet(delay)) {
        const int ms = parser.value(delay).toInt(&ok);
        if (!ok || ms < 0)
            return usage(QStringLiteral("--delay wants milliseconds, not %1").arg(parser.value(delay)));
        faults.delay = std::chrono::milliseconds(ms);
    }
    if (parser.isSet(outage)) {
        double start = 0, duration = 0;
        if (!parsePair(parser.value(outage), &start, &duration))
            return usage(QStringLiteral("--outage wants START:DURATION in seconds, not %1").arg(parser.value(outage)));
        faults.outageStart = std::chrono::milliseconds(std::llround(start * 1000));
        faults.outageDuration = std::chrono::milliseconds(std::llround(duration * 1000));
    }
    faults.silent = parser.isSet(silent);
    faults.seed = parser.value(seed).toULongLong(&ok);
    if (!ok)
        return usage(QStringLiteral("--seed wants a whole number, not %1").arg(parser.value(seed)));

    std::optional<StationId> identity;
    if (parser.isSet(uaId)) {
        int country = 0, unit = 0;
        const ItemInfo& info = itemInfo(ItemId::ID_UA_source);
        if (!parsePair(parser.value(uaId), &country, &unit) || country < info.min || country > info.max || unit > 65535)
            return usage(QStringLiteral("--ua-id wants COUNTRY:UNIT, country %1..%2, unit 0..65535")
                             .arg(info.min)
                             .arg(info.max));
        identity = StationId{static_cast<std::uint16_t>(country), static_cast<std::uint16_t>(unit)};
    }

    Airframe frame = Airframe::wellEquipped();
    if (parser.isSet(airframe)) {
        QString error;
        const auto loaded = AirframeLoader::load(parser.value(airframe), &error);
        if (!loaded)
            return usage(error);
        frame = *loaded;
    }

    std::unique_ptr<Link> link;
    if (parser.isSet(udp)) {
        const uint port = parser.value(udp).toUInt(&ok);
        if (!ok || port > 65535)
            return usage(QStringLiteral("--udp wants a port number, not %1").arg(parser.value(udp)));
        auto udpLink = std::make_unique<UdpLink>(QHostAddress(QHostAddress::LocalHost), static_cast<quint16>(port));
        udpLink->setReplyToSender(true);
        link = std::move(udpLink);
    } else {
        const qint32 rate = parser.value(baud).toInt(&ok);
        if (!ok || rate <= 0)
            return usage(QStringLiteral("--baud wants a bit rate, not %1").arg(parser.value(baud)));
        link = std::make_unique<SerialLink>(parser.value(serial), rate);
    }
    // Voice goes inside the faults, which spoil whole status frames.
    WavFile voiceRecord;
    if (parser.isSet(voiceOut) || parser.isSet(voiceIn)) {
        std::string error;
        std::shared_ptr<VoiceDecoderSink> sink;
        if (parser.isSet(voiceOut)) {
            if (!voiceRecord.create(parser.value(voiceOut).toStdString(), voice::kSampleRate, error)) {
                say(QStringLiteral("cannot write the voice: %1").arg(QString::fromStdString(error)));
                return kRunError;
            }
            sink = std::make_shared<VoiceDecoderSink>(
                [&voiceRecord](std::span<const std::int16_t> pcm) { voiceRecord.append(pcm); });
        }
        auto source = std::make_shared<VoiceEncoderSource>(std::chrono::milliseconds(0));
        if (parser.isSet(voiceIn) && !source->speakFile(parser.value(voiceIn).toStdString(), error))
            return usage(QStringLiteral("--voice-in: %1").arg(QString::fromStdString(error)));
        link = withVoice(std::move(link), std::move(source), std::move(sink));
    }
    FaultyLink* faultyLink = nullptr;
    if (faults.any()) {
        auto wrapped = std::make_unique<FaultyLink>(std::move(link), faults);
        faultyLink = wrapped.get();
        link = std::move(wrapped);
    }

    std::unique_ptr<FrameLog> frameLog;
    if (parser.isSet(log)) {
        frameLog = std::make_unique<FrameLog>();
        QString error;
        if (!frameLog->open(parser.value(log), &error)) {
            say(QStringLiteral("cannot open the log: %1").arg(error));
            return kRunError;
        }
    }

    if (::socketpair(AF_UNIX, SOCK_STREAM, 0, g_signalPipe) != 0) {
        say(QStringLiteral("socketpair: %1").arg(QString::fromLocal8Bit(std::strerror(errno))));
        return kRunError;
    }
    QSocketNotifier signalNotifier(g_signalPipe[1], QSocketNotifier::Read);
    struct sigaction action = {};
    action.sa_handler = onSignal;
    sigemptyset(&action.sa_mask);
    action.sa_flags = SA_RESTART;
    sigaction(SIGINT, &action, nullptr);
    sigaction(SIGTERM, &action, nullptr);

    LinkWorker::Options workerOptions;
    if (parser.isSet(key)) {
        std::string error;
        std::unique_ptr<secure::SecureEndpoint> endpoint =
            secure::SecureEndpoint::open(parser.value(key).toStdString(), secure::Direction::UaToGcs, error);
        if (!endpoint) {
            say(QString::fromStdString(error));
            return kRunError;
        }
        workerOptions.secure = std::move(endpoint);
    }

    const bool isVerbose = parser.isSet(verbose);
    SimulatedAircraft aircraft(frame, identity);
    LinkWorker worker(std::move(link), std::move(frameLog), workerOptions);
    QElapsedTimer simulationClock;
    simulationClock.start();

    const auto offerStatus = [&] { worker.setCommand(aircraft.status(std::chrono::system_clock::now())); };
    QObject::connect(&worker, &LinkWorker::messageReceived, &worker, [&](const ReceivedMessage& received) {
        const auto report = aircraft.apply(received.message);
        if (isVerbose)
            say(commandSummary(received, aircraft, report));
        offerStatus();
    });
    QObject::connect(&worker, &LinkWorker::frameSent, &worker, [&](quint32) {
        aircraft.statusSent();
        aircraft.advance(std::chrono::milliseconds(simulationClock.restart()));
        offerStatus();
    });
    QObject::connect(&worker, &LinkWorker::errorOccurred, &worker, [](const QString& message) { say(message); });
    // Every rejection with --verbose; otherwise the first of each kind, then
    // only the counts when uasim stops: a forger must not flood the terminal.
    QSet<QString> rejectionKinds;
    QObject::connect(&worker, &LinkWorker::frameRejected, &worker, [&](const QString& reason) {
        const QString kind = reason.section(QLatin1Char(':'), 0, 0);
        if (isVerbose || !rejectionKinds.contains(kind))
            say(QStringLiteral("command rejected: ") + reason);
        rejectionKinds.insert(kind);
    });
    QObject::connect(&worker, &LinkWorker::commandRejected, &worker, [](const QString& reasons) {
        say(QStringLiteral("status frame refused by the encoder: ") + reasons);
    });
    QObject::connect(&signalNotifier, &QSocketNotifier::activated, &app, [&] {
        char c;
        [[maybe_unused]] const ssize_t n = ::read(g_signalPipe[1], &c, 1);
        worker.stop();
        if (const LinkStatistics& s = worker.statistics(); s.secure)
            say(QStringLiteral("rejected commands: %1 forged, %2 replayed, %3 stale time, %4 plaintext")
                    .arg(s.refusedFor(rcm::Refusal::Forged))
                    .arg(s.refusedFor(rcm::Refusal::Replayed))
                    .arg(s.refusedFor(rcm::Refusal::TimeWindow))
                    .arg(s.refusedFor(rcm::Refusal::Plaintext)));
        if (isVerbose && faultyLink) {
            const FaultInjector::Counters& n = faultyLink->faults().counters();
            say(QStringLiteral("faults: %1 frames offered, %2 sent (%3 damaged, %4 bits flipped, %5 bursts), "
                               "%6 dropped, %7 lost to the outage, %8 silenced; %9 arrivals lost to the "
                               "outage")
                    .arg(n.framesOffered)
                    .arg(n.framesSent)
                    .arg(n.framesDamaged)
                    .arg(n.bitsFlipped)
                    .arg(n.bursts)
                    .arg(n.framesDropped)
                    .arg(n.framesLostToOutage)
                    .arg(n.framesSilenced)
                    .arg(n.framesNotReceived));
        }
        QCoreApplication::quit();
    });

    offerStatus();
    worker.start();
    if (parser.isSet(udp) && !worker.link()->isOpen())
        return kRunError;  // the worker said why
    if (isVerbose)
        say(QStringLiteral("%1 on %2").arg(QString::fromStdString(frame.name), worker.link()->description()));
    if (workerOptions.secure)
        say(QStringLiteral("secure link: encrypted and authenticated, key fingerprint %1")
                .arg(QString::fromStdString(workerOptions.secure->fingerprint)));
    return app.exec();
}

#include "uasim_main.moc"
