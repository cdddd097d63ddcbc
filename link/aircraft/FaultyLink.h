#pragma once

// A transport with rehearsal faults (FaultInjector) on what it sends and an
// outage on what it receives; otherwise the transport it wraps. The faults'
// time is counted from the wrapper's construction, on the session's clock.

#include "link/aircraft/FaultInjector.h"
#include "link/transport/LinkWrapper.h"

class Clock;


#include <chrono>
#include <cstdint>
#include <memory>

class FaultyLink : public LinkWrapper {
    Q_OBJECT

public:
    FaultyLink(std::unique_ptr<Link> inner, const FaultSettings& settings, std::shared_ptr<Clock> clock,
               QObject* parent = nullptr);

    QString description() const override;
    const FaultInjector& faults() const { return m_faults; }

public slots:
    // A frame the faults swallow still counts as sent, as it would for an
    // aircraft whose radio path failed: the console sees the ID_msg gap.
    bool write(const QByteArray& bytes) override;

private:
    void innerBytesReceived(const QByteArray& bytes) override;
    void innerDatagramReceived(const QByteArray& datagram) override;
    std::chrono::milliseconds elapsed() const;

    FaultInjector m_faults;
    std::shared_ptr<Clock> m_clock;
    std::int64_t m_startMicros;
};
