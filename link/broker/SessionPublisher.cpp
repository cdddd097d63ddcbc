#include "link/broker/SessionPublisher.h"

#include "codec/message/TextFormat.h"
#include "link/broker/MqttClient.h"
#include "link/session/LinkEvents.h"

#include <algorithm>

namespace {

// Statistics change with every frame; the broker hears of them at most this often.
constexpr qint64 kStatsIntervalMs = 1000;
// How long a good frame received waits for its decoded message, which the
// link sends just after it, before it goes without its text.
constexpr int kPendingFrameMs = 500;
// Frames kept for the broker while it is away: ten minutes of both ways.
constexpr std::size_t kBacklogFrames = 1200;

bool waitsForMessage(const FrameReport& r)
{
    return r.direction == FrameDirection::Received &&
           (r.status == FrameStatus::Decoded || r.status == FrameStatus::Corrected) && r.messageId.has_value();
}

}  // namespace

SessionPublisher::SessionPublisher(MqttClient* client, const QString& station, const LinkEvents* events,
                                   QObject* parent, std::shared_ptr<Clock> clock)
    : SessionPublisher(client, EnvelopeWriter(station), events, parent, std::move(clock))
{
}

SessionPublisher::SessionPublisher(MqttClient* client, EnvelopeWriter envelopes, const LinkEvents* events,
                                   QObject* parent, std::shared_ptr<Clock> clock)
    : QObject(parent),
      m_clock(clock ? std::move(clock) : std::make_shared<SystemClock>()),
      m_client(client),
      m_envelopes(std::move(envelopes)),
      m_frameBytes([](const LoggedFrame& frame) { return frame.bytes; }),
      m_frameSession(m_clock->utcMicros() / 1000 * 1000),
      m_pendingTimer(m_clock->createTimer(this)),
      m_statsTimer(m_clock->createTimer(this)),
      m_restateTimer(m_clock->createTimer(this))
{
    // While the session lives its report is restated, well before the
    // broker lets the retained one expire.
    connect(m_restateTimer, &ClockTimer::timeout, this, [this] {
        m_restateTimer->start(std::chrono::milliseconds(kRestateIntervalMs));
        publishStation();
    });
    m_restateTimer->start(std::chrono::milliseconds(kRestateIntervalMs));
    connect(m_pendingTimer, &ClockTimer::timeout, this, &SessionPublisher::flushPendingFrame);
    connect(m_statsTimer, &ClockTimer::timeout, this, &SessionPublisher::publishStats);

    if (client) {
        connect(client, &MqttClient::connected, this, &SessionPublisher::clientConnected);
        connect(client, &MqttClient::published, this, &SessionPublisher::acknowledged);
        setWill();
    }
    if (events) {
        connect(events, &LinkEvents::frameLogged, this, &SessionPublisher::frameLogged);
        connect(events, &LinkEvents::messageReceived, this, &SessionPublisher::messageReceived);
        connect(events, &LinkEvents::statisticsChanged, this, &SessionPublisher::statisticsChanged);
        connect(events, &LinkEvents::stateChanged, this, &SessionPublisher::stateChanged);
        connect(events, &LinkEvents::started, this,
                [this] { publishEvent(QStringLiteral("info"), QStringLiteral("link started")); });
        connect(events, &LinkEvents::stopped, this,
                [this] { publishEvent(QStringLiteral("info"), QStringLiteral("link stopped")); });
        connect(events, &LinkEvents::linkLost, this,
                [this] { publishEvent(QStringLiteral("alarm"), QStringLiteral("link lost")); });
        connect(events, &LinkEvents::linkRegained, this,
                [this] { publishEvent(QStringLiteral("info"), QStringLiteral("link regained")); });
        connect(events, &LinkEvents::errorOccurred, this,
                [this](const QString& message) { publishEvent(QStringLiteral("error"), message); });
        connect(events, &LinkEvents::transportStatusChanged, this,
                [this](const QString& status) { publishEvent(QStringLiteral("info"), status); });
        connect(events, &LinkEvents::commandRejected, this, [this](const QString& reasons) {
            publishEvent(QStringLiteral("warning"), QStringLiteral("command refused: ") + reasons);
        });
    }
}

