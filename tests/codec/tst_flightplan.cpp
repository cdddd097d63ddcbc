// Flight plans sent as numbered BLOCK 2 sections: cutting, cycling,
// reassembly, and what the receiver says about lost, repeated, reordered and
// damaged sections.
#include "codec/message/FlightPlanTransfer.h"
#include "codec/message/MessageDecoder.h"
#include "codec/message/MessageEncoder.h"
#include "codec/plan/PlanContents.h"

#include <QtTest>

#include <algorithm>
#include <random>

using namespace rcm;
using Kind = FlightPlanAssembler::Result::Kind;

Q_DECLARE_METATYPE(std::size_t)

namespace {

std::vector<std::uint8_t> randomPlan(std::size_t size, unsigned seed)
{
    std::mt19937 rng(seed);
    std::vector<std::uint8_t> plan(size);
    for (auto& b : plan)
        b = static_cast<std::uint8_t>(rng());
    return plan;
}

const char* kindName(Kind k)
{
    switch (k) {
        case Kind::None:
            return "None";
        case Kind::InProgress:
            return "InProgress";
        case Kind::Missing:
            return "Missing";
        case Kind::Complete:
            return "Complete";
        case Kind::AlreadyComplete:
            return "AlreadyComplete";
        case Kind::Error:
            return "Error";
    }
    return "?";
}

// Every section the uploader gives for one pass.
std::vector<FlightPlanSection> onePass(FlightPlanUploader& up)
{
    std::vector<FlightPlanSection> out;
    for (std::size_t i = 0; i < up.sections().size(); ++i)
        out.push_back(*up.next());
    return out;
}

// The section as the aircraft sees it: through BLOCK 2's encoder and decoder.
FlightPlanSection overTheAir(const FlightPlanSection& s, std::size_t maxData)
{
    Message m;
    m.flightPlan = s;
    Diagnostics errors;
    EncodeOptions options;
    options.maxFlightPlanData = maxData;
    const auto datagram = encodeDatagram(m, errors, options);
    if (!datagram)
        qFatal("encode: %s", errors.front().toString().c_str());
    return decodeFrame(*datagram).message.flightPlan;
}

}  // namespace

class TestFlightPlan : public QObject {
    Q_OBJECT

private slots:
    void crcCheckValue()
    {
        const std::string text = "123456789";
        const auto* p = reinterpret_cast<const std::uint8_t*>(text.data());
        QCOMPARE(crc32({p, text.size()}), 0xCBF43926u);
        QCOMPARE(crc32({}), 0u);
        // Running value: two halves give the CRC of the whole.
        QCOMPARE(crc32({p + 4, 5}, crc32({p, 4})), 0xCBF43926u);
    }

    // docs/protocol.md's 0x%08X, the one form a plan ID is shown in.
    void planIdShownOneWay()
    {
        QCOMPARE(planIdText(0xDEADBEEF), std::string("0xDEADBEEF"));
        QCOMPARE(planIdText(11), std::string("0x0000000B"));
        QCOMPARE(planIdText(0x5245000D), std::string("0x5245000D"));
    }

    void descriptorLayout()
    {
        const FlightPlanUploader up(0x01020304, randomPlan(300, 1));
        const std::vector<std::uint8_t>& s0 = up.sections().front().data;
        const std::uint32_t crc = crc32(randomPlan(300, 1));
        // 2 sections, 300 bytes, then the CRC.
        std::vector<std::uint8_t> expected{0x00, 0x02, 0x00, 0x00, 0x01, 0x2C};
        for (int shift : {24, 16, 8, 0})
            expected.push_back(static_cast<std::uint8_t>(crc >> shift));
        QVERIFY(std::equal(expected.begin(), expected.end(), s0.begin()));
        QCOMPARE(up.sections().front().planId, 0x01020304u);
    }

    void roundTrip_data()
    {
        QTest::addColumn<std::size_t>("planBytes");
        QTest::addColumn<std::size_t>("sectionSize");
        QTest::addColumn<std::size_t>("sections");
        for (std::size_t s : {std::size_t{215}, std::size_t{199}}) {
            const std::size_t first = s - FlightPlanDescriptor::kSize;  // plan bytes section 0 holds
            const std::vector<std::pair<std::size_t, std::size_t>> cases{
                {0, 1},
                {1, 1},
                {first - 1, 1},
                {first, 1},
                {first + 1, 2},
                {first + s - 1, 2},
                {first + s, 2},
                {first + s + 1, 3},
                {10240, (10240 + FlightPlanDescriptor::kSize + s - 1) / s},
            };
            for (const auto& [bytes, count] : cases)
                QTest::addRow("%zu bytes in %zu-byte sections", bytes, s) << bytes << s << count;
        }
    }

