#pragma once

// The radio path of a rehearsal at speed 1 with the real programs: two UDP
// sockets on the loopback interface (one the console's link sends to, one
// that sends to uasim), or two pseudo-terminal pairs (the console opens one
// pair's device, uasim the other's), and between them a RehearsalChannel
// with the scenario's faults. What the console sends reaches uasim damaged
// as the channel damages it, and uasim's answers come back the same way.
// On the serial line the bytes are cut into 600-byte frames before the
// channel sees them, as the senders write them back to back, so that a
// fault's "per frame" means a frame.

#include "link/rehearsal/RehearsalChannel.h"
#include "link/satmodem/PseudoTerminal.h"

#include <QObject>
#include <QSocketNotifier>
#include <QString>

#include <array>
#include <memory>

class UdpLink;

class RehearsalProxy : public QObject {
    Q_OBJECT

public:
    // `channel` must outlive the proxy.
    explicit RehearsalProxy(RehearsalChannel& channel, QObject* parent = nullptr);
    ~RehearsalProxy() override;

    // Binds the console's side on 127.0.0.1; false, with the reason, when it cannot.
    bool open(QString* error);
    quint16 consolePort() const;
    // uasim listens on 127.0.0.1:port: the aircraft's side sends there.
    bool connectAircraft(quint16 port, QString* error);

    // The serial line instead: two pseudo-terminal pairs, raw from the start.
    bool openSerial(QString* error);
    QString consoleDevice() const { return m_ptys[0].device; }
    QString aircraftDevice() const { return m_ptys[1].device; }

private:
    // Its slave held, so the master never reads "no one there" before a program opens it.
    struct Pty : PseudoTerminal {
        QByteArray pending;  // bytes read, short of a whole frame
        std::unique_ptr<QSocketNotifier> notifier;
    };
    void readPty(int side);
    static void writeAll(int fd, const QByteArray& bytes);

    // What `side` receives goes into the channel at `channelEnd`.
    bool openSide(UdpLink& side, Link& channelEnd, QString* error);

    std::unique_ptr<UdpLink> m_consoleSide;   // faces the console's link
    std::unique_ptr<UdpLink> m_aircraftSide;  // faces uasim
    std::unique_ptr<Link> m_consoleEnd;       // the channel's ends
    std::unique_ptr<Link> m_aircraftEnd;
    QString m_lastError;  // of either socket
    std::array<Pty, 2> m_ptys;  // 0: the console's, 1: uasim's
};
