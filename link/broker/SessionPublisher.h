#pragma once

// Publishes one console session on the broker (BrokerTopics.h): every frame
// the console logged, both ways, with its bytes; the last status received;
// the link's statistics (at most once a second); who this station is and how
// its link is; the session's events. It only listens to the session's
// LinkEvents and never touches the link or the frame log, so a broker that is
// away costs the local session nothing: publishing fails quietly, the client
// having said so once, and the retained station report, state and
// statistics are published again as soon as the client is back.
//
// The station report's will (online=false, retained) is set on the client
// here, best before the client is started: until then it follows the role
// and description set. An aircraft learned later from the first status
// moves the reports to its topics: the old retained ones are cleared, and
// the client connects anew with the will on the new topic.
//
// Every message goes in an envelope (EnvelopeWriter): signed when the
// station has a signing key, sealed when the link is keyed, so that a keyed
// session puts nothing readable on the broker: its frames are the
// enciphered bytes as they went on the air, its state, statistics, events
// and station report are sealed for the holders of the aircraft's key.
// Retained reports expire on the broker (BrokerTopics::kMessageExpirySeconds)
// and the station report is restated well within that while the session
// lives, so a console gone leaves no report behind for ever.

#include "link/broker/BrokerTopics.h"
#include "link/broker/EnvelopeWriter.h"
#include "link/clock/Clock.h"
#include "link/session/LoggedFrame.h"
#include "link/session/ReceivedMessage.h"

#include <QObject>
#include <QPointer>
#include <QString>

#include <deque>
#include <functional>
#include <memory>
#include <optional>

class LinkEvents;
class MqttClient;

class SessionPublisher : public QObject {
    Q_OBJECT

public:
    // The bytes of a logged frame. The link's LoggedFrame carries them; a
    // caller whose frames come without (LoggedFrame promises them only for a
    // frame in no file) reads them back from the frame log here.
    using FrameBytesReader = std::function<QByteArray(const LoggedFrame&)>;

    // The station report is restated this often while the session lives.
    static constexpr int kRestateIntervalMs = 60'000;
    // An event's text is cut to this many characters.
    static constexpr int kMaxEventText = 1000;

    // `client` and `events` must outlive the publisher (or be destroyed with
    // it); `station` is this console's station ID in text form ("GB_30226"):
    // its messages go unsigned and unsealed. Its timers and the times of its
    // reports run on `clock`, the session's (null: the SystemClock); the
    // envelopes' numbers on the writer's own (EnvelopeWriter::setClock).
    SessionPublisher(MqttClient* client, const QString& station, const LinkEvents* events, QObject* parent = nullptr,
                     std::shared_ptr<Clock> clock = nullptr);
    // The same, with what signs and seals them.
    SessionPublisher(MqttClient* client, EnvelopeWriter envelopes, const LinkEvents* events, QObject* parent = nullptr,
                     std::shared_ptr<Clock> clock = nullptr);
    ~SessionPublisher() override;

    // Default: LoggedFrame::bytes.
    void setFrameBytesReader(FrameBytesReader reader);

    // This station's role ("control", "backup", "observing", "unknown") and
    // the control and backup stations as the console sees them; published at
    // once in the station report. Statuses received update the latter two.
    void setRole(const QString& role, const QString& destination, const QString& backup);
    // The link, for people: "UDP 127.0.0.1:5600".
    void setDescription(const QString& description);
    // The aircraft whose topics this session goes under. Unless set, it is
    // learned from the first status's ID_UA_source; until then "unknown".
    // Changing it clears this station's retained reports under the old name.
    void setAircraft(const QString& aircraft);
    QString aircraft() const { return m_aircraft; }
    QString station() const { return m_envelopes.station(); }
    const EnvelopeWriter& envelopes() const { return m_envelopes; }

    // An event of this console's own: severity "info", "warning", "error" or
    // "alarm" (anything else is published as "info").
    void publishEvent(const QString& severity, const QString& text);

    // The session ends: publishes the station report with online=false, then
    // stops the client (a graceful goodbye sends no will).
    void finish();

    // What the publisher would put in the station report now.
    StationReport stationReport() const;

signals:
    // The station report changed, whether or not the broker heard it: what
    // this console's own Fleet row shows, broker or no broker.
    void stationReportChanged(const QString& aircraft, const StationReport& report);

private:
    void clientConnected();
    void frameLogged(const LoggedFrame& frame);
    void messageReceived(const ReceivedMessage& received);
    void statisticsChanged(const LinkStatistics& statistics);
    void stateChanged(LinkState state);
    void flushPendingFrame();
    void sendBacklog();
    void acknowledged(int messageId);
    // The retained reports under the aircraft's topics, then the frames waiting.
    void publishEverything();
    void publishFrame(const FrameReport& report);
    void publishStats();
    void publishStation();
    void publishState();
    // Wrapped in this station's envelope.
    bool publishReport(BrokerTopics::Kind kind, const QByteArray& body, int qos, bool retain, int* messageId = nullptr);
    void setWill();
    void willChanged();
    qint64 nowMicros() const;

    std::shared_ptr<Clock> m_clock;
    QPointer<MqttClient> m_client;
    EnvelopeWriter m_envelopes;
    qint64 m_willSeq = 0;  // the will's number, announced in every station report
    QString m_aircraft = BrokerTopics::kUnknownAircraft;
    bool m_aircraftSet = false;  // by setAircraft(), not learned
    FrameBytesReader m_frameBytes;

    QString m_role = QStringLiteral("unknown");
    QString m_description;
    QString m_destination;
    QString m_backup;
    LinkState m_linkState = LinkState::Closed;
    bool m_finished = false;
    // A keyed link's frames came and there is no key to seal with: no text,
    // no state, no station in control is published.
    bool m_unsealedKeyedLink = false;

    // A good frame received waits for the message decoded from it, which the
    // link says just after, so that its report carries the text.
    std::optional<FrameReport> m_pendingFrame;
    // Frames not yet on the broker, oldest first: while the aircraft, whose
    // topic they go under, is not known yet, and while the client is away.
    // Then, once published, until the broker acknowledges them: a session
    // that ends first (a broker lost, a reconnection for a new will) loses
    // what it had not acknowledged, which goes again on the next one.
    // Bounded together: a long outage keeps the newest kBacklogFrames.
    std::deque<FrameReport> m_backlog;
    std::deque<std::pair<int, FrameReport>> m_unacknowledged;  // by message ID
    quint64 m_backlogDropped = 0;
    // This session's frames: its start and the number of the last one logged.
    qint64 m_frameSession = 0;
    quint64 m_frameSeq = 0;
    ClockTimer* m_pendingTimer = nullptr;

    std::optional<LinkStatistics> m_statistics;
    std::optional<StateReport> m_state;
    // Statistics go out at most once a second: the latest, when the second is up.
    // When they last went (the clock's steady microseconds); none yet.
    std::optional<qint64> m_statsPublishedSteadyMicros;
    ClockTimer* m_statsTimer = nullptr;
    ClockTimer* m_restateTimer = nullptr;
    // lastFrameUtcMicros of the station report last published.
    qint64 m_stationLastFrame = -1;
};