    void roundTrip()
    {
        QFETCH(std::size_t, planBytes);
        QFETCH(std::size_t, sectionSize);
        QFETCH(std::size_t, sections);
        const auto plan = randomPlan(planBytes, static_cast<unsigned>(planBytes));
        FlightPlanUploader up(77, plan, sectionSize, 1);
        QCOMPARE(up.sections().size(), sections);
        QCOMPARE(up.descriptor().sectionCount, sections);
        QCOMPARE(up.descriptor().totalBytes, planBytes);
        for (std::size_t i = 0; i < sections; ++i) {
            const FlightPlanSection& s = up.sections()[i];
            QCOMPARE(s.sectionId, i);
            QVERIFY(!s.data.empty());
            if (i + 1 < sections)
                QCOMPARE(s.data.size(), sectionSize);
            else
                QVERIFY(s.data.size() <= sectionSize);
        }

        FlightPlanAssembler in;
        for (std::size_t i = 0; i < sections; ++i) {
            const auto section = up.next();
            QVERIFY(section);
            const auto r = in.add(overTheAir(*section, sectionSize));
            if (i + 1 < sections) {
                QCOMPARE(kindName(r.kind), kindName(Kind::InProgress));
                QCOMPARE(r.received, i + 1);
                QCOMPARE(r.total, sections);
            } else {
                QCOMPARE(kindName(r.kind), kindName(Kind::Complete));
                QCOMPARE(r.planId, 77u);
                QVERIFY(r.plan == plan);
            }
        }
        QVERIFY(!up.next());  // one pass allowed
        QCOMPARE(up.state(), FlightPlanUploader::State::GaveUp);
        QVERIFY(in.lastComplete());
        QCOMPARE(in.lastComplete()->descriptor, up.descriptor());
    }

    void missingSectionNamed()
    {
        FlightPlanUploader up(5, randomPlan(2000, 2));  // 10 sections
        QCOMPARE(up.sections().size(), std::size_t{10});
        FlightPlanAssembler in;
        const auto pass = onePass(up);
        for (std::size_t i = 0; i < 3; ++i)
            QCOMPARE(kindName(in.add(pass[i]).kind), kindName(Kind::InProgress));
        // Section 3 lost: found when section 4 arrives.
        auto r = in.add(pass[4]);
        QCOMPARE(kindName(r.kind), kindName(Kind::Missing));
        QCOMPARE(r.missing, std::vector<std::uint16_t>{3});
        QCOMPARE(r.received, std::size_t{4});
        QCOMPARE(r.total, std::size_t{10});
        // Section 9 lost too: found when the cycle wraps.
        for (std::size_t i = 5; i < 9; ++i)
            QCOMPARE(kindName(in.add(pass[i]).kind), kindName(Kind::InProgress));
        r = in.add(pass[0]);
        QCOMPARE(kindName(r.kind), kindName(Kind::Missing));
        QCOMPARE(r.missing, (std::vector<std::uint16_t>{3, 9}));
        QCOMPARE(kindName(in.add(pass[3]).kind), kindName(Kind::InProgress));
        r = in.add(pass[9]);
        QCOMPARE(kindName(r.kind), kindName(Kind::Complete));
        QVERIFY(r.plan == randomPlan(2000, 2));
    }

    void firstSectionLost()
    {
        FlightPlanUploader up(6, randomPlan(1000, 3));
        FlightPlanAssembler in;
        const auto pass = onePass(up);
        auto r = in.add(pass[2]);
        QCOMPARE(kindName(r.kind), kindName(Kind::Missing));
        QCOMPARE(r.missing, (std::vector<std::uint16_t>{0, 1}));
        QCOMPARE(r.total, std::size_t{0});  // the descriptor is in section 0
        for (std::size_t i = 3; i < pass.size(); ++i)
            in.add(pass[i]);
        // The wrap reveals no new loss: section 1 was named already.
        r = in.add(pass[0]);
        QCOMPARE(kindName(r.kind), kindName(Kind::InProgress));
        QCOMPARE(r.received, pass.size() - 1);
        QCOMPARE(r.total, pass.size());
        r = in.add(pass[1]);
        QCOMPARE(kindName(r.kind), kindName(Kind::Complete));
    }

