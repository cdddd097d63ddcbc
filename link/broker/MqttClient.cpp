#include "link/broker/MqttClient.h"

#include "link/broker/BrokerTrust.h"
#include "link/common/NameTable.h"

#include <QFileInfo>
#include <QMetaObject>

#include <mosquitto.h>
#include <mqtt_protocol.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <condition_variable>
#include <cstring>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <utility>

namespace {

// The pause before the n-th attempt in a row: 1 s, 2 s ... 8 s, as
// libmosquitto's own reconnection (mosquitto_reconnect_delay_set below).
constexpr unsigned kFirstDelaySeconds = 1;
constexpr unsigned kMaxDelaySeconds = 8;
// A goodbye not written by then is not going to be: the connection is dead.
constexpr std::chrono::milliseconds kGoodbyeTimeout{3000};

std::chrono::seconds delayBefore(int attempt)
{
    return std::chrono::seconds(
        std::min<unsigned>(kFirstDelaySeconds * unsigned(std::max(attempt, 1)), kMaxDelaySeconds));
}

// libmosquitto's and the C library's texts ("Connection refused", "The
// connection was lost.") as a clause after "broker HOST:PORT: ".
QString forPeople(const char* text)
{
    QString s = QString::fromUtf8(text).trimmed();
    while (s.endsWith(u'.'))
        s.chop(1);
    if (s.size() > 1 && s[0].isUpper() && !s[1].isUpper())
        s[0] = s[0].toLower();
    return s;
}

QString errnoReason(int error)
{
    return error ? forPeople(std::strerror(error)) : QStringLiteral("system error");
}

// Ours where libmosquitto's words say less than the operator needs.
constexpr auto kResultReasons = std::to_array<Named<int>>({
    {MOSQ_ERR_CONN_LOST, "connection lost"},
    {MOSQ_ERR_KEEPALIVE, "no answer within the keepalive"},
    {MOSQ_ERR_EAI, "host not found"},
});

QString resultReason(int rc)
{
    if (const char* reason = nameOf(kResultReasons, rc))
        return QString::fromUtf8(reason);
    return forPeople(mosquitto_strerror(rc));
}

// MQTT 5's reason codes, as the broker refused us:
// "connection refused: bad user name or password"
QString connackReason(int code)
{
    return QStringLiteral("connection refused: ") + forPeople(mosquitto_reason_string(code)).toLower();
}

// Refusals that no reconnection mends: credentials, authorisation, a client
// ID or protocol the broker will not take.
bool refusalIsSetup(int code)
{
    switch (code) {
        case MQTT_RC_BAD_USERNAME_OR_PASSWORD:
        case MQTT_RC_NOT_AUTHORIZED:
        case MQTT_RC_CLIENTID_NOT_VALID:
        case MQTT_RC_BANNED:
        case MQTT_RC_BAD_AUTHENTICATION_METHOD:
        case MQTT_RC_UNSUPPORTED_PROTOCOL_VERSION:
            return true;
        default:
            return false;
    }
}

// The properties of every CONNECT: the largest packet we take, and how long
// the broker keeps a persistent session. Kept by libmosquitto for its own
// reconnections.
mosquitto_property* connectProperties(const BrokerSettings& s)
{
    mosquitto_property* properties = nullptr;
    if (s.maxPacketBytes > 0)
        mosquitto_property_add_int32(&properties, MQTT_PROP_MAXIMUM_PACKET_SIZE, uint32_t(s.maxPacketBytes));
    if (s.persistentSession && s.sessionExpirySeconds > 0)
        mosquitto_property_add_int32(&properties, MQTT_PROP_SESSION_EXPIRY_INTERVAL, uint32_t(s.sessionExpirySeconds));
    return properties;
}

mosquitto_property* expiryProperty(int expirySeconds)
{
    mosquitto_property* properties = nullptr;
    if (expirySeconds > 0)
        mosquitto_property_add_int32(&properties, MQTT_PROP_MESSAGE_EXPIRY_INTERVAL, uint32_t(expirySeconds));
    return properties;
}

// "OpenSSL Error[0]: error:0A000086:SSL routines::certificate verify failed"
// -> "certificate verify failed"
QString tlsReason(const QString& logLine)
{
    const qsizetype at = logLine.lastIndexOf(QStringLiteral("::"));
    return at >= 0 ? logLine.mid(at + 2).trimmed() : logLine;
}

// Results after which libmosquitto's loop (mosquitto_loop_forever) ends
// instead of reconnecting: the client starts it again itself.
bool endsTheLoop(int rc)
{
    switch (rc) {
        case MOSQ_ERR_NOMEM:
        case MOSQ_ERR_PROTOCOL:
        case MOSQ_ERR_INVAL:
        case MOSQ_ERR_NOT_FOUND:
        case MOSQ_ERR_TLS:
        case MOSQ_ERR_PAYLOAD_SIZE:
        case MOSQ_ERR_NOT_SUPPORTED:
        case MOSQ_ERR_AUTH:
        case MOSQ_ERR_ACL_DENIED:
        case MOSQ_ERR_UNKNOWN:
        case MOSQ_ERR_EAI:
        case MOSQ_ERR_PROXY:
            return true;
        default:
            return false;
    }
}

void initLibraryOnce()
{
    static std::once_flag once;
    std::call_once(once, [] { mosquitto_lib_init(); });
}

}  // namespace

