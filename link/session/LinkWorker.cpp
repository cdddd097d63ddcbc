// First: StreamSync, under it, names a member emit(), which Qt's headers
// define as a macro.
#include "codec/receive/FrameReceiver.h"

#include "link/session/LinkWorker.h"

#include "codec/message/FlightPlanTransfer.h"
#include "codec/secure/SecureCodec.h"
#include "codec/send/FrameBuilder.h"
#include "link/transport/UdpLink.h"

#include <QStringList>

#include <algorithm>

namespace {

QString joinDiagnostics(const rcm::Diagnostics& diagnostics)
{
    QStringList lines;
    for (const rcm::Diagnostic& d : diagnostics)
        lines << QString::fromStdString(d.toString());
    return lines.join(QLatin1Char('\n'));
}

QByteArray toByteArray(std::span<const std::uint8_t> bytes)
{
    return QByteArray(reinterpret_cast<const char*>(bytes.data()), qsizetype(bytes.size()));
}

std::span<const std::uint8_t> asBytes(const QByteArray& bytes)
{
    return {reinterpret_cast<const std::uint8_t*>(bytes.constData()), std::size_t(bytes.size())};
}

// Live, what arrives is judged against the worker's clock too; a replayed
// log only for continuity between its own frames.
rcm::FrameReceiver::Options receiverOptions(const LinkWorker::Options& options, const Link& link,
                                            std::shared_ptr<Clock> clock)
{
    rcm::FrameReceiver::Options o;
    o.mode = link.transport() == FrameTransport::Replay ? rcm::FrameReceiver::Mode::Recording
                                                        : rcm::FrameReceiver::Mode::Live;
    o.clock = [clock = std::move(clock)] { return clock->utcMicros(); };
    if (options.secure) {
        o.keys.codecs = {options.secure->receiver.get()};
        // A replayed log's stamps are old, and were checked for replays
        // when they were live.
        if (o.mode == rcm::FrameReceiver::Mode::Live)
            o.keys.guard = options.secure->guard.get();
    }
    return o;
}

}  // namespace

LinkWorker::LinkWorker(std::unique_ptr<Link> link, std::unique_ptr<FrameLog> log, Options options, QObject* parent)
    : LinkEvents(parent),
      m_link(std::move(link)),
      m_log(std::move(log)),
      m_options(std::move(options)),
      m_clock(m_options.clock ? m_options.clock : std::make_shared<SystemClock>()),
      m_receiver(std::make_unique<rcm::FrameReceiver>(receiverOptions(m_options, *m_link, m_clock),
                                                      [this](const rcm::ReceivedFrame& frame) { receiveFrame(frame); })),
      m_tickTimer(m_clock->createTimer(this, Qt::PreciseTimer)),
      m_silenceTimer(m_clock->createTimer(this)),
      m_statisticsTimer(m_clock->createTimer(this)),
      m_nextMessageId(m_options.firstMessageId % kMessageIdModulus)
{
    registerMetaTypes();
    Q_ASSERT(m_link);
    // A child, so that moveToThread() takes the link and its sockets along.
    m_link->setParent(this);
    // In reply-to-sender mode the link follows only senders of frames
    // accepted here, so a refused datagram cannot steer the replies.
    m_udp = qobject_cast<UdpLink*>(m_link.get());
    if (!m_udp)
        m_udp = m_link->findChild<UdpLink*>();
    if (m_udp)
        m_udp->setFollowAcceptedSendersOnly(true);
    m_statistics.secure = m_options.secure != nullptr;

    connect(m_tickTimer, &ClockTimer::timeout, this, &LinkWorker::tick);
    connect(m_silenceTimer, &ClockTimer::timeout, this, &LinkWorker::silenceElapsed);
    connect(m_statisticsTimer, &ClockTimer::timeout, this, [this] {
        m_statisticsTimer->start(m_options.statisticsInterval);
        if (!m_statisticsDirty)
            return;
        m_statisticsDirty = false;
        emit statisticsChanged(m_statistics);
    });

    connect(m_link.get(), &Link::bytesReceived, this, &LinkWorker::receiveBytes);
    connect(m_link.get(), &Link::datagramReceived, this, &LinkWorker::receiveDatagram);
    connect(m_link.get(), &Link::closed, this, &LinkWorker::transportClosed);
    // Silence counts from when the line is up (a modem's CONNECT), not from start().
    connect(m_link.get(), &Link::opened, this, [this] {
        if (m_running && m_statistics.state != LinkState::Lost)
            m_silenceTimer->start(m_options.silenceTimeout);
    });
    connect(m_link.get(), &Link::errorOccurred, this, &LinkWorker::errorOccurred);
    connect(m_link.get(), &Link::statusChanged, this, &LinkEvents::transportStatusChanged);
    connect(m_link.get(), &Link::serviceChanged, this, &LinkEvents::modemServiceChanged);

    if (m_log)
        m_log->setErrorHandler([this](const QString& error) { reportError(QStringLiteral("frame log: ") + error); });
}