    void duplicatesHarmless()
    {
        FlightPlanUploader up(7, randomPlan(900, 4), FlightPlanSection::kMaxData, 0);
        FlightPlanAssembler in;
        const auto pass = onePass(up);
        for (std::size_t i = 0; i < pass.size(); ++i) {
            const auto r1 = in.add(pass[i]);
            if (i + 1 == pass.size()) {
                QCOMPARE(kindName(r1.kind), kindName(Kind::Complete));
                break;
            }
            const auto r2 = in.add(pass[i]);
            QCOMPARE(kindName(r1.kind), kindName(Kind::InProgress));
            QCOMPARE(kindName(r2.kind), kindName(Kind::InProgress));
            QCOMPARE(r2.received, i + 1);
        }
        // The sender keeps cycling until it sees the acknowledgement.
        for (const auto& s : pass) {
            const auto r = in.add(s);
            QCOMPARE(kindName(r.kind), kindName(Kind::AlreadyComplete));
            QCOMPARE(r.planId, 7u);
            QVERIFY(r.plan.empty());
        }
    }

    void outOfOrder()
    {
        FlightPlanUploader up(8, randomPlan(3000, 5));
        auto pass = onePass(up);
        std::mt19937 rng(9);
        for (int trial = 0; trial < 20; ++trial) {
            std::shuffle(pass.begin(), pass.end(), rng);
            FlightPlanAssembler in;
            for (std::size_t i = 0; i < pass.size(); ++i) {
                const auto r = in.add(pass[i]);
                QVERIFY2(r.kind != Kind::Error, r.error.c_str());
                QCOMPARE(r.kind == Kind::Complete, i + 1 == pass.size());
                if (r.kind == Kind::Complete)
                    QVERIFY(r.plan == randomPlan(3000, 5));
            }
        }
    }

    void crcMismatchCollectsAgain()
    {
        FlightPlanUploader up(9, randomPlan(1500, 6), FlightPlanSection::kMaxData, 0);
        FlightPlanAssembler in;
        auto damaged = onePass(up);
        damaged[2].data[17] ^= 0x20;
        for (std::size_t i = 0; i + 1 < damaged.size(); ++i)
            QCOMPARE(kindName(in.add(damaged[i]).kind), kindName(Kind::InProgress));
        auto r = in.add(damaged.back());
        QCOMPARE(kindName(r.kind), kindName(Kind::Error));
        QVERIFY2(QByteArray::fromStdString(r.error).contains("CRC-32"), r.error.c_str());
        QVERIFY(!in.lastComplete());
        // The next, clean, pass completes.
        const auto clean = onePass(up);
        for (std::size_t i = 0; i < clean.size(); ++i)
            r = in.add(clean[i]);
        QCOMPARE(kindName(r.kind), kindName(Kind::Complete));
        QVERIFY(r.plan == randomPlan(1500, 6));
    }

    void corruptDescriptor()
    {
        FlightPlanAssembler in;
        FlightPlanSection s{11, 0, {0x00, 0x01, 0x00}};
        auto r = in.add(s);
        QCOMPARE(kindName(r.kind), kindName(Kind::Error));
        QVERIFY2(QByteArray::fromStdString(r.error).contains("descriptor"), r.error.c_str());

        s.data = {0x00, 0x00, 0, 0, 0, 5, 0, 0, 0, 0, 1, 2, 3, 4, 5};  // zero sections
        QCOMPARE(kindName(in.add(s).kind), kindName(Kind::Error));
        s.data = {0x00, 0x01, 0, 0, 1, 0, 0, 0, 0, 0, 1, 2};  // one section of 256 bytes cannot be
        QCOMPARE(kindName(in.add(s).kind), kindName(Kind::Error));
        s.data = {0x00, 0x01, 0, 0, 0, 3, 0, 0, 0, 0, 1, 2};  // says 3 bytes, holds 2
        QCOMPARE(kindName(in.add(s).kind), kindName(Kind::Error));

        FlightPlanSection zeroId{0, 3, {1, 2, 3}};
        QCOMPARE(kindName(in.add(zeroId).kind), kindName(Kind::Error));
        QCOMPARE(kindName(in.add(FlightPlanSection{}).kind), kindName(Kind::None));
    }

    void newPlanRestarts()
    {
        FlightPlanUploader a(20, randomPlan(1000, 7));
        FlightPlanUploader b(21, randomPlan(700, 8));
        FlightPlanAssembler in;
        const auto passA = onePass(a);
        in.add(passA[0]);
        in.add(passA[1]);
        QCOMPARE(in.currentPlanId(), 20u);
        FlightPlanAssembler::Result r;
        for (const auto& s : onePass(b)) {
            r = in.add(s);
            QCOMPARE(r.planId, 21u);
        }
        QCOMPARE(kindName(r.kind), kindName(Kind::Complete));
        QVERIFY(r.plan == randomPlan(700, 8));
        // Plan 20's two sections went with it: its remaining sections alone do not complete it.
        r = in.add(passA[2]);
        QCOMPARE(kindName(r.kind), kindName(Kind::Missing));
        QCOMPARE(r.missing, (std::vector<std::uint16_t>{0, 1}));
        for (std::size_t i = 3; i < passA.size(); ++i)
            QCOMPARE(kindName(in.add(passA[i]).kind), kindName(Kind::InProgress));
    }

