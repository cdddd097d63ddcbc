#include "link/aircraft/FaultyLink.h"

#include <QTimer>

FaultyLink::FaultyLink(std::unique_ptr<Link> inner, const FaultSettings& settings, QObject* parent)
    : LinkWrapper(std::move(inner), parent), m_faults(settings)
{
    m_clock.start();
}

QString FaultyLink::description() const
{
    return inner()->description() + QStringLiteral(", rehearsal faults");
}

bool FaultyLink::write(const QByteArray& bytes)
{
    QByteArray damaged = bytes;
    const auto outcome = m_faults.outgoing(
        {reinterpret_cast<std::uint8_t*>(damaged.data()), static_cast<std::size_t>(damaged.size())}, elapsed());
    if (!outcome.sent())
        return inner()->isOpen();
    if (outcome.delay.count() == 0)
        return inner()->write(damaged);
    QTimer::singleShot(outcome.delay, inner(), [link = inner(), damaged] { link->write(damaged); });
    return inner()->isOpen();
}

void FaultyLink::innerBytesReceived(const QByteArray& bytes)
{
    if (m_faults.incoming(elapsed()))
        emit bytesReceived(bytes);
}

void FaultyLink::innerDatagramReceived(const QByteArray& datagram)
{
    if (m_faults.incoming(elapsed()))
        emit datagramReceived(datagram);
}

std::chrono::milliseconds FaultyLink::elapsed() const
{
    return std::chrono::milliseconds(m_clock.elapsed());
}
