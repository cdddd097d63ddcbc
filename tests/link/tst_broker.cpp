// A console's session on an MQTT broker (link/broker): the URL, the topics
// and their JSON, and against the real mosquitto on a loopback port the
// publisher, the read-only observer, the will, a broker restarted under a
// running session, passwords and TLS. Every wait is a QSignalSpy or a QTRY_*
// on what the clients say; the broker is started and stopped as a process.

#include "codec/message/TextFormat.h"
#include "codec/secure/StationSigningKey.h"
#include "link/broker/BrokerEnvelope.h"
#include "link/broker/BrokerObservation.h"
#include "link/broker/BrokerSettings.h"
#include "link/broker/BrokerTopics.h"
#include "link/broker/BrokerTrust.h"
#include "link/broker/EnvelopeWriter.h"
#include "link/broker/MqttClient.h"
#include "link/broker/SessionPublisher.h"
#include "link/clock/VirtualClock.h"
#include "link/session/LinkEvents.h"

#include "MosquittoProcess.h"
#include "TcpRelay.h"

#include <QJsonDocument>
#include <QJsonObject>
#include <QSignalSpy>
#include <QTcpServer>
#include <QTcpSocket>
#include <QTest>

#include <memory>
#include <vector>

using rcm::test::MosquittoProcess;
using rcm::test::TcpRelay;

namespace {

constexpr int kTimeoutMs = 10000;
// A broker stopped and started again: the client retries 1 s, 2 s, 3 s ...
// after losing it.
constexpr int kRejoinTimeoutMs = 20000;
constexpr qint64 kT0 = 1764000000000000;  // 2025-11-24T16:00:00Z

const QString kAircraft = QStringLiteral("GB_133");
const QString kStation = QStringLiteral("GB_30226");

BrokerSettings local(quint16 port)
{
    BrokerSettings s;
    s.host = QStringLiteral("127.0.0.1");
    s.port = port;
    return s;
}

QByteArray frameBytes(int seed, int size = 510)
{
    QByteArray b(size, '\0');
    for (int i = 0; i < size; ++i)
        b[i] = char((seed * 31 + i) & 0xFF);
    return b;
}

LoggedFrame loggedFrame(FrameDirection direction, FrameStatus status, qint64 utc, std::optional<quint32> id,
                        const QByteArray& bytes, QList<int> corrected = {})
{
    LoggedFrame f;
    f.entry.utcMicros = utc;
    f.entry.direction = direction;
    f.entry.transport = FrameTransport::Udp;
    f.entry.status = status;
    f.entry.offset = -1;
    f.entry.length = quint32(bytes.size());
    f.messageId = id;
    f.correctedSymbols = std::move(corrected);
    f.bytes = bytes;
    return f;
}

rcm::Message status(quint32 id)
{
    rcm::Message m;
    m.header.set(rcm::ItemId::ID_msg, id);
    m.header.set(rcm::ItemId::ID_UA_source, rcm::Value::station({44, 133}));
    m.header.set(rcm::ItemId::ID_GCS_destination, rcm::Value::station({44, 30226}));
    m.header.set(rcm::ItemId::ID_GCS_backup, rcm::Value::station({44, 41251}));
    m.sense.set(rcm::ItemId::SA_zoom_FWD_cam, 105);
    return m;
}

ReceivedMessage received(quint32 id, qint64 utc)
{
    ReceivedMessage r;
    r.message = status(id);
    r.corrected = {2, 0};
    r.utcMicros = utc;
    r.transport = FrameTransport::Udp;
    return r;
}

// Each station's signing key, made once a run.
std::shared_ptr<const rcm::secure::StationSigningKey> stationKey(const QString& station)
{
    static QHash<QString, std::shared_ptr<const rcm::secure::StationSigningKey>> keys;
    auto& key = keys[station];
    if (!key)
        key = std::make_shared<const rcm::secure::StationSigningKey>(rcm::secure::StationSigningKey::generate());
    return key;
}

// What a station that signs publishes with.
EnvelopeWriter signedAs(const QString& station)
{
    return EnvelopeWriter(station, stationKey(station));
}

// An observer's settings, trusting the keys of `stations`.
BrokerSettings observing(quint16 port, const QStringList& stations)
{
    BrokerSettings s = local(port);
    s.aircraft = kAircraft;
    auto trust = std::make_shared<BrokerTrust>();
    for (const QString& station : stations)
        trust->trustStation(station, stationKey(station)->publicKey());
    s.trust = trust;
    return s;
}

// The report inside an envelope as published (unsealed).
QByteArray bodyOf(const QByteArray& payload)
{
    QString error;
    const std::optional<BrokerEnvelope> e = BrokerEnvelope::fromJson(payload, &error);
    if (!e)
        qWarning("not an envelope: %s", qPrintable(error));
    return e ? e->body : QByteArray();
}

// A plain subscriber, to see what went on the broker.
struct Listener {
    explicit Listener(quint16 port, const QString& pattern)
        : client(local(port)), messages(&client, &MqttClient::messageReceived)
    {
        client.subscribe(pattern, 1);
        client.start();
    }
    // The payloads that came on `topic`, in order.
    QList<QByteArray> on(const QString& topic) const
    {
        QList<QByteArray> out;
        for (const QList<QVariant>& m : messages)
            if (m.at(0).toString() == topic)
                out.append(m.at(1).toByteArray());
        return out;
    }
    // The reports in them (an empty payload stays empty).
    QList<QByteArray> bodies(const QString& topic) const
    {
        QList<QByteArray> out;
        for (const QByteArray& payload : on(topic))
            out.append(payload.isEmpty() ? payload : bodyOf(payload));
        return out;
    }
    MqttClient client;
    QSignalSpy messages;
};

}  // namespace

class TestBroker : public QObject {
    Q_OBJECT

private slots:
    void urlParsing_data();
    void urlParsing();
    void urlErrors_data();
    void urlErrors();
    void topics();
    void jsonRoundTrips();
    void jsonExactText();
    void jsonErrors_data();
    void jsonErrors();
    void stationText();
    void refusedAtStartThenJoins();
    void publisherReachesSubscriber();
    void statisticsThrottled();
    void frameBytesFromReader();
    void observerGetsEveryFrame();
    void willWhenConnectionCut();
    void gracefulFinishSaysOffline();
    void learnedAircraftMovesReports();
    void brokerRestartRejoins();
    void framesLostOnTheWayGoAgain();
    void password();
    void tls();
};

void TestBroker::urlParsing_data()
{
    QTest::addColumn<QString>("url");
    QTest::addColumn<QString>("host");
    QTest::addColumn<int>("port");
    QTest::addColumn<QString>("aircraft");
    QTest::addColumn<QString>("user");
    QTest::addColumn<bool>("tls");
    QTest::addColumn<QString>("canonical");

    QTest::newRow("full") << "mqtt://127.0.0.1:1884/GB_133"
                          << "127.0.0.1" << 1884 << "GB_133"
                          << "" << false << "mqtt://127.0.0.1:1884/GB_133";
    QTest::newRow("default port") << "mqtt://broker.example"
                                  << "broker.example" << 1883 << ""
                                  << "" << false << "mqtt://broker.example:1883";
    QTest::newRow("tls default port") << "mqtts://broker.example/GB_133"
                                      << "broker.example" << 8883 << "GB_133"
                                      << "" << true << "mqtts://broker.example:8883/GB_133";
    QTest::newRow("user") << "mqtt://ops@10.0.0.5:1883/44_133"
                          << "10.0.0.5" << 1883 << "44_133"
                          << "ops" << false << "mqtt://ops@10.0.0.5:1883/44_133";
    QTest::newRow("ipv6") << "mqtt://[::1]:1885"
                          << "::1" << 1885 << ""
                          << "" << false << "mqtt://[::1]:1885";
    QTest::newRow("trailing slash") << "MQTT://h/"
                                    << "h" << 1883 << ""
                                    << "" << false << "mqtt://h:1883";
}

