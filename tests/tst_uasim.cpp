// The simulated aircraft: first in process, frame by frame on its own
// clock; then the built `uasim` program over UDP, spoken to as the console
// would. The program checks wait on signals and conditions, never on time.
#include "codec/message/Airframe.h"
#include "codec/message/FlightPlanTransfer.h"
#include "codec/message/MessageDecoder.h"
#include "codec/message/MessageEncoder.h"
#include "link/framelog/FrameLogReader.h"
#include "link/simulation/SimulatedAircraft.h"

#include <QNetworkDatagram>
#include <QProcess>
#include <QTemporaryDir>
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

// Generous: uasim answers once a second, and gear takes several seconds.
constexpr int kPatienceMs = 30000;

quint16 freePort()
{
    QUdpSocket probe;
    probe.bind(QHostAddress::LocalHost, 0);
    return probe.localPort();
}

// A uasim process spoken to as the console would: one command per status
// frame received, so the exchange runs at uasim's own cadence and the test
// waits only on what arrives.
class UasimRun : public QObject {
public:
    explicit UasimRun(const QStringList& extraArguments = {})
    {
        m_port = freePort();
        m_process.setProgram(QStringLiteral(RCM_BIN_DIR "/uasim"));
        m_process.setArguments(
            QStringList{QStringLiteral("--udp"), QString::number(m_port), QStringLiteral("--verbose")} +
            extraArguments);
        QObject::connect(&m_process, &QProcess::readyReadStandardError, this,
                         [this] { m_stderr += m_process.readAllStandardError(); });
        m_socket.bind(QHostAddress::LocalHost, 0);
        QObject::connect(&m_socket, &QUdpSocket::readyRead, this, [this] { receive(); });
        command = restingCommand(Airframe::wellEquipped());
        command.header.set(ItemId::ID_UA_source, Value::station({44, 133}));
    }

    ~UasimRun() override
    {
        if (m_process.state() != QProcess::NotRunning) {
            m_process.kill();
            m_process.waitForFinished();
        }
    }

    bool start()
    {
        m_process.start();
        return m_process.waitForStarted();
    }
    // uasim says so once its socket is bound: the first command can go.
    bool listening() const { return m_stderr.contains("on udp"); }

    void send()
    {
        Message m = command;
        m.header.set(ItemId::ID_msg, m_nextId++);
        if (uploader)
            if (auto section = uploader->next())
                m.flightPlan = *section;
        Diagnostics errors;
        const auto datagram = encodeDatagram(m, errors);
        QVERIFY2(datagram, errors.empty() ? "" : errors.front().toString().c_str());
        m_socket.writeDatagram(reinterpret_cast<const char*>(datagram->data()), qint64(datagram->size()),
                               QHostAddress::LocalHost, m_port);
    }

    QProcess& process() { return m_process; }
    const QByteArray& errors() const { return m_stderr; }

    Message command;
    std::optional<FlightPlanUploader> uploader;
    std::vector<DecodeResult> statuses;

private:
    void receive()
    {
        while (m_socket.hasPendingDatagrams()) {
            const QNetworkDatagram d = m_socket.receiveDatagram();
            const QByteArray bytes = d.data();
            DecodeResult r =
                decodeFrame({reinterpret_cast<const std::uint8_t*>(bytes.constData()), std::size_t(bytes.size())});
            if (uploader)
                uploader->handleReply(r.message.flightPlan);
            statuses.push_back(std::move(r));
            send();
        }
    }

    QProcess m_process;
    QUdpSocket m_socket;
    quint16 m_port = 0;
    std::uint32_t m_nextId = 0;
    QByteArray m_stderr;
};

