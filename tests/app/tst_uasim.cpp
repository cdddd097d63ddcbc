// The simulated aircraft: first frame by frame on its own clock; then flown
// by the console's worker in simulated time (AircraftFixture); then the
// built `uasim` program over UDP, spoken to as the console would, with one
// link and with two stations (docs/protocol.md section 10). The program
// checks wait on signals and conditions, never on a time.
#include "codec/message/Airframe.h"
#include "codec/message/FlightPlanTransfer.h"
#include "codec/message/MessageDecoder.h"
#include "codec/message/MessageEncoder.h"
#include "codec/secure/SecureCodec.h"
#include "link/aircraft/SimulatedAircraft.h"
#include "link/framelog/FrameLogReader.h"
#include "link/session/LinkWorker.h"
#include "link/transport/UdpLink.h"

#include "AircraftFixture.h"
#include "UasimProcess.h"

#include <QNetworkDatagram>
#include <QSignalSpy>
#include <QTemporaryDir>
#include <QDateTime>
#include <QUdpSocket>
#include <QtTest>

#include <chrono>
#include <memory>
#include <optional>

using namespace rcm;
using namespace std::chrono_literals;

namespace {

// 2026-11-22 07:32:05 UTC.
const std::chrono::system_clock::time_point kSomeUtc =
    std::chrono::sys_days{std::chrono::year{2026} / 11 / 22} + 7h + 32min + 5s;

constexpr unsigned kOff = 1, kOn = 2;
constexpr unsigned kOut = 1, kRetracted = 2;
constexpr unsigned kNone = 1, kTake = 2;

// One status frame a second: what uasim does between two frames.
Message nextStatus(SimulatedAircraft& aircraft)
{
    aircraft.advance(1000ms);
    const Message status = aircraft.status(kSomeUtc);
    aircraft.statusSent();
    return status;
}

QByteArray joined(const std::vector<std::string>& lines)
{
    QByteArray out;
    for (const auto& l : lines)
        out += QByteArray::fromStdString(l) + '\n';
    return out;
}

// Generous: only a bound for a broken build; the process tests wait on what
// arrives, a status frame or two at uasim's own 1 Hz.
constexpr int kPatienceMs = 30000;

// The built uasim spoken to as the console would: one command per status
// frame received, so the exchange runs at uasim's own cadence and the test
// waits only on what arrives.
class UasimRun : public QObject {
public:
    explicit UasimRun(const QStringList& extraArguments = {}) : uasim(extraArguments)
    {
        m_socket.bind(QHostAddress::LocalHost, 0);
        QObject::connect(&m_socket, &QUdpSocket::readyRead, this, [this] { receive(); });
        command = restingCommand(Airframe::wellEquipped());
        command.header.set(ItemId::ID_UA_source, Value::station({44, 133}));
    }

    void send()
    {
        Message m = command;
        m.header.set(ItemId::ID_msg, m_nextId++);
        // Stamped now: uasim's receive path refuses a command without its
        // time, or outside the window of its clock.
        const QDateTime now = QDateTime::currentDateTimeUtc();
        const QTime t = now.time();
        const QDate d = now.date();
        m.header.set(ItemId::time_UTC, std::int64_t(t.hour() * 10000 + t.minute() * 100 + t.second()));
        m.header.set(ItemId::date_UTC, std::int64_t((d.year() % 100) * 10000 + d.month() * 100 + d.day()));
        Diagnostics errors;
        const auto datagram = encodeDatagram(m, errors);
        QVERIFY2(datagram, errors.empty() ? "" : errors.front().toString().c_str());
        m_socket.writeDatagram(reinterpret_cast<const char*>(datagram->data()), qint64(datagram->size()),
                               QHostAddress::LocalHost, uasim.port());
    }

    test::UasimProcess uasim;
    Message command;
    std::vector<DecodeResult> statuses;

private:
    void receive()
    {
        while (m_socket.hasPendingDatagrams()) {
            const QByteArray bytes = m_socket.receiveDatagram().data();
            statuses.push_back(
                decodeFrame({reinterpret_cast<const std::uint8_t*>(bytes.constData()), std::size_t(bytes.size())}));
            send();
        }
    }

    QUdpSocket m_socket;
    std::uint32_t m_nextId = 0;
};

// The console's worker against the simulated aircraft, in simulated time;
// `statuses` are the status frames the console received.
struct Flight {
    explicit Flight(test::AircraftFixture::Options options = {})
        : fixture(std::move(options)), statuses(fixture.console.get(), &LinkWorker::messageReceived)
    {
        command = restingCommand(Airframe::wellEquipped());
        command.header.set(ItemId::ID_UA_source, Value::station({44, 133}));
    }
    // From the next frame on.
    void setCommand() { fixture.console->setCommand(command); }
    void start()
    {
        setCommand();
        fixture.start();
    }
    Message status(qsizetype i) const { return statuses.at(i).at(0).value<ReceivedMessage>().message; }
    Message latest() const { return status(statuses.count() - 1); }

    test::AircraftFixture fixture;
    QSignalSpy statuses;
    Message command;
};

// The two ground stations of the multi-station cases.
constexpr StationId kGb30226{44, 30226};
constexpr StationId kGb41251{44, 41251};

// A ground station's console, as far as the aircraft can tell: a worker
// over its own UDP socket to one of uasim's channels, sending once a second
// on the system clock, under `key` when given, with a flight plan once one
// is given to upload. `statuses` are the status frames it received.
class StationClient {
public:
    explicit StationClient(quint16 uasimPort, const QString& key = {})
        : worker(std::make_unique<UdpLink>(QHostAddress::LocalHost, 0, QHostAddress::LocalHost, uasimPort), nullptr,
                 options(key, this)),
          statuses(&worker, &LinkWorker::messageReceived)
    {
    }

