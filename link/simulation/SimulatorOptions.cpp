#include "link/simulation/SimulatorOptions.h"

#include "codec/message/ItemTable.h"
#include "link/simulation/AirframeLoader.h"
#include "link/voice/VoiceEncoderSource.h"

#include <QCommandLineParser>

using namespace rcm;

SimulatorOptions::SimulatorOptions()
    : m_udp(QStringLiteral("udp"),
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
            QStringLiteral("Keep a pcapng log of every frame sent and received; the file must not exist."),
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
                QStringLiteral("Voice: speak a WAV file (16-bit PCM, any rate) back to the console, from the start."),
                QStringLiteral("file.wav"))
{
}

void SimulatorOptions::addTo(QCommandLineParser& parser) const
{
    parser.addOptions({m_udp, m_serial, m_baud, m_modem, m_log, m_airframe, m_uaId});
    m_faults.addTo(parser);
    parser.addOptions({m_verbose, m_key, m_voiceOut, m_voiceIn});
}

std::optional<SimulatorSession::Settings> SimulatorOptions::read(const QCommandLineParser& parser, QString* error) const
{
    const auto wrong = [&](const QString& message) {
        *error = message;
        return std::nullopt;
    };
    if (parser.isSet(m_udp) == parser.isSet(m_serial))
        return wrong(QStringLiteral("give either --udp PORT or --serial DEVICE"));
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
    if (parser.isSet(m_udp)) {
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
    if (parser.isSet(m_voiceOut) || parser.isSet(m_voiceIn)) {
        settings.voiceOutFile = parser.value(m_voiceOut);
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
