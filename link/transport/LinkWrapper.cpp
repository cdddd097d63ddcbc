#include "link/transport/LinkWrapper.h"

LinkWrapper::LinkWrapper(std::unique_ptr<Link> inner, QObject* parent) : Link(parent), m_inner(inner.release())
{
    Q_ASSERT(m_inner);
    m_inner->setParent(this);
    connect(m_inner, &Link::opened, this, [this] {
        innerOpened();
        if (relaysOpenAndClose())
            emit opened();
    });
    connect(m_inner, &Link::closed, this, [this] {
        innerClosed();
        if (relaysOpenAndClose())
            emit closed();
    });
    connect(m_inner, &Link::errorOccurred, this, &Link::errorOccurred);
    connect(m_inner, &Link::statusChanged, this, &Link::statusChanged);
    connect(m_inner, &Link::serviceChanged, this, &Link::serviceChanged);
    connect(m_inner, &Link::bytesReceived, this, [this](const QByteArray& bytes) { innerBytesReceived(bytes); });
    connect(m_inner, &Link::datagramReceived, this,
            [this](const QByteArray& datagram) { innerDatagramReceived(datagram); });
}

// The inner link is deleted after this, as a child, and may say it closed:
// nobody may hear it, the wrapper's hooks are gone.
LinkWrapper::~LinkWrapper()
{
    disconnect(m_inner, nullptr, this, nullptr);
}
