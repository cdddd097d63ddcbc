#pragma once

// A console's sessions on the broker: every link a ConsoleSession runs gets
// a SessionPublisher for as long as it runs, with this station's role as
// StationControl follows it, and the console's events go along. Nothing
// here touches the link or its frame log: a broker that is away costs the
// session nothing, and is rejoined by the client itself.
//
// Each publisher signs with the station's key (settings.signingKey) and,
// when the link is keyed, seals with the broker key derived from the link's
// key (ConsoleSession::logKey()).

#include "link/broker/BrokerSettings.h"
#include "link/broker/BrokerTopics.h"

#include <QObject>
#include <QPointer>

class ConsoleSession;
class EventLog;
class LinkController;
class MqttClient;
class SessionPublisher;
struct ConsoleEvent;

class SessionBroadcast : public QObject {
    Q_OBJECT

public:
    // Starts the client at once; `session` must outlive this.
    SessionBroadcast(ConsoleSession* session, const BrokerSettings& settings, QObject* parent = nullptr);
    ~SessionBroadcast() override;

    MqttClient* client() const { return m_client; }
    // The running link's publisher; null between links.
    SessionPublisher* publisher() const;
    // Every event the console records is published too.
    void follow(const EventLog* events);

    // The station's name on the broker: its station ID, else "gcs-HOST".
    QString stationName() const;

signals:
    // The broker's trouble, once per outage, for the console's event log.
    void errorOccurred(const QString& message);
    // Instead of those, trouble no waiting mends (TLS, credentials): for the banner.
    void setupFailed(const QString& message);
    // The broker back after an outage, and for how long it was away.
    void restored(const QString& message);
    // The broker refused a message or a subscription of ours (an ACL).
    void refusedByBroker(const QString& message);
    // The running link's station report, whether or not the broker heard it.
    void stationReportChanged(const QString& aircraft, const StationReport& report);

private:
    void linkStarted(const LinkController* controller);
    void linkStopped();
    void publishRole();
    void publishEvent(const ConsoleEvent& event);

    ConsoleSession* m_session;
    BrokerSettings m_settings;
    MqttClient* m_client;
    QPointer<SessionPublisher> m_publisher;
};
