#include "link/broker/FleetFeed.h"

#include "link/broker/MqttClient.h"

#include <algorithm>
#include <tuple>

namespace {

// What "the best link" means across stations: one connected station is
// enough to reach the aircraft; a lost one says more than one still waiting.
int linkRank(LinkState state)
{
    switch (state) {
        case LinkState::Connected:
            return 3;
        case LinkState::Lost:
            return 2;
        case LinkState::Waiting:
            return 1;
        case LinkState::Closed:
            break;
    }
    return 0;
}

// A frame the receive path delivered: the link's "last good frame".
bool isGood(FrameStatus status)
{
    return status == FrameStatus::Decoded || status == FrameStatus::Corrected;
}

}  // namespace

FleetFeed::FleetFeed(MqttClient* client, QObject* parent) : QObject(parent), m_client(client)
{
    if (!m_client)
        return;
    connect(m_client, &MqttClient::messageReceived, this, &FleetFeed::handleMessage);
    // The client keeps its subscriptions and sends them again on every
    // reconnection: asking once is enough.
    const QStringList wanted = patterns();
    const int qos[] = {BrokerTopics::kStationQos, BrokerTopics::kFramesQos, BrokerTopics::kStatsQos};
    for (qsizetype i = 0; i < wanted.size(); ++i)
        m_client->subscribe(wanted[i], qos[i]);
}

FleetFeed::~FleetFeed() = default;

QStringList FleetFeed::patterns()
{
    const QString anyAircraft = QStringLiteral("+");
    return {BrokerTopics::allStationsPattern(), BrokerTopics::framesTopic(anyAircraft),
            BrokerTopics::statsTopic(anyAircraft)};
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
}

void FleetFeed::handleMessage(const QString& topic, const QByteArray& payload)
{
    const std::optional<BrokerTopics::Topic> parsed = BrokerTopics::parseTopic(topic);
    if (!parsed) {
        refuse(topic, tr("%1: not a topic of the rcm schema").arg(topic));
        return;
    }
    // A session that has not yet heard which aircraft it talks to: not an
    // aircraft of the fleet (it moves to its aircraft's topics once it knows).
    if (parsed->aircraft == BrokerTopics::kUnknownAircraft)
        return;
    QString error;
    switch (parsed->kind) {
        case BrokerTopics::Kind::Station: {
            if (payload.isEmpty()) {
                // A retained report cleared: the station is gone for good.
                const auto found = m_aircraft.find(parsed->aircraft);
                if (found == m_aircraft.end() || found->stations.erase(parsed->station) == 0)
                    return;
                break;
            }
            std::optional<StationReport> report = StationReport::fromJson(payload, &error);
            if (!report) {
                refuse(topic, error);
                return;
            }
            // Keyed by the topic: it is what the broker replaces a retained report by.
            m_aircraft[parsed->aircraft].stations[parsed->station] = std::move(*report);
            break;
        }
        case BrokerTopics::Kind::Frames: {
            std::optional<FrameReport> frame = FrameReport::fromJson(payload, &error);
            if (!frame) {
                refuse(topic, error);
                return;
            }
            Aircraft& aircraft = m_aircraft[parsed->aircraft];
            if (frame->direction == FrameDirection::Sent) {
                ++aircraft.framesUp;
            } else {
                ++aircraft.framesDown;
                if (isGood(frame->status))
                    aircraft.lastDownUtcMicros = std::max(aircraft.lastDownUtcMicros, frame->utcMicros);
            }
            emit frameReported(parsed->aircraft, *frame);
            break;
        }
        case BrokerTopics::Kind::Stats: {
            if (payload.isEmpty())
                return;  // a retained statistics message cleared: nothing to tell
            std::optional<StatsReport> stats = StatsReport::fromJson(payload, &error);
            if (!stats) {
                refuse(topic, error);
                return;
            }
            m_aircraft[parsed->aircraft].stats = std::move(*stats);
            break;
        }
        case BrokerTopics::Kind::State:
        case BrokerTopics::Kind::Events:
            // Not subscribed to: what one aircraft's observer reads, not the fleet.
            return;
    }
    emit aircraftUpdated(summarise(parsed->aircraft, m_aircraft[parsed->aircraft]));
}

AircraftSummary FleetFeed::summarise(const QString& name, const Aircraft& aircraft)
{
    AircraftSummary s;
    s.aircraft = name;
    s.framesUp = aircraft.framesUp;
    s.framesDown = aircraft.framesDown;
    s.lastFrameUtcMicros = aircraft.lastDownUtcMicros;
    if (aircraft.stats)
        s.lastFrameUtcMicros = std::max(s.lastFrameUtcMicros, aircraft.stats->lastGoodFrameUtcMicros);
    // Who is in control is what the aircraft said last: the newest report
    // that knew it, an online station's before any gone one's.
    const StationReport* newest = nullptr;
    const auto rank = [](const StationReport& r) { return std::tuple(r.online, r.utcMicros); };
    for (const auto& [station, report] : aircraft.stations) {
        ++s.stations;
        s.lastFrameUtcMicros = std::max(s.lastFrameUtcMicros, report.lastFrameUtcMicros);
        if (report.online) {
            ++s.stationsOnline;
            if (linkRank(report.link) > linkRank(s.link))
                s.link = report.link;
        }
        const bool knows = !report.destination.isEmpty() || !report.backup.isEmpty();
        if (knows && (!newest || rank(report) > rank(*newest)))
            newest = &report;
    }
    if (newest) {
        s.inControl = newest->destination;
        s.backup = newest->backup;
    }
    return s;
}
