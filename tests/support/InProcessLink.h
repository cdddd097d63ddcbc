// Two ends of a link inside one process, for the fixtures: what one end
// writes the other receives at once, within the write(), as one datagram
// (UDP-like) or as a stream piece (serial-like). No socket, nothing in
// flight: with a VirtualClock a whole session is deterministic. An end may
// live in another thread (a ConsoleSession's link thread): the other end's
// signal then reaches it queued, and either end may be destroyed in its
// own thread while the other writes. One side can be plugged in again
// (replug()): a new console on the same aircraft's port.
#pragma once

#include "link/transport/Link.h"

#include <QMutex>
#include <QMutexLocker>
#include <QSemaphore>
#include <QThread>

#include <memory>
#include <utility>

namespace rcm::test {

class InProcessLink : public Link {
public:
    enum class Kind { Datagrams, Stream };

    // A connected pair; each end is owned by whoever takes it (a LinkWorker).
    static std::pair<std::unique_ptr<InProcessLink>, std::unique_ptr<InProcessLink>> pair(Kind kind)
    {
        auto shared = std::make_shared<Pair>();
        auto a = std::unique_ptr<InProcessLink>(new InProcessLink(kind, shared, 0));
        auto b = std::unique_ptr<InProcessLink>(new InProcessLink(kind, shared, 1));
        shared->ends[0] = a.get();
        shared->ends[1] = b.get();
        return {std::move(a), std::move(b)};
    }

    // A new end in place of the one `end` is joined to, which is cut off for
    // good: another sender on the aircraft's port, or a console restarted.
    static std::unique_ptr<InProcessLink> replug(InProcessLink& end)
    {
        const QMutexLocker lock(&end.m_pair->mutex);
        const int side = 1 - end.m_side;
        auto plugged = std::unique_ptr<InProcessLink>(new InProcessLink(end.m_kind, end.m_pair, side));
        end.m_pair->ends[side] = plugged.get();
        return plugged;
    }

    // Runs what was queued to the other end in its thread so far (the frames
    // this end wrote), when it lives in another thread; returns once it ran,
    // or at once when there is none. An end whose thread ends meanwhile
    // drops the queued call, which returns then too.
    void settleOtherEnd()
    {
        auto ran = std::make_shared<QSemaphore>();
        {
            const QMutexLocker lock(&m_pair->mutex);
            InProcessLink* peer = m_pair->ends[1 - m_side];
            if (!peer || peer->thread() == QThread::currentThread())
                return;
            // Released when the call has run or has been dropped unrun.
            auto released = std::shared_ptr<void>(nullptr, [ran](void*) { ran->release(); });
            QMetaObject::invokeMethod(peer, [released] {}, Qt::QueuedConnection);
        }
        ran->acquire();
    }

    ~InProcessLink() override
    {
        const QMutexLocker lock(&m_pair->mutex);
        if (m_pair->ends[m_side] == this)
            m_pair->ends[m_side] = nullptr;
    }

    FrameTransport transport() const override
    {
        return m_kind == Kind::Stream ? FrameTransport::Serial : FrameTransport::Udp;
    }
    bool isStream() const override { return m_kind == Kind::Stream; }
    bool isOpen() const override
    {
        const QMutexLocker lock(&m_pair->mutex);
        return m_open;
    }
    QString description() const override { return QStringLiteral("in-process"); }

    void open() override
    {
        {
            const QMutexLocker lock(&m_pair->mutex);
            if (std::exchange(m_open, true))
                return;
        }
        emit opened();
    }
    void close() override
    {
        {
            const QMutexLocker lock(&m_pair->mutex);
            if (!std::exchange(m_open, false))
                return;
        }
        emit closed();
    }
    // Lost, as on air, when the other end is not open or the pair is cut.
    bool write(const QByteArray& bytes) override
    {
        const QMutexLocker lock(&m_pair->mutex);
        if (!m_open)
            return false;
        if (m_pair->ends[m_side] != this)
            return true;  // replugged: nobody hears it any more
        InProcessLink* peer = m_pair->ends[1 - m_side];
        if (peer && peer->m_open && m_pair->connected) {
            // Under the lock, so that the peer is not destroyed meanwhile;
            // recursive, for a peer in this thread that answers at once.
            if (m_kind == Kind::Stream)
                emit peer->bytesReceived(bytes);
            else
                emit peer->datagramReceived(bytes);
        }
        return true;
    }

    // Cut: both ends stay open and write, and nothing arrives (an outage,
    // an aircraft that stopped answering); joined again with true.
    void setConnected(bool connected)
    {
        const QMutexLocker lock(&m_pair->mutex);
        m_pair->connected = connected;
    }

private:
    struct Pair {
        QRecursiveMutex mutex;
        InProcessLink* ends[2] = {nullptr, nullptr};
        bool connected = true;
    };

    InProcessLink(Kind kind, std::shared_ptr<Pair> pair, int side) : m_kind(kind), m_pair(std::move(pair)), m_side(side)
    {
    }

    Kind m_kind;
    std::shared_ptr<Pair> m_pair;
    int m_side;
    bool m_open = false;  // under the pair's mutex
};

}  // namespace rcm::test