void TestBroker::urlParsing()
{
    QFETCH(QString, url);
    QString error;
    const std::optional<BrokerSettings> s = BrokerSettings::fromUrl(url, &error);
    QVERIFY2(s, qPrintable(error));
    QFETCH(QString, host);
    QFETCH(int, port);
    QFETCH(QString, aircraft);
    QFETCH(QString, user);
    QFETCH(bool, tls);
    QFETCH(QString, canonical);
    QCOMPARE(s->host, host);
    QCOMPARE(int(s->port), port);
    QCOMPARE(s->aircraft, aircraft);
    QCOMPARE(s->user, user);
    QCOMPARE(s->tls, tls);
    QCOMPARE(s->password, QString());
    QCOMPARE(s->url(), canonical);
    QCOMPARE(BrokerSettings::fromUrl(s->url()), s);
}

void TestBroker::urlErrors_data()
{
    QTest::addColumn<QString>("url");
    QTest::addColumn<QString>("error");

    QTest::newRow("port too big") << "mqtt://host:99999"
                                  << "mqtt://host:99999: port must be 1..65535";
    QTest::newRow("port zero") << "mqtt://host:0/GB_133"
                               << "mqtt://host:0/GB_133: port must be 1..65535";
    QTest::newRow("port text") << "mqtt://host:abc"
                               << "mqtt://host:abc: port must be 1..65535";
    QTest::newRow("port empty") << "mqtt://host:"
                                << "mqtt://host:: port must be 1..65535";
    QTest::newRow("scheme") << "http://host"
                            << "http://host: scheme must be mqtt or mqtts, not \"http\"";
    QTest::newRow("no scheme") << "host:1883"
                               << "host:1883: must be mqtt://HOST[:PORT][/AIRCRAFT] or mqtts://...";
    QTest::newRow("empty") << ""
                           << "broker URL: must be mqtt://HOST[:PORT][/AIRCRAFT] or mqtts://...";
    QTest::newRow("no host") << "mqtt://:1883/GB_133"
                             << "mqtt://:1883/GB_133: no host";
    QTest::newRow("two levels") << "mqtt://host/GB_133/x"
                                << "mqtt://host/GB_133/x: aircraft \"GB_133/x\" must be one topic level (no '/', "
                                   "'+' or '#')";
    QTest::newRow("wildcard") << "mqtt://host/+"
                              << "mqtt://host/+: aircraft \"+\" must be one topic level (no '/', "
                                 "'+' or '#')";
    QTest::newRow("password") << "mqtt://ops:secret@host"
                              << "mqtt://ops:***@host: give the password in a file, not in the URL";
    QTest::newRow("empty user") << "mqtt://@host"
                                << "mqtt://@host: empty user before '@'";
    QTest::newRow("ipv6 open") << "mqtt://[::1:1883"
                               << "mqtt://[::1:1883: '[' without ']' around the IPv6 address";
}

void TestBroker::urlErrors()
{
    QFETCH(QString, url);
    QFETCH(QString, error);
    QString said;
    QVERIFY(!BrokerSettings::fromUrl(url, &said));
    QCOMPARE(said, error);
    QVERIFY(!said.contains(QStringLiteral("secret")));
}

void TestBroker::topics()
{
    using namespace BrokerTopics;
    QCOMPARE(stationTopic(kAircraft, kStation), QStringLiteral("rcm/GB_133/station/GB_30226"));
    QCOMPARE(framesTopic(kAircraft, kStation), QStringLiteral("rcm/GB_133/frames/GB_30226"));
    QCOMPARE(stateTopic(kAircraft, kStation), QStringLiteral("rcm/GB_133/state/GB_30226"));
    QCOMPARE(statsTopic(kAircraft, kStation), QStringLiteral("rcm/GB_133/stats/GB_30226"));
    QCOMPARE(eventsTopic(kAircraft, kStation), QStringLiteral("rcm/GB_133/events/GB_30226"));
    QCOMPARE(allStationsPattern(), QStringLiteral("rcm/+/station/+"));
    QCOMPARE(allPattern(Kind::Frames), QStringLiteral("rcm/+/frames/+"));
    QCOMPARE(aircraftPattern(kAircraft), QStringLiteral("rcm/GB_133/#"));
    QCOMPARE(kUnknownAircraft, QStringLiteral("unknown"));

    QCOMPARE(parseTopic(QStringLiteral("rcm/GB_133/station/GB_30226")), (Topic{kAircraft, Kind::Station, kStation}));
    QCOMPARE(parseTopic(QStringLiteral("rcm/GB_133/frames/GB_30226")), (Topic{kAircraft, Kind::Frames, kStation}));
    QCOMPARE(parseTopic(QStringLiteral("rcm/unknown/state/S")),
             (Topic{QStringLiteral("unknown"), Kind::State, QStringLiteral("S")}));
    QCOMPARE(parseTopic(QStringLiteral("rcm/GB_133/stats/GB_30226")), (Topic{kAircraft, Kind::Stats, kStation}));
    QCOMPARE(parseTopic(QStringLiteral("rcm/GB_133/events/GB_30226")), (Topic{kAircraft, Kind::Events, kStation}));
    for (const char* wrong : {"rcm/GB_133", "rcm//frames/S", "xyz/GB_133/frames/S", "rcm/GB_133/station",
                              "rcm/GB_133/station/", "rcm/GB_133/station/a/b", "rcm/GB_133/frames",
                              "rcm/GB_133/other/S", "rcm/+/frames/S", "", "rcm/GB_133/station/#"})
        QVERIFY2(!parseTopic(QString::fromLatin1(wrong)), wrong);
    // What a reader takes on each kind of topic, and in all.
    QCOMPARE(maxPayloadBytes(Kind::Station), 4096);
    QCOMPARE(maxPayloadBytes(Kind::Frames), 16384);
    QCOMPARE(kMaxPacketBytes, 65536);

    for (const LinkState s : {LinkState::Closed, LinkState::Waiting, LinkState::Connected, LinkState::Lost})
        QCOMPARE(linkStateFromName(linkStateName(s)), s);
    QCOMPARE(linkStateName(LinkState::Waiting), QStringLiteral("waiting"));
    QCOMPARE(BrokerTopics::frameStatusName(FrameStatus::Uncorrectable), QStringLiteral("uncorrectable"));
    QCOMPARE(BrokerTopics::frameStatusName(FrameStatus::NotChecked), QStringLiteral("not-checked"));
    QCOMPARE(frameDirectionName(FrameDirection::Sent), QStringLiteral("up"));
    QCOMPARE(frameDirectionName(FrameDirection::Received), QStringLiteral("down"));
    QCOMPARE(BrokerTopics::frameTransportName(FrameTransport::Serial), QStringLiteral("serial"));
    for (int i = 0; i < 5; ++i)
        QCOMPARE(frameStatusFromName(BrokerTopics::frameStatusName(FrameStatus(i))), FrameStatus(i));
    for (int i = 0; i < 4; ++i)
        QCOMPARE(frameTransportFromName(BrokerTopics::frameTransportName(FrameTransport(i))), FrameTransport(i));
    QVERIFY(!frameStatusFromName(QStringLiteral("Decoded")));
    QVERIFY(isStationRole(QStringLiteral("observing")));
    QVERIFY(!isStationRole(QStringLiteral("pilot")));
    QVERIFY(isEventSeverity(QStringLiteral("alarm")));
    QVERIFY(!isEventSeverity(QStringLiteral("fatal")));
}