// What the other threads share with the client: the handle, and the client
// while it lives, under a mutex. The callbacks' userdata; it outlives the
// client until the handle is destroyed, so a callback never calls into a
// deleted object.
struct MqttClient::Core {
    mosquitto* mosq = nullptr;
    std::mutex mutex;
    std::condition_variable wake;  // ends a starter's pause when the client stops; says a goodbye went
    MqttClient* owner = nullptr;   // guarded by mutex
    bool stopRequested = false;    // guarded by mutex
    bool goodbyePending = false;   // guarded by mutex: DISCONNECT queued, not yet written
    int inFlight = 0;              // guarded by mutex: messages published, not yet acknowledged
    std::shared_ptr<const BrokerTrust> trust;  // guarded by mutex: null, messages come raw
    // Connects and starts libmosquitto's loop, off the owner's thread. Each
    // one joins the one before it, so they never overlap.
    std::thread starter;

    // Runs f(owner) in the owner's thread, if it still lives.
    template <typename F>
    void post(F&& f)
    {
        std::lock_guard lock(mutex);
        if (!owner)
            return;
        MqttClient* client = owner;
        QMetaObject::invokeMethod(
            client, [client, f = std::forward<F>(f)] { f(client); }, Qt::QueuedConnection);
    }

    void requestStop()
    {
        {
            std::lock_guard lock(mutex);
            stopRequested = true;
        }
        wake.notify_all();
    }

    // False when the client stopped meanwhile.
    bool pause(std::chrono::seconds delay)
    {
        std::unique_lock lock(mutex);
        return !wake.wait_for(lock, delay, [this] { return stopRequested; });
    }

    // Ends the session, if there is one, without losing what was published
    // before: waits (a while) for the broker to acknowledge every message in
    // flight, queues DISCONNECT, waits for libmosquitto's loop to write it,
    // then stops the loop. Each wait matters: a socket closed with the
    // broker's acknowledgements still unread is reset, not closed, and a
    // reset may reach the broker before it has read what came just before
    // (our last messages, the goodbye), so that it drops them and sends the
    // will; and a loop stopped before its next turn never writes the goodbye.
    void endSession()
    {
        bool last = false;
        {
            std::unique_lock lock(mutex);
            wake.wait_for(lock, kGoodbyeTimeout, [this] { return inFlight <= 0; });
            goodbyePending = true;
            last = stopRequested;
        }
        // The client's last goodbye ends a persistent session too: the broker
        // keeps nothing for a client that is not coming back.
        mosquitto_property* properties = nullptr;
        if (last)
            mosquitto_property_add_int32(&properties, MQTT_PROP_SESSION_EXPIRY_INTERVAL, 0);
        const int rc = mosquitto_disconnect_v5(mosq, MQTT_RC_NORMAL_DISCONNECTION, properties);
        mosquitto_property_free_all(&properties);
        if (rc == MOSQ_ERR_SUCCESS) {
            std::unique_lock lock(mutex);
            wake.wait_for(lock, kGoodbyeTimeout, [this] { return !goodbyePending; });
        }
        {
            std::lock_guard lock(mutex);
            goodbyePending = false;
            // What was not acknowledged is gone with the session.
            inFlight = 0;
        }
        mosquitto_loop_stop(mosq, false);
    }

