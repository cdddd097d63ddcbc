#pragma once

// A read-only session from the broker: what a console publishes for one
// aircraft (SessionPublisher, BrokerTopics.h), told as the link's own events,
// so that the console binds the same widgets to it as to a live link. It
// subscribes to rcm/<aircraft>/# and says
//   - frameLogged for each frame of the followed station, up and down, with
//     its bytes (offset -1: in no file of ours); frameSent for the ones up;
//   - messageReceived for each status, read back from the frame's text with
//     the codec's text format parser, and for the retained last status on
//     joining;
//   - statisticsChanged and stateChanged from the retained statistics, with
//     linkLost and linkRegained on their changes; the link is lost to us too
//     when the broker goes away or the followed station goes offline;
//   - errorOccurred for the broker's trouble and events of severity "error"
//     or "alarm", transportStatusChanged for the others and for joining.
// It keeps every station's report: who publishes for the aircraft, and as
// what. It has no way to send anything to the aircraft, nor to publish.
//
// The followed station is the one set by followStation(); else the online
// station whose report says "control"; else the first one a frame came from.

#include "link/broker/BrokerSettings.h"
#include "link/broker/BrokerTopics.h"
#include "link/session/LinkEvents.h"

#include <QHash>
#include <QMap>
#include <QString>

#include <optional>

class MqttClient;

class BrokerObservation : public LinkEvents {
    Q_OBJECT

public:
    // Observes settings.aircraft ("unknown" when empty).
    explicit BrokerObservation(const BrokerSettings& settings, QObject* parent = nullptr);
    ~BrokerObservation() override;

    void start();
    void stop();

    QString aircraft() const { return m_aircraft; }
    bool isConnected() const;
    const BrokerSettings& settings() const;

    // Every station that has a report for the aircraft, by station ID.
    const QMap<QString, StationReport>& stations() const { return m_stations; }

    // Empty: choose as the header says.
    void followStation(const QString& station);
    QString followedStation() const;

    // The last statistics received (state Lost while the broker is away).
    std::optional<LinkStatistics> statistics() const { return m_statistics; }

signals:
    void stationsChanged();
    void eventReported(const EventReport& event);

private:
    void messageArrived(const QString& topic, const QByteArray& payload);
    void brokerConnected();
    void brokerDisconnected();
    void stationReported(const QString& station, const QByteArray& payload);
    void frameReported(const QByteArray& payload);
    void stateReported(const QByteArray& payload);
    void statsReported(const QByteArray& payload);
    void eventArrived(const QByteArray& payload);
    void emitMessage(const QString& text, qint64 utcMicros, rcm::Corrections corrected, FrameTransport transport,
                     const QString& from);
    void setLinkState(LinkState state);
    void reportError(const QString& message);

    MqttClient* m_client;
    QString m_aircraft;
    QString m_followed;        // set by followStation()
    QString m_firstFrameFrom;  // the first station a frame came from
    QMap<QString, StationReport> m_stations;
    QHash<QString, qint64> m_lastFrameUtc;  // by station and direction: the newest frame told
    std::optional<LinkStatistics> m_statistics;
    LinkState m_state = LinkState::Closed;
    std::optional<rcm::Message> m_lastMessage;  // the last status told, not to tell it twice
    QString m_lastError;                        // not to repeat one unreadable payload's error
    bool m_started = false;
};
