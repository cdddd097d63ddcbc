#include "link/transport/ModemLink.h"

#include "link/clock/Clock.h"

#include "link/transport/SerialLink.h"

#include <QDeadlineTimer>

#include <algorithm>
#include <utility>

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
    : LinkWrapper(std::move(serial), parent),
      m_options(std::move(options)),
      m_clock(m_options.clock ? m_options.clock : std::make_shared<SystemClock>()),
      m_timeout(m_clock->createTimer(this)),
      m_redial(m_clock->createTimer(this)),
      m_servicePoll(m_clock->createTimer(this)),
      m_carrierPoll(m_clock->createTimer(this))
{
    connect(m_timeout, &ClockTimer::timeout, this, &ModemLink::timedOut);
    connect(m_redial, &ClockTimer::timeout, this, [this] {
        if (!port().isOpen())
            return;  // the port's reopening probes, initialises and dials
        // Registration and signal are read again before every redial.
        if (m_initialised)
            checkService();
        else
            initialise();
    });
    connect(m_servicePoll, &ClockTimer::timeout, this, [this] {
        if (m_state == CallState::WaitingForService)
            checkService();
    });
    connect(m_carrierPoll, &ClockTimer::timeout, this, &ModemLink::pollCarrier);
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
    m_serviceReported = false;
    m_initialised = false;
    if (port().isOpen())
        probe();
    else
        port().open();  // innerOpened() goes on
}

void ModemLink::close()
{
    m_wanted = false;
    m_timeout->stop();
    m_redial->stop();
    m_servicePoll->stop();
    m_carrierPoll->stop();
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
    m_initialised = false;
    if (m_wanted)
        probe();
}

void ModemLink::innerClosed()
{
    // The port went away under us (close() set the state first).
    if (m_state == CallState::Closed)
        return;
    const bool wasConnected = m_state == CallState::Connected;
    m_timeout->stop();
    m_redial->stop();
    m_servicePoll->stop();
    m_carrierPoll->stop();
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
    m_command = command;
    if (status.isEmpty())
        m_state = state;
    else
        setState(state, status);
    m_timeout->start(timeout);
    port().write(command + '\r');
}

// A modem in command mode answers "AT" at once; one still in a call from an
// earlier session (the console was killed, the cable pulled) passes it on
// as data and says nothing.
void ModemLink::probe()
{
    m_pending.clear();
    sendCommand("AT", CallState::Probing, m_options.probeTimeout, tr("checking the modem"));
}

void ModemLink::escapeStaleCall()
{
    emit statusChanged(tr("the modem did not answer AT within %1 s: taken to be still in a call, escaped (+++) and "
                          "hung up (ATH)")
                           .arg(seconds(m_options.probeTimeout.count())));
    hangUp(false);
}

void ModemLink::initialise()
{
    m_pending = m_options.profile.setup;
    if (!m_options.profile.indications.isEmpty())
        m_pending << m_options.profile.indications;
    sendCommand(m_options.initString, CallState::Initialising, m_options.commandTimeout,
                tr("initialising the modem: %1").arg(QString::fromLatin1(m_options.initString)));
}

void ModemLink::nextSetupCommand()
{
    if (!m_pending.isEmpty()) {
        const QByteArray command = m_pending.takeFirst();
        sendCommand(command, CallState::Initialising, m_options.commandTimeout,
                    tr("setting the modem up (%1): %2")
                        .arg(m_options.profile.title, QString::fromLatin1(command)));
        return;
    }
    m_timeout->stop();
    m_initialised = true;
    if (m_options.number.isEmpty())
        setState(CallState::AwaitingCall, tr("waiting for a call"));
    else
        checkService();
}

// Registration and signal, asked before every dial (and again and again
// while there is no service): a phone with no network is never dialled.
void ModemLink::checkService()
{
    if (!m_options.profile.hasNetwork()) {
        dial();
        return;
    }
    m_pending = {m_options.profile.registrationQuery};
    if (!m_options.profile.signalQuery.isEmpty())
        m_pending << m_options.profile.signalQuery;
    // Not remembered from the last time: only what the phone says now counts.
    m_service.registration = modem::Registration::Unknown;
    m_service.bars = -1;
    nextServiceQuery();
}