    void connectionEnded()
    {
        {
            std::lock_guard lock(mutex);
            goodbyePending = false;
        }
        wake.notify_all();
    }

    bool stopping()
    {
        std::lock_guard lock(mutex);
        return stopRequested;
    }

    // In libmosquitto's thread.
    static void onConnect(mosquitto*, void* userdata, int resultCode, int, const mosquitto_property*)
    {
        const QString reason = resultCode ? connackReason(resultCode) : QString();
        static_cast<Core*>(userdata)->post([resultCode, reason](MqttClient* c) { c->onConnect(resultCode, reason); });
    }

    static void onDisconnect(mosquitto*, void* userdata, int resultCode, const mosquitto_property*)
    {
        const int error = errno;
        const QString reason = resultCode == MOSQ_ERR_ERRNO ? errnoReason(error) : resultReason(resultCode);
        const bool expected = resultCode == MOSQ_ERR_SUCCESS;
        const bool restart = endsTheLoop(resultCode) || (resultCode == MOSQ_ERR_ERRNO && error == EPROTO);
        auto* core = static_cast<Core*>(userdata);
        core->connectionEnded();
        core->post([reason, expected, restart](MqttClient* c) { c->onDisconnect(reason, expected, restart); });
    }

    static void onPublish(mosquitto*, void* userdata, int messageId, int reasonCode, const mosquitto_property*)
    {
        auto* core = static_cast<Core*>(userdata);
        {
            std::lock_guard lock(core->mutex);
            // Messages resent after a new session began are not counted.
            if (core->inFlight > 0)
                --core->inFlight;
        }
        core->wake.notify_all();
        core->post([messageId, reasonCode](MqttClient* c) { c->onPublished(messageId, reasonCode); });
    }

    static void onSubscribe(mosquitto*, void* userdata, int messageId, int count, const int* granted,
                            const mosquitto_property*)
    {
        QList<int> codes(granted, granted + std::max(count, 0));
        static_cast<Core*>(userdata)->post(
            [messageId, codes = std::move(codes)](MqttClient* c) { c->onSubscribed(messageId, codes); });
    }

    // The payload is looked at only after its size: one larger than its
    // kind allows (and than any we publish) is refused without a copy.
    static void onMessage(mosquitto*, void* userdata, const mosquitto_message* message, const mosquitto_property*)
    {
        auto* core = static_cast<Core*>(userdata);
        QString topic = QString::fromUtf8(message->topic);
        std::shared_ptr<const BrokerTrust> trust;
        {
            std::lock_guard lock(core->mutex);
            trust = core->trust;
        }
        if (!trust) {
            QByteArray payload(static_cast<const char*>(message->payload), message->payloadlen);
            core->post([topic = std::move(topic), payload = std::move(payload)](MqttClient* c) {
                emit c->messageReceived(topic, payload);
            });
            return;
        }
        OpenedMessage opened;
        const std::optional<BrokerTopics::Topic> where = BrokerTopics::parseTopic(topic);
        const qsizetype limit = where ? BrokerTopics::maxPayloadBytes(where->kind) : 0;
        if (where && message->payloadlen > limit) {
            opened.topic = topic;
            opened.where = where;
            opened.station = where->station;
            opened.retained = message->retain;
            opened.refuse(
                QStringLiteral("too large: %1 bytes on %2, at most %3").arg(message->payloadlen).arg(topic).arg(limit));
        } else {
            const QByteArray payload =
                where ? QByteArray(static_cast<const char*>(message->payload), message->payloadlen) : QByteArray();
            opened = trust->open(topic, payload, message->retain);
        }
        core->post([opened = std::move(opened)](MqttClient* c) { emit c->messageOpened(opened); });
    }

