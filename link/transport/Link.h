#pragma once

// A transport that only moves bytes. Parsing, counting, logging and the send
// cadence belong to LinkWorker; a Link knows nothing of frames, so a new
// transport is only this class to implement.

#include "link/framelog/FrameFacts.h"

#include <QByteArray>
#include <QObject>
#include <QString>

class Link : public QObject {
    Q_OBJECT

public:
    explicit Link(QObject* parent = nullptr);
    ~Link() override;

    virtual FrameTransport transport() const = 0;
    // A stream delivers bytesReceived() in whatever pieces the transport
    // chose, so frames must be found again by a synchroniser; a datagram
    // transport delivers datagramReceived(), one frame per datagram.
    virtual bool isStream() const = 0;
    virtual bool isOpen() const = 0;
    // For people: "/dev/ttyUSB0 9600 8N1", "udp 0.0.0.0:5000 -> 10.0.0.2:5001".
    virtual QString description() const = 0;
    // Bytes write() took that the device has not taken yet: what a modem's
    // flow control (CTS) holds back. 0 for a transport that never queues.
    virtual qint64 bytesToWrite() const { return 0; }
    // The transport is bringing its line up (a modem dialling, redialling or
    // waiting for a call): silence now is not the far end's.
    virtual bool isConnecting() const { return false; }
    // The transport knows where to send: false for a UDP link that replies
    // to its sender and has heard none yet (what it would send is lost).
    virtual bool canSend() const { return isOpen(); }

public slots:
    // Both are idempotent. open() reports failure through errorOccurred().
    virtual void open() = 0;
    virtual void close() = 0;
    // True when the transport took the bytes; false when closed or with no
    // one to send to. Never blocks.
    virtual bool write(const QByteArray& bytes) = 0;

signals:
    // opened() again after a transport that reopens by itself came back.
    void opened();
    // On close() and when the transport failed or disappeared.
    void closed();
    void bytesReceived(const QByteArray& bytes);
    void datagramReceived(const QByteArray& datagram);
    // Once per failure, not once per retry or per frame.
    void errorOccurred(const QString& message);
    // For people: what the transport itself is doing, when it has more to
    // say than opened and closed (a modem dialling, connected, redialling).
    void statusChanged(const QString& status);
    // A satellite phone's network service, as it last said it: signal bars
    // 0..5 (-1 not known), registered or not, and both in words
    // ("registered, signal 3 of 5"). Only modems say it.
    void serviceChanged(int signalBars, bool registered, const QString& text);
};