SessionPublisher::~SessionPublisher() = default;

void SessionPublisher::setFrameBytesReader(FrameBytesReader reader)
{
    m_frameBytes = reader ? std::move(reader) : [](const LoggedFrame& frame) { return frame.bytes; };
}

void SessionPublisher::setRole(const QString& role, const QString& destination, const QString& backup)
{
    m_role = BrokerTopics::isStationRole(role) ? role : QStringLiteral("unknown");
    m_destination = destination;
    m_backup = backup;
    willChanged();
    publishStation();
}

void SessionPublisher::setDescription(const QString& description)
{
    if (description == m_description)
        return;
    m_description = description;
    willChanged();
    publishStation();
}

void SessionPublisher::setAircraft(const QString& aircraft)
{
    m_aircraftSet = true;
    if (aircraft == m_aircraft || !BrokerTopics::isTopicLevel(aircraft))
        return;
    // This station's retained reports under the old name would describe it
    // there until they expire: an empty retained message removes them.
    if (m_client) {
        const QString station = m_envelopes.station();
        m_client->publish(BrokerTopics::stationTopic(m_aircraft, station), {}, BrokerTopics::kStationQos, true);
        if (m_statistics)
            m_client->publish(BrokerTopics::statsTopic(m_aircraft, station), {}, BrokerTopics::kStatsQos, true);
        if (m_state)
            m_client->publish(BrokerTopics::stateTopic(m_aircraft, station), {}, BrokerTopics::kStateQos, true);
    }
    m_aircraft = aircraft;
    setWill();
    // Published at once if still connected; otherwise on the reconnection
    // that renews the will, by clientConnected().
    publishEverything();
}

void SessionPublisher::publishEvent(const QString& severity, const QString& text)
{
    if (!m_client)
        return;
    EventReport e;
    e.utcMicros = nowMicros();
    e.severity = BrokerTopics::isEventSeverity(severity) ? severity : QStringLiteral("info");
    e.text = text.size() > kMaxEventText ? text.left(kMaxEventText - 1) + QChar(0x2026) : text;
    e.station = m_envelopes.station();
    publishReport(BrokerTopics::Kind::Events, e.toJson(), BrokerTopics::kEventsQos, false);
}

void SessionPublisher::finish()
{
    if (m_finished)
        return;
    flushPendingFrame();
    if (m_statsTimer->isActive()) {
        m_statsTimer->stop();
        publishStats();
    }
    m_finished = true;
    m_restateTimer->stop();
    emit stationReportChanged(m_aircraft, stationReport());
    if (!m_client)
        return;
    // The same report as the will, said before the goodbye, which makes the
    // broker drop the will.
    publishReport(BrokerTopics::Kind::Station, stationReport().toJson(), BrokerTopics::kStationQos, true);
    m_client->stop();
}

StationReport SessionPublisher::stationReport() const
{
    StationReport r;
    r.station = m_envelopes.station();
    r.role = m_role;
    r.link = m_linkState;
    r.description = m_description;
    r.online = !m_finished;
    r.utcMicros = nowMicros();
    r.lastFrameUtcMicros = m_statistics ? m_statistics->lastGoodFrameUtcMicros : 0;
    r.destination = m_destination;
    r.backup = m_backup;
    return r;
}

void SessionPublisher::clientConnected()
{
    if (m_finished)
        return;
    // Retained state is restated on every connection: the broker may have
    // restarted without it, or the aircraft's topics changed meanwhile. The
    // frames the last session did not see acknowledged go again, first.
    while (!m_unacknowledged.empty()) {
        m_backlog.push_front(std::move(m_unacknowledged.back().second));
        m_unacknowledged.pop_back();
    }
    publishEverything();
}

void SessionPublisher::acknowledged(int messageId)
{
    const auto it = std::find_if(m_unacknowledged.begin(), m_unacknowledged.end(),
                                 [messageId](const auto& sent) { return sent.first == messageId; });
    if (it != m_unacknowledged.end())
        m_unacknowledged.erase(it);
}

