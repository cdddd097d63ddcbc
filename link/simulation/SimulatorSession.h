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

#include "codec/message/Airframe.h"
#include "codec/voice/WavFile.h"
#include "link/simulation/FaultInjector.h"
#include "link/transport/SerialLink.h"

#include <QElapsedTimer>
#include <QObject>
#include <QSet>
#include <QString>

#include <functional>
#include <memory>
#include <optional>

class FaultyLink;
class Link;
class LinkWorker;
class SimulatedAircraft;
class VoiceEncoderSource;

class SimulatorSession : public QObject {
    Q_OBJECT

public:
    struct Settings {
        std::optional<quint16> udpPort;  // 127.0.0.1:port, replying to the last sender; else serialDevice
        QString serialDevice;
        qint32 baudRate = SerialLink::kDefaultBaudRate;
        // The serial device is a satellite phone's modem that answers calls
        // (ModemLink without a number): the link is up while a call is.
        bool modem = false;
        QByteArray modemInit = "ATE0V1&C1&D2";
        QString logFile;  // a pcapng log to create; empty: none
        rcm::Airframe airframe = rcm::Airframe::wellEquipped();
        std::optional<rcm::StationId> identity;  // none: the first command's ID_UA_source
        FaultSettings faults;
        bool verbose = false;  // a line per command, every rejection, the faults' counts
        QString keyFile;       // the secure link's key; empty: the plain link
        // Voice beside the commands when not null: what the aircraft says.
        std::shared_ptr<VoiceEncoderSource> voiceSource;
        QString voiceOutFile;  // a WAV file for the voice heard; empty: dropped
    };
    // Where the session's lines for the operator go.
    using Say = std::function<void(const QString& line)>;

    SimulatorSession(Settings settings, Say say, QObject* parent = nullptr);
    ~SimulatorSession() override;

    // Opens the files and the link and starts answering; false, after
    // saying why, when it cannot.
    bool start();
    // Stops answering and says how many commands were rejected and, when
    // verbose, what the faults did.
    void stop();

private:
    std::unique_ptr<Link> openLink();
    void offerStatus();

    Settings m_settings;
    Say m_say;
    rcm::WavFile m_voiceRecord;
    std::unique_ptr<SimulatedAircraft> m_aircraft;
    std::unique_ptr<LinkWorker> m_worker;
    FaultyLink* m_faultyLink = nullptr;  // the worker's link, when it has faults
    QElapsedTimer m_simulationClock;
    QSet<QString> m_rejectionKinds;
    QString m_lastError;  // the link's last error, not said again by the status that repeats it
};