void TestBroker::jsonRoundTrips()
{
    StationReport station;
    station.station = kStation;
    station.role = QStringLiteral("backup");
    station.link = LinkState::Lost;
    station.description = QStringLiteral("UDP 127.0.0.1:5600");
    station.online = true;
    station.utcMicros = kT0 + 5;
    station.lastFrameUtcMicros = kT0 - 1000000;
    station.destination = QStringLiteral("GB_41251");
    station.backup = kStation;
    QString error;
    QCOMPARE(StationReport::fromJson(station.toJson(), &error), station);

    FrameReport frame;
    frame.station = kStation;
    frame.direction = FrameDirection::Received;
    frame.status = FrameStatus::Corrected;
    frame.utcMicros = kT0;
    frame.messageId = 4294967295u;
    frame.corrected = {3, -1};
    frame.bytes = frameBytes(1);
    frame.text = QString::fromStdString(rcm::formatMessage(status(8)));
    frame.transport = FrameTransport::Serial;
    frame.enciphered = true;
    frame.session = kT0 - 60'000'000;
    frame.seq = 42;
    QCOMPARE(FrameReport::fromJson(frame.toJson(), &error), frame);
    FrameReport up;
    up.station = kStation;
    up.direction = FrameDirection::Sent;
    up.utcMicros = kT0 + 1;
    up.bytes = frameBytes(2, 600);
    QCOMPARE(FrameReport::fromJson(up.toJson(), &error), up);

    StateReport state{kT0 + 7, frame.text, kStation, QStringLiteral("GB_41251")};
    QCOMPARE(StateReport::fromJson(state.toJson(), &error), state);

    LinkStatistics s;
    s.state = LinkState::Connected;
    s.framesSent = 3600;
    s.framesReceived = 3590;
    s.refused[1] = 4;
    s.refused[3] = 2;
    s.correctedBytesBlock1 = 17;
    s.correctedBytesBlock2 = 9;
    s.lastGoodFrameUtcMicros = kT0 + 9;
    s.bytesReceived = 123456;  // not in the report
    const StatsReport stats = StatsReport::of(s);
    QCOMPARE(stats.refused, quint64(6));
    QCOMPARE(StatsReport::fromJson(stats.toJson(), &error), stats);
    const LinkStatistics back = stats.toStatistics();
    QCOMPARE(back.refusedTotal(), quint64(6));
    QCOMPARE(back.framesSent, quint64(3600));
    QCOMPARE(back.bytesReceived, quint64(0));
    QCOMPARE(back.state, LinkState::Connected);

    EventReport event{kT0 + 11, QStringLiteral("alarm"), QStringLiteral("link lost"), kStation};
    QCOMPARE(EventReport::fromJson(event.toJson(), &error), event);
    QCOMPARE(error, QString());
}

void TestBroker::jsonExactText()
{
    FrameReport up;
    up.station = kStation;
    up.direction = FrameDirection::Sent;
    up.status = FrameStatus::NotChecked;
    up.utcMicros = kT0;
    up.messageId = 7;
    up.bytes = QByteArray("\x01\x02\xff", 3);
    up.transport = FrameTransport::Udp;
    QCOMPARE(up.toJson(), QByteArray(R"({"bytes":"AQL/","direction":"up","messageId":7,"station":"GB_30226",)"
                                     R"("status":"not-checked","transport":"udp","utcMicros":1764000000000000})"));

    StationReport r;
    r.station = kStation;
    r.role = QStringLiteral("control");
    r.link = LinkState::Connected;
    r.description = QStringLiteral("UDP 127.0.0.1:5600");
    r.online = false;
    r.utcMicros = kT0;
    r.lastFrameUtcMicros = kT0 - 1;
    r.destination = kStation;
    QCOMPARE(r.toJson(), QByteArray(R"({"backup":"","description":"UDP 127.0.0.1:5600","destination":"GB_30226",)"
                                    R"("lastFrameUtcMicros":1763999999999999,"link":"connected","online":false,)"
                                    R"("role":"control","station":"GB_30226","utcMicros":1764000000000000})"));

    StatsReport s;
    s.framesSent = 2;
    s.state = LinkState::Waiting;
    QCOMPARE(s.toJson(), QByteArray(R"({"correctedBytesBlock1":0,"correctedBytesBlock2":0,"framesReceived":0,)"
                                    R"("framesSent":2,"lastGoodFrameUtcMicros":0,"refused":0,"state":"waiting"})"));
}

void TestBroker::jsonErrors_data()
{
    QTest::addColumn<int>("kind");
    QTest::addColumn<QByteArray>("json");
    QTest::addColumn<QString>("error");

    const QByteArray frame = R"("station":"S","status":"decoded","utcMicros":1,"bytes":"AQID")";
    QTest::newRow("not json") << 1 << QByteArray("{") << "frames: not JSON: unterminated object at byte 1";
    QTest::newRow("array") << 1 << QByteArray("[]") << "frames: not a JSON object";
    QTest::newRow("direction") << 1 << QByteArray("{" + frame + R"(,"direction":"sideways"})")
                               << "frames: direction must be \"up\" or \"down\", not \"sideways\"";
    QTest::newRow("direction missing") << 1 << QByteArray("{" + frame + "}") << "frames: direction is missing";
    QTest::newRow("status") << 1
                            << QByteArray(
                                   R"({"station":"S","direction":"up","status":"Fine","utcMicros":1,"bytes":""})")
                            << "frames: status must be \"decoded\", \"corrected\", \"uncorrectable\", \"rejected\" or "
                               "\"not-checked\", not \"Fine\"";
    QTest::newRow("bytes") << 1
                           << QByteArray(R"({"station":"S","direction":"up","status":"decoded","utcMicros":1,)"
                                         R"("bytes":"A*=="})")
                           << "frames: bytes must be base64";
    QTest::newRow("corrected") << 1 << QByteArray("{" + frame + R"(,"direction":"up","corrected":[1,"x"]})")
                               << "frames: corrected must hold whole numbers -1..255";
    QTest::newRow("messageId") << 1 << QByteArray("{" + frame + R"(,"direction":"up","messageId":-1})")
                               << "frames: messageId must be 0..4294967295, not -1";
    QTest::newRow("time") << 1 << QByteArray(R"({"station":"S","direction":"up","status":"decoded","utcMicros":1.5})")
                          << "frames: utcMicros must be a whole number, not 1.5";
    QTest::newRow("online") << 0
                            << QByteArray(
                                   R"({"station":"S","role":"control","link":"lost","online":"yes","utcMicros":1})")
                            << "station: online must be true or false";
    QTest::newRow("role")
        << 0 << QByteArray(R"({"station":"S","role":"pilot","link":"lost","online":true,"utcMicros":1})")
        << "station: role must be \"control\", \"backup\", \"observing\" or \"unknown\", not \"pilot\"";
    QTest::newRow("link") << 0
                          << QByteArray(R"({"station":"S","role":"backup","link":"up","online":true,"utcMicros":1})")
                          << "station: link must be \"closed\", \"waiting\", \"connected\" or \"lost\", not \"up\"";
    QTest::newRow("station type") << 0 << QByteArray(R"({"station":5})") << "station: station must be a string";
    QTest::newRow("state text") << 2 << QByteArray(R"({"utcMicros":1})") << "state: text is missing";
    QTest::newRow("stats negative") << 3
                                    << QByteArray(R"({"framesSent":-2,"framesReceived":0,"refused":0,)"
                                                  R"("correctedBytesBlock1":0,"correctedBytesBlock2":0,)"
                                                  R"("lastGoodFrameUtcMicros":0,"state":"closed"})")
                                    << "stats: framesSent must be 0..9223372036854775807, not -2";
    QTest::newRow("severity")
        << 4 << QByteArray(R"({"utcMicros":1,"severity":"fatal","text":"x"})")
        << "events: severity must be \"info\", \"warning\", \"error\" or \"alarm\", not \"fatal\"";
}

void TestBroker::jsonErrors()
{
    QFETCH(int, kind);
    QFETCH(QByteArray, json);
    QFETCH(QString, error);
    QString said;
    bool read = true;
    switch (kind) {
        case 0:
            read = StationReport::fromJson(json, &said).has_value();
            break;
        case 1:
            read = FrameReport::fromJson(json, &said).has_value();
            break;
        case 2:
            read = StateReport::fromJson(json, &said).has_value();
            break;
        case 3:
            read = StatsReport::fromJson(json, &said).has_value();
            break;
        case 4:
            read = EventReport::fromJson(json, &said).has_value();
            break;
    }
    QVERIFY(!read);
    QCOMPARE(said, error);
}

