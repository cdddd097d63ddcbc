#pragma once

// What the operator chose for the link: a serial port, or UDP endpoints, and
// the aircraft's key file for a secure link. A value type: kept in QSettings
// between sessions (the key file's path, never the key), shown and edited by
// LinkSettingsWidget, turned into a transport by createLink().

#include "link/clock/Clock.h"
#include "link/transport/Link.h"

#include <QString>

#include <chrono>
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
    // A satellite phone's modem on the serial port (ModemLink, docs/modem.md):
    // the number to dial; empty: the line is connected already (a cable, a
    // radio modem). The init string goes first; RTS/CTS flow control is on
    // for a modem unless the operator turns it off.
    QString dialNumber;
    QString modemInit = QStringLiteral("ATE0V1&C1&D2");
    // The phone (modem::Profile's name): its set-up after the init string,
    // and how it tells its registration and signal.
    QString modemProfile = QStringLiteral("generic");
    bool rtsCts = true;
    // The call's price per started minute, shown when the call ends; 0: not shown.
    double callCostPerMinute = 0;
    // The price's currency, "USD"; by default the system locale's.
    QString callCurrency = defaultCurrency();
    static QString defaultCurrency();
    // The profile of that name (any case); false, the reason in *error, for none.
    bool setModemProfile(const QString& name, QString* error = nullptr);
    // The satellite's one-way delay: the console waits twice this before it
    // calls a reported value that disagrees with the command a mismatch.
    int satelliteDelayMs = 1500;

    // The transport, not yet open (it opens in the link thread), its timers
    // (a serial port's reopening, a modem's) on `clock`, the session's (null:
    // the SystemClock). Nothing, with the reason, when the settings are incomplete.
    std::unique_ptr<Link> createLink(QString* error = nullptr, std::shared_ptr<Clock> clock = nullptr) const;
    // "UDP 127.0.0.1:5600", "serial ttyUSB0 at 9600 bit/s"; ", encrypted" with a key file
    QString summary() const;

    // "HOST:PORT", as --udp-remote takes it.
    static std::optional<LinkSettings> udpRemote(const QString& hostAndPort, QString* error = nullptr);
    // A modem to dial: a serial port with a number.
    bool dialsModem() const { return transport == Transport::Serial && !dialNumber.trimmed().isEmpty(); }
    // From a frame's first byte sent to its last received: for a dialled
    // modem the satellite's delay and a frame's 600 bytes at 1,200 a second;
    // else none worth counting.
    std::chrono::milliseconds oneWayDelay() const
    {
        return std::chrono::milliseconds(dialsModem() ? satelliteDelayMs + kFrameAirtimeMs : 0);
    }
    static constexpr int kFrameAirtimeMs = 500;
    // A serial port at a bit rate, as --serial and --baud take them.
    static std::optional<LinkSettings> serial(const QString& port, const QString& baudRate, QString* error = nullptr);

    void save(QSettings& settings) const;
    static LinkSettings load(const QSettings& settings);

    friend bool operator==(const LinkSettings&, const LinkSettings&) = default;
};
