#include "link/rehearsal/RehearsalProxy.h"

#include "codec/frame/Frame.h"
#include "link/transport/UdpLink.h"

#include <cerrno>
#include <fcntl.h>
#include <poll.h>
#include <pty.h>
#include <termios.h>
#include <unistd.h>

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
    connect(m_consoleEnd.get(), &Link::bytesReceived, this, [this](const QByteArray& bytes) {
        if (m_ptys[0].master >= 0)
            writeAll(m_ptys[0].master, bytes);
    });
    connect(m_aircraftEnd.get(), &Link::bytesReceived, this, [this](const QByteArray& bytes) {
        if (m_ptys[1].master >= 0)
            writeAll(m_ptys[1].master, bytes);
    });
}

RehearsalProxy::~RehearsalProxy()
{
    for (Pty& p : m_ptys) {
        p.notifier.reset();
        if (p.master >= 0)
            ::close(p.master);
        if (p.slave >= 0)
            ::close(p.slave);
    }
}

bool RehearsalProxy::openSerial(QString* error)
{
    for (int side = 0; side < 2; ++side) {
        Pty& p = m_ptys[std::size_t(side)];
        if (!openRawPseudoTerminal(p, error))
            return false;
        p.notifier = std::make_unique<QSocketNotifier>(p.master, QSocketNotifier::Read);
        connect(p.notifier.get(), &QSocketNotifier::activated, this, [this, side] { readPty(side); });
    }
    return true;
}

void RehearsalProxy::readPty(int side)
{
    Pty& p = m_ptys[std::size_t(side)];
    char buffer[4096];
    for (ssize_t n; (n = ::read(p.master, buffer, sizeof buffer)) > 0;)
        p.pending.append(buffer, qsizetype(n));
    Link& end = side == 0 ? *m_consoleEnd : *m_aircraftEnd;
    while (p.pending.size() >= qsizetype(rcm::kFrameSize)) {
        end.write(p.pending.first(qsizetype(rcm::kFrameSize)));
        p.pending.remove(0, qsizetype(rcm::kFrameSize));
    }
}

// 600 bytes a second into a pty's buffer: it has room; a full one is waited on.
void RehearsalProxy::writeAll(int fd, const QByteArray& bytes)
{
    for (qsizetype done = 0; done < bytes.size();) {
        const ssize_t w = ::write(fd, bytes.constData() + done, std::size_t(bytes.size() - done));
        if (w > 0) {
            done += w;
        } else if (errno == EAGAIN) {
            pollfd out{fd, POLLOUT, 0};
            ::poll(&out, 1, 100);
        } else if (errno != EINTR) {
            return;
        }
    }
}

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
