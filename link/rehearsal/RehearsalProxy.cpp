#include "link/rehearsal/RehearsalProxy.h"

#include "link/transport/UdpLink.h"

RehearsalProxy::RehearsalProxy(RehearsalChannel& channel, QObject* parent)
    : QObject(parent),
      m_consoleEnd(channel.takeEnd(RehearsalChannel::Console)),
      m_aircraftEnd(channel.takeEnd(RehearsalChannel::Aircraft))
{
    // What one real side receives goes into the channel as its sender's;
    // what the channel delivers to an end goes out of the other real side.
    m_consoleEnd->open();
    m_aircraftEnd->open();
    connect(m_consoleEnd.get(), &Link::datagramReceived, this, [this](const QByteArray& bytes) {
        if (m_consoleSide)
            m_consoleSide->write(bytes);
    });
    connect(m_aircraftEnd.get(), &Link::datagramReceived, this, [this](const QByteArray& bytes) {
        if (m_aircraftSide)
            m_aircraftSide->write(bytes);
    });
}

RehearsalProxy::~RehearsalProxy() = default;

bool RehearsalProxy::open(QString* error)
{
    m_consoleSide = std::make_unique<UdpLink>(QHostAddress(QHostAddress::LocalHost), 0);
    m_consoleSide->setReplyToSender(true);  // back to the console's link, wherever it is bound
    return openSide(*m_consoleSide, *m_consoleEnd, error);
}

quint16 RehearsalProxy::consolePort() const
{
    return m_consoleSide ? m_consoleSide->boundPort() : 0;
}

bool RehearsalProxy::connectAircraft(quint16 port, QString* error)
{
    m_aircraftSide = std::make_unique<UdpLink>(QHostAddress(QHostAddress::LocalHost), 0,
                                               QHostAddress(QHostAddress::LocalHost), port);
    return openSide(*m_aircraftSide, *m_aircraftEnd, error);
}

bool RehearsalProxy::openSide(UdpLink& side, Link& channelEnd, QString* error)
{
    connect(&side, &Link::datagramReceived, this, [&channelEnd](const QByteArray& bytes) { channelEnd.write(bytes); });
    connect(&side, &Link::errorOccurred, this, [this](const QString& e) { m_lastError = e; });
    side.open();
    if (!side.isOpen() && error)
        *error = m_lastError;
    return side.isOpen();
}