    // A failed TLS handshake is said only here, and ends libmosquitto's loop
    // without a disconnect callback.
    static void onLog(mosquitto*, void* userdata, int level, const char* text)
    {
        if (!(level & MOSQ_LOG_ERR) || !text || std::strncmp(text, "OpenSSL Error[0]", 16) != 0)
            return;
        const QString reason = QStringLiteral("TLS failed: ") + tlsReason(QString::fromUtf8(text));
        static_cast<Core*>(userdata)->post([reason](MqttClient* c) {
            c->reportSetupFailure(reason);
            c->onDisconnect(reason, false, true);
        });
    }
};

MqttClient::MqttClient(BrokerSettings settings, QObject* parent, std::shared_ptr<Clock> clock)
    : QObject(parent),
      m_settings(std::move(settings)),
      m_core(std::make_shared<Core>()),
      m_clock(clock ? std::move(clock) : std::make_shared<SystemClock>())
{
    initLibraryOnce();
    const QByteArray id = m_settings.clientId.toUtf8();
    // Clean sessions unless asked (the broker then keeps our subscriptions
    // and what came for them while we were away); the client restates its
    // subscriptions itself either way.
    const bool clean = !m_settings.persistentSession || id.isEmpty();
    m_core->mosq = mosquitto_new(id.isEmpty() ? nullptr : id.constData(), clean, m_core.get());
    m_core->owner = this;
    if (!m_core->mosq)
        return;
    mosquitto_int_option(m_core->mosq, MOSQ_OPT_PROTOCOL_VERSION, MQTT_PROTOCOL_V5);
    mosquitto_connect_v5_callback_set(m_core->mosq, &Core::onConnect);
    mosquitto_disconnect_v5_callback_set(m_core->mosq, &Core::onDisconnect);
    mosquitto_message_v5_callback_set(m_core->mosq, &Core::onMessage);
    mosquitto_publish_v5_callback_set(m_core->mosq, &Core::onPublish);
    mosquitto_subscribe_v5_callback_set(m_core->mosq, &Core::onSubscribe);
    mosquitto_log_callback_set(m_core->mosq, &Core::onLog);
    mosquitto_reconnect_delay_set(m_core->mosq, kFirstDelaySeconds, kMaxDelaySeconds, false);
}

MqttClient::~MqttClient()
{
    {
        std::lock_guard lock(m_core->mutex);
        m_core->owner = nullptr;
    }
    m_core->requestStop();
    // Joining libmosquitto's thread can take as long as a reconnection
    // attempt or the pause between two: a thread of its own waits for it,
    // so that whoever deletes the client does not.
    std::thread([core = m_core] {
        if (core->starter.joinable())
            core->starter.join();
        if (core->mosq) {
            core->endSession();
            mosquitto_destroy(core->mosq);
        }
    }).detach();
}

namespace {

void setWillOf(mosquitto* mosq, const QByteArray& topic, const QByteArray& payload, bool retain, int expirySeconds)
{
    // Takes the properties when it succeeds.
    mosquitto_property* properties = expiryProperty(expirySeconds);
    if (mosquitto_will_set_v5(mosq, topic.constData(), int(payload.size()), payload.constData(), 1, retain,
                              properties) != MOSQ_ERR_SUCCESS)
        mosquitto_property_free_all(&properties);
}

}  // namespace

void MqttClient::setTrust(std::shared_ptr<const BrokerTrust> trust)
{
    std::lock_guard lock(m_core->mutex);
    m_core->trust = std::move(trust);
}

void MqttClient::setWill(const QString& topic, const QByteArray& payload, bool retain, int expirySeconds)
{
    if (!m_core->mosq || m_stopping)
        return;
    Will will{topic.toUtf8(), payload, retain, expirySeconds};
    if (!m_started) {
        setWillOf(m_core->mosq, will.topic, will.payload, will.retain, will.expirySeconds);
        return;
    }
    // libmosquitto's thread reads the will when it connects: it is changed
    // only once that thread has stopped, by the thread that starts it again.
    m_connected = false;
    connectInThread(true, will, std::chrono::seconds(0));
}