    // From the next frame on, a section a frame until acknowledged.
    void upload(std::uint32_t planId, std::size_t bytes)
    {
        std::vector<std::uint8_t> plan(bytes);
        for (std::size_t i = 0; i < plan.size(); ++i)
            plan[i] = static_cast<std::uint8_t>(i * 3 + planId);
        uploader = std::make_unique<FlightPlanUploader>(planId, plan);
    }

    // From the next frame on: the stations named, the gear, the right wing light.
    void command(StationId destination, StationId backup, unsigned gear = kOut, unsigned wingLight = kOff)
    {
        Message m = restingCommand(Airframe::wellEquipped());
        m.header.set(ItemId::ID_UA_source, Value::station({44, 133}));
        m.header.set(ItemId::ID_GCS_destination, Value::station(destination));
        m.header.set(ItemId::ID_GCS_backup, Value::station(backup));
        for (int wheel = 0; wheel < 4; ++wheel)
            m.settings.setFieldCode(ItemId::land_wheels, wheel, gear);
        m.settings.setFieldCode(ItemId::lights, 0, wingLight);
        worker.setCommand(m);
    }
    Message status(qsizetype i) const { return statuses.at(i).at(0).value<ReceivedMessage>().message; }
    Message latest() const { return status(statuses.count() - 1); }
    // Whether the last status frame names `control` in control and `backup` the backup.
    bool latestNames(StationId control, StationId backup) const
    {
        if (statuses.isEmpty())
            return false;
        const Message m = latest();
        const Value* d = m.header.find(ItemId::ID_GCS_destination);
        const Value* b = m.header.find(ItemId::ID_GCS_backup);
        return d && b && *d == Value::station(control) && *b == Value::station(backup);
    }
    unsigned latestGear() const { return latest().settings.fieldCode(ItemId::land_wheels, 0); }
    unsigned latestWingLight() const { return latest().settings.fieldCode(ItemId::lights, 0); }

    std::unique_ptr<FlightPlanUploader> uploader;  // before the worker that calls it
    LinkWorker worker;
    QSignalSpy statuses;

private:
    static LinkWorker::Options options(const QString& key, StationClient* client)
    {
        LinkWorker::Options o;
        o.block2Source = [client]() -> std::optional<FlightPlanSection> {
            return client->uploader ? client->uploader->next() : std::nullopt;
        };
        o.block2Reply = [client](const FlightPlanSection& reply) {
            if (client->uploader)
                client->uploader->handleReply(reply);
        };
        if (!key.isEmpty()) {
            // Its counter in memory: two clients may hold the same key.
            secure::SecureEndpoint::Options e;
            e.persistState = false;
            std::string error;
            o.secure = secure::SecureEndpoint::open(key.toStdString(), secure::Direction::GcsToUa, error, e);
            if (!o.secure)
                qFatal("%s", error.c_str());
        }
        return o;
    }
};

QString makeKey(const QTemporaryDir& dir, const char* name)
{
    const QString path = dir.filePath(QLatin1String(name));
    std::string error;
    if (!secure::writeKeyFile(path.toStdString(), secure::generateKey(), error))
        qFatal("%s", error.c_str());
    return path;
}

// "not in control: GB_30226 0 frames, GB_41251 12 frames" -> the count of `station`.
int notInControlSaid(const QByteArray& said, const QByteArray& station)
{
    const qsizetype line = said.lastIndexOf("not in control: GB_30226 ");
    if (line < 0)
        return -1;
    const QByteArray rest = said.mid(line, said.indexOf('\n', line) - line);
    const qsizetype at = rest.indexOf(station + ' ');
    return at < 0 ? -1 : rest.mid(at + station.size() + 1).split(' ').value(0).toInt();
}

}  // namespace

class TestUasim : public QObject {
    Q_OBJECT

private slots:
    void statusIsAnEncodableMessage()
    {
        SimulatedAircraft aircraft;
        for (std::uint32_t n = 0; n < 3; ++n) {
            const Message status = aircraft.status(kSomeUtc);
            QCOMPARE(aircraft.status(kSomeUtc), status);  // asking again is not another frame
            aircraft.statusSent();
            QCOMPARE(status.header.number(ItemId::ID_msg), n);
            QCOMPARE(status.header.number(ItemId::time_UTC), 73205);
            QCOMPARE(status.header.number(ItemId::date_UTC), 261122);
            QCOMPARE(*status.header.find(ItemId::ID_UA_source), Value::station(SimulatedAircraft::kDefaultIdentity));
            QCOMPARE(status.engines.size(), std::size_t{3});
            QCOMPARE(status.radios.size(), std::size_t{3});
            QCOMPARE(status.cameras.size(), std::size_t{2});
            QVERIFY(status.flightPlan.empty());
            Diagnostics errors;
            const auto datagram = encodeDatagram(status, errors);
            QVERIFY2(datagram, errors.empty() ? "" : errors.front().toString().c_str());
            const DecodeResult back = decodeFrame(*datagram);
            QVERIFY(back.diagnostics.empty());
            QCOMPARE(back.message, status);
        }
        QCOMPARE(aircraft.statusFrames(), 3u);
    }

    void adoptsTheCommandedIdentityAndEchoesTheHeader()
    {
        SimulatedAircraft aircraft;
        Message command = restingCommand(aircraft.airframe());
        command.header.set(ItemId::ID_UA_source, Value::station({33, 7}));
        command.header.set(ItemId::ID_GCS_destination, Value::station({33, 1}));
        aircraft.apply(command);
        command.header.set(ItemId::ID_UA_source, Value::station({1, 2}));
        aircraft.apply(command);
        const Message status = aircraft.status(kSomeUtc);
        QCOMPARE(*status.header.find(ItemId::ID_UA_source), Value::station({33, 7}));
        QCOMPARE(*status.header.find(ItemId::ID_GCS_destination), Value::station({33, 1}));

        SimulatedAircraft fixed(Airframe::wellEquipped(), StationId{44, 9});
        fixed.apply(command);
        QCOMPARE(*fixed.status(kSomeUtc).header.find(ItemId::ID_UA_source), Value::station({44, 9}));
    }

