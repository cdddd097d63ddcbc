#pragma once

// A link that wraps another: voice beside the commands, rehearsal faults.
// The inner link is moved in and made a child; what it says (opened, closed,
// errors, bytes, datagrams) is said again by the wrapper, through the hooks
// below, so a wrapper overrides only what it changes.

#include "link/transport/Link.h"

#include <memory>

class LinkWrapper : public Link {
    Q_OBJECT

public:
    ~LinkWrapper() override;

    FrameTransport transport() const override { return m_inner->transport(); }
    bool isStream() const override { return m_inner->isStream(); }
    bool isOpen() const override { return m_inner->isOpen(); }
    QString description() const override { return m_inner->description(); }
    qint64 bytesToWrite() const override { return m_inner->bytesToWrite(); }
    bool isConnecting() const override { return m_inner->isConnecting(); }
    bool canSend() const override { return m_inner->canSend(); }

    Link* inner() const { return m_inner; }

public slots:
    void open() override { m_inner->open(); }
    void close() override { m_inner->close(); }
    bool write(const QByteArray& bytes) override { return m_inner->write(bytes); }

protected:
    explicit LinkWrapper(std::unique_ptr<Link> inner, QObject* parent = nullptr);

    // Each runs when the inner link said so; the defaults say it again.
    // innerOpened() and innerClosed() run before opened() and closed().
    virtual void innerOpened() {}
    virtual void innerClosed() {}
    // False for a wrapper that decides itself when it is open (a modem: the
    // port is open long before the call is up); it then says opened() and
    // closed() itself.
    virtual bool relaysOpenAndClose() const { return true; }
    virtual void innerBytesReceived(const QByteArray& bytes) { emit bytesReceived(bytes); }
    virtual void innerDatagramReceived(const QByteArray& datagram) { emit datagramReceived(datagram); }

private:
    Link* m_inner;  // a child
};
