#include "link/aircraft/SimulatorOptions.h"

#include "codec/message/ItemTable.h"
#include "codec/message/TextFormat.h"
#include "link/airframe/AirframeLoader.h"
#include "link/voice/VoiceEncoderSource.h"

#include <QCommandLineParser>
#include <QFileInfo>

#include <cmath>

using namespace rcm;

SimulatorOptions::SimulatorOptions()
    : m_station(QStringLiteral("station"),
                QStringLiteral("A ground station with a channel of its own (docs/protocol.md section 10): listen "
                               "for it on 127.0.0.1:PORT, replying to whoever sent last, under its own key file "
                               "when one is given (the secure link, as --key). Give one for each station: the "
                               "first is in control at start, the second its backup. Only the commands of the "
                               "station in control are acted on, flight plans included; every status frame, on "
                               "every channel, names the station in control and the backup. Not with --udp or "
                               "--serial."),
                QStringLiteral("id,port[,keyfile]")),
      m_failover(QStringLiteral("failover"),
                 QStringLiteral("With two --station or more: when nothing has come from the station in control "
                                "for this many seconds and the backup was heard within them, the backup is given "
                                "control (default 5)."),
                 QStringLiteral("seconds"), QStringLiteral("5")),
      m_udp(QStringLiteral("udp"),
            QStringLiteral("Listen on 127.0.0.1:<port>; reply to whoever sent the last command."),
            QStringLiteral("port")),
      m_serial(QStringLiteral("serial"), QStringLiteral("Use a serial device (a pseudo-terminal works)."),
               QStringLiteral("device")),
      m_baud(QStringLiteral("baud"), QStringLiteral("Serial bit rate (default %1).").arg(SerialLink::kDefaultBaudRate),
             QStringLiteral("n"), QString::number(SerialLink::kDefaultBaudRate)),
      m_modem(QStringLiteral("modem"),
              QStringLiteral("The serial device is a satellite phone's modem (docs/modem.md): initialise it, answer "
                             "each call (RING -> ATA, or the modem's own auto-answer) and take a dropped call as "
                             "link loss, then wait for the next call.")),
      m_log(QStringLiteral("log"),
            QStringLiteral("Keep a pcapng log of every frame sent and received; the file must not exist. With "
                           "--station, one log per station: uasim-GB_30226.pcapng for uasim.pcapng."),
            QStringLiteral("file")),
      m_airframe(QStringLiteral("airframe"),
                 QStringLiteral("The aircraft's units, as JSON: {\"name\", \"engines\": [{\"id\", \"name\"}], "
                                "\"radios\": [{\"systemId\", \"name\"}], \"cameras\": [{\"maker\", \"number\", "
                                "\"name\"}], \"senseAndAvoid\"}. Default: three engines, three radios, sense and "
                                "avoid, two cameras."),
                 QStringLiteral("file")),
      m_uaId(QStringLiteral("ua-id"),
             QStringLiteral("The aircraft's ID_UA_source, country:unit. Default: the first command's ID_UA_source."),
             QStringLiteral("country:unit")),
      m_verbose(QStringLiteral("verbose"), QStringLiteral("Print one line per command received to stderr.")),
      m_key(QStringLiteral("key"),
            QStringLiteral("The secure link (docs/security.md): the aircraft's key file, 64 hex digits, mode 0600. "
                           "Status frames are enciphered; a command that does not authenticate, repeats an earlier "
                           "ID_msg or is more than 30 s from this clock is rejected and counted. The replay state "
                           "and the send counter are kept beside the key file."),
            QStringLiteral("file")),
      m_voiceOut(QStringLiteral("voice-out"),
                 QStringLiteral("Voice (docs/protocol.md section 7): take the voice beside the commands, decode it "
                                "and write what the VHF radio would transmit to a WAV file (8 kHz, 16-bit mono), "
                                "silence included."),
                 QStringLiteral("file.wav")),
      m_voiceIn(QStringLiteral("voice-in"),
                QStringLiteral("Voice: speak a WAV file (16-bit PCM, any rate) back to the console, from the start "
                               "of the link (over UDP: from the console's first command, when uasim knows where "
                               "to send)."),
                QStringLiteral("file.wav")),
      m_voice(QStringLiteral("voice"),
              QStringLiteral("Voice beside the commands (docs/protocol.md section 7), as the console has it: "
                             "implied by --voice-out, --voice-in and --voice-echo. With --key, enciphered and "
                             "authenticated (docs/security.md section 8).")),
      m_voiceEcho(QStringLiteral("voice-echo"),
                  QStringLiteral("Voice: say back what is heard, as a radio check (what gcs --rehearsal asks for "
                                 "when the console has voice)."))
{
}