    void gearTakesMoreThanTwoFrames()
    {
        SimulatedAircraft aircraft;
        Message command = restingCommand(aircraft.airframe());
        for (int wheel = 0; wheel < 4; ++wheel)
            command.settings.setFieldCode(ItemId::land_wheels, wheel, kRetracted);
        const auto report = aircraft.apply(command);
        QVERIFY2(joined(report.events).contains("retracting"), joined(report.events));
        QVERIFY(aircraft.gearMoving());
        int frames = 0;
        Message status;
        do {
            status = nextStatus(aircraft);
            ++frames;
        } while (status.settings.fieldCode(ItemId::land_wheels, 0) == kOut && frames < 10);
        QCOMPARE(frames, 4);  // three status frames still show the gear out
        for (int wheel = 0; wheel < 4; ++wheel)
            QCOMPARE(status.settings.fieldCode(ItemId::land_wheels, wheel), kRetracted);
        QVERIFY(!aircraft.gearMoving());
    }

    void corruptFieldsAreNotActedOn()
    {
        SimulatedAircraft aircraft;
        Message command = restingCommand(aircraft.airframe());
        // wing_RHS 00 (corrupt), wing_LHS ON, tail 11 (corrupt), wheel_brake ON.
        command.settings.set(ItemId::lights, 0b00'10'11'10);
        // Engine 2 control 11 is the RC transmitter: valid.
        command.engines[1].setFieldCode(ItemId::eng_status, 0, 3);
        const auto report = aircraft.apply(command);
        const QByteArray ignored = joined(report.ignored);
        QVERIFY2(ignored.contains("lights wing_RHS: code 00"), ignored);
        QVERIFY2(ignored.contains("lights tail: code 11"), ignored);
        QVERIFY2(!ignored.contains("eng_status"), ignored);
        const Message status = nextStatus(aircraft);
        QCOMPARE(status.settings.fieldCode(ItemId::lights, 0), kOff);
        QCOMPARE(status.settings.fieldCode(ItemId::lights, 1), kOn);
        QCOMPARE(status.settings.fieldCode(ItemId::lights, 2), kOff);
        QCOMPARE(status.settings.fieldCode(ItemId::lights, 3), kOn);
        QCOMPARE(status.engines[1].fieldCode(ItemId::eng_status, 0), 3u);
    }

    void unitsNotFittedAreReported()
    {
        Airframe small;
        small.name = "Small";
        small.engines = {{1, "Engine"}};
        small.senseAndAvoid = false;
        SimulatedAircraft aircraft(small);
        Message command = restingCommand(Airframe::wellEquipped());
        command.engines[0].set(ItemId::eng_carb_SET, 200);
        const auto report = aircraft.apply(command);
        const QByteArray ignored = joined(report.ignored);
        QVERIFY2(ignored.contains("engine 2: not fitted"), ignored);
        QVERIFY2(ignored.contains("engine 3: not fitted"), ignored);
        QVERIFY2(ignored.contains("radio VHF1: not fitted"), ignored);
        QVERIFY2(ignored.contains("camera NIK 2: not fitted"), ignored);
        QVERIFY2(ignored.contains("sense and avoid: not fitted"), ignored);
        const Message status = nextStatus(aircraft);
        QCOMPARE(status.engines.size(), std::size_t{1});
        QCOMPARE(status.engines[0].number(ItemId::eng_carb_SET), 200);
        QVERIFY(status.radios.empty() && status.cameras.empty() && status.sense.empty());
    }

    void photoOnEachNoneToTakeEdge()
    {
        SimulatedAircraft aircraft;
        Message command = restingCommand(aircraft.airframe());
        const auto photoIn = [](const Message& m) { return m.cameras[0].fieldCode(ItemId::take_one_photo, 0); };
        const auto send = [&](unsigned code) {
            command.cameras[0].set(ItemId::take_one_photo, static_cast<std::int64_t>(code << 6));
            aircraft.apply(command);
            return nextStatus(aircraft);
        };
        QCOMPARE(photoIn(send(kTake)), kTake);
        QCOMPARE(aircraft.photoCount(0), 1);
        QCOMPARE(photoIn(send(kTake)), kNone);  // held, not repeated
        QCOMPARE(photoIn(send(kTake)), kNone);
        QCOMPARE(aircraft.photoCount(0), 1);
        QCOMPARE(photoIn(send(0)), kNone);  // corrupt: neither a release nor a press
        QCOMPARE(photoIn(send(kTake)), kNone);
        QCOMPARE(aircraft.photoCount(0), 1);
        send(kNone);
        QCOMPARE(photoIn(send(kTake)), kTake);
        QCOMPARE(aircraft.photoCount(0), 2);
        QCOMPARE(aircraft.photoCount(1), 0);
    }

    void surfacesSlew()
    {
        SimulatedAircraft aircraft;
        Message command = restingCommand(aircraft.airframe());
        command.flaps.set(ItemId::F_elev_set, 30);
        command.flaps.set(ItemId::F_lift_set, -20);
        aircraft.apply(command);
        aircraft.advance(500ms);
        Message status = aircraft.status(kSomeUtc);
        QCOMPARE(status.flaps.number(ItemId::F_elev_set), 20);
        QCOMPARE(status.flaps.number(ItemId::F_lift_set), -5);
        aircraft.advance(1500ms);
        status = aircraft.status(kSomeUtc);
        QCOMPARE(status.flaps.number(ItemId::F_elev_set), 30);
        QCOMPARE(status.flaps.number(ItemId::F_lift_set), -20);
    }

    void fuelDumpNeedsTheFacility()
    {
        SimulatedAircraft aircraft;
        Message command = restingCommand(aircraft.airframe());
        command.fuelDump.setFieldCode(ItemId::ENABLE_fuel_dump, 2, 2);  // dump tank 2, facility disabled
        aircraft.apply(command);
        QCOMPARE(nextStatus(aircraft).fuelDump.fieldCode(ItemId::ENABLE_fuel_dump, 2), 1u);
        command.fuelDump.setFieldCode(ItemId::ENABLE_fuel_dump, 0, 2);
        aircraft.apply(command);
        QCOMPARE(nextStatus(aircraft).fuelDump.fieldCode(ItemId::ENABLE_fuel_dump, 2), 2u);
    }

    void flightPlanAcknowledged()
    {
        SimulatedAircraft aircraft;
        std::vector<std::uint8_t> plan(1000);
        for (std::size_t i = 0; i < plan.size(); ++i)
            plan[i] = static_cast<std::uint8_t>(i * 7);
        FlightPlanUploader uploader(0xC0FFEE, plan);
        Message command = restingCommand(aircraft.airframe());
        int frames = 0;
        while (auto section = uploader.next()) {
            command.flightPlan = *section;
            aircraft.apply(command);
            const Message status = nextStatus(aircraft);
            uploader.handleReply(status.flightPlan);
            ++frames;
        }
        QCOMPARE(uploader.state(), FlightPlanUploader::State::Acknowledged);
        QCOMPARE(frames, 5);
        QCOMPARE(aircraft.flightPlanId(), 0xC0FFEEu);
        QVERIFY(aircraft.flightPlan() == plan);
    }

    void helpNamesEveryOption()
    {
        QProcess p;
        p.start(QStringLiteral(RCM_BIN_DIR "/uasim"), {QStringLiteral("--help")});
        QVERIFY(p.waitForFinished());
        QCOMPARE(p.exitCode(), 0);
        const QByteArray help = p.readAllStandardOutput();
        for (const char* option :
             {"--udp", "--serial", "--station", "--failover", "--baud", "--log", "--ber", "--burst", "--drop",
              "--delay", "--outage", "--silent", "--seed", "--airframe", "--verbose", "--help"})
            QVERIFY2(help.contains(option), option);
        QVERIFY(help.contains("Example"));
        QVERIFY(help.contains("uasim --udp"));
        QVERIFY(help.contains("uasim --station GB_30226,5601,a.key --station GB_41251,5602,b.key"));
    }

    void refusesBadOptions_data()
    {
        QTest::addColumn<QStringList>("arguments");
        QTest::addColumn<QByteArray>("says");  // the start of the line saying why; empty: not checked
        QTest::newRow("no transport") << QStringList{} << QByteArray();
        QTest::newRow("both transports") << QStringList{"--udp", "5000", "--serial", "/dev/null"} << QByteArray();
        QTest::newRow("ber above 1") << QStringList{"--udp", "5000", "--ber", "2"} << QByteArray();
        QTest::newRow("burst without rate") << QStringList{"--udp", "5000", "--burst", "16"} << QByteArray();
        QTest::newRow("outage not a pair") << QStringList{"--udp", "5000", "--outage", "soon"} << QByteArray();
        QTest::newRow("missing airframe")
            << QStringList{"--udp", "5000", "--airframe", "/nonexistent.json"} << QByteArray();
        QTest::newRow("station and udp")
            << QStringList{"--station", "GB_30226,5601", "--udp", "5000"}
            << QByteArray("--station gives each station a UDP port of its own: not with --udp or --serial\n");
        QTest::newRow("station and serial")
            << QStringList{"--station", "GB_30226,5601", "--serial", "/dev/null"}
            << QByteArray("--station gives each station a UDP port of its own: not with --udp or --serial\n");
        QTest::newRow("station and key")
            << QStringList{"--station", "GB_30226,5601", "--key", "a.key"}
            << QByteArray("with --station, give each station's key as --station ID,PORT,KEYFILE, not --key\n");
        QTest::newRow("station without port")
            << QStringList{"--station", "GB_30226"}
            << QByteArray("--station wants ID,PORT[,KEYFILE] such as GB_30226,5601,a.key, not GB_30226\n");
        QTest::newRow("station not a station")
            << QStringList{"--station", "XX_1,5601"} << QByteArray("--station XX_1,5601: unknown country 'XX'");
        QTest::newRow("station twice") << QStringList{"--station", "GB_1,5601", "--station", "GB_1,5602"}
                                       << QByteArray("--station GB_1,5602: that station was given already\n");
        QTest::newRow("port twice") << QStringList{"--station", "GB_1,5601", "--station", "GB_2,5601"}
                                    << QByteArray("--station GB_2,5601: port 5601 was given to another station\n");
        QTest::newRow("key twice") << QStringList{"--station", "GB_1,5601,a.key", "--station", "GB_2,5602,a.key"}
                                   << QByteArray("--station GB_2,5602,a.key: each station needs a key of its own\n");
        QTest::newRow("failover, one station")
            << QStringList{"--station", "GB_1,5601", "--failover", "2"}
            << QByteArray("--failover is for an aircraft with two --station or more\n");
        QTest::newRow("failover not seconds")
            << QStringList{"--station", "GB_1,5601", "--station", "GB_2,5602", "--failover", "soon"}
            << QByteArray("--failover wants seconds, 0.001 to 3600, not soon\n");
    }

    void refusesBadOptions()
    {
        QFETCH(QStringList, arguments);
        QProcess p;
        p.start(QStringLiteral(RCM_BIN_DIR "/uasim"), arguments);
        QVERIFY(p.waitForFinished());
        QCOMPARE(p.exitStatus(), QProcess::NormalExit);
        QCOMPARE(p.exitCode(), 2);
        QFETCH(QByteArray, says);
        const QByteArray said = p.readAllStandardError();
        QVERIFY(said.startsWith("uasim: "));
        QVERIFY2(said.startsWith("uasim: " + says), said.constData());
    }

    // In simulated time from here on: the console's worker against the
    // aircraft, both ticking on the second from 07:32:00.250.
    void reportsTheCommandedState()
    {
        Flight f;
        Message& c = f.command;
        for (int wheel = 0; wheel < 4; ++wheel)
            c.settings.setFieldCode(ItemId::land_wheels, wheel, kRetracted);
        c.settings.setFieldCode(ItemId::lights, 0, kOn);      // right wing light
        c.settings.setFieldCode(ItemId::lights, 3, kOn);      // wheel brake
        c.engines[1].setFieldCode(ItemId::eng_status, 0, 2);  // GCS control
        c.engines[1].set(ItemId::eng_prop_pitch, 120);
        c.engines[1].set(ItemId::eng_carb_SET, 200);
        f.start();
        f.fixture.run(6s);

        // On each second the aircraft's status goes first, then the command:
        // status 0 is the resting aircraft, status 1 the first with the
        // command acted on. The gear takes 3.5 s, so the lights are on while
        // it is still down in four of them: the mismatch the console highlights.
        QCOMPARE(f.statuses.count(), 6);
        for (int i = 0; i < 6; ++i) {
            const ReceivedMessage r = f.statuses.at(i).at(0).value<ReceivedMessage>();
            QCOMPARE(r.corrected.block1 + r.corrected.block2, 0);
            QVERIFY(r.diagnostics.empty());
            const Message& s = r.message;
            QCOMPARE(s.header.number(ItemId::ID_msg), i);
            QCOMPARE(s.header.number(ItemId::time_UTC), 73201 + i);
            QCOMPARE(*s.header.find(ItemId::ID_UA_source), Value::station({44, 133}));
            const unsigned lights = i == 0 ? kOff : kOn;
            QCOMPARE(s.settings.fieldCode(ItemId::lights, 0), lights);
            QCOMPARE(s.settings.fieldCode(ItemId::lights, 1), kOff);
            QCOMPARE(s.settings.fieldCode(ItemId::lights, 3), lights);
            for (int wheel = 0; wheel < 4; ++wheel)
                QCOMPARE(s.settings.fieldCode(ItemId::land_wheels, wheel), i < 5 ? kOut : kRetracted);
            QCOMPARE(s.engines[1].fieldCode(ItemId::eng_status, 0), i == 0 ? 1u : 2u);
            QCOMPARE(s.engines[1].number(ItemId::eng_prop_pitch), i == 0 ? 0 : 120);
            QCOMPARE(s.engines[1].number(ItemId::eng_carb_SET), i == 0 ? 0 : 200);
        }
        QCOMPARE(f.fixture.aircraftWorker->statistics().framesReceived, quint64(6));
        QVERIFY(!f.fixture.aircraft.gearMoving());
    }

    void countsOnePhotoPerPress()
    {
        Flight f;
        QStringList events;
        QObject::connect(f.fixture.responder.get(), &AircraftResponder::commandApplied,
                         [&](const ReceivedMessage&, const SimulatedAircraft::ApplyReport& report) {
                             for (const std::string& e : report.events)
                                 events << QString::fromStdString(e);
                         });
        const auto photoIn = [&](qsizetype i) { return f.status(i).cameras.at(0).fieldCode(ItemId::take_one_photo, 0); };
        const auto press = [&](unsigned code) {
            f.command.cameras[0].set(ItemId::take_one_photo, std::int64_t(code << 6));
            f.setCommand();
        };
        press(kTake);
        f.start();
        // TAKE held for four commands: one photograph, in the status after the first.
        f.fixture.run(5s);
        QCOMPARE(f.statuses.count(), 5);
        QCOMPARE(f.fixture.aircraft.photoCount(0), 1);
        for (int i = 0; i < 5; ++i)
            QCOMPARE(photoIn(i), i == 1 ? kTake : kNone);

        // Released, then pressed again: the second.
        press(kNone);
        f.fixture.run(2s);
        press(kTake);
        f.fixture.run(2s);
        QCOMPARE(f.statuses.count(), 9);
        for (int i = 5; i < 9; ++i)
            QCOMPARE(photoIn(i), i == 8 ? kTake : kNone);
        QCOMPARE(f.fixture.aircraft.photoCount(0), 2);
        QCOMPARE(f.fixture.aircraft.photoCount(1), 0);
        QCOMPARE(events, QStringList({"camera NIK 1: photograph 1 taken", "camera NIK 1: photograph 2 taken"}));
    }

    void acknowledgesAnUploadedFlightPlan()
    {
        std::vector<std::uint8_t> plan(700);
        for (std::size_t i = 0; i < plan.size(); ++i)
            plan[i] = static_cast<std::uint8_t>(i ^ 0x5A);
        FlightPlanUploader uploader(0xF1A9, plan, FlightPlanSection::kMaxData, 0);
        QCOMPARE(uploader.sections().size(), std::size_t{4});
        test::AircraftFixture::Options options;
        options.console.block2Source = [&] { return uploader.next(); };
        options.console.block2Reply = [&](const FlightPlanSection& reply) { uploader.handleReply(reply); };
        Flight f(std::move(options));
        f.start();
        // One section a second from 07:32:01; the last one reaches the
        // aircraft at 07:32:04 and its acknowledgement the console at :05.
        f.fixture.run(4s);
        QVERIFY(uploader.state() != FlightPlanUploader::State::Acknowledged);
        QCOMPARE(f.fixture.aircraft.flightPlanId(), 0xF1A9u);
        QVERIFY(f.fixture.aircraft.flightPlan() == plan);
        f.fixture.run(1s);
        QCOMPARE(uploader.state(), FlightPlanUploader::State::Acknowledged);
        const auto ack = FlightPlanAcknowledgement::read(f.latest().flightPlan);
        QVERIFY(ack);
        QCOMPARE(ack->planId, 0xF1A9u);
        QCOMPARE(ack->descriptor, uploader.descriptor());
        // Before the plan was complete, BLOCK 2 was empty.
        for (int i = 0; i < 4; ++i)
            QVERIFY(f.status(i).flightPlan.empty());
    }

    // The built uasim, as few seconds as it takes: its options, its verbose
    // lines, its log and its signals.
    void appliesItsFaults()
    {
        // About eight flipped bits per 510-byte datagram: Reed-Solomon repairs them.
        UasimRun run({QStringLiteral("--ber"), QStringLiteral("0.002"), QStringLiteral("--seed"), QStringLiteral("3")});
        QVERIFY(run.uasim.start());
        QTRY_VERIFY_WITH_TIMEOUT(run.uasim.listening(), kPatienceMs);
        run.send();
        QTRY_VERIFY_WITH_TIMEOUT(!run.statuses.empty(), kPatienceMs);
        for (const DecodeResult& r : run.statuses) {
            QVERIFY(r.ok());
            QVERIFY(r.corrected.block1 + r.corrected.block2 > 0);
        }
    }

    void usesTheGivenAirframe()
    {
        QTemporaryDir dir;
        QFile file(dir.filePath(QStringLiteral("glider.json")));
        QVERIFY(file.open(QIODevice::WriteOnly));
        file.write(R"({"name": "Motor glider", "engines": [{"id": 4, "name": "Engine"}],
                       "radios": [{"systemId": "UHF", "name": "UHF"}], "cameras": [], "senseAndAvoid": false})");
        file.close();
        UasimRun run({QStringLiteral("--airframe"), file.fileName()});
        QVERIFY(run.uasim.start());
        QTRY_VERIFY_WITH_TIMEOUT(run.uasim.listening(), kPatienceMs);
        QVERIFY2(run.uasim.stderrText().contains("Motor glider on udp"), run.uasim.stderrText());
        run.send();
        QTRY_VERIFY_WITH_TIMEOUT(!run.statuses.empty(), kPatienceMs);
        const Message& s = run.statuses.back().message;
        QCOMPARE(s.engines.size(), std::size_t{1});
        QCOMPARE(s.engines[0].number(ItemId::eng_ID), 4);
        QCOMPARE(s.radios.size(), std::size_t{1});
        QCOMPARE(s.radios[0].find(ItemId::system_ID)->text, std::string("UHF"));
        QVERIFY(s.cameras.empty() && s.sense.empty());
        // The well-equipped command's other units are reported, not acted on.
        QTRY_VERIFY_WITH_TIMEOUT(run.uasim.stderrText().contains("IGNORED engine 1: not fitted"), kPatienceMs);
    }

