#pragma once

// The radio path of a rehearsal at speed 1 with the real programs: two UDP
// sockets on the loopback interface, one the console's link sends to, one
// that sends to uasim, and between them a RehearsalChannel with the
// scenario's faults. What the console sends reaches uasim damaged as the
// channel damages it, and uasim's answers come back the same way.

#include "link/rehearsal/RehearsalChannel.h"

#include <QObject>
#include <QString>

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

private:
    // What `side` receives goes into the channel at `channelEnd`.
    bool openSide(UdpLink& side, Link& channelEnd, QString* error);

    std::unique_ptr<UdpLink> m_consoleSide;   // faces the console's link
    std::unique_ptr<UdpLink> m_aircraftSide;  // faces uasim
    std::unique_ptr<Link> m_consoleEnd;       // the channel's ends
    std::unique_ptr<Link> m_aircraftEnd;
    QString m_lastError;  // of either socket
};
