#pragma once

// Every aircraft a broker hears of, one summary each, for the fleet view.
// Subscribes its MqttClient to every aircraft's station reports, frames and
// statistics (BrokerTopics: rcm/+/station/+, rcm/+/frames, rcm/+/stats;
// the client renews them on every reconnection), reads each payload with BrokerTopics, and
// says after each one what the aircraft it concerns now looks like.
//
// A summary holds only what the reports say, never a time of its own: the
// view computes ages against its clock when it draws them, as it does for a
// link's statistics. Frames are not retained, so the frame counts are those
// this feed has seen since it subscribed; the station reports and the
// statistics are, so a late feed knows every station and its link at once.

#include "link/broker/BrokerTopics.h"

#include <QHash>
#include <QList>
#include <QMetaType>
#include <QObject>
#include <QString>
#include <QStringList>

#include <map>
#include <optional>

class MqttClient;

struct AircraftSummary {
    QString aircraft;  // ID_UA_source in the text format's form, "GB_133"
    // The station in control and its backup, as the aircraft last reported
    // them (ID_GCS_destination, ID_GCS_backup) in the newest station report
    // that knew them; empty when none did.
    QString inControl;
    QString backup;
    // The best link any online station has to the aircraft (connected, then
    // lost, then waiting); closed when no station is online.
    LinkState link = LinkState::Closed;
    int stations = 0;        // stations that have reported for this aircraft
    int stationsOnline = 0;  // of those, the ones whose last report says online
    // The newest good frame from the aircraft (delivered: decoded or
    // corrected) any report told of: a frame down, a station report's last
    // frame, the statistics' last good frame. 0: none yet.
    qint64 lastFrameUtcMicros = 0;
    quint64 framesUp = 0;    // FrameReports seen going to the aircraft, from any station
    quint64 framesDown = 0;  // and coming from it, as each station received them

    friend bool operator==(const AircraftSummary&, const AircraftSummary&) = default;
};

Q_DECLARE_METATYPE(AircraftSummary)

class FleetFeed : public QObject {
    Q_OBJECT

public:
    // `client` is not owned and must outlive the feed; it may be connected
    // already or connect later: the feed asks it once for the patterns, and
    // the client sends them again after every reconnection. Null: messages
    // come by handleMessage() only.
    explicit FleetFeed(MqttClient* client, QObject* parent = nullptr);
    ~FleetFeed() override;

    // The patterns subscribed to, in order.
    static QStringList patterns();

    int aircraftCount() const { return int(m_aircraft.size()); }
    std::optional<AircraftSummary> summary(const QString& aircraft) const;
    // Every aircraft, by name.
    QList<AircraftSummary> summaries() const;

    // Payloads refused (not JSON of the schema) and messages on a topic
    // outside the schema, since the feed was made.
    quint64 refusedPayloads() const { return m_refused; }

public slots:
    // One message as the broker delivered it (MqttClient::messageReceived).
    // An empty payload on a station topic is a retained report cleared: the
    // station is forgotten.
    void handleMessage(const QString& topic, const QByteArray& payload);

signals:
    // After every message that concerns an aircraft, with what it now is.
    void aircraftUpdated(const AircraftSummary& summary);
    // Each frame reported, before the aircraftUpdated() that counts it.
    void frameReported(const QString& aircraft, const FrameReport& frame);
    // A message that could not be read, and why.
    void payloadRefused(const QString& topic, const QString& error);

private:
    struct Aircraft {
        std::map<QString, StationReport> stations;  // by station
        std::optional<StatsReport> stats;
        qint64 lastDownUtcMicros = 0;  // newest good frame down
        quint64 framesUp = 0;
        quint64 framesDown = 0;
    };

    void subscribe();
    void refuse(const QString& topic, const QString& error);
    static AircraftSummary summarise(const QString& name, const Aircraft& aircraft);

    MqttClient* m_client;
    QHash<QString, Aircraft> m_aircraft;
    quint64 m_refused = 0;
};