void ModemLink::nextServiceQuery()
{
    if (m_pending.isEmpty()) {
        m_timeout->stop();
        serviceKnown();
        return;
    }
    // Said once when it starts, not for every poll.
    const QString status =
        m_state == CallState::WaitingForService || m_state == CallState::CheckingService
            ? QString()
            : tr("reading the phone's registration and signal");
    sendCommand(m_pending.takeFirst(), CallState::CheckingService, m_options.commandTimeout, status);
}

void ModemLink::serviceKnown()
{
    emit serviceChanged(m_service.bars, modem::isRegistered(m_service.registration), m_service.text());
    m_serviceKnownOnce = true;
    if (m_service.canDial()) {
        m_serviceReported = false;
        dial();
        return;
    }
    const QString why = tr("not dialling %1: %2; dialling as soon as the phone has service")
                            .arg(m_options.number, m_service.text());
    const bool first = !m_serviceReported;
    m_serviceReported = true;
    const QString before = m_lastServiceWait;
    m_lastServiceWait = why;
    m_state = CallState::WaitingForService;
    if (first)
        emit errorOccurred(why);
    if (first || why != before)
        emit statusChanged(why);
    m_servicePoll->start(m_options.servicePollInterval);
}

void ModemLink::takeServiceLine(const QByteArray& line)
{
    const modem::Service before = m_service;
    if (!modem::parseServiceLine(line, m_options.profile.scale, m_service) || m_state == CallState::CheckingService)
        return;  // an answer being gathered is told once, when the query ends
    if (m_service == before && m_serviceKnownOnce)
        return;
    // The phone's own report, between commands.
    emit serviceChanged(m_service.bars, modem::isRegistered(m_service.registration), m_service.text());
    m_serviceKnownOnce = true;
    // Any news while waiting: registration and signal are read afresh, and
    // the phone dialled if they now allow it.
    if (m_state == CallState::WaitingForService) {
        m_servicePoll->stop();
        checkService();
    }
}

void ModemLink::giveUp(const QString& why)
{
    m_timeout->stop();
    m_state = CallState::GaveUp;
    m_failureShown = false;
    fail(why);
}

void ModemLink::dial()
{
    ++m_dials;
    m_sinceMicros = m_clock->steadyMicros();
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
        const QByteArray line = std::exchange(m_line, {});
        if (const std::optional<modem::Result> parsed = modem::parseResult(line))
            result(*parsed);
        else
            takeServiceLine(line);
        if (m_state == CallState::Connected)
            return;  // what follows CONNECT in this read is data, and is lost: a frame's worth at most
    }
}