void MqttClient::start()
{
    if (m_started)
        return;
    m_started = true;
    // Said in the next pass of the event loop, as every other outcome is:
    // whoever connects to the client just after start() hears it.
    const auto fail = [this](const QString& reason, bool setup) {
        QMetaObject::invokeMethod(
            this, [this, reason, setup] { setup ? reportSetupFailure(reason) : reportError(reason); },
            Qt::QueuedConnection);
    };
    if (!m_core->mosq) {
        fail(QStringLiteral("cannot create a client: ") + errnoReason(errno), false);
        return;
    }
    if (!m_settings.user.isEmpty()) {
        const QByteArray user = m_settings.user.toUtf8();
        const QByteArray password = m_settings.password.toUtf8();
        mosquitto_username_pw_set(m_core->mosq, user.constData(),
                                  m_settings.password.isEmpty() ? nullptr : password.constData());
    }
    if (m_settings.tls) {
        // No CA file named: the system's CA certificates, as a browser would.
        const QString caPath = m_settings.caFile.isEmpty() ? BrokerSettings::kSystemCaPath : QString();
        for (const QString& file : {m_settings.caFile, m_settings.certFile, m_settings.keyFile}) {
            const QFileInfo info(file);
            if (!file.isEmpty() && (!info.isFile() || !info.isReadable())) {
                fail(QStringLiteral("TLS: cannot read \"%1\": %2")
                         .arg(file,
                              info.exists() ? QStringLiteral("not a readable file") : QStringLiteral("no such file")),
                     true);
                return;
            }
        }
        if (!caPath.isEmpty() && !QFileInfo(caPath).isDir()) {
            fail(QStringLiteral("TLS: no CA file given and no system CA certificates in %1: give --broker-cafile")
                     .arg(caPath),
                 true);
            return;
        }
        const QByteArray ca = m_settings.caFile.toLocal8Bit();
        const QByteArray capath = caPath.toLocal8Bit();
        const QByteArray cert = m_settings.certFile.toLocal8Bit();
        const QByteArray key = m_settings.keyFile.toLocal8Bit();
        const int rc = mosquitto_tls_set(
            m_core->mosq, ca.isEmpty() ? nullptr : ca.constData(), capath.isEmpty() ? nullptr : capath.constData(),
            cert.isEmpty() ? nullptr : cert.constData(), key.isEmpty() ? nullptr : key.constData(), nullptr);
        if (rc != MOSQ_ERR_SUCCESS) {
            fail(QStringLiteral("TLS: cannot use the CA \"%1\"%2: %3")
                     .arg(ca.isEmpty() ? caPath : m_settings.caFile,
                          cert.isEmpty() ? QString()
                                         : QStringLiteral(" or the certificate \"%1\" and key \"%2\"")
                                               .arg(m_settings.certFile, m_settings.keyFile),
                          resultReason(rc)),
                 true);
            return;
        }
    }
    connectInThread(false, std::nullopt, std::chrono::seconds(0));
}

std::optional<QString> MqttClient::firstFailure(const QString& reason)
{
    markOutage();
    if (m_errorReported)
        return std::nullopt;
    m_errorReported = true;
    return QStringLiteral("broker %1: %2").arg(m_settings.hostAndPort(), reason);
}

void MqttClient::reportSetupFailure(const QString& reason)
{
    if (const std::optional<QString> text = firstFailure(reason))
        emit setupFailed(*text);
}

