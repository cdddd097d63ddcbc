#pragma once

// Every aircraft a broker hears of, one summary each, for the fleet view.
// Subscribes its MqttClient to every aircraft's station reports and
// statistics (BrokerTopics: rcm/+/station/+, rcm/+/stats/+; the client
// renews them on every reconnection), judges each message by its trust
// (BrokerTrust: signature, seal, size; then its number, SequenceCheck) and
// says after each one what the aircraft it concerns now looks like.
//
// Not the frames: each is a signature to verify, two a second an aircraft,
// and the statistics, once a second, say how many went each way and when
// the last good one came (docs/performance.md, "Fleet through one broker").
// Frames are for the observer of one aircraft.
//
// What it believes: the station in control, the link and the statistics
// come from verified stations only. A station whose key is not
// trusted is counted as unverified, and an aircraft only such stations
// report is unverified: never shown in control. A keyed station's sealed
// session, without its key, says only that it exists. Refused messages are
// counted and said by messageRefused().
//
// A summary holds only what the reports say, never a time of its own: the
// view computes ages against its clock when it draws them, as it does for a
// link's statistics. The station reports and the statistics are retained,
// so a late feed knows every station and its link at once.
//
// Aircraft expire: one not heard of for the time to live (kTimeToLiveMicros,
// by this feed's clock) is removed, by expireStale(), which a timer calls.
// This console's own session (setLocalStation) is known without the broker:
// with the broker unreachable (setBrokerReachable), its aircraft shows its
// own link and the others show that nothing is known of them now.

#include "link/broker/BrokerEnvelope.h"
#include "link/broker/BrokerTopics.h"
#include "link/broker/SequenceCheck.h"
#include "link/clock/Clock.h"

#include <QHash>
#include <QList>
#include <QMetaType>
#include <QObject>
#include <QString>
#include <QStringList>

#include <map>
#include <memory>
#include <optional>

class BrokerTrust;
class MqttClient;

struct AircraftSummary {
    QString aircraft;  // ID_UA_source in the text format's form, "GB_133"
    // The station in control and its backup, as the aircraft last reported
    // them (ID_GCS_destination, ID_GCS_backup) in the newest verified
    // station report that knew them; empty when none did.
    QString inControl;
    QString backup;
    // The best link any online verified station has to the aircraft
    // (connected, then lost, then waiting); closed when none is online.
    LinkState link = LinkState::Closed;
    int stations = 0;        // verified stations that have reported for this aircraft
    int stationsOnline = 0;  // of those, the ones whose last report says online
    int unverifiedStations = 0;  // stations heard whose key is not trusted
    int sealedStations = 0;      // verified stations whose keyed session no key of ours opens
    // The newest good frame from the aircraft (delivered: decoded or
    // corrected) any verified report told of: a station report's last
    // frame, the statistics' last good frame. 0: none yet.
    qint64 lastFrameUtcMicros = 0;
    // Frames sent to the aircraft and received from it, by all its verified
    // stations' links together, as their latest statistics say.
    quint64 framesUp = 0;
    quint64 framesDown = 0;
    bool local = false;  // this console flies it (setLocalStation)
    // False while the broker is unreachable: what other stations said is
    // then as of the outage's start.
    bool brokerReachable = true;

    // Some verified station (or this console) reports it.
    bool verified() const { return stations > 0 || sealedStations > 0; }

    friend bool operator==(const AircraftSummary&, const AircraftSummary&) = default;
};

Q_DECLARE_METATYPE(AircraftSummary)

class FleetFeed : public QObject {
    Q_OBJECT

public:
    static constexpr qint64 kTimeToLiveMicros = 300'000'000;
    // How often a timer removes aircraft not heard of for the time to live.
    static constexpr int kExpiryIntervalMs = 10'000;
    // `client` is not owned and must outlive the feed; it may be connected
    // already or connect later: the feed asks it once for the patterns, and
    // the client sends them again after every reconnection. Null: messages
    // come by handleMessage() only. Until setTrust(), nobody is trusted.
    // When an aircraft was heard of, and the expiry's cadence, are on
    // `clock` (null: the SystemClock; tests pass a VirtualClock).
    explicit FleetFeed(MqttClient* client, QObject* parent = nullptr, std::shared_ptr<Clock> clock = nullptr);
    ~FleetFeed() override;

    // Whom the feed believes, and which sealed sessions it reads; given to
    // the client too, which judges each message in its network thread.
    void setTrust(std::shared_ptr<const BrokerTrust> trust);

    // The patterns subscribed to, in order.
    static QStringList patterns();

    int aircraftCount() const { return int(m_aircraft.size()); }
    std::optional<AircraftSummary> summary(const QString& aircraft) const;
    // Every aircraft, by name.
    QList<AircraftSummary> summaries() const;

    // Messages refused (forged, unsigned in a trusted station's name,
    // replayed, malformed, too large, unreadable), since the feed was made.
    quint64 refusedPayloads() const { return m_refused; }
    bool isBrokerReachable() const { return m_brokerReachable; }

public slots:
    // One message as the broker delivered it (MqttClient::messageReceived),
    // judged here. An empty payload on a station topic is a retained report
    // cleared: an unverified station is forgotten (a verified one stays until
    // a signed report replaces it or it expires).
    void handleMessage(const QString& topic, const QByteArray& payload);
    // One message as the client judged it (MqttClient::messageOpened).
    void handleOpened(const OpenedMessage& message);
    // This console's own station report, for `aircraft`: trusted without the
    // broker. An empty aircraft: this console flies none now.
    void setLocalStation(const QString& aircraft, const StationReport& report);
    void setBrokerReachable(bool reachable);
    // Removes the aircraft not heard of for the time to live.
    void expireStale();

signals:
    // After every message that concerns an aircraft, with what it now is.
    void aircraftUpdated(const AircraftSummary& summary);
    // An aircraft expired: nothing heard of it for the time to live.
    void aircraftRemoved(const QString& aircraft);
    // Each verified statistics message, before the aircraftUpdated() that
    // counts it; `publishedUtcMicros` is its envelope's number.
    void statsReported(const QString& aircraft, const StatsReport& stats, qint64 publishedUtcMicros);
    // A message that could not be read or believed, and why.
    void payloadRefused(const QString& topic, const QString& error);
    // The same, as refused frames are told: "forged: ...".
    void messageRefused(const QString& reasonAndDetail);

private:
    struct Station {
        StationReport report;
        bool verified = false;
        bool sealed = false;  // verified, and no key of ours opens it
    };
    struct Aircraft {
        std::map<QString, Station> stations;   // by station
        std::map<QString, StatsReport> stats;  // by verified station
        qint64 heardMicros = 0;                // by our clock: the last message about it
    };

    void subscribe();
    void refuse(const QString& topic, const QString& error);
    void updated(const QString& aircraft);
    AircraftSummary summarise(const QString& name, const Aircraft& aircraft) const;

    MqttClient* m_client;
    std::shared_ptr<const BrokerTrust> m_trust;
    SequenceCheck m_sequence;
    QHash<QString, Aircraft> m_aircraft;
    QString m_localAircraft;
    std::optional<StationReport> m_local;
    bool m_brokerReachable = true;
    quint64 m_refused = 0;
    std::shared_ptr<Clock> m_clock;
    ClockTimer* m_expiryTimer;
};