    void logsAndExitsCleanlyOnSigterm()
    {
        QTemporaryDir dir;
        const QString path = dir.filePath(QStringLiteral("uasim.pcapng"));
        UasimRun run({QStringLiteral("--log"), path});
        QVERIFY(run.uasim.start());
        QTRY_VERIFY_WITH_TIMEOUT(run.uasim.listening(), kPatienceMs);
        run.send();
        QTRY_VERIFY_WITH_TIMEOUT(!run.statuses.empty(), kPatienceMs);
        QTRY_VERIFY_WITH_TIMEOUT(run.uasim.stderrText().contains("command 0 (RS 0+0); gear OUT/OUT/OUT/OUT"),
                                 kPatienceMs);
        QVERIFY(run.uasim.stop(kPatienceMs));
        QCOMPARE(run.uasim.process().exitStatus(), QProcess::NormalExit);
        QCOMPARE(run.uasim.process().exitCode(), 0);

        FrameLogReader reader;
        QVERIFY2(reader.open(path), qPrintable(reader.errorString()));
        QVERIFY(!reader.truncatedTail());
        const auto records = reader.readAll();
        const auto sent = std::count_if(records.begin(), records.end(),
                                        [](const FrameRecord& r) { return r.direction == FrameDirection::Sent; });
        QVERIFY(sent >= 1);
        QVERIFY(records.size() > sent);  // the commands too
        for (const FrameRecord& r : records) {
            QCOMPARE(r.transport, FrameTransport::Udp);
            QCOMPARE(r.bytes.size(), qsizetype(kDatagramSize));
        }
    }