void ModemLink::result(const modem::Result& r)
{
    const QString said = QString::fromLatin1(modem::resultText(r));
    switch (m_state) {
        case CallState::Probing:
            // Any answer is from a modem in command mode.
            if (r.code == ResultCode::Ok || r.code == ResultCode::Error) {
                m_timeout->stop();
                initialise();
            }
            break;
        case CallState::Initialising:
            if (r.code == ResultCode::Ok) {
                nextSetupCommand();
            } else if (r.code == ResultCode::Error) {
                const QString command = QString::fromLatin1(m_command);
                if (m_command == m_options.initString) {
                    failed(tr("the modem refused \"%1\": %2").arg(command, said));
                } else if (m_command == m_options.profile.indications) {
                    emit statusChanged(tr("the phone does not report its service by itself (%1: %2): asking it "
                                          "every %3 s")
                                           .arg(command, said, seconds(m_options.servicePollInterval.count())));
                    nextSetupCommand();
                } else {
                    giveUp(tr("the modem refused %1 (%2), part of the %3 profile's set-up: the profile does not "
                              "fit this phone; choose its own in the link pane, or \"%4\" and the phone's "
                              "commands in the init string")
                               .arg(command, said, m_options.profile.title, modem::defaultProfile().title));
                }
            }
            break;
        case CallState::CheckingService:
            // ERROR to AT+CREG? leaves the registration unknown: no dial.
            if (r.code == ResultCode::Ok || r.code == ResultCode::Error)
                nextServiceQuery();
            break;
        case CallState::Dialling:
            if (r.code == ResultCode::Connect)
                connected(r.rate);
            else if (r.code != ResultCode::Ok && r.code != ResultCode::Ring)
                failed(tr("%1 after %2 s").arg(said, seconds(sinceMs())));
            break;
        case CallState::AwaitingCall:
            if (r.code == ResultCode::Ring) {
                m_sinceMicros = m_clock->steadyMicros();
                sendCommand("ATA", CallState::Answering, m_options.dialTimeout, tr("answering a call"));
            } else if (r.code == ResultCode::Connect) {
                m_sinceMicros = m_clock->steadyMicros();
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
    m_timeout->stop();
    const qint64 setUp = sinceMs();
    m_rate = rate;
    ++m_calls;
    // m_attempt goes on: only a call that lasts starts the redials afresh.
    m_failureShown = false;
    m_dataTail.clear();
    m_sinceMicros = m_clock->steadyMicros();
    setState(CallState::Connected, rate > 0 ? tr("connected at %1 bit/s after %2 s").arg(rate).arg(seconds(setUp))
                                            : tr("connected after %1 s").arg(seconds(setUp)));
    if (m_options.watchCarrierDetect)
        m_carrierPoll->start(m_options.carrierPollInterval);
    emit opened();
}

void ModemLink::timedOut()
{
    switch (m_state) {
        case CallState::Probing:
            escapeStaleCall();
            initialise();
            break;
        case CallState::Initialising:
            failed(tr("the modem did not answer \"%1\" within %2 s")
                       .arg(QString::fromLatin1(m_command), seconds(m_options.commandTimeout.count())));
            break;
        case CallState::CheckingService:
            nextServiceQuery();  // what it did not say stays unknown
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
    m_timeout->stop();
    if (m_options.number.isEmpty()) {
        // The answering side has no one to call back: it waits for the next call.
        setState(CallState::AwaitingCall, tr("%1; waiting for a call").arg(what));
        return;
    }
    scheduleRedial(what);
}

void ModemLink::callEnded(const QString& why)
{
    m_carrierPoll->stop();
    const bool lasted = sinceMs() >= m_options.minimumCallDuration.count();
    if (lasted)
        m_attempt = 0;
    const QString what =
        lasted ? tr("call dropped (%1) after %2").arg(why, callSummary())
               : tr("call dropped (%1) after %2, sooner than the %3 s a call must last to count as good")
                     .arg(why, callSummary(), seconds(m_options.minimumCallDuration.count()));
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
    m_redial->start(delay);
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
        m_carrierPoll->stop();
        return;
    }
    const std::optional<bool> carrier = port().carrierDetect();
    if (!carrier)
        m_carrierPoll->stop();  // no pins to watch: NO CARRIER alone tells
    else if (!*carrier)
        callEnded(tr("carrier lost, DCD off"));
    else
        m_carrierPoll->start(m_options.carrierPollInterval);
}

qint64 ModemLink::sinceMs() const
{
    return m_sinceMicros < 0 ? 0 : (m_clock->steadyMicros() - m_sinceMicros) / 1000;
}

void ModemLink::hangUp(bool dropDtr)
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
    if (dropDtr)
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
    const qint64 ms = sinceMs();
    if (m_options.costPerMinute <= 0)
        return duration(ms);
    const qint64 minutes = std::max<qint64>(1, (ms + 59999) / 60000);
    const QString currency = m_options.costCurrency.trimmed();
    return tr("%1, %2 min billed at %3 a minute, cost %4")
        .arg(duration(ms))
        .arg(minutes)
        .arg(cost(m_options.costPerMinute),
             currency.isEmpty() ? tr("%1 (no currency set)").arg(cost(double(minutes) * m_options.costPerMinute))
                                : cost(double(minutes) * m_options.costPerMinute));
}

QString ModemLink::cost(double amount) const
{
    const QString number = QString::number(amount, 'f', 2);
    const QString currency = m_options.costCurrency.trimmed();
    return currency.isEmpty() ? number : QStringLiteral("%1 %2").arg(number, currency);
}