    void uploaderCyclesUntilAcknowledged()
    {
        FlightPlanUploader up(30, randomPlan(500, 9), FlightPlanSection::kMaxData, 2);
        QCOMPARE(up.sections().size(), std::size_t{3});
        QCOMPARE(up.progress().pass, 0);
        std::vector<std::uint16_t> ids;
        FlightPlanAssembler in;
        while (auto s = up.next()) {
            ids.push_back(s->sectionId);
            in.add(*s);
            if (ids.size() == 1)
                QCOMPARE(up.progress().sent, std::size_t{1});
        }
        QCOMPARE(ids, (std::vector<std::uint16_t>{0, 1, 2, 0, 1, 2}));
        QCOMPARE(up.state(), FlightPlanUploader::State::GaveUp);
        QCOMPARE(up.progress().sent, std::size_t{3});
        QCOMPARE(up.progress().total, std::size_t{3});
        QCOMPARE(up.progress().pass, 2);

        FlightPlanUploader again(30, randomPlan(500, 9), FlightPlanSection::kMaxData, 0);
        QVERIFY(again.next());
        const FlightPlanSection ack = overTheAir(in.lastComplete()->toSection(), FlightPlanSection::kMaxData);
        QCOMPARE(ack.sectionId, kAcknowledgementSectionId);
        QVERIFY(FlightPlanAcknowledgement::read(ack));
        // The assembler takes the aircraft's acknowledgement for no plan data.
        QCOMPARE(kindName(in.add(ack).kind), kindName(Kind::None));

        FlightPlanUploader other(30, randomPlan(500, 10), FlightPlanSection::kMaxData, 0);
        QVERIFY(!other.handleReply(ack));  // same ID, other content
        QVERIFY(!again.handleReply(FlightPlanSection{}));
        QVERIFY(again.handleReply(ack));
        QCOMPARE(again.state(), FlightPlanUploader::State::Acknowledged);
        QVERIFY(!again.next());
    }