    // Two stations, each with a channel of its own (docs/protocol.md section
    // 10), over real loopback sockets at uasim's own 1 Hz.
    void actsOnlyOnTheStationInControl()
    {
        QTemporaryDir dir;
        test::UasimProcess uasim(test::kTwoStations, {QStringLiteral("--log"), dir.filePath(QStringLiteral("uasim.pcapng"))});
        QVERIFY(uasim.start());
        QTRY_VERIFY2_WITH_TIMEOUT(uasim.listening(), uasim.stderrText().constData(), kPatienceMs);
        QVERIFY2(uasim.said("uasim: stations: GB_30226 in control (not yet taken up), GB_41251 backup; failover after "
                            "5 s\n"),
                 uasim.stderrText().constData());

        StationClient primary(uasim.ports[0]), backup(uasim.ports[1]);
        primary.command(kGb30226, kGb30226, kOut);  // its claim: Take control
        // The backup's console before any status: it names itself, commands
        // the gear up and uploads a flight plan.
        backup.command(kGb41251, kGb30226, kRetracted);
        backup.upload(0xB0, 300);
        primary.worker.start();
        backup.worker.start();
        QTRY_VERIFY_WITH_TIMEOUT(uasim.said("taken up: GB_30226 in control, GB_41251 backup\n"), kPatienceMs);
        QTRY_VERIFY_WITH_TIMEOUT(
            uasim.said("not in control: GB_41251's frames are not acted on; GB_30226 in control\n"), kPatienceMs);
        QTRY_VERIFY_WITH_TIMEOUT(uasim.said("GB_41251: command 2 not acted on: not in control\n"), kPatienceMs);
        // Two status frames more on each channel after the backup's third command.
        const qsizetype seen[] = {primary.statuses.count(), backup.statuses.count()};
        QTRY_VERIFY_WITH_TIMEOUT(primary.statuses.count() >= seen[0] + 2 && backup.statuses.count() >= seen[1] + 2,
                                 kPatienceMs);
        // Every status frame, on both channels, names GB_30226 in control
        // and GB_41251 the backup; the gear stays down.
        for (StationClient* client : {&primary, &backup})
            for (qsizetype i = 0; i < client->statuses.count(); ++i) {
                const Message status = client->status(i);
                QCOMPARE(*status.header.find(ItemId::ID_GCS_destination), Value::station(kGb30226));
                QCOMPARE(*status.header.find(ItemId::ID_GCS_backup), Value::station(kGb41251));
                for (int wheel = 0; wheel < 4; ++wheel)
                    QCOMPARE(status.settings.fieldCode(ItemId::land_wheels, wheel), kOut);
            }
        QVERIFY(!uasim.said("retracting"));
        QVERIFY(!uasim.said("flight plan"));
        QVERIFY(backup.latest().flightPlan.empty());

        // The station in control commands it: the gear comes up, as both see.
        primary.command(kGb30226, kGb41251, kRetracted);
        QTRY_VERIFY_WITH_TIMEOUT(uasim.said("GB_30226: command "), kPatienceMs);
        QTRY_VERIFY_WITH_TIMEOUT(uasim.said("Left wheel: retracting"), kPatienceMs);
        QTRY_VERIFY_WITH_TIMEOUT(!primary.statuses.isEmpty() && primary.latestGear() == kRetracted, kPatienceMs);
        QTRY_VERIFY_WITH_TIMEOUT(backup.latestGear() == kRetracted, kPatienceMs);
        QVERIFY(primary.latestNames(kGb30226, kGb41251) && backup.latestNames(kGb30226, kGb41251));

        // Its flight plan is acted on, and both see the acknowledgement of it.
        primary.upload(0xA0, 300);
        QTRY_VERIFY_WITH_TIMEOUT(primary.uploader->state() == FlightPlanUploader::State::Acknowledged, kPatienceMs);
        QTRY_VERIFY_WITH_TIMEOUT(!backup.latest().flightPlan.empty(), kPatienceMs);
        QCOMPARE(FlightPlanAcknowledgement::read(backup.latest().flightPlan)->planId, 0xA0u);
        QVERIFY(backup.uploader->state() != FlightPlanUploader::State::Acknowledged);

        primary.worker.stop();
        backup.worker.stop();
        QVERIFY(uasim.stop(kPatienceMs));
        const QByteArray said = uasim.stderrText();
        QVERIFY(said.contains("GB_30226: command ") && said.contains("flight plan 0x000000A0 section"));
        QVERIFY(!said.contains("flight plan 0x000000B0"));
        QCOMPARE(notInControlSaid(said, "GB_30226"), 0);
        QVERIFY2(notInControlSaid(said, "GB_41251") >= 3, said.constData());
        QVERIFY(!said.contains("handover") && !said.contains("failover:"));

        // One log per channel, each with the frames both ways.
        for (const char* name : {"uasim-GB_30226.pcapng", "uasim-GB_41251.pcapng"}) {
            FrameLogReader reader;
            QVERIFY2(reader.open(dir.filePath(QLatin1String(name))), qPrintable(reader.errorString()));
            const auto records = reader.readAll();
            const auto sent = std::count_if(records.begin(), records.end(),
                                            [](const FrameRecord& r) { return r.direction == FrameDirection::Sent; });
            QVERIFY2(sent >= 2, name);
            QVERIFY2(records.size() > sent, name);
        }
        QVERIFY(!QFile::exists(dir.filePath(QStringLiteral("uasim.pcapng"))));
    }