void SimulatorOptions::addTo(QCommandLineParser& parser) const
{
    parser.addOptions({m_udp, m_serial, m_station, m_failover, m_baud, m_modem, m_log, m_airframe, m_uaId});
    m_faults.addTo(parser);
    parser.addOptions({m_verbose, m_key, m_voice, m_voiceOut, m_voiceIn, m_voiceEcho});
}

std::optional<SimulatorSession::Settings> SimulatorOptions::read(const QCommandLineParser& parser, QString* error) const
{
    const auto wrong = [&](const QString& message) {
        *error = message;
        return std::nullopt;
    };
    const bool stations = parser.isSet(m_station);
    if (stations && (parser.isSet(m_udp) || parser.isSet(m_serial)))
        return wrong(QStringLiteral("--station gives each station a UDP port of its own: not with --udp or --serial"));
    if (!stations && parser.isSet(m_udp) == parser.isSet(m_serial))
        return wrong(
            QStringLiteral("give either --udp PORT, --serial DEVICE or --station ID,PORT[,KEYFILE] for "
                           "each station"));
    if (stations && parser.isSet(m_key))
        return wrong(
            QStringLiteral("with --station, give each station's key as --station ID,PORT,KEYFILE, not "
                           "--key"));
    const bool voice =
        parser.isSet(m_voice) || parser.isSet(m_voiceOut) || parser.isSet(m_voiceIn) || parser.isSet(m_voiceEcho);
    if (stations && voice)
        return wrong(
            QStringLiteral("--voice, --voice-out, --voice-in and --voice-echo are for one link (--udp or --serial), "
                           "not with --station"));
    if (parser.isSet(m_modem) && !parser.isSet(m_serial))
        return wrong(QStringLiteral("--modem needs --serial DEVICE: the modem is on a serial port"));
    if (!parser.positionalArguments().isEmpty())
        return wrong(QStringLiteral("unexpected argument %1").arg(parser.positionalArguments().first()));

    SimulatorSession::Settings settings;
    const std::optional<FaultSettings> faults = m_faults.read(parser, error);
    if (!faults)
        return std::nullopt;
    settings.faults = *faults;

    if (parser.isSet(m_uaId)) {
        double country = 0, unit = 0;
        const ItemInfo& info = itemInfo(ItemId::ID_UA_source);
        if (!parseNumberPair(parser.value(m_uaId), &country, &unit) || int(country) < info.min ||
            int(country) > info.max || int(unit) > 65535)
            return wrong(QStringLiteral("--ua-id wants COUNTRY:UNIT, country %1..%2, unit 0..65535")
                             .arg(info.min)
                             .arg(info.max));
        settings.identity = StationId{static_cast<std::uint16_t>(country), static_cast<std::uint16_t>(unit)};
    }
    if (parser.isSet(m_airframe)) {
        const auto loaded = AirframeLoader::load(parser.value(m_airframe), error);
        if (!loaded)
            return std::nullopt;
        settings.airframe = *loaded;
    }

    bool ok = true;
    if (stations) {
        std::optional<std::vector<SimulatorSession::Station>> read = readStations(parser, error);
        if (!read)
            return std::nullopt;
        settings.stations = std::move(*read);
    } else if (parser.isSet(m_udp)) {
        const uint port = parser.value(m_udp).toUInt(&ok);
        if (!ok || port > 65535)
            return wrong(QStringLiteral("--udp wants a port number, not %1").arg(parser.value(m_udp)));
        settings.udpPort = static_cast<quint16>(port);
    } else {
        settings.serialDevice = parser.value(m_serial);
        settings.modem = parser.isSet(m_modem);
        settings.baudRate = parser.value(m_baud).toInt(&ok);
        if (!ok || settings.baudRate <= 0)
            return wrong(QStringLiteral("--baud wants a bit rate, not %1").arg(parser.value(m_baud)));
    }
    if (parser.isSet(m_failover)) {
        if (settings.stations.size() < 2)
            return wrong(QStringLiteral("--failover is for an aircraft with two --station or more"));
        const double seconds = parser.value(m_failover).toDouble(&ok);
        if (!ok || !std::isfinite(seconds) || seconds < 0.001 || seconds > 3600)
            return wrong(
                QStringLiteral("--failover wants seconds, 0.001 to 3600, not %1").arg(parser.value(m_failover)));
        settings.failover = std::chrono::milliseconds(std::llround(seconds * 1000));
    }
    if (voice) {
        settings.voiceOutFile = parser.value(m_voiceOut);
        settings.voiceEcho = parser.isSet(m_voiceEcho);
        settings.voiceSource = std::make_shared<VoiceEncoderSource>(std::chrono::milliseconds(0));
        std::string voiceError;
        if (parser.isSet(m_voiceIn) &&
            !settings.voiceSource->speakFile(parser.value(m_voiceIn).toStdString(), voiceError))
            return wrong(QStringLiteral("--voice-in: %1").arg(QString::fromStdString(voiceError)));
    }
    settings.logFile = parser.value(m_log);
    settings.verbose = parser.isSet(m_verbose);
    settings.keyFile = parser.value(m_key);
    return settings;
}

