#include "link/aircraft/FaultyLink.h"

#include "link/clock/Clock.h"

FaultyLink::FaultyLink(std::unique_ptr<Link> inner, const FaultSettings& settings, std::shared_ptr<Clock> clock,
                       QObject* parent)
    : LinkWrapper(std::move(inner), parent),
      m_faults(settings),
      m_clock(std::move(clock)),
      m_startMicros(m_clock->steadyMicros())
{
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
    ClockTimer* late = m_clock->createTimer(inner(), Qt::PreciseTimer);
    connect(late, &ClockTimer::timeout, inner(), [link = inner(), late, damaged] {
        link->write(damaged);
        late->deleteLater();
    });
    late->start(std::chrono::duration_cast<std::chrono::milliseconds>(outcome.delay));
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
    return std::chrono::duration_cast<std::chrono::milliseconds>(
        std::chrono::microseconds(m_clock->steadyMicros() - m_startMicros));
}
