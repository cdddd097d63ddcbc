#include "link/transport/ModemLink.h"

#include "link/transport/SerialLink.h"

#include <QDeadlineTimer>

#include <algorithm>

namespace {

using modem::ResultCode;

const QByteArray kNoCarrierInData = "\r\nNO CARRIER\r\n";

QString seconds(qint64 ms)
{
    return QString::number((ms + 500) / 1000);
}

// "14 s", "12 min 3 s", "2 h 5 min"
QString duration(qint64 ms)
{
    const qint64 s = (ms + 500) / 1000;
    if (s < 60)
        return QStringLiteral("%1 s").arg(s);
    if (s < 3600)
        return QStringLiteral("%1 min %2 s").arg(s / 60).arg(s % 60);
    return QStringLiteral("%1 h %2 min").arg(s / 3600).arg(s % 3600 / 60);
}

}  // namespace

ModemLink::ModemLink(std::unique_ptr<SerialLink> serial, Options options, QObject* parent)
    : LinkWrapper(std::move(serial), parent), m_options(std::move(options)), m_timeout(this), m_redial(this),
      m_carrierPoll(this)
{
    m_timeout.setSingleShot(true);
    m_redial.setSingleShot(true);
    m_carrierPoll.setInterval(m_options.carrierPollInterval);
    connect(&m_timeout, &QTimer::timeout, this, &ModemLink::timedOut);
    connect(&m_redial, &QTimer::timeout, this, [this] {
        if (port().isOpen())
            dial();  // else the port's reopening initialises and dials
    });
    connect(&m_carrierPoll, &QTimer::timeout, this, &ModemLink::pollCarrier);
}

ModemLink::~ModemLink()
{
    // Quit or a link replaced without close(): the call must not outlive the console.
    m_wanted = false;
    if (m_state == CallState::Connected)
        hangUp();
}

SerialLink& ModemLink::port() const
{
    return *static_cast<SerialLink*>(inner());
}

bool ModemLink::isOpen() const
{
    return m_state == CallState::Connected;
}

bool ModemLink::isConnecting() const
{
    return m_state != CallState::Closed && m_state != CallState::Connected && m_state != CallState::GaveUp;
}

QString ModemLink::description() const
{
    const QString role = m_options.number.isEmpty() ? QStringLiteral("answering calls")
                                                    : QStringLiteral("dialling %1").arg(m_options.number);
    return QStringLiteral("%1, modem %2").arg(inner()->description(), role);
}

ModemLink::Milliseconds ModemLink::hangUpBound() const
{
    return 2 * m_options.guardTime + 2 * m_options.hangUpTimeout;
}

void ModemLink::open()
{
    if (m_wanted)
        return;
    m_wanted = true;
    m_attempt = 0;
    m_failureShown = false;
    if (port().isOpen())
        initialise();
    else
        port().open();  // innerOpened() goes on
}

void ModemLink::close()
{
    m_wanted = false;
    m_timeout.stop();
    m_redial.stop();
    m_carrierPoll.stop();
    const CallState was = m_state;
    if (was == CallState::Connected) {
        hangUp();
        m_state = CallState::Closed;
        emit statusChanged(tr("hung up: %1").arg(callSummary()));
        emit closed();
    } else if (was == CallState::Dialling || was == CallState::Answering) {
        // Any character aborts a dial; ATH then makes sure the line is on hook.
        port().write("\rATH\r");
        port().waitForBytesWritten(m_options.hangUpTimeout);
    }
    m_state = CallState::Closed;
    port().close();
    if (was != CallState::Closed && was != CallState::Connected)
        emit statusChanged(tr("modem closed"));
}

bool ModemLink::write(const QByteArray& bytes)
{
    return m_state == CallState::Connected && port().write(bytes);
}

void ModemLink::innerOpened()
{
    if (m_wanted)
        initialise();
}

void ModemLink::innerClosed()
{
    // The port went away under us (close() set the state first).
    if (m_state == CallState::Closed)
        return;
    const bool wasConnected = m_state == CallState::Connected;
    m_timeout.stop();
    m_redial.stop();
    m_carrierPoll.stop();
    m_state = CallState::Closed;
    emit statusChanged(wasConnected ? tr("call lost with the serial port: %1").arg(callSummary())
                                    : tr("modem lost with the serial port"));
    if (wasConnected)
        emit closed();
}

void ModemLink::setState(CallState state, const QString& status)
{
    m_state = state;
    emit statusChanged(status);
}

