#pragma once

// A console's sessions on the broker: every link a ConsoleSession runs gets
// a SessionPublisher for as long as it runs, with this station's role as
// StationControl follows it, and the console's events go along. Nothing
// here touches the link or its frame log: a broker that is away costs the
// session nothing, and is rejoined by the client itself.

#include "link/broker/BrokerSettings.h"

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

signals:
    // The broker's trouble, once per outage, for the console's event log.
    void errorOccurred(const QString& message);

private:
    void linkStarted(const LinkController* controller);
    void linkStopped();
    void publishRole();
    void publishEvent(const ConsoleEvent& event);
    QString stationName() const;

    ConsoleSession* m_session;
    MqttClient* m_client;
    QPointer<SessionPublisher> m_publisher;
};