LinkWorker::LinkWorker(std::unique_ptr<Link> link, std::unique_ptr<FrameLog> log)
    : LinkWorker(std::move(link), std::move(log), Options{})
{
}

LinkWorker::~LinkWorker()
{
    // The link goes before the log and the synchroniser it feeds; quietly.
    disconnect(m_link.get(), nullptr, this, nullptr);
    m_link.reset();
}

void LinkWorker::registerMetaTypes()
{
    qRegisterMetaType<LinkState>();
    qRegisterMetaType<LinkStatistics>();
    qRegisterMetaType<ReceivedMessage>();
    qRegisterMetaType<LoggedFrame>();
    qRegisterMetaType<rcm::Message>();
}

void LinkWorker::start()
{
    if (m_running)
        return;
    m_running = true;
    setState(LinkState::Waiting);
    m_link->open();
    m_silenceTimer->start(m_options.silenceTimeout);
    m_statisticsTimer->start(m_options.statisticsInterval);
    armTick();
    if (m_options.secure && !m_options.secure->notice.empty())
        reportError(QString::fromStdString(m_options.secure->notice));
    emit started();
    emit statisticsChanged(m_statistics);
    m_statisticsDirty = false;
}

void LinkWorker::stop()
{
    if (!m_running)
        return;
    m_running = false;  // first, so the link's closed() is not taken for a loss
    m_tickTimer->stop();
    m_silenceTimer->stop();
    m_statisticsTimer->stop();
    m_link->close();
    if (m_link->isStream())
        m_receiver->flush();
    setState(LinkState::Closed);
    emit stopped();
    emit statisticsChanged(m_statistics);
    m_statisticsDirty = false;
}

void LinkWorker::setCommand(const rcm::Message& command, bool withPlanSections)
{
    const rcm::Diagnostics errors = rcm::validateCommand(command, sendFormat());
    if (!errors.empty()) {
        emit commandRejected(joinDiagnostics(errors));
        return;
    }
    m_command = command;
    m_withPlanSections = withPlanSections;
}

void LinkWorker::armTick()
{
    const std::int64_t now = m_clock->utcMicros();
    m_idealTickMicros = rcm::nextSendMicros(now, m_options.interval);
    // Rounded up: a timer that fires a little late costs spread, one that
    // fires early would stamp the frame with the previous second.
    m_tickTimer->start(std::chrono::milliseconds((m_idealTickMicros - now + 999) / 1000));
}

void LinkWorker::tick()
{
    if (!m_running)
        return;
    const std::int64_t now = m_clock->utcMicros();
    const std::int64_t period = std::chrono::microseconds(m_options.interval).count();
    if (now < m_idealTickMicros) {
        // The timer runs on the monotonic clock, ticks are on the UTC one.
        // Woken a little early, wait the rest; if the UTC clock was stepped
        // back, align afresh rather than wait out the step.
        if (m_idealTickMicros - now < period)
            m_tickTimer->start(std::chrono::milliseconds((m_idealTickMicros - now + 999) / 1000));
        else
            armTick();
        return;
    }
    const std::int64_t missed = (now - m_idealTickMicros) / period;
    m_statistics.ticksMissed += std::uint64_t(missed);
    sendFrame(m_idealTickMicros + missed * period);
    armTick();
}

