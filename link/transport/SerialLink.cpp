#include "link/transport/SerialLink.h"

SerialLink::SerialLink(const QString& portName, qint32 baudRate, QObject* parent, std::shared_ptr<Clock> clock)
    : Link(parent),
      m_portName(portName),
      m_baudRate(baudRate),
      m_port(this),
      m_clock(clock ? std::move(clock) : std::make_shared<SystemClock>()),
      m_reopenTimer(m_clock->createTimer(this))
{
    connect(m_reopenTimer, &ClockTimer::timeout, this, &SerialLink::retryOpen);
    connect(&m_port, &QSerialPort::readyRead, this, [this] { emit bytesReceived(m_port.readAll()); });
    connect(&m_port, &QSerialPort::errorOccurred, this, &SerialLink::handleError);
}

SerialLink::SerialLink(const QString& portName, qint32 baudRate, FlowControl flowControl, QObject* parent,
                       std::shared_ptr<Clock> clock)
    : SerialLink(portName, baudRate, parent, std::move(clock))
{
    m_flowControl = flowControl;
}

SerialLink::~SerialLink()
{
    // Quietly: nobody should hear from a link being destroyed.
    m_wanted = false;
    m_reopenTimer->stop();
    m_port.close();
}

QList<QSerialPortInfo> SerialLink::availablePorts()
{
    return QSerialPortInfo::availablePorts();
}

void SerialLink::setReopenInterval(std::chrono::milliseconds interval)
{
    m_reopenInterval = interval;
}

std::chrono::milliseconds SerialLink::reopenInterval() const
{
    return m_reopenInterval;
}

QString SerialLink::description() const
{
    return QStringLiteral("%1 %2 8N1%3")
        .arg(m_portName)
        .arg(m_baudRate)
        .arg(m_flowControl == FlowControl::RtsCts ? QStringLiteral(" RTS/CTS") : QString());
}

void SerialLink::open()
{
    m_wanted = true;
    if (m_port.isOpen() || m_reopenTimer->isActive())
        return;
    if (!tryOpen()) {
        reportFailure(QStringLiteral("%1: cannot open: %2; retrying").arg(m_portName, m_port.errorString()));
        m_reopenTimer->start(m_reopenInterval);
    }
}

void SerialLink::close()
{
    m_wanted = false;
    m_losing = false;
    m_reopenTimer->stop();
    if (!m_port.isOpen())
        return;
    m_port.close();
    emit closed();
}

bool SerialLink::write(const QByteArray& bytes)
{
    if (!m_port.isOpen())
        return false;
    // QSerialPort buffers and writes from its notifier as soon as the event
    // loop runs again; flush() would do it now but ends in tcdrain(), which
    // blocks for the whole frame's airtime at 9,600 bit/s.
    return m_port.write(bytes) == bytes.size();
}

bool SerialLink::tryOpen()
{
    m_port.setPortName(m_portName);
    // Stored now, applied by open(). A pseudo-terminal accepts or ignores
    // them; the speed means nothing there, and nothing here depends on it.
    m_port.setBaudRate(m_baudRate);
    m_port.setDataBits(QSerialPort::Data8);
    m_port.setParity(QSerialPort::NoParity);
    m_port.setStopBits(QSerialPort::OneStop);
    m_port.setFlowControl(m_flowControl == FlowControl::RtsCts ? QSerialPort::HardwareControl
                                                               : QSerialPort::NoFlowControl);
    if (!m_port.open(QIODevice::ReadWrite))
        return false;
    m_port.clearError();
    m_failureReported = false;
    m_lastError.clear();
    m_reopenTimer->stop();
    emit opened();
    return true;
}

std::optional<bool> SerialLink::carrierDetect()
{
    if (!m_port.isOpen())
        return std::nullopt;
    m_askingPins = true;
    const QSerialPort::PinoutSignals pins = m_port.pinoutSignals();
    m_askingPins = false;
    if (m_port.error() != QSerialPort::NoError) {
        // A pseudo-terminal has no pins: the ioctl fails, which is no fault of the port.
        m_port.clearError();
        return std::nullopt;
    }
    return pins.testFlag(QSerialPort::DataCarrierDetectSignal);
}

void SerialLink::setDataTerminalReady(bool ready)
{
    if (!m_port.isOpen())
        return;
    m_askingPins = true;
    if (!m_port.setDataTerminalReady(ready))
        m_port.clearError();  // no such pin (a pseudo-terminal)
    m_askingPins = false;
}

void SerialLink::discardOutput()
{
    if (m_port.isOpen())
        m_port.clear(QSerialPort::Output);
}

bool SerialLink::waitForBytesWritten(std::chrono::milliseconds timeout)
{
    return m_port.isOpen() && (m_port.bytesToWrite() == 0 || m_port.waitForBytesWritten(int(timeout.count())));
}

bool SerialLink::waitForBytesReceived(std::chrono::milliseconds timeout)
{
    return m_port.isOpen() && m_port.waitForReadyRead(int(timeout.count()));
}

void SerialLink::retryOpen()
{
    if (!m_wanted || m_port.isOpen()) {
        m_reopenTimer->stop();
        return;
    }
    ++m_reopenAttempts;
    if (!tryOpen())  // failures were reported when the port was lost
        m_reopenTimer->start(m_reopenInterval);
}

void SerialLink::handleError(QSerialPort::SerialPortError error)
{
    // Errors while closed belong to an open attempt, which reports them itself.
    if (error == QSerialPort::NoError || error == QSerialPort::TimeoutError || !m_port.isOpen() || m_losing ||
        m_askingPins)
        return;
    switch (error) {
        case QSerialPort::ResourceError:  // the device went away
        case QSerialPort::ReadError:      // read() returned end of file: hung up (a pty's master closed)
            // Closed from the event loop, not here: this runs inside the
            // port's own notifier, which close() deletes.
            m_losing = true;
            QMetaObject::invokeMethod(
                this, [this, reason = m_port.errorString()] { lose(reason); }, Qt::QueuedConnection);
            break;
        default: {
            const QString message = QStringLiteral("%1: %2").arg(m_portName, m_port.errorString());
            m_port.clearError();
            if (message != m_lastError) {
                m_lastError = message;
                emit errorOccurred(message);
            }
            break;
        }
    }
}

void SerialLink::lose(const QString& reason)
{
    m_losing = false;
    if (!m_port.isOpen())
        return;  // closed meanwhile, by close()
    m_port.close();
    reportFailure(QStringLiteral("%1: port lost: %2; reopening every %3 ms")
                      .arg(m_portName, reason)
                      .arg(m_reopenInterval.count()));
    emit closed();
    if (m_wanted)
        m_reopenTimer->start(m_reopenInterval);
}

void SerialLink::reportFailure(const QString& message)
{
    if (m_failureReported)
        return;
    m_failureReported = true;
    emit errorOccurred(message);
}