std::optional<std::vector<SimulatorSession::Station>> SimulatorOptions::readStations(const QCommandLineParser& parser,
                                                                                     QString* error) const
{
    const auto wrong = [&](const QString& message) {
        *error = message;
        return std::nullopt;
    };
    std::vector<SimulatorSession::Station> stations;
    QStringList keyFiles;
    for (const QString& value : parser.values(m_station)) {
        // A key file's path may hold commas: everything after the second is the path.
        const QStringList parts = value.split(QLatin1Char(','));
        if (parts.size() < 2)
            return wrong(
                QStringLiteral("--station wants ID,PORT[,KEYFILE] such as GB_30226,5601,a.key, not %1").arg(value));
        SimulatorSession::Station station;
        std::string stationError;
        const std::optional<rcm::StationId> id = rcm::parseStation(parts[0].toStdString(), &stationError);
        if (!id)
            return wrong(QStringLiteral("--station %1: %2").arg(value, QString::fromStdString(stationError)));
        station.id = *id;
        bool ok = false;
        const uint port = parts[1].toUInt(&ok);
        if (!ok || port == 0 || port > 65535)
            return wrong(QStringLiteral("--station %1: the port is 1 to 65535, not %2").arg(value, parts[1]));
        station.udpPort = static_cast<quint16>(port);
        if (parts.size() > 2) {
            station.keyFile = parts.mid(2).join(QLatin1Char(','));
            if (station.keyFile.isEmpty())
                return wrong(QStringLiteral("--station %1: the key file is empty").arg(value));
        }
        for (const SimulatorSession::Station& earlier : stations) {
            if (earlier.id == station.id)
                return wrong(QStringLiteral("--station %1: that station was given already").arg(value));
            if (earlier.udpPort == station.udpPort)
                return wrong(QStringLiteral("--station %1: port %2 was given to another station").arg(value).arg(port));
        }
        // Each station's key must open its channel only; and the secure
        // link's state beside a key file is one sender's.
        if (!station.keyFile.isEmpty()) {
            const QString path = QFileInfo(station.keyFile).absoluteFilePath();
            if (keyFiles.contains(path))
                return wrong(QStringLiteral("--station %1: each station needs a key of its own").arg(value));
            keyFiles << path;
        }
        stations.push_back(station);
    }
    return stations;
}
