#include "link/broker/BrokerObservation.h"

#include "codec/message/TextFormat.h"
#include "link/broker/MqttClient.h"

BrokerObservation::BrokerObservation(const BrokerSettings& settings, QObject* parent)
    : LinkEvents(parent),
      m_client(new MqttClient(settings, this)),
      m_aircraft(settings.aircraft.isEmpty() ? BrokerTopics::kUnknownAircraft : settings.aircraft)
{
    connect(m_client, &MqttClient::messageReceived, this, &BrokerObservation::messageArrived);
    connect(m_client, &MqttClient::connected, this, &BrokerObservation::brokerConnected);
    connect(m_client, &MqttClient::disconnected, this, &BrokerObservation::brokerDisconnected);
    connect(m_client, &MqttClient::errorOccurred, this, &BrokerObservation::errorOccurred);
    m_client->subscribe(BrokerTopics::aircraftPattern(m_aircraft), 1);
}

BrokerObservation::~BrokerObservation() = default;

void BrokerObservation::start()
{
    if (m_started)
        return;
    m_started = true;
    m_client->start();
    setLinkState(LinkState::Waiting);
    emit started();
}

void BrokerObservation::stop()
{
    if (!m_started)
        return;
    m_started = false;
    m_client->stop();
    setLinkState(LinkState::Closed);
    emit stopped();
}

bool BrokerObservation::isConnected() const
{
    return m_client->isConnected();
}

const BrokerSettings& BrokerObservation::settings() const
{
    return m_client->settings();
}

void BrokerObservation::followStation(const QString& station)
{
    m_followed = station;
}

QString BrokerObservation::followedStation() const
{
    if (!m_followed.isEmpty())
        return m_followed;
    for (const StationReport& r : m_stations)
        if (r.online && r.role == QLatin1String("control"))
            return r.station;
    return m_firstFrameFrom;
}

void BrokerObservation::messageArrived(const QString& topic, const QByteArray& payload)
{
    const std::optional<BrokerTopics::Topic> t = BrokerTopics::parseTopic(topic);
    if (!t || t->aircraft != m_aircraft)
        return;
    switch (t->kind) {
        case BrokerTopics::Kind::Station:
            stationReported(t->station, payload);
            break;
        case BrokerTopics::Kind::Frames:
            frameReported(payload);
            break;
        case BrokerTopics::Kind::State:
            stateReported(payload);
            break;
        case BrokerTopics::Kind::Stats:
            statsReported(payload);
            break;
        case BrokerTopics::Kind::Events:
            eventArrived(payload);
            break;
    }
}

void BrokerObservation::brokerConnected()
{
    emit transportStatusChanged(
        QStringLiteral("broker %1: observing %2").arg(m_client->settings().hostAndPort(), m_aircraft));
}

void BrokerObservation::brokerDisconnected()
{
    // We see nothing of the link until the broker is back; the retained
    // statistics then say how it is.
    setLinkState(LinkState::Lost);
}

void BrokerObservation::stationReported(const QString& station, const QByteArray& payload)
{
    // An empty retained message removes a report.
    if (payload.isEmpty()) {
        if (m_stations.remove(station))
            emit stationsChanged();
        return;
    }
    QString error;
    const std::optional<StationReport> r = StationReport::fromJson(payload, &error);
    if (!r) {
        reportError(QStringLiteral("broker: station %1's report unreadable: %2").arg(station, error));
        return;
    }
    const bool wasFollowed = followedStation() == station;
    m_stations.insert(station, *r);
    emit stationsChanged();
    // The followed station gone (its will, or its goodbye): its link is lost
    // to us, whatever it last said.
    if (wasFollowed && !r->online)
        setLinkState(LinkState::Lost);
}