    void handsOverToTheBackup()
    {
        test::UasimProcess uasim(test::kTwoStations);
        QVERIFY(uasim.start());
        QTRY_VERIFY2_WITH_TIMEOUT(uasim.listening(), uasim.stderrText().constData(), kPatienceMs);
        StationClient primary(uasim.ports[0]), backup(uasim.ports[1]);
        primary.command(kGb30226, kGb30226);  // its claim: Take control
        backup.command(kGb30226, kGb41251);  // the backup, observing
        primary.worker.start();
        backup.worker.start();
        QTRY_VERIFY_WITH_TIMEOUT(uasim.said("taken up: GB_30226 in control, GB_41251 backup\n"), kPatienceMs);

        // Handing over: the primary names the backup as destination.
        primary.command(kGb41251, kGb30226);
        QTRY_VERIFY_WITH_TIMEOUT(uasim.said("handover: GB_30226 hands control to GB_41251, not yet taken up\n"),
                                 kPatienceMs);
        QTRY_VERIFY_WITH_TIMEOUT(primary.latestNames(kGb41251, kGb30226) && backup.latestNames(kGb41251, kGb30226),
                                 kPatienceMs);

        // Given control, not yet taken up: it names the reported backup, and
        // its commands are not acted on.
        backup.command(kGb30226, kGb41251, kOut, kOn);
        QTRY_VERIFY_WITH_TIMEOUT(uasim.said("not acted on: control not yet taken up (names GB_30226 as destination)\n"),
                                 kPatienceMs);
        QCOMPARE(backup.latestWingLight(), kOff);
        // Naming itself is not enough: only its operator's claim (itself as
        // destination and backup) takes control up; the light goes on.
        backup.command(kGb41251, kGb41251, kOut, kOn);
        QTRY_VERIFY_WITH_TIMEOUT(uasim.said("taken up: GB_41251 in control, GB_30226 backup\n"), kPatienceMs);
        QTRY_VERIFY_WITH_TIMEOUT(primary.latestWingLight() == kOn && backup.latestWingLight() == kOn, kPatienceMs);
        QVERIFY(primary.latestNames(kGb41251, kGb30226) && backup.latestNames(kGb41251, kGb30226));

        // The former primary, now the backup, commands nothing.
        primary.command(kGb30226, kGb41251, kOut, kOff);
        QTRY_VERIFY_WITH_TIMEOUT(
            uasim.said("not in control: GB_30226's frames are not acted on; GB_41251 in control\n"), kPatienceMs);
        const qsizetype seen = primary.statuses.count();
        QTRY_VERIFY_WITH_TIMEOUT(primary.statuses.count() >= seen + 2, kPatienceMs);
        QCOMPARE(primary.latestWingLight(), kOn);
        primary.worker.stop();
        backup.worker.stop();
        QVERIFY(uasim.stop(kPatienceMs));
        QVERIFY(!uasim.said("failover:"));
    }