void MqttClient::connectInThread(bool restart, std::optional<Will> will, std::chrono::seconds delay)
{
    // Looking the host up and opening the socket may take a while: the
    // connection starts in a thread of its own, which then hands over to
    // libmosquitto's loop. That loop reconnects by itself once it runs, but
    // it never starts after a first attempt that failed at once (a refused
    // connection on loopback, an unknown host): those are retried here,
    // paced as the loop would. To restart, the thread first says goodbye on
    // the connection there is (the broker drops the old will) and waits for
    // the loop to end.
    const std::string host = m_settings.host.toStdString();
    const int port = m_settings.port;
    const int keepAlive = m_settings.keepAliveSeconds;
    // MQTT 5's CONNECT properties go only with libmosquitto's blocking
    // connect, which then keeps them for its own reconnections: it runs
    // here, off the owner's thread, as the asynchronous one would.
    std::shared_ptr<mosquitto_property> properties(connectProperties(m_settings),
                                                   [](mosquitto_property* p) { mosquitto_property_free_all(&p); });
    Core* core = m_core.get();
    core->starter = std::thread([core, host, port, keepAlive, restart, will = std::move(will), delay, properties,
                                 before = std::move(core->starter)]() mutable {
        if (before.joinable())
            before.join();
        if (restart)
            core->endSession();
        if (will)
            setWillOf(core->mosq, will->topic, will->payload, will->retain, will->expirySeconds);
        if (delay.count() > 0 && !core->pause(delay))
            return;
        for (int attempt = 1;; ++attempt) {
            if (core->stopping())
                return;
            errno = 0;
            const int rc =
                mosquitto_connect_bind_v5(core->mosq, host.c_str(), port, keepAlive, nullptr, properties.get());
            if (rc == MOSQ_ERR_SUCCESS)
                break;
            const int error = errno;
            const QString reason = rc == MOSQ_ERR_ERRNO ? errnoReason(error) : resultReason(rc);
            if (rc == MOSQ_ERR_TLS)
                // The handshake failed in the connect itself; onLog said why.
                core->post([reason](MqttClient* c) { c->reportSetupFailure(QStringLiteral("TLS failed: ") + reason); });
            else
                core->post([reason](MqttClient* c) { c->reportError(reason); });
            if (!core->pause(delayBefore(attempt)))
                return;
        }
        const int loop = mosquitto_loop_start(core->mosq);
        if (loop != MOSQ_ERR_SUCCESS) {
            const QString reason = QStringLiteral("cannot start the network thread: ") + resultReason(loop);
            core->post([reason](MqttClient* c) { c->reportError(reason); });
        }
    });
}

void MqttClient::stop()
{
    if (!m_started || m_stopping || !m_core->mosq)
        return;
    m_stopping = true;
    m_core->requestStop();
    // The goodbye goes behind whatever was published before, so the broker
    // has those first; its waits are in a thread of their own.
    Core* core = m_core.get();
    core->starter = std::thread([core, before = std::move(core->starter)]() mutable {
        if (before.joinable())
            before.join();
        core->endSession();
    });
    if (m_connected) {
        m_connected = false;
        emit disconnected(QStringLiteral("stopped"));
    }
}

bool MqttClient::publish(const QString& topic, const QByteArray& payload, int qos, bool retain, int* messageId,
                         int expirySeconds)
{
    if (!m_connected || m_stopping)
        return false;
    const QByteArray t = topic.toUtf8();
    if (qos > 0) {
        // Counted before it may be acknowledged, in libmosquitto's thread.
        std::lock_guard lock(m_core->mutex);
        ++m_core->inFlight;
    }
    int id = 0;
    mosquitto_property* properties = expiryProperty(expirySeconds);
    const int rc = mosquitto_publish_v5(m_core->mosq, &id, t.constData(), int(payload.size()), payload.constData(), qos,
                                        retain, properties);
    mosquitto_property_free_all(&properties);
    if (messageId)
        *messageId = id;
    if (rc == MOSQ_ERR_SUCCESS) {
        if (qos > 0)
            m_unanswered.insert(id, topic);
        return true;
    }
    if (qos > 0) {
        std::lock_guard lock(m_core->mutex);
        --m_core->inFlight;
    }
    // Gone between our hearing of it and now: the disconnection will say so.
    if (rc != MOSQ_ERR_NO_CONN && rc != MOSQ_ERR_CONN_LOST)
        reportError(QStringLiteral("cannot publish to %1: %2").arg(topic, resultReason(rc)));
    return false;
}

