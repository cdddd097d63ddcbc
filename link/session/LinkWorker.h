#pragma once

// The link thread's one object: sends the commanded state once per tick,
// finds and decodes what arrives, logs every frame both ways and keeps the
// statistics. It lives in its own QThread (LinkController puts it there); the
// GUI talks to it only through queued calls and signals, so the GUI thread
// never waits on a port or a socket.
//
// Each of its parts is passed in or owned, never global: the Link moves the
// bytes, rcm::FrameReceiver (the one receive path: sync, RS, decipher,
// decode, the acceptance decision of docs/protocol.md section 8) turns what
// arrives into frames delivered or refused, rcm::buildFrame (the one send
// path) turns the stamped command into the bytes sent, FrameLog records.

#include "codec/message/Message.h"
#include "link/clock/Clock.h"
#include "link/framelog/FrameLog.h"
#include "link/session/LinkEvents.h"
#include "link/session/LinkStatistics.h"
#include "link/session/LoggedFrame.h"
#include "link/session/MessageMetaType.h"
#include "link/session/ReceivedMessage.h"
#include "link/transport/Link.h"

#include <QObject>

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <vector>

namespace rcm {
class FrameReceiver;
struct ReceivedFrame;
struct SendFormat;
namespace secure {
struct SecureEndpoint;
}  // namespace secure
}  // namespace rcm

class UdpLink;

// What it says (LinkEvents) reaches the GUI thread through LinkController.
class LinkWorker : public LinkEvents {
    Q_OBJECT

public:
    // BLOCK 2 hooks, both called in the link thread, so whatever they share
    // with other threads they must guard themselves. Block2Source is asked
    // once per frame, just before it is encoded, for the flight plan section
    // to carry; nothing keeps the command's own section (normally empty).
    // rcm::FlightPlanUploader::next() fits it as is. Block2Reply gets BLOCK 2
    // of every good frame received, e.g. for FlightPlanUploader::handleReply().
    using Block2Source = std::function<std::optional<rcm::FlightPlanSection>()>;
    using Block2Reply = std::function<void(const rcm::FlightPlanSection&)>;

    struct Options {
        // Ticks fall on multiples of the interval in UTC: at 1000 ms, on the second.
        std::chrono::milliseconds interval{1000};
        // Silence after which the link is reported lost.
        std::chrono::milliseconds silenceTimeout{3000};
        // Statistics are emitted at most this often.
        std::chrono::milliseconds statisticsInterval{250};
        // ID_msg of the first frame; IDs count up from it and wrap at 2^24.
        std::uint32_t firstMessageId = 0;
        Block2Source block2Source;
        Block2Reply block2Reply;
        // The secure link (codec/secure/SecureCodec.h, docs/security.md): null for
        // the plain link. With it every frame sent is enciphered, its ID_msg
        // taken from the endpoint's send counter (firstMessageId is then
        // unused); every frame received must authenticate, be new and be
        // within the time window. Used by the link thread only.
        // Plain or keyed, a frame the receive path refuses is counted by
        // reason in the statistics, logged (Uncorrectable, or Rejected) with
        // its bytes as received, and reported by frameRejected().
        std::shared_ptr<rcm::secure::SecureEndpoint> secure;
        // What stamps the frames and paces the ticks and timeouts; null: the
        // system clock. Tests pass a VirtualClock.
        std::shared_ptr<Clock> clock;
    };

    static constexpr std::uint32_t kMessageIdModulus = rcm::kMessageIdModulus;

    // `log` may be null (no frame log) and must already be open otherwise.
    LinkWorker(std::unique_ptr<Link> link, std::unique_ptr<FrameLog> log, Options options, QObject* parent = nullptr);
    explicit LinkWorker(std::unique_ptr<Link> link, std::unique_ptr<FrameLog> log = {});
    ~LinkWorker() override;

    // For the cross-thread signals of the link layer; idempotent.
    static void registerMetaTypes();

    const Options& options() const { return m_options; }
    // In the link thread only (or before it starts).
    const LinkStatistics& statistics() const { return m_statistics; }
    Link* link() const { return m_link.get(); }
    // options().clock, or the system clock the worker made for itself.
    Clock& clock() const { return *m_clock; }
    std::shared_ptr<Clock> sharedClock() const { return m_clock; }

public slots:
    // Opens the link and starts the cadence.
    void start();
    // Stops sending, closes the link. The frame log stays open until the
    // worker is destroyed, so a restart goes on in the same log.
    void stop();
    // The state to command from the next frame on. Refused, with the reasons
    // in commandRejected(), when it cannot be encoded; the previous command
    // then stays. No frame is sent before the first command. Without
    // `withPlanSections` the frames carry no section from the BLOCK 2 source:
    // a command held back holds its flight plan upload back too.
    void setCommand(const rcm::Message& command, bool withPlanSections = true);

private:
    void armTick();
    void tick();
    void sendFrame(std::int64_t idealTickMicros);
    // The link's framing and, keyed, the sending direction's codec.
    rcm::SendFormat sendFormat() const;
    // The stamped message through the send path (codec/send/FrameBuilder.h);
    // a flight plan section that cannot go is dropped, and said so, once.
    std::optional<QByteArray> encode(rcm::Message& message);
    void receiveBytes(const QByteArray& bytes);
    void receiveDatagram(const QByteArray& datagram);
    void receiveFrame(const rcm::ReceivedFrame& frame);
    void transportClosed();
    void silenceElapsed();
    void setState(LinkState state);
    void log(FrameDirection direction, QByteArray bytes, FrameStatus status, QList<int> corrected = {},
             std::optional<quint32> messageId = std::nullopt);
    void statisticsDirty();
    void reportError(const QString& message);

    std::unique_ptr<Link> m_link;
    // The UDP link under m_link (itself, or wrapped for voice or faults),
    // told which senders to follow; null for other transports.
    UdpLink* m_udp = nullptr;
    std::unique_ptr<FrameLog> m_log;
    Options m_options;
    std::shared_ptr<Clock> m_clock;
    // Held by pointer so that this header does not include StreamSync.h
    // (under FrameReceiver.h), whose private emit() clashes with Qt's emit
    // macro in Qt headers.
    std::unique_ptr<rcm::FrameReceiver> m_receiver;
    // Children, so that moveToThread() takes them along.
    ClockTimer* m_tickTimer;
    ClockTimer* m_silenceTimer;
    ClockTimer* m_statisticsTimer;
    LinkStatistics m_statistics;
    bool m_statisticsDirty = false;
    bool m_running = false;
    std::optional<rcm::Message> m_command;
    bool m_withPlanSections = true;
    std::uint32_t m_nextMessageId;
    std::int64_t m_idealTickMicros = 0;  // UTC of the tick the timer is armed for
    QString m_lastEncodeError;           // so a bad BLOCK 2 source is reported once, not every second
    QString m_lastPersistError;          // secure link: a replay state that cannot be written, once
};