void SessionPublisher::publishEverything()
{
    publishStation();
    if (m_statistics)
        publishStats();
    if (m_state)
        publishState();
    sendBacklog();
}

void SessionPublisher::frameLogged(const LoggedFrame& frame)
{
    flushPendingFrame();
    FrameReport r;
    r.station = m_envelopes.station();
    r.session = m_frameSession;
    // Numbered when logged, published or not: a reader sees what it missed.
    r.seq = ++m_frameSeq;
    r.direction = frame.entry.direction;
    r.status = frame.entry.status;
    r.utcMicros = frame.entry.utcMicros;
    r.messageId = frame.messageId;
    r.corrected = frame.correctedSymbols;
    r.bytes = m_frameBytes(frame);
    r.transport = frame.entry.transport;
    r.enciphered = frame.entry.enciphered;
    if (r.enciphered && !m_envelopes.seals()) {
        // A keyed link and nothing to seal with: nothing decrypted goes out,
        // only the frame as it went on the air.
        m_unsealedKeyedLink = true;
        r.messageId.reset();
    }
    if (waitsForMessage(r)) {
        m_pendingFrame = std::move(r);
        m_pendingTimer->start(std::chrono::milliseconds(kPendingFrameMs));
        return;
    }
    publishFrame(r);
}

void SessionPublisher::messageReceived(const ReceivedMessage& received)
{
    const rcm::Message& m = received.message;
    if (!m_aircraftSet && m_aircraft == BrokerTopics::kUnknownAircraft) {
        const QString aircraft = BrokerTopics::stationText(m, rcm::ItemId::ID_UA_source);
        if (BrokerTopics::isTopicLevel(aircraft)) {
            setAircraft(aircraft);
            // Learned, not set: a later status may not move it again, but
            // the caller may.
            m_aircraftSet = false;
        }
    }

    const QString text = QString::fromStdString(rcm::formatMessage(m));
    if (m_pendingFrame && m_pendingFrame->messageId == quint32(m.header.number(rcm::ItemId::ID_msg)))
        m_pendingFrame->text = text;
    flushPendingFrame();
    if (m_unsealedKeyedLink)
        return;

    const QString destination = BrokerTopics::stationText(m, rcm::ItemId::ID_GCS_destination);
    const QString backup = BrokerTopics::stationText(m, rcm::ItemId::ID_GCS_backup);
    bool stationChanged = false;
    if (!destination.isEmpty() && destination != m_destination) {
        m_destination = destination;
        stationChanged = true;
    }
    if (!backup.isEmpty() && backup != m_backup) {
        m_backup = backup;
        stationChanged = true;
    }
    if (stationChanged)
        publishStation();

    StateReport s;
    s.utcMicros = received.utcMicros;
    s.text = text;
    s.destination = destination;
    s.backup = backup;
    m_state = s;
    publishState();
}

void SessionPublisher::statisticsChanged(const LinkStatistics& statistics)
{
    m_statistics = statistics;
    const qint64 sinceStatsMs =
        m_statsPublishedSteadyMicros ? (m_clock->steadyMicros() - *m_statsPublishedSteadyMicros) / 1000 : 0;
    if (!m_statsPublishedSteadyMicros || sinceStatsMs >= kStatsIntervalMs) {
        m_statsTimer->stop();
        publishStats();
    } else if (!m_statsTimer->isActive()) {
        m_statsTimer->start(std::chrono::milliseconds(kStatsIntervalMs - sinceStatsMs));
    }
}

void SessionPublisher::stateChanged(LinkState state)
{
    if (state == m_linkState)
        return;
    m_linkState = state;
    publishStation();
}

void SessionPublisher::flushPendingFrame()
{
    m_pendingTimer->stop();
    if (!m_pendingFrame)
        return;
    const FrameReport r = std::move(*m_pendingFrame);
    m_pendingFrame.reset();
    publishFrame(r);
}