void MqttClient::subscribe(const QString& pattern, int qos)
{
    m_subscriptions.append({pattern, qos});
    if (m_connected) {
        const QByteArray p = pattern.toUtf8();
        int id = 0;
        if (mosquitto_subscribe_v5(m_core->mosq, &id, p.constData(), qos, 0, nullptr) == MOSQ_ERR_SUCCESS)
            m_unanswered.insert(id, pattern);
    }
}

void MqttClient::onConnect(int resultCode, const QString& reason)
{
    if (m_stopping)
        return;
    if (resultCode != 0) {
        // Refused by the broker (a wrong password): the loop tries again.
        if (refusalIsSetup(resultCode))
            reportSetupFailure(reason);
        else
            reportError(reason);
        markOutage();
        return;
    }
    m_connected = true;
    m_errorReported = false;
    m_restarts = 0;
    m_unanswered.clear();
    const bool everConnected = m_everConnected;
    m_everConnected = true;
    if (m_outageSinceSteadyMicros) {
        const qint64 ms = (m_clock->steadyMicros() - *m_outageSinceSteadyMicros) / 1000;
        m_outageSinceSteadyMicros.reset();
        const qint64 seconds = (ms + 500) / 1000;
        const QString length =
            seconds < 60 ? QStringLiteral("%1 s").arg(seconds)
                         : QStringLiteral("%1 min %2 s").arg(seconds / 60).arg(seconds % 60, 2, 10, QLatin1Char('0'));
        emit restored(
            QStringLiteral("broker %1: %2 %3")
                .arg(m_settings.hostAndPort(),
                     everConnected ? QStringLiteral("back after") : QStringLiteral("reached after trying for"), length),
            ms);
    }
    sendSubscriptions();
    emit connected();
}

void MqttClient::markOutage()
{
    if (!m_outageSinceSteadyMicros)
        m_outageSinceSteadyMicros = m_clock->steadyMicros();
}

void MqttClient::onPublished(int messageId, int reasonCode)
{
    const QString topic = m_unanswered.take(messageId);
    // MQTT 5: 0 accepted, 16 accepted with no subscriber; 128 and above refused.
    if (reasonCode >= 128 && !m_refusalsSaid.contains(topic)) {
        m_refusalsSaid.insert(topic, true);
        emit refusedByBroker(
            QStringLiteral("broker %1 refused a message on %2: %3")
                .arg(m_settings.hostAndPort(), topic, forPeople(mosquitto_reason_string(reasonCode)).toLower()));
    }
    emit published(messageId);
}

void MqttClient::onSubscribed(int messageId, QList<int> granted)
{
    const QString pattern = m_unanswered.take(messageId);
    if (!granted.isEmpty() && granted.first() < 128)
        emit subscribed(pattern);
    for (const int code : granted)
        if (code >= 128 && !m_refusalsSaid.contains(pattern)) {
            m_refusalsSaid.insert(pattern, true);
            emit refusedByBroker(
                QStringLiteral("broker %1 refused the subscription to %2: %3")
                    .arg(m_settings.hostAndPort(), pattern, forPeople(mosquitto_reason_string(code)).toLower()));
        }
}

void MqttClient::onDisconnect(const QString& reason, bool expected, bool restart)
{
    if (m_stopping || expected)
        return;
    markOutage();
    // A refused connection was reported with its broker's reason already.
    reportError(reason);
    if (m_connected) {
        m_connected = false;
        emit disconnected(reason);
    }
    if (restart) {
        ++m_restarts;
        connectInThread(true, std::nullopt, delayBefore(m_restarts));
    }
}

void MqttClient::reportError(const QString& reason)
{
    if (const std::optional<QString> text = firstFailure(reason))
        emit errorOccurred(*text);
}

void MqttClient::sendSubscriptions()
{
    for (const Subscription& s : std::as_const(m_subscriptions)) {
        const QByteArray p = s.pattern.toUtf8();
        int id = 0;
        if (mosquitto_subscribe_v5(m_core->mosq, &id, p.constData(), s.qos, 0, nullptr) == MOSQ_ERR_SUCCESS)
            m_unanswered.insert(id, s.pattern);
    }
}
