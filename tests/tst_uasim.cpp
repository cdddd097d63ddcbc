// The simulated aircraft: first in process, frame by frame on its own
// clock; then the built `uasim` program over UDP, spoken to as the console
// would. The program checks wait on signals and conditions, never on time.
#include "codec/Airframe.h"
#include "codec/FlightPlanTransfer.h"
#include "codec/MessageDecoder.h"
#include "codec/MessageEncoder.h"
#include "link/SimulatedAircraft.h"

#include <QtTest>

#include <chrono>

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
};

QTEST_GUILESS_MAIN(TestUasim)
#include "tst_uasim.moc"
