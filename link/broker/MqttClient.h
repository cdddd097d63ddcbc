#pragma once

// One connection to an MQTT broker, through libmosquitto. Its network loop
// runs in libmosquitto's own thread (mosquitto_loop_start), never in the
// owner's: connecting, reading, writing and reconnecting all happen there,
// and what it has to say comes back to the owner's thread as queued calls.
// publish() and subscribe() only queue, so the GUI thread never waits on the
// broker.
//
// The client rejoins by itself: when the broker goes away, refuses it or
// fails the TLS handshake, it keeps trying (after 1 s, then a second longer
// each time, at most 8 s apart), and on
// each connection it subscribes again to every pattern it was asked for and
// says connected(), upon which a publisher republishes its retained state.
// An outage is reported once by errorOccurred(), whatever the number of
// attempts it takes, and its end by restored(), with its length.
//
// MQTT 5: the client tells the broker the largest packet it takes
// (settings.maxPacketBytes: BrokerTopics::kMaxPacketBytes), so a huge message
// on the broker costs it nothing; with a trust set (setTrust), each message
// is also judged in the network thread, its size against its kind's limit
// before it is copied, and comes as messageOpened().
//
// Not to be restarted: start() once, stop() (or destruction) once. The will
// may change while connected (MQTT 3.1.1 takes it only with CONNECT): the
// client then says goodbye and connects anew with it.

#include "link/broker/BrokerEnvelope.h"
#include "link/broker/BrokerSettings.h"
#include "link/clock/Clock.h"

#include <QByteArray>
#include <QHash>
#include <QList>
#include <QObject>
#include <QString>

#include <chrono>
#include <memory>
#include <optional>

class MqttClient : public QObject {
    Q_OBJECT

public:
    // An outage is timed on `clock`, the session's (null: the SystemClock);
    // libmosquitto's own reconnection delays stay on the system's.
    explicit MqttClient(BrokerSettings settings, QObject* parent = nullptr, std::shared_ptr<Clock> clock = nullptr);
    // Disconnects gracefully (the broker drops the will) without waiting:
    // libmosquitto's thread is stopped and joined in a thread of its own.
    ~MqttClient() override;

    const BrokerSettings& settings() const { return m_settings; }

    // What the broker publishes for us when we vanish without a word (a
    // crash, a cut network); retained if `retain`; QoS 1. After start(), the
    // client disconnects gracefully (so the old will is dropped, not sent)
    // and connects again carrying the new one: disconnected() is not said,
    // connected() is, as after any reconnection.
    void setWill(const QString& topic, const QByteArray& payload, bool retain, int expirySeconds = 0);

    // From now on each message is judged by `trust` (BrokerTrust::open) in
    // the network thread and said by messageOpened(), not messageReceived();
    // one larger than its kind allows is refused there, before it is copied.
    // May change at any time (a new link key to open sessions with).
    void setTrust(std::shared_ptr<const BrokerTrust> trust);

    // Connects asynchronously; connected() or errorOccurred() tells how it went.
    void start();
    // Says goodbye to the broker after what was published before it; no will.
    void stop();

    // Queues one message; false (and nothing is kept) while not connected:
    // the publisher restates its retained state on connected(), and a
    // session's frames while the broker is away are in its frame log.
    // `messageId`, when given, gets the ID that published() will name.
    // `expirySeconds` > 0: the broker drops the message after that long
    // (MQTT 5 message expiry), retained or queued for a client away.
    bool publish(const QString& topic, const QByteArray& payload, int qos, bool retain, int* messageId = nullptr,
                 int expirySeconds = 0);
    // Kept, and sent again after every reconnection (a clean session keeps
    // none; a persistent one would not need them, and a retained message
    // sent again is a duplicate its reader drops).
    void subscribe(const QString& pattern, int qos);

    bool isConnected() const { return m_connected; }
    bool isStarted() const { return m_started; }

signals:
    void connected();
    // After a connection that had been made; `reason` for people.
    void disconnected(const QString& reason);
    // Without a trust: each message as it came.
    void messageReceived(const QString& topic, const QByteArray& payload);
    // With a trust: each message judged.
    void messageOpened(const OpenedMessage& message);
    // The broker took a subscription (its SUBACK), on each connection.
    void subscribed(const QString& pattern);
    // The broker has the message publish() gave this ID (QoS 1: its PUBACK).
    // A message whose session ended first may never be named here.
    void published(int messageId);
    // Once per outage: "broker 127.0.0.1:1884: connection refused".
    void errorOccurred(const QString& message);
    // Instead of errorOccurred(), once per outage too, trouble that will not
    // mend by waiting: a TLS set-up or handshake that failed, credentials
    // refused, a CA file missing. For the banner, not only the event log.
    void setupFailed(const QString& message);
    // Connected again after an outage: "broker 127.0.0.1:1884: back after 15 s".
    void restored(const QString& message, qint64 outageMs);
    // The broker refused a message we published or a subscription (MQTT 5
    // reason codes: an ACL, a size limit), once per topic:
    // "broker 127.0.0.1:1884 refused a message on rcm/A/frames/S: not authorized".
    void refusedByBroker(const QString& message);

private:
    struct Core;
    struct Subscription {
        QString pattern;
        int qos = 0;
    };
    struct Will {
        QByteArray topic;
        QByteArray payload;
        bool retain = false;
        int expirySeconds = 0;
    };

    // Called in this object's thread, queued from libmosquitto's.
    void onConnect(int resultCode, const QString& reason);
    void onPublished(int messageId, int reasonCode);
    void onSubscribed(int messageId, QList<int> granted);
    // A failure marks an outage; only the first since the last connection is
    // told, as "broker <host:port>: <reason>" (nothing for the others).
    std::optional<QString> firstFailure(const QString& reason);
    void reportSetupFailure(const QString& reason);
    // `restart`: libmosquitto's loop has ended (TLS and protocol failures)
    // and is started again after a pause.
    void onDisconnect(const QString& reason, bool expected, bool restart);
    void reportError(const QString& reason);
    void sendSubscriptions();
    void connectInThread(bool restart, std::optional<Will> will, std::chrono::seconds delay);
    void markOutage();

    BrokerSettings m_settings;
    std::shared_ptr<Core> m_core;
    QList<Subscription> m_subscriptions;
    bool m_started = false;
    bool m_stopping = false;
    bool m_connected = false;
    // Set when an outage has been reported; cleared by the next connection.
    bool m_errorReported = false;
    int m_restarts = 0;  // in a row, since the last connection
    std::shared_ptr<Clock> m_clock;
    // When the outage began (the first error or the connection lost), in the
    // clock's steady microseconds; none while connected or before the first
    // connection was tried.
    std::optional<qint64> m_outageSinceSteadyMicros;
    bool m_everConnected = false;
    // Topics and patterns of messages and subscriptions not yet answered,
    // to name them when the broker refuses one; each refusal said once.
    QHash<int, QString> m_unanswered;
    QHash<QString, bool> m_refusalsSaid;
};