void LinkWorker::sendFrame(std::int64_t idealTickMicros)
{
    if (!m_command)
        return;
    rcm::Message message = *m_command;
    if (m_options.block2Source && m_withPlanSections) {
        if (std::optional<rcm::FlightPlanSection> section = m_options.block2Source())
            message.flightPlan = std::move(*section);
    }
    std::uint32_t id = m_nextMessageId;
    if (m_options.secure) {
        // Never reused under the key, across restarts too: the aircraft
        // would reject a reused ID as replayed.
        std::string error;
        id = m_options.secure->counter->next(&error);
        if (!error.empty() && QString::fromStdString(error) != m_lastEncodeError) {
            m_lastEncodeError = QString::fromStdString(error);
            reportError(m_lastEncodeError);
        }
    }
    rcm::stampMessage(message, rcm::SendStamp{id, m_clock->utcMicros()});
    const std::optional<QByteArray> bytes = encode(message);
    if (!bytes)
        return;
    // Closed, or no peer yet: the aircraft hears nothing, so nothing is counted.
    if (!m_link->write(*bytes))
        return;
    m_statistics.addSendDelay(m_clock->utcMicros() - idealTickMicros);
    ++m_statistics.framesSent;
    // What the far end reports next shows what was just commanded: a
    // prediction for reading its frames through noise.
    m_receiver->expect(message);
    m_nextMessageId = (id + 1) % kMessageIdModulus;
    log(FrameDirection::Sent, *bytes, FrameStatus::NotChecked, {}, id);
    emit frameSent(id);
    statisticsDirty();
}

rcm::SendFormat LinkWorker::sendFormat() const
{
    return rcm::SendFormat{!m_link->isStream(), m_options.secure ? m_options.secure->sender.get() : nullptr};
}

std::optional<QByteArray> LinkWorker::encode(rcm::Message& message)
{
    const rcm::SendFormat format = sendFormat();
    const auto attempt = [&format](const rcm::Message& m, rcm::Diagnostics& errors) -> std::optional<QByteArray> {
        const std::vector<std::uint8_t> bytes = rcm::buildFrame(m, format, errors);
        if (bytes.empty())
            return std::nullopt;
        return toByteArray(bytes);
    };
    rcm::Diagnostics errors;
    std::optional<QByteArray> bytes = attempt(message, errors);
    if (!bytes && !message.flightPlan.empty()) {
        // The command was validated when it was set, so the section is at
        // fault: the frame still goes, without it.
        const QString reason = QStringLiteral("BLOCK 2: flight plan %1 section %2 not sent: %3")
                                   .arg(QString::fromStdString(rcm::planIdText(message.flightPlan.planId)))
                                   .arg(message.flightPlan.sectionId)
                                   .arg(joinDiagnostics(errors));
        if (reason != m_lastEncodeError) {
            m_lastEncodeError = reason;
            reportError(reason);
        }
        message.flightPlan = {};
        errors.clear();
        bytes = attempt(message, errors);
    }
    if (!bytes) {
        const QString reason = QStringLiteral("frame not sent: ") + joinDiagnostics(errors);
        if (reason != m_lastEncodeError) {
            m_lastEncodeError = reason;
            reportError(reason);
        }
    }
    return bytes;
}

void LinkWorker::receiveBytes(const QByteArray& bytes)
{
    m_statistics.bytesReceived += quint64(bytes.size());
    statisticsDirty();
    m_receiver->feed(asBytes(bytes));
    m_statistics.bytesSkipped = m_receiver->syncStats().bytesSkipped;
}

void LinkWorker::receiveDatagram(const QByteArray& datagram)
{
    m_statistics.bytesReceived += quint64(datagram.size());
    if (std::size_t(datagram.size()) == rcm::kDatagramSize) {
        m_receiver->receive(asBytes(datagram));
        return;
    }
    // The receiver also takes a delimited 600-byte frame; on UDP that is a
    // wrong size too.
    rcm::ReceivedFrame frame;
    frame.raw = asBytes(datagram);
    frame.refusal = rcm::Refusal::WrongSize;
    frame.detail = std::to_string(datagram.size()) + " bytes; a datagram is " + std::to_string(rcm::kDatagramSize);
    receiveFrame(frame);
}

