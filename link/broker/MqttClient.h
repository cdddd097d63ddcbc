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
// attempts it takes.
//
// Not to be restarted: start() once, stop() (or destruction) once. The will
// may change while connected (MQTT 3.1.1 takes it only with CONNECT): the
// client then says goodbye and connects anew with it.

#include "link/broker/BrokerSettings.h"

#include <QByteArray>
#include <QList>
#include <QObject>
#include <QString>

#include <chrono>
#include <memory>
#include <optional>

class MqttClient : public QObject {
    Q_OBJECT

public:
    explicit MqttClient(BrokerSettings settings, QObject* parent = nullptr);
    // Disconnects gracefully (the broker drops the will) without waiting:
    // libmosquitto's thread is stopped and joined in a thread of its own.
    ~MqttClient() override;

    const BrokerSettings& settings() const { return m_settings; }

    // What the broker publishes for us when we vanish without a word (a
    // crash, a cut network); retained if `retain`; QoS 1. After start(), the
    // client disconnects gracefully (so the old will is dropped, not sent)
    // and connects again carrying the new one: disconnected() is not said,
    // connected() is, as after any reconnection.
    void setWill(const QString& topic, const QByteArray& payload, bool retain);

    // Connects asynchronously; connected() or errorOccurred() tells how it went.
    void start();
    // Says goodbye to the broker after what was published before it; no will.
    void stop();

    // Queues one message; false (and nothing is kept) while not connected:
    // the publisher restates its retained state on connected(), and a
    // session's frames while the broker is away are in its frame log.
    // `messageId`, when given, gets the ID that published() will name.
    bool publish(const QString& topic, const QByteArray& payload, int qos, bool retain, int* messageId = nullptr);
    // Kept, and sent again after every reconnection (sessions are clean).
    void subscribe(const QString& pattern, int qos);

    bool isConnected() const { return m_connected; }
    bool isStarted() const { return m_started; }

signals:
    void connected();
    // After a connection that had been made; `reason` for people.
    void disconnected(const QString& reason);
    void messageReceived(const QString& topic, const QByteArray& payload);
    // The broker has the message publish() gave this ID (QoS 1: its PUBACK).
    // A message whose session ended first may never be named here.
    void published(int messageId);
    // Once per outage: "broker 127.0.0.1:1884: connection refused".
    void errorOccurred(const QString& message);

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
    };

    // Called in this object's thread, queued from libmosquitto's.
    void onConnect(int resultCode, const QString& reason);
    // `restart`: libmosquitto's loop has ended (TLS and protocol failures)
    // and is started again after a pause.
    void onDisconnect(const QString& reason, bool expected, bool restart);
    void reportError(const QString& reason);
    void sendSubscriptions();
    void connectInThread(bool restart, std::optional<Will> will, std::chrono::seconds delay);

    BrokerSettings m_settings;
    std::shared_ptr<Core> m_core;
    QList<Subscription> m_subscriptions;
    bool m_started = false;
    bool m_stopping = false;
    bool m_connected = false;
    // Set when an outage has been reported; cleared by the next connection.
    bool m_errorReported = false;
    int m_restarts = 0;  // in a row, since the last connection
};