void TestBroker::stationText()
{
    rcm::Message m = status(1);
    QCOMPARE(BrokerTopics::stationText(m, rcm::ItemId::ID_UA_source), QStringLiteral("GB_133"));
    QCOMPARE(BrokerTopics::stationText(m, rcm::ItemId::ID_GCS_backup), QStringLiteral("GB_41251"));
    // A dialling code no country has is printed as the number, as the text format does.
    m.header.set(rcm::ItemId::ID_UA_source, rcm::Value::station({999, 7}));
    QCOMPARE(BrokerTopics::stationText(m, rcm::ItemId::ID_UA_source), QStringLiteral("999_7"));
    m.header.erase(rcm::ItemId::ID_UA_source);
    QCOMPARE(BrokerTopics::stationText(m, rcm::ItemId::ID_UA_source), QString());
}

void TestBroker::refusedAtStartThenJoins()
{
    MosquittoProcess broker;
    MqttClient client(local(broker.port()));
    QSignalSpy errors(&client, &MqttClient::errorOccurred);
    QSignalSpy connected(&client, &MqttClient::connected);
    client.start();
    QTRY_COMPARE_WITH_TIMEOUT(errors.count(), 1, kTimeoutMs);
    QCOMPARE(errors.at(0).at(0).toString(),
             QStringLiteral("broker 127.0.0.1:%1: connection refused").arg(broker.port()));
    QVERIFY(!client.isConnected());
    QVERIFY(!client.publish(QStringLiteral("rcm/x/events"), "{}", 1, false));

    // The broker comes up on that port: the client joins by itself, the
    // outage having been reported once, however many attempts it took.
    QVERIFY(broker.start());
    QTRY_COMPARE_WITH_TIMEOUT(connected.count(), 1, kRejoinTimeoutMs);
    QVERIFY(client.isConnected());
    QCOMPARE(errors.count(), 1);
}

void TestBroker::publisherReachesSubscriber()
{
    MosquittoProcess broker;
    QVERIFY(broker.start());
    QTRY_VERIFY_WITH_TIMEOUT(broker.accepts(), kTimeoutMs);

    Listener listener(broker.port(), BrokerTopics::aircraftPattern(kAircraft));
    QSignalSpy listening(&listener.client, &MqttClient::connected);
    QTRY_COMPARE_WITH_TIMEOUT(listening.count(), 1, kTimeoutMs);

    LinkEvents events;
    MqttClient client(local(broker.port()));
    SessionPublisher publisher(&client, kStation, &events);
    publisher.setAircraft(kAircraft);
    publisher.setDescription(QStringLiteral("UDP 127.0.0.1:5600"));
    QSignalSpy connected(&client, &MqttClient::connected);
    QSignalSpy errors(&client, &MqttClient::errorOccurred);
    client.start();
    QTRY_COMPARE_WITH_TIMEOUT(connected.count(), 1, kTimeoutMs);

    const QString stationTopic = BrokerTopics::stationTopic(kAircraft, kStation);
    QTRY_COMPARE_WITH_TIMEOUT(listener.on(stationTopic).size(), 1, kTimeoutMs);
    std::optional<StationReport> report = StationReport::fromJson(listener.bodies(stationTopic).last(), nullptr);
    QVERIFY(report);
    QCOMPARE(report->station, kStation);
    QCOMPARE(report->role, QStringLiteral("unknown"));
    QCOMPARE(report->link, LinkState::Closed);
    QCOMPARE(report->description, QStringLiteral("UDP 127.0.0.1:5600"));
    QCOMPARE(report->online, true);

    publisher.setRole(QStringLiteral("control"), kStation, QStringLiteral("GB_41251"));
    emit events.stateChanged(LinkState::Waiting);
    QTRY_COMPARE_WITH_TIMEOUT(listener.on(stationTopic).size(), 3, kTimeoutMs);
    report = StationReport::fromJson(listener.bodies(stationTopic).last(), nullptr);
    QCOMPARE(report->role, QStringLiteral("control"));
    QCOMPARE(report->link, LinkState::Waiting);
    QCOMPARE(report->destination, kStation);
    QCOMPARE(report->backup, QStringLiteral("GB_41251"));

    // A command up, a status down (corrected), its decoded message, an
    // uncorrectable frame.
    const QByteArray upBytes = frameBytes(10);
    const QByteArray downBytes = frameBytes(11);
    const QByteArray badBytes = frameBytes(12);
    emit events.frameLogged(loggedFrame(FrameDirection::Sent, FrameStatus::NotChecked, kT0, 7, upBytes));
    emit events.frameSent(7);
    emit events.frameLogged(
        loggedFrame(FrameDirection::Received, FrameStatus::Corrected, kT0 + 400000, 8, downBytes, {2, 0}));
    emit events.messageReceived(received(8, kT0 + 400100));
    emit events.frameLogged(
        loggedFrame(FrameDirection::Received, FrameStatus::Uncorrectable, kT0 + 900000, {}, badBytes, {-1, 0}));
    emit events.linkLost();

    const QString framesTopic = BrokerTopics::framesTopic(kAircraft, kStation);
    QTRY_COMPARE_WITH_TIMEOUT(listener.on(framesTopic).size(), 3, kTimeoutMs);
    const QList<QByteArray> frames = listener.bodies(framesTopic);
    QString error;
    const std::optional<FrameReport> up = FrameReport::fromJson(frames[0], &error);
    QVERIFY2(up, qPrintable(error));
    QCOMPARE(up->station, kStation);
    QCOMPARE(up->direction, FrameDirection::Sent);
    QCOMPARE(up->status, FrameStatus::NotChecked);
    QCOMPARE(up->utcMicros, kT0);
    QCOMPARE(up->messageId, std::optional<quint32>(7));
    QCOMPARE(up->corrected, QList<int>{});
    QCOMPARE(up->bytes, upBytes);
    QCOMPARE(up->text, QString());
    QCOMPARE(up->transport, FrameTransport::Udp);
    const std::optional<FrameReport> down = FrameReport::fromJson(frames[1], &error);
    QVERIFY2(down, qPrintable(error));
    QCOMPARE(down->direction, FrameDirection::Received);
    QCOMPARE(down->status, FrameStatus::Corrected);
    QCOMPARE(down->utcMicros, kT0 + 400000);
    QCOMPARE(down->messageId, std::optional<quint32>(8));
    QCOMPARE(down->corrected, (QList<int>{2, 0}));
    QCOMPARE(down->bytes, downBytes);
    QCOMPARE(down->text, QString::fromStdString(rcm::formatMessage(status(8))));
    const std::optional<FrameReport> bad = FrameReport::fromJson(frames[2], &error);
    QVERIFY2(bad, qPrintable(error));
    QCOMPARE(bad->status, FrameStatus::Uncorrectable);
    QCOMPARE(bad->messageId, std::nullopt);
    QCOMPARE(bad->corrected, (QList<int>{-1, 0}));
    QCOMPARE(bad->bytes, badBytes);
    QCOMPARE(bad->text, QString());

    const QString stateTopic = BrokerTopics::stateTopic(kAircraft, kStation);
    QTRY_COMPARE_WITH_TIMEOUT(listener.on(stateTopic).size(), 1, kTimeoutMs);
    const std::optional<StateReport> state = StateReport::fromJson(listener.bodies(stateTopic).last(), &error);
    QVERIFY2(state, qPrintable(error));
    QCOMPARE(state->utcMicros, kT0 + 400100);
    QCOMPARE(state->text, QString::fromStdString(rcm::formatMessage(status(8))));
    QCOMPARE(state->destination, kStation);
    QCOMPARE(state->backup, QStringLiteral("GB_41251"));

    const QString eventsTopic = BrokerTopics::eventsTopic(kAircraft, kStation);
    QTRY_COMPARE_WITH_TIMEOUT(listener.on(eventsTopic).size(), 1, kTimeoutMs);
    const std::optional<EventReport> event = EventReport::fromJson(listener.bodies(eventsTopic).last(), &error);
    QVERIFY2(event, qPrintable(error));
    QCOMPARE(event->severity, QStringLiteral("alarm"));
    QCOMPARE(event->text, QStringLiteral("link lost"));
    QCOMPARE(event->station, kStation);
    publisher.publishEvent(QStringLiteral("warning"), QStringLiteral("key file refused"));
    emit events.errorOccurred(QStringLiteral("udp: cannot bind 0.0.0.0:5600"));
    QTRY_COMPARE_WITH_TIMEOUT(listener.on(eventsTopic).size(), 3, kTimeoutMs);
    QCOMPARE(EventReport::fromJson(listener.bodies(eventsTopic)[1], nullptr)->text, QStringLiteral("key file refused"));
    QCOMPARE(EventReport::fromJson(listener.bodies(eventsTopic)[2], nullptr)->severity, QStringLiteral("error"));

    // A late subscriber finds the station report and the state retained.
    Listener late(broker.port(), BrokerTopics::aircraftPattern(kAircraft));
    QTRY_COMPARE_WITH_TIMEOUT(late.on(stateTopic).size(), 1, kTimeoutMs);
    QTRY_COMPARE_WITH_TIMEOUT(late.on(stationTopic).size(), 1, kTimeoutMs);
    QCOMPARE(StationReport::fromJson(late.bodies(stationTopic)[0], nullptr)->role, QStringLiteral("control"));
    QCOMPARE(late.on(framesTopic).size(), 0);
    QCOMPARE(errors.count(), 0);
}