void LinkWorker::receiveFrame(const rcm::ReceivedFrame& frame)
{
    if (!frame.warning.empty() && QString::fromStdString(frame.warning) != m_lastPersistError) {
        m_lastPersistError = QString::fromStdString(frame.warning);
        reportError(m_lastPersistError);
    }
    const rcm::DecodedBlocks& blocks = frame.blocks;
    // A wrong-size datagram was not read at all: no codewords to tell of.
    const QList<int> corrected = frame.refusal == rcm::Refusal::WrongSize
                                     ? QList<int>{}
                                     : QList<int>{blocks.corrected.block1, blocks.corrected.block2};
    if (frame.refusal) {
        // Not delivered: it neither counts as received nor keeps the link
        // connected. Logged with the bytes as they arrived (a keyed link's
        // ciphertext, which `rcm decode --key` reads again).
        ++m_statistics.refused[std::size_t(*frame.refusal)];
        log(FrameDirection::Received, toByteArray(frame.raw),
            frame.refusal == rcm::Refusal::Uncorrectable ? FrameStatus::Uncorrectable : FrameStatus::Rejected,
            corrected);
        statisticsDirty();
        const std::string_view name = rcm::refusalName(*frame.refusal);
        emit frameRejected(QString::fromLatin1(name.data(), qsizetype(name.size())) + QStringLiteral(": ") +
                           QString::fromStdString(frame.detail));
        return;
    }
    // For a datagram, still inside the link's datagramReceived(): its sender.
    if (m_udp)
        m_udp->acceptSender();
    const bool clean = blocks.corrected.block1 == 0 && blocks.corrected.block2 == 0;
    const rcm::Unit& header = frame.decoded.message.header;
    log(FrameDirection::Received, toByteArray(frame.raw), clean ? FrameStatus::Decoded : FrameStatus::Corrected,
        corrected, quint32(header.number(rcm::ItemId::ID_msg)));

    const std::int64_t now = m_clock->utcMicros();
    ++m_statistics.framesReceived;
    m_statistics.framesFromPrediction += frame.fromPrediction;
    m_statistics.correctedBytesBlock1 += std::uint64_t(blocks.corrected.block1);
    m_statistics.correctedBytesBlock2 += std::uint64_t(blocks.corrected.block2);
    m_statistics.lastGoodFrameUtcMicros = now;
    statisticsDirty();

    if (m_running) {
        m_silenceTimer->start(m_options.silenceTimeout);
        const LinkState before = m_statistics.state;
        setState(LinkState::Connected);
        if (before == LinkState::Lost)
            emit linkRegained();
    }
    if (m_options.block2Reply)
        m_options.block2Reply(frame.decoded.message.flightPlan);

    ReceivedMessage received;
    received.message = frame.decoded.message;
    received.corrected.block1 = blocks.corrected.block1;
    received.corrected.block2 = blocks.corrected.block2;
    received.utcMicros = now;
    received.transport = m_link->transport();
    emit messageReceived(received);
}

void LinkWorker::transportClosed()
{
    if (!m_running)
        return;
    // No frame spans the gap: what the synchroniser holds is decided now.
    if (m_link->isStream())
        m_receiver->flush();
    m_silenceTimer->stop();
    if (m_statistics.state == LinkState::Waiting || m_statistics.state == LinkState::Connected) {
        setState(LinkState::Lost);
        emit linkLost();
    }
}

void LinkWorker::silenceElapsed()
{
    if (!m_running)
        return;
    if (m_link->isConnecting()) {
        // A call being set up takes tens of seconds; silence counts from CONNECT.
        m_silenceTimer->start(m_options.silenceTimeout);
        return;
    }
    if (m_statistics.state == LinkState::Waiting || m_statistics.state == LinkState::Connected) {
        setState(LinkState::Lost);
        emit linkLost();
    }
}

void LinkWorker::setState(LinkState state)
{
    if (m_statistics.state == state)
        return;
    m_statistics.state = state;
    statisticsDirty();
    emit stateChanged(state);
}

void LinkWorker::log(FrameDirection direction, QByteArray bytes, FrameStatus status, QList<int> corrected,
                     std::optional<quint32> messageId)
{
    FrameRecord record;
    record.bytes = std::move(bytes);
    record.utcMicros = m_clock->utcMicros();
    record.direction = direction;
    record.transport = m_link->transport();
    record.status = status;
    record.enciphered = m_options.secure != nullptr;
    record.correctedSymbols = std::move(corrected);

    LoggedFrame logged;
    logged.entry.offset = -1;
    static_cast<FrameFacts&>(logged.entry) = record;
    logged.entry.length = quint32(record.bytes.size());
    logged.messageId = messageId;
    if (m_log && m_log->isOpen())
        m_log->append(record, &logged.entry.offset);
    // The bytes go along even when in the file, for whoever passes frames on
    // (the broker) without reading the file back; a view keeps them only for
    // a frame in no file.
    logged.bytes = std::move(record.bytes);
    logged.correctedSymbols = std::move(record.correctedSymbols);
    emit frameLogged(logged);
}

void LinkWorker::statisticsDirty()
{
    m_statisticsDirty = true;
}

void LinkWorker::reportError(const QString& message)
{
    emit errorOccurred(message);
}
