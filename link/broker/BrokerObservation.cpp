#include "link/broker/BrokerObservation.h"

#include "codec/message/TextFormat.h"
#include "link/broker/BrokerTrust.h"
#include "link/broker/MqttClient.h"

#include <QRandomGenerator>

namespace {

BrokerSettings observerSettings(BrokerSettings settings, const QString& aircraft)
{
    // A persistent session, under a name of its own: the broker keeps what
    // comes for the observer while either is away.
    if (settings.clientId.isEmpty())
        settings.clientId = QStringLiteral("rcm-observer-%1-%2")
                                .arg(aircraft)
                                .arg(QRandomGenerator::global()->generate(), 8, 16, QLatin1Char('0'));
    settings.persistentSession = true;
    return settings;
}

}  // namespace

BrokerObservation::BrokerObservation(const BrokerSettings& settings, QObject* parent, std::shared_ptr<Clock> clock)
    : Observation(parent), m_aircraft(settings.aircraft.isEmpty() ? BrokerTopics::kUnknownAircraft : settings.aircraft)
{
    m_client = new MqttClient(observerSettings(settings, m_aircraft), this, std::move(clock));
    m_client->setTrust(settings.trust ? settings.trust : std::make_shared<const BrokerTrust>());
    connect(m_client, &MqttClient::messageOpened, this, &BrokerObservation::messageOpened);
    connect(m_client, &MqttClient::connected, this, &BrokerObservation::brokerConnected);
    connect(m_client, &MqttClient::disconnected, this, &BrokerObservation::brokerDisconnected);
    connect(m_client, &MqttClient::errorOccurred, this, &BrokerObservation::errorOccurred);
    connect(m_client, &MqttClient::setupFailed, this, &BrokerObservation::errorOccurred);
    connect(m_client, &MqttClient::refusedByBroker, this, &BrokerObservation::errorOccurred);
    connect(m_client, &MqttClient::restored, this,
            [this](const QString& message) { emit transportStatusChanged(message); });
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

QStringList BrokerObservation::unverifiedStations() const
{
    QStringList names(m_unverified.cbegin(), m_unverified.cend());
    names.sort();
    return names;
}

void BrokerObservation::followStation(const QString& station)
{
    m_followed = station;
    followedChanged();
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

void BrokerObservation::refuse(const QString& reasonAndDetail)
{
    ++m_refused;
    emit messageRefused(reasonAndDetail);
}

template <typename Report>
std::optional<Report> BrokerObservation::readReport(const OpenedMessage& message, const char* what)
{
    QString error;
    std::optional<Report> r = Report::fromJson(message.body, &error);
    if (!r)
        refuse(QStringLiteral("unreadable: %1's %2: %3").arg(message.station, QLatin1String(what), error));
    return r;
}

template <typename Report>
void BrokerObservation::keepNewest(const OpenedMessage& message, const char* what, QHash<QString, Report>& newest,
                                   void (BrokerObservation::*apply)(const Report&))
{
    const std::optional<Report> r = readReport<Report>(message, what);
    if (!r)
        return;
    newest.insert(message.station, *r);
    if (message.station == followedStation())
        (this->*apply)(*r);
}

void BrokerObservation::messageOpened(const OpenedMessage& message)
{
    if (message.refused()) {
        refuse(message.refusal);
        return;
    }
    if (!message.where || message.where->aircraft != m_aircraft)
        return;
    const QString& station = message.station;
    if (message.cleared) {
        // Nobody can sign an empty message: a verified station's report
        // stays until a signed one replaces it; an unverified one goes.
        if (!m_stations.contains(station) && m_unverified.remove(station))
            emit stationsChanged();
        return;
    }
    if (!message.verified()) {
        noteUnverified(station);
        return;
    }
    switch (m_sequence.check(message)) {
        case SequenceCheck::Result::Duplicate:
            return;
        case SequenceCheck::Result::Replayed:
            refuse(SequenceCheck::refusal(message, m_sequence.newest(message.topic)));
            return;
        case SequenceCheck::Result::Fresh:
            break;
    }
    if (!message.opened) {
        noteSealed(station, message.keyFingerprint);
        return;
    }
    switch (message.where->kind) {
        case BrokerTopics::Kind::Station:
            stationReported(message);
            break;
        case BrokerTopics::Kind::Frames:
            frameReported(message);
            break;
        case BrokerTopics::Kind::State:
            keepNewest(message, "state", m_states, &BrokerObservation::applyState);
            break;
        case BrokerTopics::Kind::Stats:
            keepNewest(message, "statistics", m_stats, &BrokerObservation::applyStats);
            break;
        case BrokerTopics::Kind::Events:
            eventArrived(message);
            break;
    }
}

void BrokerObservation::noteUnverified(const QString& station)
{
    if (m_unverified.contains(station))
        return;
    m_unverified.insert(station);
    emit stationsChanged();
    emit warning(QStringLiteral("broker: %1 publishes for %2 unverified (its key is not trusted here): not shown; "
                                "trust its key (--broker-trust) to observe it")
                     .arg(station, m_aircraft));
}

void BrokerObservation::noteSealed(const QString& station, const QString& fingerprint)
{
    if (m_sealed.value(station) == fingerprint)
        return;
    m_sealed.insert(station, fingerprint);
    emit stationsChanged();
    emit warning(QStringLiteral("broker: %1's session with %2 is keyed and sealed (key fingerprint %3): give that "
                                "key (--key) to observe it")
                     .arg(station, m_aircraft, fingerprint));
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

void BrokerObservation::stationReported(const OpenedMessage& message)
{
    QString error;
    const std::optional<StationReport> r = StationReport::fromJson(message.body, &error);
    if (!r || r->station != message.station) {
        refuse(QStringLiteral("unreadable: %1's station report: %2")
                   .arg(message.station, r ? QStringLiteral("it names %1").arg(r->station) : error));
        return;
    }
    const bool wasFollowed = followedStation() == message.station;
    m_sealed.remove(message.station);
    m_stations.insert(message.station, *r);
    emit stationsChanged();
    // The followed station gone (its will, or its goodbye): its link is lost
    // to us, whatever it last said.
    if (wasFollowed && !r->online)
        setLinkState(LinkState::Lost);
    followedChanged();
}

void BrokerObservation::followedChanged()
{
    const QString followed = followedStation();
    if (followed == m_lastFollowed)
        return;
    m_lastFollowed = followed;
    if (followed.isEmpty())
        return;
    // What the newly followed station said last, which was kept aside.
    if (const auto stats = m_stats.constFind(followed); stats != m_stats.cend())
        applyStats(*stats);
    if (const auto state = m_states.constFind(followed); state != m_states.cend())
        applyState(*state);
}

void BrokerObservation::frameReported(const OpenedMessage& message)
{
    const std::optional<FrameReport> r = readReport<FrameReport>(message, "frame");
    if (!r)
        return;
    if (m_firstFrameFrom.isEmpty()) {
        m_firstFrameFrom = message.station;
        followedChanged();
    }
    if (message.station != followedStation())
        return;
    // A frame published again after its session ended unacknowledged, or
    // delivered twice, is told once; frames that never came are said.
    FrameRun& run = m_frameRuns[message.station];
    if (r->seq != 0) {
        if (r->session == run.session && r->seq <= run.last)
            return;
        if (r->session == run.session && r->seq > run.last + 1) {
            const quint64 missed = r->seq - run.last - 1;
            m_missedFrames += missed;
            emit warning(QStringLiteral("broker: missed %1 frame%2 of %3 (its frames %4 to %5 never came)")
                             .arg(missed)
                             .arg(missed == 1 ? QString() : QStringLiteral("s"))
                             .arg(message.station)
                             .arg(run.last + 1)
                             .arg(r->seq - 1));
        }
        run.session = r->session;
        run.last = r->seq;
    }

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
    emitMessage(r->text, r->utcMicros, corrected, r->transport, QStringLiteral("frame from ") + message.station);
}

void BrokerObservation::applyState(const StateReport& state)
{
    // Usually the status its frame told already; news on joining.
    emitMessage(state.text, state.utcMicros, {}, FrameTransport::Replay, QStringLiteral("last status"));
}

void BrokerObservation::applyStats(const StatsReport& stats)
{
    m_statistics = stats.toStatistics();
    setLinkState(stats.state);
    emit statisticsChanged(*m_statistics);
}

void BrokerObservation::eventArrived(const OpenedMessage& message)
{
    std::optional<EventReport> r = readReport<EventReport>(message, "event");
    if (!r)
        return;
    // The event is its signer's, whatever its text says.
    r->station = message.station;
    emit eventReported(*r);
    const QString text = r->station + QStringLiteral(": ") + r->text;
    const bool followed = message.station == followedStation();
    if (followed && (r->severity == QLatin1String("error") || r->severity == QLatin1String("alarm")))
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
