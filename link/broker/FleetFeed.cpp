#include "link/broker/FleetFeed.h"

#include "link/broker/BrokerTrust.h"
#include "link/broker/MqttClient.h"

#include <algorithm>
#include <tuple>

FleetFeed::FleetFeed(MqttClient* client, QObject* parent, std::shared_ptr<Clock> clock)
    : QObject(parent),
      m_client(client),
      m_trust(std::make_shared<const BrokerTrust>()),
      m_clock(clock ? std::move(clock) : std::make_shared<SystemClock>()),
      m_expiryTimer(m_clock->createTimer(this))
{
    connect(m_expiryTimer, &ClockTimer::timeout, this, [this] {
        m_expiryTimer->start(std::chrono::milliseconds(kExpiryIntervalMs));
        expireStale();
    });
    m_expiryTimer->start(std::chrono::milliseconds(kExpiryIntervalMs));
    if (!m_client)
        return;
    m_client->setTrust(m_trust);
    connect(m_client, &MqttClient::messageOpened, this, &FleetFeed::handleOpened);
    // The client keeps its subscriptions and sends them again on every
    // reconnection: asking once is enough.
    const QStringList wanted = patterns();
    const int qos[] = {BrokerTopics::kStationQos, BrokerTopics::kStatsQos};
    for (qsizetype i = 0; i < wanted.size(); ++i)
        m_client->subscribe(wanted[i], qos[i]);
}

FleetFeed::~FleetFeed() = default;

void FleetFeed::setTrust(std::shared_ptr<const BrokerTrust> trust)
{
    m_trust = trust ? std::move(trust) : std::make_shared<const BrokerTrust>();
    if (m_client)
        m_client->setTrust(m_trust);
}

QStringList FleetFeed::patterns()
{
    return {BrokerTopics::allStationsPattern(), BrokerTopics::allPattern(BrokerTopics::Kind::Stats)};
}

std::optional<AircraftSummary> FleetFeed::summary(const QString& aircraft) const
{
    const auto found = m_aircraft.constFind(aircraft);
    if (found == m_aircraft.cend())
        return std::nullopt;
    return summarise(aircraft, *found);
}

QList<AircraftSummary> FleetFeed::summaries() const
{
    QStringList names = m_aircraft.keys();
    names.sort();
    QList<AircraftSummary> all;
    all.reserve(names.size());
    for (const QString& name : names)
        all.append(summarise(name, *m_aircraft.constFind(name)));
    return all;
}

void FleetFeed::refuse(const QString& topic, const QString& error)
{
    ++m_refused;
    emit payloadRefused(topic, error);
    emit messageRefused(error);
}

void FleetFeed::updated(const QString& aircraft)
{
    emit aircraftUpdated(summarise(aircraft, m_aircraft[aircraft]));
}

void FleetFeed::handleMessage(const QString& topic, const QByteArray& payload)
{
    const std::optional<BrokerTopics::Topic> where = BrokerTopics::parseTopic(topic);
    if (where && payload.size() > BrokerTopics::maxPayloadBytes(where->kind)) {
        // As the client does: not even copied.
        OpenedMessage m;
        m.topic = topic;
        m.where = where;
        m.refuse(QStringLiteral("too large: %1 bytes on %2, at most %3")
                     .arg(payload.size())
                     .arg(topic)
                     .arg(BrokerTopics::maxPayloadBytes(where->kind)));
        handleOpened(m);
        return;
    }
    handleOpened(m_trust->open(topic, payload, false));
}