void TestBroker::statisticsThrottled()
{
    MosquittoProcess broker;
    QVERIFY(broker.start());
    QTRY_VERIFY_WITH_TIMEOUT(broker.accepts(), kTimeoutMs);
    Listener listener(broker.port(), BrokerTopics::aircraftPattern(kAircraft));
    QSignalSpy listening(&listener.client, &MqttClient::connected);
    QTRY_COMPARE_WITH_TIMEOUT(listening.count(), 1, kTimeoutMs);

    LinkEvents events;
    MqttClient client(local(broker.port()));
    const auto clock = std::make_shared<VirtualClock>(kT0);
    SessionPublisher publisher(&client, kStation, &events, nullptr, clock);
    publisher.setAircraft(kAircraft);
    QSignalSpy connected(&client, &MqttClient::connected);
    client.start();
    QTRY_COMPARE_WITH_TIMEOUT(connected.count(), 1, kTimeoutMs);
    const QString stationTopic = BrokerTopics::stationTopic(kAircraft, kStation);
    QTRY_COMPARE_WITH_TIMEOUT(listener.on(stationTopic).size(), 1, kTimeoutMs);

    // What the publisher said before an event of its own, which the
    // listener hears after them: the publisher's timers fire only when the
    // test moves its clock on, so what it has not said by then it never will.
    const QString eventsTopic = BrokerTopics::eventsTopic(kAircraft, kStation);
    const auto heardUpToNow = [&] {
        const qsizetype events = listener.on(eventsTopic).size();
        publisher.publishEvent(QStringLiteral("info"), QStringLiteral("mark"));
        return QTest::qWaitFor([&] { return listener.on(eventsTopic).size() == events + 1; }, kTimeoutMs);
    };

    // Ten changes at once: the first goes, the last follows when the second
    // is up, the eight between are never published.
    LinkStatistics s;
    s.state = LinkState::Connected;
    for (int i = 1; i <= 10; ++i) {
        s.framesReceived = quint64(i);
        s.lastGoodFrameUtcMicros = kT0 + i;
        emit events.statisticsChanged(s);
    }
    const QString topic = BrokerTopics::statsTopic(kAircraft, kStation);
    clock->advance(std::chrono::milliseconds(999));
    QVERIFY(heardUpToNow());
    QCOMPARE(listener.on(topic).size(), 1);
    clock->advance(std::chrono::milliseconds(1));
    QTRY_COMPARE_WITH_TIMEOUT(listener.on(topic).size(), 2, kTimeoutMs);
    QCOMPARE(StatsReport::fromJson(listener.bodies(topic)[0], nullptr)->framesReceived, quint64(1));
    const std::optional<StatsReport> last = StatsReport::fromJson(listener.bodies(topic)[1], nullptr);
    QCOMPARE(last->framesReceived, quint64(10));
    QCOMPARE(last->lastGoodFrameUtcMicros, kT0 + 10);
    QCOMPARE(last->state, LinkState::Connected);
    // The station report keeps up with the last good frame, as often.
    QTRY_COMPARE_WITH_TIMEOUT(listener.on(stationTopic).size(), 3, kTimeoutMs);
    QCOMPARE(StationReport::fromJson(listener.bodies(stationTopic)[1], nullptr)->lastFrameUtcMicros, kT0 + 1);
    QCOMPARE(StationReport::fromJson(listener.bodies(stationTopic)[2], nullptr)->lastFrameUtcMicros, kT0 + 10);
    // And nothing more comes of them.
    clock->advance(std::chrono::seconds(5));
    QVERIFY(heardUpToNow());
    QCOMPARE(listener.on(topic).size(), 2);
    QCOMPARE(listener.on(stationTopic).size(), 3);
}

void TestBroker::frameBytesFromReader()
{
    MosquittoProcess broker;
    QVERIFY(broker.start());
    QTRY_VERIFY_WITH_TIMEOUT(broker.accepts(), kTimeoutMs);
    Listener listener(broker.port(), BrokerTopics::framesTopic(kAircraft, kStation));
    QSignalSpy listening(&listener.client, &MqttClient::connected);
    QTRY_COMPARE_WITH_TIMEOUT(listening.count(), 1, kTimeoutMs);

    LinkEvents events;
    MqttClient client(local(broker.port()));
    SessionPublisher publisher(&client, kStation, &events);
    publisher.setAircraft(kAircraft);
    // A frame in the frame log, its bytes read back from there by the caller.
    QList<qint64> asked;
    publisher.setFrameBytesReader([&asked](const LoggedFrame& f) {
        asked.append(f.entry.offset);
        return frameBytes(int(f.entry.offset), int(f.entry.length));
    });
    QSignalSpy connected(&client, &MqttClient::connected);
    client.start();
    QTRY_COMPARE_WITH_TIMEOUT(connected.count(), 1, kTimeoutMs);

    LoggedFrame inLog = loggedFrame(FrameDirection::Sent, FrameStatus::NotChecked, kT0, 3, {});
    inLog.entry.offset = 4096;
    inLog.entry.length = 600;
    emit events.frameLogged(inLog);
    QTRY_COMPARE_WITH_TIMEOUT(listener.messages.count(), 1, kTimeoutMs);
    QCOMPARE(asked, QList<qint64>{4096});
    QCOMPARE(FrameReport::fromJson(bodyOf(listener.messages.at(0).at(1).toByteArray()), nullptr)->bytes,
             frameBytes(4096, 600));
}

