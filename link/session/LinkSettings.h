#pragma once

// What the operator chose for the link: a serial port, or UDP endpoints, and
// the aircraft's key file for a secure link. A value type: kept in QSettings
// between sessions (the key file's path, never the key), shown and edited by
// LinkSettingsWidget, turned into a transport by createLink().

#include "link/transport/Link.h"

#include <QString>

#include <memory>
#include <optional>

class QSettings;

struct LinkSettings {
    enum class Transport { Serial, Udp };

    static constexpr quint16 kDefaultRemotePort = 5600;

    Transport transport = Transport::Udp;
    QString serialPort;  // "ttyUSB0" or a path such as /dev/pts/3
    qint32 baudRate = 9600;
    QString localAddress = QStringLiteral("0.0.0.0");
    quint16 localPort = 0;  // 0: any free port
    QString remoteAddress = QStringLiteral("127.0.0.1");
    quint16 remotePort = kDefaultRemotePort;
    // The aircraft's key file (docs/security.md); empty: the plain link.
    QString keyPath;

    // The transport, not yet open (it opens in the link thread). Nothing,
    // with the reason, when the settings are incomplete.
    std::unique_ptr<Link> createLink(QString* error = nullptr) const;
    // "UDP 127.0.0.1:5600", "serial ttyUSB0 at 9600 bit/s"; ", encrypted" with a key file
    QString summary() const;

    // "HOST:PORT", as --udp-remote takes it.
    static std::optional<LinkSettings> udpRemote(const QString& hostAndPort, QString* error = nullptr);
    // A serial port at a bit rate, as --serial and --baud take them.
    static std::optional<LinkSettings> serial(const QString& port, const QString& baudRate, QString* error = nullptr);

    void save(QSettings& settings) const;
    static LinkSettings load(const QSettings& settings);

    friend bool operator==(const LinkSettings&, const LinkSettings&) = default;
};