void SessionPublisher::publishFrame(const FrameReport& report)
{
    if (!m_client || m_finished)
        return;
    m_backlog.push_back(report);
    if (m_backlog.size() + m_unacknowledged.size() > kBacklogFrames) {
        if (!m_unacknowledged.empty())
            m_unacknowledged.pop_front();
        else
            m_backlog.pop_front();
        ++m_backlogDropped;
    }
    sendBacklog();
}

void SessionPublisher::sendBacklog()
{
    // Under "unknown" an observer of the aircraft would never see them.
    if (!m_client || (!m_aircraftSet && m_aircraft == BrokerTopics::kUnknownAircraft))
        return;
    int messageId = 0;
    // Each goes in a new envelope, with a new number, even when it goes
    // again: a reader takes a station's messages in increasing number only.
    while (!m_backlog.empty() && publishReport(BrokerTopics::Kind::Frames, m_backlog.front().toJson(),
                                               BrokerTopics::kFramesQos, false, &messageId)) {
        m_unacknowledged.emplace_back(messageId, std::move(m_backlog.front()));
        m_backlog.pop_front();
    }
    if (m_backlogDropped && m_backlog.empty()) {
        publishEvent(QStringLiteral("warning"),
                     QStringLiteral("%1 frames were not published: the broker was away longer than %2 frames")
                         .arg(m_backlogDropped)
                         .arg(kBacklogFrames));
        m_backlogDropped = 0;
    }
}

void SessionPublisher::publishStats()
{
    if (!m_statistics || m_finished)
        return;
    m_statsPublishedSteadyMicros = m_clock->steadyMicros();
    if (!m_client)
        return;
    publishReport(BrokerTopics::Kind::Stats, StatsReport::of(*m_statistics).toJson(), BrokerTopics::kStatsQos, true);
    // The station report says when the last good frame came: kept as fresh
    // as the statistics, for a fleet view that reads only the reports.
    if (m_statistics->lastGoodFrameUtcMicros != m_stationLastFrame)
        publishStation();
}

void SessionPublisher::publishStation()
{
    if (m_finished)
        return;
    const StationReport r = stationReport();
    emit stationReportChanged(m_aircraft, r);
    if (m_client && publishReport(BrokerTopics::Kind::Station, r.toJson(), BrokerTopics::kStationQos, true))
        m_stationLastFrame = r.lastFrameUtcMicros;
}

void SessionPublisher::publishState()
{
    if (m_client && m_state && !m_finished)
        publishReport(BrokerTopics::Kind::State, m_state->toJson(), BrokerTopics::kStateQos, true);
}

bool SessionPublisher::publishReport(BrokerTopics::Kind kind, const QByteArray& body, int qos, bool retain,
                                     int* messageId)
{
    if (!m_client || !m_client->isConnected())
        return false;
    const QString topic = BrokerTopics::topic(m_aircraft, kind, m_envelopes.station());
    // Station reports say which will is set now, so that a reader takes it
    // when the broker publishes it, and no older one.
    const qint64 willSeq = kind == BrokerTopics::Kind::Station ? m_willSeq : 0;
    return m_client->publish(topic, m_envelopes.wrap(topic, body, false, willSeq), qos, retain, messageId,
                             BrokerTopics::kMessageExpirySeconds);
}

void SessionPublisher::willChanged()
{
    // Before the client starts the will costs nothing to change, so it says
    // who this station is as fully as it can; later, only a new aircraft is
    // worth a new connection (setAircraft).
    if (m_client && !m_client->isStarted())
        setWill();
}

void SessionPublisher::setWill()
{
    if (!m_client)
        return;
    StationReport will = stationReport();
    will.online = false;
    const QString topic = BrokerTopics::stationTopic(m_aircraft, m_envelopes.station());
    m_willSeq = m_envelopes.nextSeq();
    m_client->setWill(topic, m_envelopes.wrapNumbered(topic, will.toJson(), m_willSeq, true, 0), true,
                      BrokerTopics::kMessageExpirySeconds);
}

qint64 SessionPublisher::nowMicros() const
{
    // Milliseconds, as the reports always said.
    return m_clock->utcMicros() / 1000 * 1000;
}