void TestBroker::observerGetsEveryFrame()
{
    MosquittoProcess broker;
    QVERIFY(broker.start());
    QTRY_VERIFY_WITH_TIMEOUT(broker.accepts(), kTimeoutMs);

    LinkEvents events;
    MqttClient client(local(broker.port()));
    SessionPublisher publisher(&client, signedAs(kStation), &events);
    publisher.setAircraft(kAircraft);
    publisher.setRole(QStringLiteral("control"), kStation, {});
    QSignalSpy connected(&client, &MqttClient::connected);
    client.start();
    QTRY_COMPARE_WITH_TIMEOUT(connected.count(), 1, kTimeoutMs);

    const QString backupStation = QStringLiteral("GB_41251");
    BrokerObservation observer(observing(broker.port(), {kStation, backupStation}));
    QSignalSpy logged(&observer, &LinkEvents::frameLogged);
    QSignalSpy messages(&observer, &LinkEvents::messageReceived);
    QSignalSpy sent(&observer, &LinkEvents::frameSent);
    QSignalSpy statistics(&observer, &LinkEvents::statisticsChanged);
    QSignalSpy errors(&observer, &LinkEvents::errorOccurred);
    observer.start();
    // The retained station report arrived: the subscription is in place.
    QTRY_VERIFY_WITH_TIMEOUT(observer.stations().contains(kStation), kTimeoutMs);
    QCOMPARE(observer.stations()[kStation].role, QStringLiteral("control"));
    QCOMPARE(observer.followedStation(), kStation);

    // The backup station publishes its own frames: the observer follows the
    // station in control, and only it.
    LinkEvents backupEvents;
    MqttClient backupClient(local(broker.port()));
    SessionPublisher backup(&backupClient, signedAs(backupStation), &backupEvents);
    backup.setAircraft(kAircraft);
    backup.setRole(QStringLiteral("backup"), kStation, backupStation);
    backupClient.start();
    QTRY_VERIFY_WITH_TIMEOUT(observer.stations().contains(backupStation), kTimeoutMs);
    QCOMPARE(observer.stations()[backupStation].role, QStringLiteral("backup"));
    QCOMPARE(observer.followedStation(), kStation);

    // 50 frames, alternately up and down, each status with its message.
    constexpr int kFrames = 50;
    for (int i = 0; i < kFrames; ++i) {
        const quint32 id = quint32(100 + i);
        const qint64 t = kT0 + qint64(i) * 500000;
        if (i % 10 == 0)
            emit backupEvents.frameLogged(
                loggedFrame(FrameDirection::Sent, FrameStatus::NotChecked, t, id, frameBytes(1000 + i)));
        if (i % 2 == 0) {
            emit events.frameLogged(loggedFrame(FrameDirection::Sent, FrameStatus::NotChecked, t, id, frameBytes(i)));
        } else {
            emit events.frameLogged(
                loggedFrame(FrameDirection::Received, FrameStatus::Decoded, t, id, frameBytes(i), {0, 0}));
            emit events.messageReceived(received(id, t + 50));
        }
    }
    LinkStatistics s;
    s.state = LinkState::Connected;
    s.framesSent = 25;
    s.framesReceived = 25;
    emit events.statisticsChanged(s);

    QTRY_COMPARE_WITH_TIMEOUT(logged.count(), kFrames, kTimeoutMs);
    for (int i = 0; i < kFrames; ++i) {
        const auto f = logged.at(i).at(0).value<LoggedFrame>();
        QCOMPARE(f.bytes, frameBytes(i));
        QCOMPARE(f.entry.utcMicros, kT0 + qint64(i) * 500000);
        QCOMPARE(f.entry.direction, i % 2 == 0 ? FrameDirection::Sent : FrameDirection::Received);
        QCOMPARE(f.entry.status, i % 2 == 0 ? FrameStatus::NotChecked : FrameStatus::Decoded);
        QCOMPARE(f.entry.transport, FrameTransport::Udp);
        QCOMPARE(f.entry.offset, qint64(-1));
        QCOMPARE(f.entry.length, quint32(510));
        QCOMPARE(f.messageId, std::optional<quint32>(quint32(100 + i)));
        QCOMPARE(f.inLog(), false);
    }
    QCOMPARE(sent.count(), kFrames / 2);
    QCOMPARE(sent.at(0).at(0).value<quint32>(), quint32(100));
    // Every status, read back from its text, the retained state adding none.
    QTRY_COMPARE_WITH_TIMEOUT(messages.count(), kFrames / 2, kTimeoutMs);
    for (int k = 0; k < kFrames / 2; ++k) {
        const auto m = messages.at(k).at(0).value<ReceivedMessage>();
        QCOMPARE(m.message, status(quint32(100 + 2 * k + 1)));
        QCOMPARE(m.utcMicros, kT0 + qint64(2 * k + 1) * 500000);
        QCOMPARE(m.corrected, (rcm::Corrections{0, 0}));
    }
    QTRY_VERIFY_WITH_TIMEOUT(
        !statistics.isEmpty() && statistics.last().at(0).value<LinkStatistics>().framesReceived == 25, kTimeoutMs);
    QCOMPARE(statistics.last().at(0).value<LinkStatistics>().state, LinkState::Connected);
    QCOMPARE(logged.count(), kFrames);
    QCOMPARE(errors.count(), 0);
}

void TestBroker::willWhenConnectionCut()
{
    MosquittoProcess broker;
    QVERIFY(broker.start());
    QTRY_VERIFY_WITH_TIMEOUT(broker.accepts(), kTimeoutMs);
    TcpRelay relay(broker.port());

    BrokerObservation observer(observing(broker.port(), {kStation}));
    QSignalSpy stationsChanged(&observer, &BrokerObservation::stationsChanged);
    QSignalSpy lost(&observer, &LinkEvents::linkLost);
    QSignalSpy refused(&observer, &BrokerObservation::messageRefused);
    observer.start();

    LinkEvents events;
    MqttClient client(local(relay.port()));
    SessionPublisher publisher(&client, signedAs(kStation), &events);
    publisher.setAircraft(kAircraft);
    publisher.setRole(QStringLiteral("control"), kStation, {});
    client.start();
    QTRY_VERIFY_WITH_TIMEOUT(observer.stations().value(kStation).online, kTimeoutMs);
    LinkStatistics s;
    s.state = LinkState::Connected;
    emit events.statisticsChanged(s);
    QTRY_VERIFY_WITH_TIMEOUT(observer.statistics() && observer.statistics()->state == LinkState::Connected, kTimeoutMs);

    // The console's connection goes without a goodbye: the broker publishes
    // its will, retained, and the observer sees the station gone and its
    // link lost.
    relay.cut();
    QTRY_VERIFY_WITH_TIMEOUT(!observer.stations().value(kStation).online, kTimeoutMs);
    // The will, made before the client started: the role set by then, the
    // link as it was then.
    const StationReport will = observer.stations().value(kStation);
    QCOMPARE(will.station, kStation);
    QCOMPARE(will.online, false);
    QCOMPARE(will.role, QStringLiteral("control"));
    QCOMPARE(will.destination, kStation);
    QCOMPARE(will.link, LinkState::Closed);
    QTRY_COMPARE_WITH_TIMEOUT(lost.count(), 1, kTimeoutMs);
    // Numbered before the reports that followed it, and taken all the same:
    // each of them named it.
    QCOMPARE(refused.count(), 0);

    // And it stays, retained, for whoever subscribes later.
    Listener late(broker.port(), BrokerTopics::stationTopic(kAircraft, kStation));
    QTRY_COMPARE_WITH_TIMEOUT(late.messages.count(), 1, kTimeoutMs);
    QCOMPARE(StationReport::fromJson(bodyOf(late.messages.at(0).at(1).toByteArray()), nullptr)->online, false);
}

void TestBroker::gracefulFinishSaysOffline()
{
    MosquittoProcess broker;
    QVERIFY(broker.start());
    QTRY_VERIFY_WITH_TIMEOUT(broker.accepts(), kTimeoutMs);

    const QString topic = BrokerTopics::stationTopic(kAircraft, kStation);
    LinkEvents events;
    auto client = std::make_unique<MqttClient>(local(broker.port()));
    SessionPublisher publisher(client.get(), kStation, &events);
    publisher.setAircraft(kAircraft);
    publisher.setRole(QStringLiteral("backup"), QStringLiteral("GB_41251"), kStation);
    QSignalSpy connected(client.get(), &MqttClient::connected);
    QSignalSpy disconnected(client.get(), &MqttClient::disconnected);
    client->start();
    QTRY_COMPARE_WITH_TIMEOUT(connected.count(), 1, kTimeoutMs);
    emit events.stateChanged(LinkState::Connected);

    publisher.finish();
    QCOMPARE(disconnected.count(), 1);
    QCOMPARE(disconnected.at(0).at(0).toString(), QStringLiteral("stopped"));
    QVERIFY(!client->isConnected());
    client.reset();

    Listener late(broker.port(), topic);
    QTRY_COMPARE_WITH_TIMEOUT(late.messages.count(), 1, kTimeoutMs);
    const std::optional<StationReport> r =
        StationReport::fromJson(bodyOf(late.messages.at(0).at(1).toByteArray()), nullptr);
    QVERIFY(r);
    // The goodbye's report, not the will (which says the link was closed).
    QCOMPARE(r->online, false);
    QCOMPARE(r->link, LinkState::Connected);
    QCOMPARE(r->role, QStringLiteral("backup"));
    QCOMPARE(r->destination, QStringLiteral("GB_41251"));
    QCOMPARE(r->backup, kStation);
}

