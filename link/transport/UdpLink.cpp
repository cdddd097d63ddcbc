#include "link/transport/UdpLink.h"

#include <QNetworkDatagram>

UdpLink::UdpLink(const QHostAddress& localAddress, quint16 localPort, const QHostAddress& remoteAddress,
                 quint16 remotePort, QObject* parent)
    : Link(parent),
      m_localAddress(localAddress),
      m_localPort(localPort),
      m_remoteAddress(remoteAddress),
      m_remotePort(remotePort),
      m_socket(this)
{
    connect(&m_socket, &QUdpSocket::readyRead, this, &UdpLink::readPending);
    connect(&m_socket, &QUdpSocket::errorOccurred, this, [this] {
        if (!m_binding)
            reportOnce(QStringLiteral("udp: %1").arg(m_socket.errorString()));
    });
}

UdpLink::~UdpLink()
{
    m_socket.close();
}

static QString endpoint(const QHostAddress& address, quint16 port)
{
    if (address.isNull())
        return QStringLiteral("(none)");
    return address.protocol() == QAbstractSocket::IPv6Protocol
               ? QStringLiteral("[%1]:%2").arg(address.toString()).arg(port)
               : QStringLiteral("%1:%2").arg(address.toString()).arg(port);
}

QString UdpLink::description() const
{
    const quint16 local = boundPort() ? boundPort() : m_localPort;
    const QString remote = !m_replyToSender        ? endpoint(m_remoteAddress, m_remotePort)
                           : m_acceptedSendersOnly ? QStringLiteral("last accepted sender")
                                                   : QStringLiteral("last sender");
    return QStringLiteral("udp %1 -> %2").arg(endpoint(m_localAddress, local), remote);
}

void UdpLink::open()
{
    if (isOpen())
        return;
    m_binding = true;
    const bool bound = m_socket.bind(m_localAddress, m_localPort);
    m_binding = false;
    if (!bound) {
        reportOnce(QStringLiteral("udp: cannot bind %1: %2")
                       .arg(endpoint(m_localAddress, m_localPort), m_socket.errorString()));
        return;
    }
    m_boundPort = m_socket.localPort();
    m_lastError.clear();
    emit opened();
}

void UdpLink::close()
{
    if (!isOpen())
        return;
    m_socket.close();
    m_boundPort = 0;
    emit closed();
}

bool UdpLink::write(const QByteArray& bytes)
{
    if (!isOpen() || m_remoteAddress.isNull() || m_remotePort == 0)
        return false;
    if (m_socket.writeDatagram(bytes, m_remoteAddress, m_remotePort) != bytes.size())
        return false;  // errorOccurred() said why
    m_lastError.clear();
    return true;
}

void UdpLink::setRemote(const QHostAddress& address, quint16 port)
{
    m_remoteAddress = address;
    m_remotePort = port;
}

void UdpLink::acceptSender()
{
    if (!m_replyToSender || m_senderAddress.isNull() || m_senderPort == 0)
        return;
    m_remoteAddress = m_senderAddress;
    m_remotePort = m_senderPort;
}

void UdpLink::readPending()
{
    while (m_socket.hasPendingDatagrams()) {
        const QNetworkDatagram datagram = m_socket.receiveDatagram();
        if (!datagram.isValid())
            break;
        m_senderAddress = datagram.senderAddress();
        m_senderPort = quint16(datagram.senderPort());
        if (!m_replyToSender && !m_remoteAddress.isNull() && m_remotePort != 0 &&
            (m_senderPort != m_remotePort ||
             !m_senderAddress.isEqual(m_remoteAddress, QHostAddress::TolerantConversion))) {
            if (m_strangerDatagrams.fetch_add(1) == 0)
                emit errorOccurred(QStringLiteral("udp: datagrams from %1 dropped unread: only %2 is listened to "
                                                  "(every further one is counted, not reported)")
                                       .arg(endpoint(m_senderAddress, m_senderPort),
                                            endpoint(m_remoteAddress, m_remotePort)));
            m_senderAddress.clear();
            m_senderPort = 0;
            continue;
        }
        if (m_replyToSender && !m_acceptedSendersOnly)
            acceptSender();
        emit datagramReceived(datagram.data());
        m_senderAddress.clear();
        m_senderPort = 0;
    }
}

void UdpLink::reportOnce(const QString& message)
{
    if (message == m_lastError)
        return;
    m_lastError = message;
    emit errorOccurred(message);
}