    void failsOverWhenTheStationInControlFallsSilent()
    {
        test::UasimProcess uasim(test::kTwoStations, {QStringLiteral("--failover"), QStringLiteral("2")});
        QVERIFY(uasim.start());
        QTRY_VERIFY2_WITH_TIMEOUT(uasim.listening(), uasim.stderrText().constData(), kPatienceMs);
        QVERIFY(uasim.said("; failover after 2 s\n"));
        StationClient primary(uasim.ports[0]), backup(uasim.ports[1]);
        primary.command(kGb30226, kGb30226);  // its claim: Take control
        backup.command(kGb30226, kGb41251);
        primary.worker.start();
        backup.worker.start();
        QTRY_VERIFY_WITH_TIMEOUT(uasim.said("taken up: GB_30226 in control, GB_41251 backup\n"), kPatienceMs);
        QTRY_VERIFY_WITH_TIMEOUT(backup.latestNames(kGb30226, kGb41251), kPatienceMs);

        primary.worker.stop();
        QTRY_VERIFY_WITH_TIMEOUT(
            uasim.said("failover: nothing from GB_30226 for 2 s; GB_41251 in control, not yet taken up\n"),
            kPatienceMs);
        QTRY_VERIFY_WITH_TIMEOUT(backup.latestNames(kGb41251, kGb30226), kPatienceMs);
        // Not acted on until the new station in control takes it up.
        backup.command(kGb41251, kGb41251, kOut, kOn);
        QTRY_VERIFY_WITH_TIMEOUT(uasim.said("taken up: GB_41251 in control, GB_30226 backup\n"), kPatienceMs);
        QTRY_VERIFY_WITH_TIMEOUT(backup.latestWingLight() == kOn, kPatienceMs);
        backup.worker.stop();
        QVERIFY(uasim.stop(kPatienceMs));
    }