void TestBroker::learnedAircraftMovesReports()
{
    MosquittoProcess broker;
    QVERIFY(broker.start());
    QTRY_VERIFY_WITH_TIMEOUT(broker.accepts(), kTimeoutMs);
    Listener listener(broker.port(), QStringLiteral("rcm/#"));
    QSignalSpy listening(&listener.client, &MqttClient::connected);
    QTRY_COMPARE_WITH_TIMEOUT(listening.count(), 1, kTimeoutMs);

    TcpRelay relay(broker.port());
    LinkEvents events;
    MqttClient client(local(relay.port()));
    SessionPublisher publisher(&client, kStation, &events);
    QSignalSpy connected(&client, &MqttClient::connected);
    QSignalSpy errors(&client, &MqttClient::errorOccurred);
    client.start();
    QTRY_COMPARE_WITH_TIMEOUT(connected.count(), 1, kTimeoutMs);
    const QString unknownTopic = BrokerTopics::stationTopic(QStringLiteral("unknown"), kStation);
    QTRY_COMPARE_WITH_TIMEOUT(listener.on(unknownTopic).size(), 1, kTimeoutMs);
    QCOMPARE(publisher.aircraft(), QStringLiteral("unknown"));

    // The first status names the aircraft: the report under "unknown" is
    // cleared, the client reconnects carrying the will on the new topic.
    emit events.messageReceived(received(1, kT0));
    QCOMPARE(publisher.aircraft(), kAircraft);
    QTRY_COMPARE_WITH_TIMEOUT(connected.count(), 2, kTimeoutMs);
    const QString stationTopic = BrokerTopics::stationTopic(kAircraft, kStation);
    QTRY_VERIFY_WITH_TIMEOUT(!listener.on(stationTopic).isEmpty(), kTimeoutMs);
    // Cleared: an empty retained message, perhaps twice (QoS 1 is at least
    // once: one not acknowledged before the goodbye is sent again).
    const QList<QByteArray> unknown = listener.on(unknownTopic);
    QVERIFY2(unknown.size() == 2 || unknown.size() == 3, unknown.join('|').constData());
    QCOMPARE(StationReport::fromJson(bodyOf(unknown[0]), nullptr)->online, true);
    for (qsizetype i = 1; i < unknown.size(); ++i)
        QCOMPARE(unknown[i], QByteArray());
    QTRY_COMPARE_WITH_TIMEOUT(listener.on(BrokerTopics::stateTopic(kAircraft, kStation)).size(), 1, kTimeoutMs);

    // A crash now: the will is on the aircraft's topic, and "unknown" stays empty.
    relay.cut();
    QTRY_VERIFY_WITH_TIMEOUT(!StationReport::fromJson(listener.bodies(stationTopic).last(), nullptr)->online,
                             kTimeoutMs);
    QCOMPARE(listener.on(unknownTopic), unknown);
    QCOMPARE(errors.count(), 1);
}