void BrokerObservation::frameReported(const QByteArray& payload)
{
    QString error;
    const std::optional<FrameReport> r = FrameReport::fromJson(payload, &error);
    if (!r) {
        reportError(QStringLiteral("broker: frame unreadable: ") + error);
        return;
    }
    if (m_firstFrameFrom.isEmpty())
        m_firstFrameFrom = r->station;
    if (r->station != followedStation())
        return;
    // A frame published again after its session ended unacknowledged, or
    // resent by the client library, is told once: a station publishes its
    // frames in order, each way.
    qint64& last = m_lastFrameUtc[r->station + QLatin1Char(r->direction == FrameDirection::Sent ? '>' : '<')];
    if (r->utcMicros <= last)
        return;
    last = r->utcMicros;

    LoggedFrame frame;
    frame.entry.utcMicros = r->utcMicros;
    frame.entry.direction = r->direction;
    frame.entry.transport = r->transport;
    frame.entry.status = r->status;
    frame.entry.enciphered = r->enciphered;
    frame.entry.offset = -1;
    frame.entry.length = quint32(r->bytes.size());
    frame.correctedSymbols = r->corrected;
    frame.messageId = r->messageId;
    frame.bytes = r->bytes;
    emit frameLogged(frame);

    if (r->direction == FrameDirection::Sent) {
        if (r->messageId)
            emit frameSent(*r->messageId);
        return;
    }
    if (r->text.isEmpty())
        return;
    rcm::Corrections corrected;
    if (r->corrected.size() == 2) {
        corrected.block1 = r->corrected[0];
        corrected.block2 = r->corrected[1];
    }
    emitMessage(r->text, r->utcMicros, corrected, r->transport, QStringLiteral("frame from ") + r->station);
}

void BrokerObservation::stateReported(const QByteArray& payload)
{
    if (payload.isEmpty())
        return;
    QString error;
    const std::optional<StateReport> r = StateReport::fromJson(payload, &error);
    if (!r) {
        reportError(QStringLiteral("broker: state unreadable: ") + error);
        return;
    }
    // Usually the status its frame told already; news on joining.
    emitMessage(r->text, r->utcMicros, {}, FrameTransport::Replay, QStringLiteral("last status"));
}

void BrokerObservation::statsReported(const QByteArray& payload)
{
    if (payload.isEmpty())
        return;
    QString error;
    const std::optional<StatsReport> r = StatsReport::fromJson(payload, &error);
    if (!r) {
        reportError(QStringLiteral("broker: statistics unreadable: ") + error);
        return;
    }
    m_statistics = r->toStatistics();
    setLinkState(r->state);
    emit statisticsChanged(*m_statistics);
}

void BrokerObservation::eventArrived(const QByteArray& payload)
{
    QString error;
    const std::optional<EventReport> r = EventReport::fromJson(payload, &error);
    if (!r) {
        reportError(QStringLiteral("broker: event unreadable: ") + error);
        return;
    }
    emit eventReported(*r);
    const QString text = r->station.isEmpty() ? r->text : r->station + QStringLiteral(": ") + r->text;
    if (r->severity == QLatin1String("error") || r->severity == QLatin1String("alarm"))
        emit errorOccurred(text);
    else
        emit transportStatusChanged(text);
}

void BrokerObservation::emitMessage(const QString& text, qint64 utcMicros, rcm::Corrections corrected,
                                    FrameTransport transport, const QString& from)
{
    const std::string utf8 = text.toStdString();
    rcm::ParseResult parsed = rcm::parseMessage(utf8);
    if (!parsed.ok()) {
        reportError(QStringLiteral("broker: %1: text unreadable: %2")
                        .arg(from, QString::fromStdString(parsed.errors.front().toString())));
        return;
    }
    if (m_lastMessage && *m_lastMessage == parsed.message)
        return;
    m_lastMessage = parsed.message;
    ReceivedMessage received;
    received.message = std::move(parsed.message);
    received.corrected = corrected;
    received.utcMicros = utcMicros;
    received.transport = transport;
    emit messageReceived(received);
}

void BrokerObservation::setLinkState(LinkState state)
{
    if (state == m_state)
        return;
    const LinkState before = m_state;
    m_state = state;
    if (m_statistics && m_statistics->state != state) {
        m_statistics->state = state;
        emit statisticsChanged(*m_statistics);
    }
    emit stateChanged(state);
    if (state == LinkState::Lost && (before == LinkState::Connected || before == LinkState::Waiting))
        emit linkLost();
    else if (state == LinkState::Connected && before == LinkState::Lost)
        emit linkRegained();
}

void BrokerObservation::reportError(const QString& message)
{
    if (message == m_lastError)
        return;
    m_lastError = message;
    emit errorOccurred(message);
}