    void uploaderRefusesBadParameters()
    {
        const auto plan = randomPlan(10, 1);
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, FlightPlanUploader(0, plan));
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, FlightPlanUploader(1, plan, 9));
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, FlightPlanUploader(1, plan, 216));
        const std::vector<std::uint8_t> huge(kMaxFlightPlanSections * 10);
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, FlightPlanUploader(1, huge, 10));
    }

    void planFormat2Layout()
    {
        // One waypoint, an inclusion square, an exclusion circle, one rally point.
        plan::Contents c;
        c.homeLatitude = 522076813;  // 52.2076813 deg
        c.homeLongitude = 1189255;
        c.homeAltitude = 14200;
        plan::Item wp;
        wp.command = 16;
        wp.frame = 3;
        wp.params = {0, 0, 0, 0x7FC00000};
        wp.x = 522151260;
        wp.y = 1205000;
        wp.z = 120000;
        c.items.push_back(wp);
        QCOMPARE(c.format(), std::uint8_t{1});
        QCOMPARE(plan::encode(c).size(), plan::kHeaderBytes + plan::kItemBytes);
        c.polygons.push_back({true, {{1, 2}, {3, 4}, {5, 6}, {7, 8}}});
        c.circles.push_back({false, {-10, -20}, 150000});
        c.rallyPoints.push_back({{100, 200}, 50000});
        QCOMPARE(c.format(), std::uint8_t{2});
        const std::vector<std::uint8_t> bytes = plan::encode(c);
        QCOMPARE(bytes.size(), std::size_t{16 + 34 + 2 + 4 + 32 + 2 + 14 + 2 + 12});
        QCOMPARE(bytes[0], std::uint8_t{2});
        const auto hex = [&](std::size_t at, std::size_t n) {
            return QByteArray(reinterpret_cast<const char*>(bytes.data() + at), qsizetype(n)).toHex();
        };
        // P = 1, inclusion, reserved, V = 4, the first vertex (1, 2).
        QCOMPARE(hex(50, 14), QByteArray("0001010000040000000100000002"));
        // C = 1, exclusion, reserved, centre (-10, -20), radius 150 m = 150000 mm.
        QCOMPARE(hex(50 + 2 + 4 + 32, 16), QByteArray("00010000fffffff6ffffffec000249f0"));
        // R = 1, (100, 200), 50 m above home.
        QCOMPARE(hex(50 + 2 + 36 + 16, 14), QByteArray("0001000000640000 00c80000c350").replace(" ", ""));
        std::string error;
        const auto back = plan::decode(bytes, &error);
        QVERIFY2(back, error.c_str());
        QVERIFY(*back == c);

        const plan::Report report = plan::Report::of(c);
        QCOMPARE(QByteArray(reinterpret_cast<const char*>(report.toBytes().data()), 11).toHex(),
                 QByteArray("020001000100040001" "0001"));
        QCOMPARE(report.describe(),
                 std::string("1 mission item, fence 1 polygon (4 vertices) and 1 circle, 1 rally point"));
        QVERIFY(plan::Report::read(report.toBytes()) == report);
    }

    void planDecodeErrors_data()
    {
        QTest::addColumn<QByteArray>("bytes");
        QTest::addColumn<QString>("error");
        const QByteArray header2 = QByteArray::fromHex("02000000" "80000000" "80000000" "80000000");
        QTest::newRow("short header") << QByteArray::fromHex("0100") << "byte 0: the plan header needs 16 bytes; 2 left";
        QTest::newRow("format 3") << QByteArray::fromHex("03000000800000008000000080000000")
                                  << "byte 1: plan format 3; formats 1 and 2 are known";
        QTest::newRow("item cut") << QByteArray::fromHex("01000001800000008000000080000000") + QByteArray(20, 0)
                                  << "byte 16: mission item 1 of 1 needs 34 bytes; 20 left";
        QTest::newRow("no fence count") << header2 << "byte 16: the fence polygon count needs 2 bytes; 0 left";
        QTest::newRow("two vertices") << header2 + QByteArray::fromHex("000101000002")
                                      << "byte 22: fence polygon 1 has 2 vertices; a polygon needs 3";
        QTest::newRow("zero radius") << header2 + QByteArray::fromHex("0000" "0001" "0100" "0000000000000000" "00000000")
                                     << "byte 34: fence circle 1 has no radius";
        QTest::newRow("trailing") << header2 + QByteArray::fromHex("000000000000ff")
                                  << "byte 22: 1 byte after the end of a format 2 plan";
    }

    void planDecodeErrors()
    {
        QFETCH(QByteArray, bytes);
        QFETCH(QString, error);
        std::string reason;
        QVERIFY(!plan::decode({reinterpret_cast<const std::uint8_t*>(bytes.constData()), std::size_t(bytes.size())},
                              &reason));
        QCOMPARE(QString::fromStdString(reason), error);
    }

    void acknowledgementCarriesAReport()
    {
        FlightPlanAcknowledgement ack{77, {2, 300, 0xDEADBEEF}, {}};
        // Without a report: the 10-byte descriptor, as before.
        QCOMPARE(ack.toSection().data.size(), FlightPlanDescriptor::kSize);
        ack.report = {2, 0, 9, 0, 1, 0, 4, 0, 0, 0, 3};
        const FlightPlanSection s = overTheAir(ack.toSection(), FlightPlanSection::kMaxData);
        QCOMPARE(s.data.size(), FlightPlanDescriptor::kSize + 11);
        const auto back = FlightPlanAcknowledgement::read(s);
        QVERIFY(back);
        QVERIFY(*back == ack);
        // The sender takes it for its plan and keeps what the aircraft said.
        const auto bytes = randomPlan(300, 12);
        FlightPlanUploader up(77, bytes);
        ack.descriptor = up.descriptor();
        QVERIFY(up.handleReply(ack.toSection()));
        QVERIFY(up.acknowledgedReport() == ack.report);
    }

    void secureSectionSize()
    {
        // 199-byte sections go through an encoder limited to 199 and still complete.
        const auto plan = randomPlan(5000, 11);
        FlightPlanUploader up(40, plan, 199, 1);
        FlightPlanAssembler in;
        FlightPlanAssembler::Result r;
        while (auto s = up.next()) {
            QVERIFY(s->data.size() <= 199);
            r = in.add(overTheAir(*s, 199));
        }
        QCOMPARE(kindName(r.kind), kindName(Kind::Complete));
        QVERIFY(r.plan == plan);
        // A 215-byte section does not fit the secure encoder.
        FlightPlanUploader wide(41, plan);
        Message m;
        m.flightPlan = wide.sections().front();
        EncodeOptions secure;
        secure.maxFlightPlanData = 199;
        QVERIFY(!validate(m, secure).empty());
    }
};

QTEST_APPLESS_MAIN(TestFlightPlan)
#include "tst_flightplan.moc"