void TestBroker::brokerRestartRejoins()
{
    MosquittoProcess broker;
    QVERIFY(broker.start());
    QTRY_VERIFY_WITH_TIMEOUT(broker.accepts(), kTimeoutMs);

    // The publisher through a relay, so that it comes back only after the
    // observer has: frames are not retained, and an observer not yet
    // subscribed again would miss them.
    TcpRelay relay(broker.port());
    LinkEvents events;
    // The session's clock, which the outage is timed on.
    const auto clock = std::make_shared<VirtualClock>(kT0);
    MqttClient client(local(relay.port()), nullptr, clock);
    SessionPublisher publisher(&client, signedAs(kStation), &events, nullptr, clock);
    publisher.setAircraft(kAircraft);
    publisher.setRole(QStringLiteral("control"), kStation, {});
    QSignalSpy connected(&client, &MqttClient::connected);
    QSignalSpy disconnected(&client, &MqttClient::disconnected);
    QSignalSpy errors(&client, &MqttClient::errorOccurred);
    QSignalSpy restored(&client, &MqttClient::restored);
    client.start();

    BrokerObservation observer(observing(broker.port(), {kStation}));
    QSignalSpy logged(&observer, &LinkEvents::frameLogged);
    QSignalSpy observerErrors(&observer, &LinkEvents::errorOccurred);
    QSignalSpy observerLost(&observer, &LinkEvents::linkLost);
    QSignalSpy observerRegained(&observer, &LinkEvents::linkRegained);
    observer.start();
    QTRY_VERIFY_WITH_TIMEOUT(observer.stations().contains(kStation), kTimeoutMs);
    LinkStatistics s;
    s.state = LinkState::Connected;
    s.framesSent = 1;
    emit events.statisticsChanged(s);
    QTRY_VERIFY_WITH_TIMEOUT(observer.statistics() && observer.statistics()->state == LinkState::Connected, kTimeoutMs);
    emit events.frameLogged(loggedFrame(FrameDirection::Sent, FrameStatus::NotChecked, kT0, 1, frameBytes(1)));
    QTRY_COMPARE_WITH_TIMEOUT(logged.count(), 1, kTimeoutMs);

    QVERIFY(broker.stop());
    relay.cut();
    QTRY_COMPARE_WITH_TIMEOUT(disconnected.count(), 1, kTimeoutMs);
    QCOMPARE(errors.count(), 1);
    QCOMPARE(errors.at(0).at(0).toString(), QStringLiteral("broker 127.0.0.1:%1: connection lost").arg(relay.port()));
    QCOMPARE(disconnected.at(0).at(0).toString(), QStringLiteral("connection lost"));
    // The broker is away for 67 s of the session's time.
    clock->advance(std::chrono::seconds(67));
    QTRY_COMPARE_WITH_TIMEOUT(observerErrors.count(), 1, kTimeoutMs);
    QCOMPARE(observerErrors.at(0).at(0).toString(),
             QStringLiteral("broker 127.0.0.1:%1: connection lost").arg(broker.port()));
    QCOMPARE(observer.isConnected(), false);
    // Seeing nothing, the observer calls the link lost.
    QCOMPARE(observerLost.count(), 1);
    QCOMPARE(observer.statistics()->state, LinkState::Lost);

    // The local session goes on: frames logged while the broker is away wait
    // for it, in order.
    for (int i = 2; i <= 5; ++i)
        emit events.frameLogged(
            loggedFrame(FrameDirection::Sent, FrameStatus::NotChecked, kT0 + i, quint32(i), frameBytes(i)));

    // Same port, no persistence: the retained reports are gone until the
    // publisher restates them.
    QVERIFY(broker.start());
    QTRY_VERIFY_WITH_TIMEOUT(observer.isConnected(), kRejoinTimeoutMs);
    QVERIFY(relay.reopen());
    QTRY_COMPARE_WITH_TIMEOUT(connected.count(), 2, kRejoinTimeoutMs);
    Listener late(broker.port(), BrokerTopics::stationTopic(kAircraft, kStation));
    QTRY_COMPARE_WITH_TIMEOUT(late.messages.count(), 1, kTimeoutMs);
    QCOMPARE(StationReport::fromJson(bodyOf(late.messages.at(0).at(1).toByteArray()), nullptr)->role,
             QStringLiteral("control"));
    // The statistics restated: the observer has the link back.
    QTRY_COMPARE_WITH_TIMEOUT(observerRegained.count(), 1, kTimeoutMs);
    QCOMPARE(observer.statistics()->framesSent, quint64(1));

    // The observer's subscription was restored: the frames of the outage
    // reach it, then those after the restart, every one once, in order.
    emit events.frameLogged(loggedFrame(FrameDirection::Sent, FrameStatus::NotChecked, kT0 + 6, 6, frameBytes(6)));
    QTRY_COMPARE_WITH_TIMEOUT(logged.count(), 6, kTimeoutMs);
    for (int i = 0; i < 6; ++i)
        QCOMPARE(logged.at(i).at(0).value<LoggedFrame>().bytes, frameBytes(i + 1));
    QCOMPARE(errors.count(), 1);
    QCOMPARE(observerErrors.count(), 1);
    // Its return, said once, with how long the broker was away.
    QCOMPARE(restored.count(), 1);
    QCOMPARE(restored.at(0).at(0).toString(),
             QStringLiteral("broker 127.0.0.1:%1: back after 1 min 07 s").arg(relay.port()));
    QCOMPARE(restored.at(0).at(1).toLongLong(), 67'000);
}

// Frames the client wrote into a connection that then died, which the
// broker never acknowledged, go again once the client is back: an observer
// gets every frame, once each, in order.
void TestBroker::framesLostOnTheWayGoAgain()
{
    MosquittoProcess broker;
    QVERIFY(broker.start());
    QTRY_VERIFY_WITH_TIMEOUT(broker.accepts(), kTimeoutMs);
    TcpRelay relay(broker.port());

    LinkEvents events;
    MqttClient client(local(relay.port()));
    SessionPublisher publisher(&client, signedAs(kStation), &events);
    publisher.setAircraft(kAircraft);
    QSignalSpy connected(&client, &MqttClient::connected);
    client.start();
    QTRY_COMPARE_WITH_TIMEOUT(connected.count(), 1, kTimeoutMs);

    BrokerObservation observer(observing(broker.port(), {kStation}));
    QSignalSpy logged(&observer, &LinkEvents::frameLogged);
    observer.start();
    QTRY_VERIFY_WITH_TIMEOUT(observer.isConnected(), kTimeoutMs);
    const auto frame = [](int i) {
        return loggedFrame(FrameDirection::Sent, FrameStatus::NotChecked, kT0 + i, quint32(i), frameBytes(i));
    };
    emit events.frameLogged(frame(1));
    QTRY_COMPARE_WITH_TIMEOUT(logged.count(), 1, kTimeoutMs);

    // Written, never delivered, never acknowledged; then the connection dies.
    relay.dropToBroker();
    for (int i = 2; i <= 4; ++i)
        emit events.frameLogged(frame(i));
    QCoreApplication::processEvents();
    relay.cut();
    QVERIFY(relay.reopen());
    QTRY_COMPARE_WITH_TIMEOUT(connected.count(), 2, kRejoinTimeoutMs);
    emit events.frameLogged(frame(5));
    QTRY_COMPARE_WITH_TIMEOUT(logged.count(), 5, kTimeoutMs);
    for (int i = 0; i < 5; ++i)
        QCOMPARE(logged.at(i).at(0).value<LoggedFrame>().bytes, frameBytes(i + 1));
    // Nothing more comes (no frame twice): one more frame is the sixth.
    emit events.frameLogged(frame(6));
    QTRY_COMPARE_WITH_TIMEOUT(logged.count(), 6, kTimeoutMs);
    QCOMPARE(logged.at(5).at(0).value<LoggedFrame>().bytes, frameBytes(6));
}

void TestBroker::password()
{
    MosquittoProcess broker({QStringLiteral("ops"), QStringLiteral("s3cret pass"), false});
    QVERIFY2(broker.start(), qPrintable(broker.setupError()));
    QTRY_VERIFY_WITH_TIMEOUT(broker.accepts(), kTimeoutMs);

    BrokerSettings wrong = local(broker.port());
    wrong.user = QStringLiteral("ops");
    wrong.password = QStringLiteral("guess");
    MqttClient refused(wrong);
    QSignalSpy refusedErrors(&refused, &MqttClient::setupFailed);
    refused.start();
    QTRY_COMPARE_WITH_TIMEOUT(refusedErrors.count(), 1, kTimeoutMs);
    const QString error = refusedErrors.at(0).at(0).toString();
    QCOMPARE(error, QStringLiteral("broker 127.0.0.1:%1: connection refused: not authorized").arg(broker.port()));
    QVERIFY(!error.contains(QStringLiteral("guess")));

    MqttClient anonymous(local(broker.port()));
    QSignalSpy anonymousErrors(&anonymous, &MqttClient::setupFailed);
    anonymous.start();
    QTRY_COMPARE_WITH_TIMEOUT(anonymousErrors.count(), 1, kTimeoutMs);
    QCOMPARE(anonymousErrors.at(0).at(0).toString(), error);

    BrokerSettings right = wrong;
    right.password = QStringLiteral("s3cret pass");
    MqttClient client(right);
    QSignalSpy connected(&client, &MqttClient::connected);
    QSignalSpy errors(&client, &MqttClient::errorOccurred);
    client.subscribe(QStringLiteral("rcm/x/events"), 1);
    QSignalSpy messages(&client, &MqttClient::messageReceived);
    client.start();
    QTRY_COMPARE_WITH_TIMEOUT(connected.count(), 1, kTimeoutMs);
    QVERIFY(client.publish(QStringLiteral("rcm/x/events"), "hello", 1, false));
    QTRY_COMPARE_WITH_TIMEOUT(messages.count(), 1, kTimeoutMs);
    QCOMPARE(messages.at(0).at(1).toByteArray(), QByteArray("hello"));
    QCOMPARE(errors.count(), 0);
    // The refused clients go on trying, and are not told again.
    QCOMPARE(refusedErrors.count(), 1);
}

void TestBroker::tls()
{
    MosquittoProcess broker({{}, {}, true});
    QVERIFY2(broker.start(), qPrintable(broker.setupError()));
    QTRY_VERIFY_WITH_TIMEOUT(broker.accepts(), kTimeoutMs);

    QString urlError;
    std::optional<BrokerSettings> settings =
        BrokerSettings::fromUrl(QStringLiteral("mqtts://127.0.0.1:%1/GB_133").arg(broker.port()), &urlError);
    QVERIFY2(settings, qPrintable(urlError));
    settings->caFile = broker.caFile();
    MqttClient client(*settings);
    QSignalSpy connected(&client, &MqttClient::connected);
    QSignalSpy errors(&client, &MqttClient::errorOccurred);
    QSignalSpy messages(&client, &MqttClient::messageReceived);
    client.subscribe(QStringLiteral("rcm/GB_133/#"), 1);
    client.start();
    QTRY_COMPARE_WITH_TIMEOUT(connected.count(), 1, kTimeoutMs);
    QVERIFY(client.publish(QStringLiteral("rcm/GB_133/events"), "over TLS", 1, false));
    QTRY_COMPARE_WITH_TIMEOUT(messages.count(), 1, kTimeoutMs);
    QCOMPARE(messages.at(0).at(1).toByteArray(), QByteArray("over TLS"));
    QCOMPARE(errors.count(), 0);

    // Another CA: the broker's certificate is not trusted.
    MosquittoProcess other({{}, {}, true});
    QVERIFY2(other.start(), qPrintable(other.setupError()));
    BrokerSettings untrusting = *settings;
    untrusting.caFile = other.caFile();
    MqttClient refused(untrusting);
    QSignalSpy refusedErrors(&refused, &MqttClient::setupFailed);
    refused.start();
    QTRY_COMPARE_WITH_TIMEOUT(refusedErrors.count(), 1, kTimeoutMs);
    const QString error = refusedErrors.at(0).at(0).toString();
    QVERIFY2(error.startsWith(QStringLiteral("broker 127.0.0.1:%1: TLS failed").arg(broker.port())), qPrintable(error));
    QVERIFY2(error.contains(QStringLiteral("certificate verify failed")), qPrintable(error));

    // A CA file that is not there is said at once.
    untrusting.caFile = broker.dir() + QStringLiteral("/none.crt");
    MqttClient missing(untrusting);
    QSignalSpy missingErrors(&missing, &MqttClient::setupFailed);
    missing.start();
    QTRY_COMPARE(missingErrors.count(), 1);
    QCOMPARE(missingErrors.at(0).at(0).toString(),
             QStringLiteral("broker 127.0.0.1:%1: TLS: cannot read \"%2\": no such file")
                 .arg(broker.port())
                 .arg(untrusting.caFile));
}

QTEST_GUILESS_MAIN(TestBroker)
#include "tst_broker.moc"
