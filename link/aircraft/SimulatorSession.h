#pragma once

// The simulated aircraft at the far end of a link, for rehearsals and tests
// (uasim): it answers each command with the state it actually has, once a
// second, through the same LinkWorker and transports as the console, and
// can spoil its own replies with rehearsal faults.
//
// The worker runs in the caller's thread: a simulator has no GUI to keep
// responsive, and one thread makes every status frame exactly the state
// after the commands received before it (a one-frame indication such as a
// photograph taken cannot be cleared by a frame that did not carry it).
//
// With several ground stations (docs/protocol.md section 10) each has a
// channel of its own, a worker over its own UDP port under its own key, and
// rcm::ControlArbiter decides whose commands the aircraft acts on; the same
// status frame, naming the station in control and the backup, goes out on
// every channel each second.

#include "codec/control/ControlArbiter.h"
#include "codec/message/Airframe.h"
#include "codec/voice/WavFile.h"
#include "link/aircraft/FaultInjector.h"
#include "link/transport/SerialLink.h"

#include <QObject>
#include <QSet>
#include <QString>

#include <chrono>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <vector>

class Clock;
class ClockTimer;
class FaultyLink;
class Link;
class LinkWorker;
struct ReceivedMessage;
class SimulatedAircraft;
class VoiceEncoderSource;
namespace rcm::secure {
struct SecureEndpoint;
}

class SimulatorSession : public QObject {
    Q_OBJECT

public:
    // A ground station with a channel of its own.
    struct Station {
        rcm::StationId id;
        quint16 udpPort = 0;  // 127.0.0.1:port, replying to the last sender
        QString keyFile;      // the secure link under this station's key; empty: the plain link
    };

    struct Settings {
        // One channel each, the first in control at start and the second its
        // backup; none: the one link, udpPort or else serialDevice.
        std::vector<Station> stations;
        // With two stations or more: silence of the station in control after
        // which the backup, if heard, takes over.
        std::chrono::milliseconds failover{5000};
        std::optional<quint16> udpPort;  // 127.0.0.1:port, replying to the last sender; else serialDevice
        QString serialDevice;
        qint32 baudRate = SerialLink::kDefaultBaudRate;
        // The serial device is a satellite phone's modem that answers calls
        // (ModemLink without a number): the link is up while a call is.
        bool modem = false;
        QByteArray modemInit = "ATE0V1&C1&D2";
        QString logFile;  // a pcapng log to create; empty: none. With stations, one each (logFileFor)
        rcm::Airframe airframe = rcm::Airframe::wellEquipped();
        std::optional<rcm::StationId> identity;  // none: the first command's ID_UA_source
        FaultSettings faults;
        bool verbose = false;  // a line per command, every rejection, the faults' counts
        QString keyFile;       // the secure link's key; empty: the plain link
        // Voice beside the commands when not null: what the aircraft says.
        std::shared_ptr<VoiceEncoderSource> voiceSource;
        QString voiceOutFile;  // a WAV file for the voice heard; empty: dropped
        bool voiceEcho = false;  // what is heard is said back (a radio check), as voiceSource
        // The one time source of the session: its channels' cadence, the
        // aircraft's motion, its status's time stamp, control's timeouts.
        // Null: the SystemClock.
        std::shared_ptr<Clock> clock;
        // Makes each channel's transport instead of its UDP port or the
        // serial device (called with the station, null for the one link):
        // tests run the session in process on a VirtualClock, joined to the
        // console by in-process links. Unset: the ports and devices above.
        std::function<std::unique_ptr<Link>(const Station* station)> transport;
    };
    // Where the session's lines for the operator go.
    using Say = std::function<void(const QString& line)>;

    SimulatorSession(Settings settings, Say say, QObject* parent = nullptr);
    ~SimulatorSession() override;

    // Opens the files and the link and starts answering; false, after
    // saying why, when it cannot.
    bool start();
    // Stops answering and says how many commands were rejected, how many
    // frames came from stations not in control and, when verbose, what the
    // faults did.
    void stop();

    // The log of `station`'s channel: `logFile` with "-GB_30226" before its extension.
    static QString logFileFor(const QString& logFile, rcm::StationId station);

private:
    // One link and its worker: the only one, or one station's.
    struct Channel {
        std::optional<rcm::StationId> station;  // none: the one link of --udp or --serial
        QString prefix;                         // "GB_30226: " before what is said of it; empty for the one link
        std::unique_ptr<LinkWorker> worker;
        FaultyLink* faultyLink = nullptr;  // the worker's link, when it has faults
        QSet<QString> rejectionKinds;
        QString lastError;  // the link's last error, not said again by the status that repeats it
    };

    std::unique_ptr<Link> openLink(const Station* station, Channel& channel, const rcm::secure::SecureEndpoint* key);
    void echo(VoiceEncoderSource& source, std::span<const std::int16_t> pcm);
    bool openChannel(const Station* station);
    void connectChannel(Channel& channel);
    void commandReceived(Channel& channel, const ReceivedMessage& received);
    void statusFrameSent(Channel& channel);
    void armControlTimer();
    void checkControl();
    void sayControlEvent(const rcm::ControlArbiter::Event& event);
    void offerStatus();
    rcm::Message status() const;

    Settings m_settings;
    Say m_say;
    rcm::WavFile m_voiceRecord;
    std::vector<std::int16_t> m_echoHeld;  // --voice-echo: the start of a talk, held
    bool m_echoTalking = false;
    std::unique_ptr<SimulatedAircraft> m_aircraft;
    rcm::ControlArbiter m_arbiter;
    // The session's time: the workers' frames and ticks, the arbiter's, the control timer's.
    std::shared_ptr<Clock> m_clock;
    ClockTimer* m_controlTimer = nullptr;  // failover, checked on every half second
    std::vector<std::unique_ptr<Channel>> m_channels;
    // The second whose status frames are going out: the first channel to
    // send in it ends the frame's one-frame indications, after the others
    // were handed the same frame.
    std::int64_t m_statusSecond = -1;
    std::int64_t m_lastAdvanceMicros = 0;  // steady time the aircraft was last moved on to
};