    // Each station's key opens its own channel only.
    void refusesTheOtherStationsKey()
    {
        QTemporaryDir dir;
        const QString keyA = makeKey(dir, "a.key"), keyB = makeKey(dir, "b.key");
        test::UasimProcess uasim(test::kTwoStations, {}, {keyA, keyB});
        QVERIFY(uasim.start());
        QTRY_VERIFY2_WITH_TIMEOUT(uasim.listening(), uasim.stderrText().constData(), kPatienceMs);
        QVERIFY(uasim.said("GB_30226: secure link: encrypted and authenticated, key fingerprint "));
        QVERIFY(uasim.said("GB_41251: secure link: encrypted and authenticated, key fingerprint "));

        // On GB_30226's channel under GB_41251's key, and the other way round:
        // both would command the gear up.
        StationClient intruderOnA(uasim.ports[0], keyB), intruderOnB(uasim.ports[1], keyA);
        intruderOnA.command(kGb41251, kGb30226, kRetracted);
        intruderOnB.command(kGb30226, kGb41251, kRetracted);
        intruderOnA.worker.start();
        intruderOnB.worker.start();
        QTRY_VERIFY_WITH_TIMEOUT(uasim.said("GB_30226: command rejected: forged: "), kPatienceMs);
        QTRY_VERIFY_WITH_TIMEOUT(uasim.said("GB_41251: command rejected: forged: "), kPatienceMs);

        // Each station with its own key: status frames both can read.
        StationClient primary(uasim.ports[0], keyA), backup(uasim.ports[1], keyB);
        primary.command(kGb30226, kGb30226);  // its claim: Take control
        backup.command(kGb30226, kGb41251);
        primary.worker.start();
        backup.worker.start();
        QTRY_VERIFY_WITH_TIMEOUT(uasim.said("taken up: GB_30226 in control, GB_41251 backup\n"), kPatienceMs);
        QTRY_VERIFY_WITH_TIMEOUT(primary.latestNames(kGb30226, kGb41251) && backup.latestNames(kGb30226, kGb41251),
                                 kPatienceMs);
        for (StationClient* client : {&intruderOnA, &intruderOnB, &primary, &backup})
            client->worker.stop();
        QCOMPARE(intruderOnA.statuses.count(), 0);
        QCOMPARE(intruderOnB.statuses.count(), 0);
        QCOMPARE(primary.latestGear(), kOut);
        QVERIFY(!uasim.said("retracting"));

        QVERIFY(uasim.stop(kPatienceMs));
        const QByteArray said = uasim.stderrText();
        for (const char* station : {"GB_30226", "GB_41251"}) {
            const QByteArray prefix = QByteArray(station) + ": rejected commands: ";
            const qsizetype at = said.indexOf(prefix);
            QVERIFY2(at >= 0, said.constData());
            const int forged = said.mid(at + prefix.size()).split(' ').value(0).toInt();
            QVERIFY2(forged >= 1, said.constData());
            QVERIFY(said.mid(at).startsWith(prefix + QByteArray::number(forged) +
                                            " forged, 0 replayed, 0 stale time, 0 plaintext\n"));
        }
    }
};

QTEST_GUILESS_MAIN(TestUasim)
#include "tst_uasim.moc"
