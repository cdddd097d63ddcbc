#pragma once

// The radio modem's serial port: 600-byte frames at 9,600 bit/s 8N1 by
// default, with RTS/CTS flow control when the modem asks for it (a modem
// whose buffer fills drops CTS; the bytes then wait here, in bytesToWrite(),
// instead of being lost in the modem). A port that fails or disappears (USB modem unplugged, pty master
// closed) is closed at once, reported once, and reopened by a timer until it
// is back, so a modem that comes back needs no action from the operator.

#include "link/clock/Clock.h"
#include "link/transport/Link.h"

#include <QList>
#include <QSerialPort>
#include <QSerialPortInfo>

#include <atomic>
#include <chrono>
#include <memory>
#include <optional>

class SerialLink : public Link {
    Q_OBJECT

public:
    static constexpr qint32 kDefaultBaudRate = 9600;
    static constexpr std::chrono::milliseconds kDefaultReopenInterval{1000};

    // portName: as QSerialPortInfo lists it ("ttyUSB0") or a path, which may
    // be a pseudo-terminal ("/dev/pts/3") or a symlink to the device.
    enum class FlowControl { None, RtsCts };

    // The reopen timer runs on `clock`, the session's (null: the SystemClock).
    explicit SerialLink(const QString& portName, qint32 baudRate = kDefaultBaudRate, QObject* parent = nullptr,
                        std::shared_ptr<Clock> clock = nullptr);
    SerialLink(const QString& portName, qint32 baudRate, FlowControl flowControl, QObject* parent = nullptr,
               std::shared_ptr<Clock> clock = nullptr);
    ~SerialLink() override;

    // The ports the system knows, for the operator to choose from.
    static QList<QSerialPortInfo> availablePorts();

    QString portName() const { return m_portName; }
    qint32 baudRate() const { return m_baudRate; }
    FlowControl flowControl() const { return m_flowControl; }
    // Set before open().
    void setReopenInterval(std::chrono::milliseconds interval);
    std::chrono::milliseconds reopenInterval() const;
    // Reopen attempts since the link was created. Any thread: for status views and tests.
    int reopenAttempts() const { return m_reopenAttempts.load(); }

    FrameTransport transport() const override { return FrameTransport::Serial; }
    bool isStream() const override { return true; }
    bool isOpen() const override { return m_port.isOpen(); }
    QString description() const override;
    qint64 bytesToWrite() const override { return m_port.bytesToWrite(); }

    // For a modem's control (ModemLink), in the link's thread. The data
    // carrier detect pin; nothing when the port cannot tell (a pseudo-terminal).
    std::optional<bool> carrierDetect();
    void setDataTerminalReady(bool ready);
    // Drops what write() queued and the device has not taken.
    void discardOutput();
    // Block the link's thread, at most `timeout`, until the device took
    // what is queued, or until bytes arrived (bytesReceived() is said
    // before it returns). For a modem's hang-up, which must run to its end
    // even while the thread is ending; nothing else waits.
    bool waitForBytesWritten(std::chrono::milliseconds timeout);
    bool waitForBytesReceived(std::chrono::milliseconds timeout);

public slots:
    // Failing to open is reported once and retried like a lost port: the
    // modem may be plugged in after the operator chose it.
    void open() override;
    void close() override;
    bool write(const QByteArray& bytes) override;

private:
    bool tryOpen();
    void retryOpen();
    void handleError(QSerialPort::SerialPortError error);
    void lose(const QString& reason);
    void reportFailure(const QString& message);

    QString m_portName;
    qint32 m_baudRate;
    FlowControl m_flowControl = FlowControl::None;
    QSerialPort m_port;
    std::shared_ptr<Clock> m_clock;
    ClockTimer* m_reopenTimer;
    std::chrono::milliseconds m_reopenInterval = kDefaultReopenInterval;
    bool m_wanted = false;           // open() asked for, close() not since
    bool m_askingPins = false;       // a pin asked for or set: a port without pins is no error
    bool m_losing = false;           // the port failed; lose() is queued to close it
    bool m_failureReported = false;  // this outage was reported; cleared when the port opens
    QString m_lastError;             // an error the open port reported, so a flood of them shows once
    std::atomic<int> m_reopenAttempts{0};
};