void ModemLink::sendCommand(const QByteArray& command, CallState state, Milliseconds timeout, const QString& status)
{
    m_line.clear();
    setState(state, status);
    m_timeout.start(timeout);
    port().write(command + '\r');
}

void ModemLink::initialise()
{
    sendCommand(m_options.initString, CallState::Initialising, m_options.commandTimeout,
                tr("initialising the modem: %1").arg(QString::fromLatin1(m_options.initString)));
}

void ModemLink::dial()
{
    m_since.start();
    const QString attempt = m_attempt > 0 ? tr(", attempt %1 of %2").arg(m_attempt + 1).arg(m_options.redialAttempts + 1)
                                          : QString();
    sendCommand("ATD" + m_options.number.toLatin1(), CallState::Dialling, m_options.dialTimeout,
                tr("dialling %1%2").arg(m_options.number, attempt));
}

void ModemLink::innerBytesReceived(const QByteArray& bytes)
{
    if (m_state != CallState::Connected) {
        takeLines(bytes);
        return;
    }
    // In a call the modem says NO CARRIER in the data stream when the call
    // drops; frames are binary, so the 14 bytes are looked for anywhere,
    // across reads. (The chance of them in a second of random data is 2^-112.)
    const QByteArray seen = m_dataTail + bytes;
    const qsizetype at = seen.indexOf(kNoCarrierInData);
    if (at < 0) {
        emit bytesReceived(bytes);
        m_dataTail = seen.right(kNoCarrierInData.size() - 1);
        return;
    }
    const qsizetype before = at - m_dataTail.size();
    if (before > 0)
        emit bytesReceived(bytes.left(before));
    m_dataTail.clear();
    callEnded(QStringLiteral("NO CARRIER"));
}

void ModemLink::takeLines(const QByteArray& bytes)
{
    for (const char c : bytes) {
        if (c != '\r' && c != '\n') {
            if (m_line.size() < 256)  // a result line is short; anything else is noise
                m_line += c;
            continue;
        }
        if (m_line.isEmpty())
            continue;
        const std::optional<modem::Result> parsed = modem::parseResult(m_line);
        m_line.clear();
        if (parsed)
            result(*parsed);
        if (m_state == CallState::Connected)
            return;  // what follows CONNECT in this read is data, and is lost: a frame's worth at most
    }
}

void ModemLink::result(const modem::Result& r)
{
    const QString said = QString::fromLatin1(modem::resultText(r));
    switch (m_state) {
        case CallState::Initialising:
            if (r.code == ResultCode::Ok) {
                m_timeout.stop();
                if (m_options.number.isEmpty())
                    setState(CallState::AwaitingCall, tr("waiting for a call"));
                else
                    dial();
            } else if (r.code == ResultCode::Error) {
                failed(tr("the modem refused \"%1\": %2").arg(QString::fromLatin1(m_options.initString), said));
            }
            break;
        case CallState::Dialling:
            if (r.code == ResultCode::Connect)
                connected(r.rate);
            else if (r.code != ResultCode::Ok && r.code != ResultCode::Ring)
                failed(tr("%1 after %2 s").arg(said, seconds(m_since.elapsed())));
            break;
        case CallState::AwaitingCall:
            if (r.code == ResultCode::Ring) {
                m_since.start();
                sendCommand("ATA", CallState::Answering, m_options.dialTimeout, tr("answering a call"));
            } else if (r.code == ResultCode::Connect) {
                m_since.start();
                connected(r.rate);  // the modem answered by itself (ATS0)
            }
            break;
        case CallState::Answering:
            if (r.code == ResultCode::Connect)
                connected(r.rate);
            else if (r.code != ResultCode::Ok && r.code != ResultCode::Ring)
                failed(tr("answering: %1").arg(said));
            break;
        case CallState::HangingUp:
            if (r.code == ResultCode::Ok)
                m_okSeen = true;
            break;
        default:
            break;  // late words of a call that ended: a NO CARRIER after DCD went off
    }
}

void ModemLink::connected(int rate)
{
    m_timeout.stop();
    const qint64 setUp = m_since.elapsed();
    m_rate = rate;
    ++m_calls;
    m_attempt = 0;
    m_failureShown = false;
    m_dataTail.clear();
    m_since.start();
    setState(CallState::Connected, rate > 0 ? tr("connected at %1 bit/s after %2 s").arg(rate).arg(seconds(setUp))
                                            : tr("connected after %1 s").arg(seconds(setUp)));
    if (m_options.watchCarrierDetect)
        m_carrierPoll.start();
    emit opened();
}