const Message& latest(const UasimRun& run)
{
    return run.statuses.back().message;
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
        for (const char* option : {"--udp", "--serial", "--baud", "--log", "--ber", "--burst", "--drop", "--delay",
                                   "--outage", "--silent", "--seed", "--airframe", "--verbose", "--help"})
            QVERIFY2(help.contains(option), option);
        QVERIFY(help.contains("Example"));
        QVERIFY(help.contains("uasim --udp"));
    }

    void refusesBadOptions_data()
    {
        QTest::addColumn<QStringList>("arguments");
        QTest::newRow("no transport") << QStringList{};
        QTest::newRow("both transports") << QStringList{"--udp", "5000", "--serial", "/dev/null"};
        QTest::newRow("ber above 1") << QStringList{"--udp", "5000", "--ber", "2"};
        QTest::newRow("burst without rate") << QStringList{"--udp", "5000", "--burst", "16"};
        QTest::newRow("outage not a pair") << QStringList{"--udp", "5000", "--outage", "soon"};
        QTest::newRow("missing airframe") << QStringList{"--udp", "5000", "--airframe", "/nonexistent.json"};
    }

    void refusesBadOptions()
    {
        QFETCH(QStringList, arguments);
        QProcess p;
        p.start(QStringLiteral(RCM_BIN_DIR "/uasim"), arguments);
        QVERIFY(p.waitForFinished());
        QCOMPARE(p.exitStatus(), QProcess::NormalExit);
        QCOMPARE(p.exitCode(), 2);
        QVERIFY(p.readAllStandardError().startsWith("uasim: "));
    }

    void reportsTheCommandedState()
    {
        UasimRun run;
        Message& c = run.command;
        for (int wheel = 0; wheel < 4; ++wheel)
            c.settings.setFieldCode(ItemId::land_wheels, wheel, kRetracted);
        c.settings.setFieldCode(ItemId::lights, 0, kOn);      // right wing light
        c.settings.setFieldCode(ItemId::lights, 3, kOn);      // wheel brake
        c.engines[1].setFieldCode(ItemId::eng_status, 0, 2);  // GCS control
        c.engines[1].set(ItemId::eng_prop_pitch, 120);
        c.engines[1].set(ItemId::eng_carb_SET, 200);
        QVERIFY(run.start());
        QTRY_VERIFY_WITH_TIMEOUT(run.listening(), kPatienceMs);
        run.send();

        const auto reached = [&] {
            if (run.statuses.empty())
                return false;
            const Message& s = latest(run);
            for (int wheel = 0; wheel < 4; ++wheel)
                if (s.settings.fieldCode(ItemId::land_wheels, wheel) != kRetracted)
                    return false;
            return s.settings.fieldCode(ItemId::lights, 0) == kOn && s.settings.fieldCode(ItemId::lights, 1) == kOff &&
                   s.settings.fieldCode(ItemId::lights, 3) == kOn &&
                   s.engines[1].fieldCode(ItemId::eng_status, 0) == 2 &&
                   s.engines[1].number(ItemId::eng_prop_pitch) == 120 &&
                   s.engines[1].number(ItemId::eng_carb_SET) == 200;
        };
        QTRY_VERIFY_WITH_TIMEOUT(reached(), kPatienceMs);

        // On the way the lights were on while the gear was still down: the
        // mismatch the console highlights.
        const bool lightsBeforeGear = std::any_of(run.statuses.begin(), run.statuses.end(), [](const DecodeResult& r) {
            return r.message.settings.fieldCode(ItemId::lights, 0) == kOn &&
                   r.message.settings.fieldCode(ItemId::land_wheels, 0) == kOut;
        });
        QVERIFY(lightsBeforeGear);
        for (std::size_t i = 0; i < run.statuses.size(); ++i) {
            const DecodeResult& r = run.statuses[i];
            QVERIFY(r.ok());
            QCOMPARE(r.corrected1 + r.corrected2, 0);
            QCOMPARE(*r.message.header.find(ItemId::ID_UA_source), Value::station({44, 133}));
            if (i > 0)  // its own frame count, one a frame
                QCOMPARE(r.message.header.number(ItemId::ID_msg),
                         run.statuses[i - 1].message.header.number(ItemId::ID_msg) + 1);
        }
        QTRY_VERIFY_WITH_TIMEOUT(
            run.errors().contains("command 0 (RS 0+0); gear RETRACTED/RETRACTED/RETRACTED/RETRACTED"), kPatienceMs);
    }

    void countsOnePhotoPerPress()
    {
        UasimRun run;
        const auto photoIn = [](const DecodeResult& r) {
            return r.message.cameras.at(0).fieldCode(ItemId::take_one_photo, 0);
        };
        const auto takes = [&](std::size_t from) {
            return std::count_if(run.statuses.begin() + std::ptrdiff_t(from), run.statuses.end(),
                                 [&](const DecodeResult& r) { return photoIn(r) == kTake; });
        };
        run.command.cameras[0].set(ItemId::take_one_photo, std::int64_t(kTake << 6));
        QVERIFY(run.start());
        QTRY_VERIFY_WITH_TIMEOUT(run.listening(), kPatienceMs);
        run.send();
        // TAKE held for four frames: one photograph.
        QTRY_VERIFY_WITH_TIMEOUT(run.statuses.size() >= 4, kPatienceMs);
        QCOMPARE(takes(0), 1);
        QCOMPARE(photoIn(run.statuses.front()), kTake);
        QTRY_VERIFY_WITH_TIMEOUT(run.errors().contains("photos taken 1/0"), kPatienceMs);

        // Released, then pressed again: the second.
        run.command.cameras[0].set(ItemId::take_one_photo, std::int64_t(kNone << 6));
        const std::size_t released = run.statuses.size();
        QTRY_VERIFY_WITH_TIMEOUT(run.statuses.size() >= released + 2, kPatienceMs);
        run.command.cameras[0].set(ItemId::take_one_photo, std::int64_t(kTake << 6));
        const std::size_t pressed = run.statuses.size();
        QTRY_VERIFY_WITH_TIMEOUT(takes(pressed) == 1, kPatienceMs);
        QTRY_VERIFY_WITH_TIMEOUT(run.errors().contains("camera NIK 1: photograph 2 taken"), kPatienceMs);
        QTRY_VERIFY_WITH_TIMEOUT(run.errors().contains("photos taken 2/0"), kPatienceMs);
        QCOMPARE(takes(0), 2);
    }

    void acknowledgesAnUploadedFlightPlan()
    {
        UasimRun run;
        std::vector<std::uint8_t> plan(700);
        for (std::size_t i = 0; i < plan.size(); ++i)
            plan[i] = static_cast<std::uint8_t>(i ^ 0x5A);
        run.uploader.emplace(0xF1A9, plan, FlightPlanSection::kMaxData, 0);
        QCOMPARE(run.uploader->sections().size(), std::size_t{4});
        QVERIFY(run.start());
        QTRY_VERIFY_WITH_TIMEOUT(run.listening(), kPatienceMs);
        run.send();
        QTRY_COMPARE_WITH_TIMEOUT(run.uploader->state(), FlightPlanUploader::State::Acknowledged, kPatienceMs);
        const auto ack = FlightPlanAcknowledgement::read(latest(run).flightPlan);
        QVERIFY(ack);
        QCOMPARE(ack->planId, 0xF1A9u);
        QCOMPARE(ack->descriptor, run.uploader->descriptor());
        QTRY_VERIFY_WITH_TIMEOUT(run.errors().contains("flight plan 61865 complete: 700 bytes in 4 sections"),
                                 kPatienceMs);
        // Before the plan was complete, BLOCK 2 was empty.
        QVERIFY(run.statuses.front().message.flightPlan.empty());
    }

    void appliesItsFaults()
    {
        // About eight flipped bits per 510-byte datagram: Reed-Solomon repairs them.
        UasimRun run({QStringLiteral("--ber"), QStringLiteral("0.002"), QStringLiteral("--seed"), QStringLiteral("3")});
        QVERIFY(run.start());
        QTRY_VERIFY_WITH_TIMEOUT(run.listening(), kPatienceMs);
        run.send();
        QTRY_VERIFY_WITH_TIMEOUT(run.statuses.size() >= 2, kPatienceMs);
        for (const DecodeResult& r : run.statuses) {
            QVERIFY(r.ok());
            QVERIFY(r.corrected1 + r.corrected2 > 0);
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
        QVERIFY(run.start());
        QTRY_VERIFY_WITH_TIMEOUT(run.listening(), kPatienceMs);
        QVERIFY2(run.errors().contains("Motor glider on udp"), run.errors());
        run.send();
        QTRY_VERIFY_WITH_TIMEOUT(!run.statuses.empty(), kPatienceMs);
        const Message& s = latest(run);
        QCOMPARE(s.engines.size(), std::size_t{1});
        QCOMPARE(s.engines[0].number(ItemId::eng_ID), 4);
        QCOMPARE(s.radios.size(), std::size_t{1});
        QCOMPARE(s.radios[0].find(ItemId::system_ID)->text, std::string("UHF"));
        QVERIFY(s.cameras.empty() && s.sense.empty());
        // The well-equipped command's other units are reported, not acted on.
        QTRY_VERIFY_WITH_TIMEOUT(run.errors().contains("IGNORED engine 1: not fitted"), kPatienceMs);
    }

    void logsAndExitsCleanlyOnSigterm()
    {
        QTemporaryDir dir;
        const QString path = dir.filePath(QStringLiteral("uasim.pcapng"));
        UasimRun run({QStringLiteral("--log"), path});
        QVERIFY(run.start());
        QTRY_VERIFY_WITH_TIMEOUT(run.listening(), kPatienceMs);
        run.send();
        QTRY_VERIFY_WITH_TIMEOUT(run.statuses.size() >= 2, kPatienceMs);
        run.process().terminate();
        QTRY_COMPARE_WITH_TIMEOUT(run.process().state(), QProcess::NotRunning, kPatienceMs);
        QCOMPARE(run.process().exitStatus(), QProcess::NormalExit);
        QCOMPARE(run.process().exitCode(), 0);

        FrameLogReader reader;
        QVERIFY2(reader.open(path), qPrintable(reader.errorString()));
        QVERIFY(!reader.truncatedTail());
        const auto records = reader.readAll();
        const auto sent = std::count_if(records.begin(), records.end(),
                                        [](const FrameRecord& r) { return r.direction == FrameDirection::Sent; });
        QVERIFY(sent >= 2);
        QVERIFY(records.size() > sent);  // the commands too
        for (const FrameRecord& r : records) {
            QCOMPARE(r.transport, FrameTransport::Udp);
            QCOMPARE(r.bytes.size(), qsizetype(kDatagramSize));
        }
    }
};

QTEST_GUILESS_MAIN(TestUasim)
#include "tst_uasim.moc"
