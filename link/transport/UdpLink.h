#pragma once

// One 510-byte datagram per message (the two codewords, no preamble: UDP
// already delimits frames). Binding to port 0 takes an ephemeral port, which
// boundPort() then tells. In reply-to-sender mode, used by the simulated
// aircraft, the sender of a datagram becomes the remote end; with a receiver
// that judges the datagrams (LinkWorker), only of one it accepted.
// Otherwise, with a remote end set (the console's aircraft), a datagram from
// any other address or port is dropped before anyone reads it: counted
// (strangerDatagrams()) and reported once, so that a flood from elsewhere
// costs a socket read, not a decode.

#include "link/transport/Link.h"

#include <QHostAddress>
#include <QUdpSocket>

#include <atomic>

class UdpLink : public Link {
    Q_OBJECT

public:
    // A null remote address (or port 0) sends nothing until setRemote() or,
    // in reply-to-sender mode, until a sender is followed (see below).
    UdpLink(const QHostAddress& localAddress, quint16 localPort, const QHostAddress& remoteAddress = {},
            quint16 remotePort = 0, QObject* parent = nullptr);
    ~UdpLink() override;

    // Set before open().
    void setReplyToSender(bool on) { m_replyToSender = on; }
    bool replyToSender() const { return m_replyToSender; }
    // Reply-to-sender with a judge: a datagram's sender becomes the remote
    // end only through acceptSender(), not on arrival, so that a datagram the
    // receiver refuses (forged, replayed, undecodable) cannot steer the
    // replies. LinkWorker sets it on the link it drives. Off, every sender is
    // followed: what a bare link standing in for an aircraft in a test wants.
    void setFollowAcceptedSendersOnly(bool on) { m_acceptedSendersOnly = on; }
    // In reply-to-sender mode, makes the sender of the datagram being
    // delivered the remote end. Not a slot: only from a slot directly
    // connected to datagramReceived() (the same thread), while it runs. The
    // sender is forgotten as soon as the signal returns, so a late call
    // adopts nothing rather than the wrong peer.
    void acceptSender();

    // Datagrams dropped for coming from other than the remote end. Any thread.
    quint64 strangerDatagrams() const { return m_strangerDatagrams.load(); }

    // The local port actually bound: the ephemeral one when 0 was asked for;
    // 0 while closed. Any thread.
    quint16 boundPort() const { return m_boundPort.load(); }

    FrameTransport transport() const override { return FrameTransport::Udp; }
    bool isStream() const override { return false; }
    bool isOpen() const override { return m_socket.state() == QAbstractSocket::BoundState; }
    bool canSend() const override { return isOpen() && !m_remoteAddress.isNull() && m_remotePort != 0; }
    QString description() const override;

public slots:
    void open() override;
    void close() override;
    bool write(const QByteArray& bytes) override;
    // From another thread only through a queued call.
    void setRemote(const QHostAddress& address, quint16 port);

private:
    void readPending();
    void reportOnce(const QString& message);

    QHostAddress m_localAddress;
    quint16 m_localPort;
    QHostAddress m_remoteAddress;
    quint16 m_remotePort;
    bool m_replyToSender = false;
    bool m_acceptedSendersOnly = false;
    QHostAddress m_senderAddress;  // of the datagram being delivered
    quint16 m_senderPort = 0;
    QUdpSocket m_socket;
    std::atomic<quint16> m_boundPort{0};
    std::atomic<quint64> m_strangerDatagrams{0};
    QString m_lastError;  // so a failure repeated every second shows once
    bool m_binding = false;  // open() reports a failed bind itself, with the address
};
