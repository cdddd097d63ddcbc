#pragma once

// Where a console's session goes on an MQTT broker, and as whom: the broker's
// address, the aircraft to observe, the credentials and TLS files. A value
// type, made from the operator's URL (fromUrl) and the password file the
// caller read; the password is never part of any text this type produces.

#include <QString>

#include <optional>

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
    // optionally this client's own certificate and key.
    bool tls = false;
    QString caFile;
    QString certFile;
    QString keyFile;
    // Empty: the library makes up one for each connection.
    QString clientId;
    // How long the broker waits without a word from us before it calls us
    // gone and sends our will (at 1.5 times this), and we ping it.
    int keepAliveSeconds = 10;

    // "mqtt://HOST[:PORT][/AIRCRAFT]" or "mqtts://..." (TLS, default port
    // 8883); a user may stand before the host ("mqtt://ops@HOST"), a password
    // may not. Nothing, with an error naming what is wrong
    // ("mqtt://host:99999: port must be 1..65535"), for anything else.
    static std::optional<BrokerSettings> fromUrl(const QString& url, QString* error = nullptr);
    // "mqtt://127.0.0.1:1883/GB_133", the user but never the password.
    QString url() const;
    // "127.0.0.1:1883", as errors name the broker.
    QString hostAndPort() const;

    friend bool operator==(const BrokerSettings&, const BrokerSettings&) = default;
};
