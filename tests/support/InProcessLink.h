// Two ends of a link inside one process, for the fixtures: what one end
// writes the other receives at once, within the write(), as one datagram
// (UDP-like) or as a stream piece (serial-like). No socket, no event loop,
// nothing in flight: with a VirtualClock a whole session is deterministic.
#pragma once

#include "link/transport/Link.h"

#include <QPointer>

#include <memory>
#include <utility>

namespace rcm::test {

class InProcessLink : public Link {
public:
    enum class Kind { Datagrams, Stream };

    // A connected pair; each end is owned by whoever takes it (a LinkWorker).
    static std::pair<std::unique_ptr<InProcessLink>, std::unique_ptr<InProcessLink>> pair(Kind kind)
    {
        auto a = std::unique_ptr<InProcessLink>(new InProcessLink(kind));
        auto b = std::unique_ptr<InProcessLink>(new InProcessLink(kind));
        a->m_peer = b.get();
        b->m_peer = a.get();
        return {std::move(a), std::move(b)};
    }

    FrameTransport transport() const override
    {
        return m_kind == Kind::Stream ? FrameTransport::Serial : FrameTransport::Udp;
    }
    bool isStream() const override { return m_kind == Kind::Stream; }
    bool isOpen() const override { return m_open; }
    QString description() const override { return QStringLiteral("in-process"); }

    void open() override
    {
        if (m_open)
            return;
        m_open = true;
        emit opened();
    }
    void close() override
    {
        if (!m_open)
            return;
        m_open = false;
        emit closed();
    }
    // Lost, as on air, when the other end is not open.
    bool write(const QByteArray& bytes) override
    {
        if (!m_open)
            return false;
        if (m_peer && m_peer->m_open) {
            if (m_kind == Kind::Stream)
                emit m_peer->bytesReceived(bytes);
            else
                emit m_peer->datagramReceived(bytes);
        }
        return true;
    }

private:
    explicit InProcessLink(Kind kind) : m_kind(kind) {}

    Kind m_kind;
    QPointer<InProcessLink> m_peer;
    bool m_open = false;
};

}  // namespace rcm::test