void ModemLink::timedOut()
{
    switch (m_state) {
        case CallState::Initialising:
            failed(tr("the modem did not answer \"%1\" within %2 s")
                       .arg(QString::fromLatin1(m_options.initString), seconds(m_options.commandTimeout.count())));
            break;
        case CallState::Dialling:
        case CallState::Answering:
            port().write("\r");  // any character aborts the call set-up
            failed(tr("no CONNECT within %1 s").arg(seconds(m_options.dialTimeout.count())));
            break;
        default:
            break;
    }
}

void ModemLink::failed(const QString& what)
{
    m_timeout.stop();
    if (m_options.number.isEmpty()) {
        // The answering side has no one to call back: it waits for the next call.
        setState(CallState::AwaitingCall, tr("%1; waiting for a call").arg(what));
        return;
    }
    scheduleRedial(what);
}

void ModemLink::callEnded(const QString& why)
{
    m_carrierPoll.stop();
    const QString what = tr("call dropped (%1) after %2").arg(why, callSummary());
    m_state = CallState::WaitingToRedial;  // not Connected any more, before anyone hears closed()
    emit closed();
    if (m_options.number.isEmpty()) {
        fail(tr("%1; waiting for a call").arg(what));
        m_state = CallState::AwaitingCall;
        return;
    }
    scheduleRedial(what);
}

void ModemLink::scheduleRedial(const QString& what)
{
    if (m_attempt >= m_options.redialAttempts) {
        m_state = CallState::GaveUp;
        m_failureShown = false;  // giving up is news even after the errors before it
        fail(tr("%1; gave up after %2 attempts; hang up and dial again to retry").arg(what).arg(m_attempt + 1));
        return;
    }
    const Milliseconds doubled(m_options.redialDelay.count() << std::min(m_attempt, 20));
    const Milliseconds delay = std::min(doubled, m_options.redialDelayLimit);
    ++m_attempt;
    m_state = CallState::WaitingToRedial;
    fail(tr("%1; redialling in %2 s, attempt %3 of %4")
             .arg(what, seconds(delay.count()))
             .arg(m_attempt + 1)
             .arg(m_options.redialAttempts + 1));
    m_redial.start(delay);
}

void ModemLink::fail(const QString& message)
{
    // The error first: who hears both says the status again only when it is not that error.
    if (!m_failureShown) {
        m_failureShown = true;
        emit errorOccurred(message);
    }
    emit statusChanged(message);
}

void ModemLink::pollCarrier()
{
    if (m_state != CallState::Connected) {
        m_carrierPoll.stop();
        return;
    }
    const std::optional<bool> carrier = port().carrierDetect();
    if (!carrier)
        m_carrierPoll.stop();  // no pins to watch: NO CARRIER alone tells
    else if (!*carrier)
        callEnded(tr("carrier lost, DCD off"));
}

void ModemLink::hangUp()
{
    m_state = CallState::HangingUp;
    m_line.clear();
    // What waits to go out would only delay the escape; the call is ending.
    port().discardOutput();
    waitFor(m_options.guardTime, false);
    port().write(modem::kEscapeSequence);
    waitFor(m_options.guardTime + m_options.hangUpTimeout, true);
    port().write("ATH\r");
    waitFor(m_options.hangUpTimeout, true);
    // A modem set to &D2 hangs up when DTR drops, should the words have failed.
    port().setDataTerminalReady(false);
}

// Without untilOk it is the guard time: silence on our side, whatever the
// modem says meanwhile (the far end's last bytes).
void ModemLink::waitFor(Milliseconds duration, bool untilOk)
{
    const QDeadlineTimer deadline(duration);
    m_okSeen = false;
    port().waitForBytesWritten(duration);
    while (!deadline.hasExpired() && !(untilOk && m_okSeen)) {
        if (!port().waitForBytesReceived(Milliseconds(std::max<qint64>(1, deadline.remainingTime()))))
            break;  // the time is up, or the port failed
    }
}

QString ModemLink::callSummary() const
{
    const qint64 ms = m_since.isValid() ? m_since.elapsed() : 0;
    if (m_options.costPerMinute <= 0)
        return duration(ms);
    const qint64 minutes = std::max<qint64>(1, (ms + 59999) / 60000);
    return tr("%1, %2 min billed, cost %3")
        .arg(duration(ms))
        .arg(minutes)
        .arg(QString::number(double(minutes) * m_options.costPerMinute, 'f', 2));
}
