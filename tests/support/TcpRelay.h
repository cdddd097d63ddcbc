// A TCP relay between a client and the broker (or any server on loopback),
// whose cut() drops every connection at once without a word and takes no
// more: what the broker sees when a console crashes or its network goes.
#pragma once

#include <QHostAddress>
#include <QList>
#include <QObject>
#include <QTcpServer>
#include <QTcpSocket>

namespace rcm::test {

class TcpRelay : public QObject {
public:
    explicit TcpRelay(quint16 brokerPort) : m_brokerPort(brokerPort)
    {
        m_server.listen(QHostAddress::LocalHost, 0);
        connect(&m_server, &QTcpServer::newConnection, this, [this] {
            while (QTcpSocket* in = m_server.nextPendingConnection()) {
                auto* out = new QTcpSocket(this);
                in->setParent(this);
                m_sockets << in << out;
                connect(in, &QTcpSocket::readyRead, out, [this, in, out] {
                    const QByteArray bytes = in->readAll();
                    if (!m_dropToBroker)
                        out->write(bytes);
                });
                connect(out, &QTcpSocket::readyRead, in, [in, out] { in->write(out->readAll()); });
                connect(out, &QTcpSocket::connected, in, [in, out] { out->write(in->readAll()); });
                connect(in, &QTcpSocket::disconnected, out, &QTcpSocket::disconnectFromHost);
                connect(out, &QTcpSocket::disconnected, in, &QTcpSocket::disconnectFromHost);
                out->connectToHost(QHostAddress::LocalHost, m_brokerPort);
            }
        });
    }
    quint16 port() const { return m_server.isListening() ? m_server.serverPort() : m_port; }
    void cut()
    {
        m_port = m_server.serverPort();
        m_server.close();
        for (QTcpSocket* s : std::as_const(m_sockets))
            s->abort();
        m_sockets.clear();
    }
    // After cut(): listens again on the same port, passing everything.
    bool reopen()
    {
        m_dropToBroker = false;
        return m_server.listen(QHostAddress::LocalHost, m_port);
    }
    // What the client writes from now on is lost on the way: a network that
    // takes the bytes and delivers none.
    void dropToBroker() { m_dropToBroker = true; }

private:
    quint16 m_brokerPort;
    quint16 m_port = 0;
    QTcpServer m_server;
    QList<QTcpSocket*> m_sockets;
    bool m_dropToBroker = false;
};

}  // namespace rcm::test