void FleetFeed::handleOpened(const OpenedMessage& m)
{
    if (m.refused()) {
        refuse(m.topic, m.refusal);
        return;
    }
    // A session that has not yet heard which aircraft it talks to: not an
    // aircraft of the fleet (it moves to its aircraft's topics once it knows).
    if (m.where->aircraft == BrokerTopics::kUnknownAircraft)
        return;
    const QString& name = m.where->aircraft;
    if (m.cleared) {
        const auto found = m_aircraft.find(name);
        if (found == m_aircraft.end() || m.where->kind != BrokerTopics::Kind::Station)
            return;
        // Nobody can sign an empty message: only an unverified station goes.
        const auto station = found->stations.find(m.station);
        if (station == found->stations.end() || station->second.verified)
            return;
        found->stations.erase(station);
        updated(name);
        return;
    }
    if (m.verified()) {
        switch (m_sequence.check(m)) {
            case SequenceCheck::Result::Duplicate:
                return;
            case SequenceCheck::Result::Replayed:
                refuse(m.topic, SequenceCheck::refusal(m, m_sequence.newest(m.topic)));
                return;
            case SequenceCheck::Result::Fresh:
                break;
        }
    }
    QString error;
    switch (m.where->kind) {
        case BrokerTopics::Kind::Station: {
            Station station;
            station.verified = m.verified();
            station.sealed = m.verified() && !m.opened;
            if (m.opened) {
                std::optional<StationReport> report = StationReport::fromJson(m.body, &error);
                const bool readable = report && report->station == m.station;
                if (!readable && m.verified()) {
                    refuse(m.topic,
                           QStringLiteral("unreadable: %1's station report: %2")
                               .arg(m.station, report ? QStringLiteral("it names %1").arg(report->station) : error));
                    return;
                }
                // Unverified and unreadable: still a station heard of.
                if (readable)
                    station.report = std::move(*report);
            }
            station.report.station = m.station;
            // Keyed by the topic: it is what the broker replaces a retained report by.
            Aircraft& aircraft = m_aircraft[name];
            aircraft.stations[m.station] = std::move(station);
            aircraft.heardMicros = m_clock->utcMicros();
            break;
        }
        case BrokerTopics::Kind::Stats: {
            if (!m.verified() || !m.opened)
                return;
            std::optional<StatsReport> stats = StatsReport::fromJson(m.body, &error);
            if (!stats) {
                refuse(m.topic, QStringLiteral("unreadable: %1's statistics: %2").arg(m.station, error));
                return;
            }
            Aircraft& aircraft = m_aircraft[name];
            aircraft.stats[m.station] = *stats;
            aircraft.heardMicros = m_clock->utcMicros();
            emit statsReported(name, *stats, m.seq);
            break;
        }
        case BrokerTopics::Kind::Frames:
        case BrokerTopics::Kind::State:
        case BrokerTopics::Kind::Events:
            // Not subscribed to: what one aircraft's observer reads, not the fleet.
            return;
    }
    updated(name);
}

void FleetFeed::setLocalStation(const QString& aircraft, const StationReport& report)
{
    const QString before = m_localAircraft;
    m_localAircraft = aircraft == BrokerTopics::kUnknownAircraft ? QString() : aircraft;
    m_local = report;
    if (!before.isEmpty() && before != m_localAircraft && m_aircraft.contains(before))
        updated(before);
    if (m_localAircraft.isEmpty())
        return;
    m_aircraft[m_localAircraft].heardMicros = m_clock->utcMicros();
    updated(m_localAircraft);
}

void FleetFeed::setBrokerReachable(bool reachable)
{
    if (reachable == m_brokerReachable)
        return;
    m_brokerReachable = reachable;
    QStringList names = m_aircraft.keys();
    names.sort();
    for (const QString& name : names)
        updated(name);
}

void FleetFeed::expireStale()
{
    // While the broker is away nothing is heard of anyone: not their fault.
    if (!m_brokerReachable)
        return;
    const qint64 now = m_clock->utcMicros();
    QStringList gone;
    for (auto it = m_aircraft.cbegin(); it != m_aircraft.cend(); ++it)
        if (it.key() != m_localAircraft && now - it->heardMicros > kTimeToLiveMicros)
            gone.append(it.key());
    gone.sort();
    for (const QString& name : gone) {
        m_aircraft.remove(name);
        emit aircraftRemoved(name);
    }
}

AircraftSummary FleetFeed::summarise(const QString& name, const Aircraft& aircraft) const
{
    AircraftSummary s;
    s.aircraft = name;
    s.brokerReachable = m_brokerReachable;
    for (const auto& [station, stats] : aircraft.stats) {
        s.lastFrameUtcMicros = std::max(s.lastFrameUtcMicros, stats.lastGoodFrameUtcMicros);
        s.framesUp += stats.framesSent;
        s.framesDown += stats.framesReceived;
    }
    const bool local = m_local && name == m_localAircraft;
    s.local = local;
    // Who is in control is what the aircraft said last: the newest verified
    // report that knew it, an online station's before any gone one's.
    const StationReport* newest = nullptr;
    const auto rank = [](const StationReport& r) { return std::tuple(r.online, r.utcMicros); };
    const auto consider = [&](const StationReport& report, bool online) {
        ++s.stations;
        s.lastFrameUtcMicros = std::max(s.lastFrameUtcMicros, report.lastFrameUtcMicros);
        if (online) {
            ++s.stationsOnline;
            if (linkRank(report.link) > linkRank(s.link))
                s.link = report.link;
        }
        const bool knows = !report.destination.isEmpty() || !report.backup.isEmpty();
        if (knows && (!newest || rank(report) > rank(*newest)))
            newest = &report;
    };
    for (const auto& [station, entry] : aircraft.stations) {
        // This console's own report comes back from the broker too: ours is the newer.
        if (local && station == m_local->station)
            continue;
        if (!entry.verified) {
            ++s.unverifiedStations;
            continue;
        }
        if (entry.sealed) {
            ++s.sealedStations;
            continue;
        }
        // With the broker away, nobody else's link is known now.
        consider(entry.report, entry.report.online && m_brokerReachable);
    }
    if (local)
        consider(*m_local, m_local->online);
    if (newest) {
        s.inControl = newest->destination;
        s.backup = newest->backup;
    }
    return s;
}
