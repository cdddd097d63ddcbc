#pragma once

// Where a console's session goes on an MQTT broker, and as whom: the broker's
// address, the aircraft to observe, the credentials and TLS files. A value
// type, made from the operator's URL (fromUrl) and the password file the
// caller read; the password is never part of any text this type produces.

#include <QString>

#include <memory>
#include <optional>

class BrokerTrust;
namespace rcm::secure {
class StationSigningKey;
}

struct BrokerSettings {
    static constexpr quint16 kDefaultPort = 1883;
    static constexpr quint16 kDefaultTlsPort = 8883;

    QString host;
    quint16 port = kDefaultPort;
    // The aircraft to observe, as its ID_UA_source in text form ("GB_133");
    // empty: none named (a publisher learns it from the first status).
    QString aircraft;
    // Empty user: no credentials. The password comes from a file the caller
    // reads; it is never printed, nor written to settings.
    QString user;
    QString password;
    // TLS (mqtts://): the CA that signed the broker's certificate, and
    // optionally this client's own certificate and key. No CA file: the
    // system's CA certificates (kSystemCaPath) are trusted.
    static inline const QString kSystemCaPath = QStringLiteral("/etc/ssl/certs");
    bool tls = false;
    QString caFile;
    QString certFile;
    QString keyFile;
    // Empty: the library makes up one for each connection.
    QString clientId;
    // The broker keeps our subscriptions and queues what comes for them
    // while we are away, for sessionExpirySeconds (MQTT 5, clean start
    // off): an observer misses nothing over a short outage. Needs a
    // clientId that stays the same across reconnections.
    bool persistentSession = false;
    int sessionExpirySeconds = 600;
    // The largest MQTT packet we take (BrokerTopics::kMaxPacketBytes); 0: any.
    int maxPacketBytes = 64 * 1024;
    // How long the broker waits without a word from us before it calls us
    // gone and sends our will (at 1.5 times this), and we ping it.
    int keepAliveSeconds = 10;

    // Whom this console believes and which sealed sessions it can read
    // (null: nobody, none), and the key this station signs with (null:
    // it publishes unsigned). docs/security.md, "The broker".
    std::shared_ptr<const BrokerTrust> trust;
    std::shared_ptr<const rcm::secure::StationSigningKey> signingKey;

    // "mqtt://HOST[:PORT][/AIRCRAFT]" or "mqtts://..." (TLS, default port
    // 8883); a user may stand before the host ("mqtt://ops@HOST"), a password
    // may not. Nothing, with an error naming what is wrong
    // ("mqtt://host:99999: port must be 1..65535"), for anything else.
    static std::optional<BrokerSettings> fromUrl(const QString& url, QString* error = nullptr);
    // "mqtt://127.0.0.1:1883/GB_133", the user but never the password.
    QString url() const;
    // "127.0.0.1:1883", as errors name the broker.
    QString hostAndPort() const;

    // The first line of a password file, which must be readable by its
    // owner only (as a key file): nothing, with the reason and the fix, else.
    static std::optional<QString> readPasswordFile(const QString& path, QString* error);

    friend bool operator==(const BrokerSettings&, const BrokerSettings&) = default;
};
