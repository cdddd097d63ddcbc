// FrameReceiver: no wrong frame delivered through any damage the soak
// (tests/bench/soak_receive.cpp) applies, here at 10^4 frames a row; every
// frame within RS's reach delivered; and each refusal with its reason.
#include "codec/message/FlightPlanTransfer.h"
#include "codec/receive/FrameReceiver.h"
#include "codec/secure/SecureCodec.h"
#include "tests/support/ReceiveAttacks.h"

#include <QtTest>

#include <functional>
#include <initializer_list>
#include "tests/support/BerSession.h"

using namespace rcm;
using namespace rcm::test;

namespace {

// 2026-12-31 12:00:00 UTC: time_UTC 120000, date_UTC 261231.
constexpr std::int64_t kNoon = 1'798'718'400;

struct Collected {
    std::vector<ReceivedFrame> frames;
    FrameReceiver receiver;
    std::int64_t nowMicros = kNoon * 1'000'000;

    explicit Collected(FrameReceiver::Options options = {})
        : receiver(withClock(std::move(options)), [this](const ReceivedFrame& f) {
              frames.push_back(f);
              frames.back().raw = {};  // valid only in the handler
          })
    {
    }
    FrameReceiver::Options withClock(FrameReceiver::Options o)
    {
        o.clock = [this] { return nowMicros; };
        return o;
    }
    Collected(const Collected&) = delete;
    Collected& operator=(const Collected&) = delete;
};

// Frames first .. last of a session as one stream, each as `edit` leaves it
// (cut, slipped), through the receiver on the sender's clock.
void feedSession(const CommandSession& session, Collected& c, std::uint64_t first, std::uint64_t last,
                 const std::function<void(std::uint64_t frame, Bytes& bytes)>& edit)
{
    Bytes stream;
    for (std::uint64_t frame = first; frame <= last; ++frame) {
        const FrameBytes f = session.frameAt(frame);
        Bytes b(f.begin(), f.end());
        edit(frame, b);
        stream.insert(stream.end(), b.begin(), b.end());
        c.nowMicros = session.secondsAt(frame) * 1'000'000 + 500'000;
    }
    c.receiver.feed(stream);
    c.receiver.flush();
}

// What the receiver delivered of a session: frame indices in order, their
// offsets, and the first delivered frame that is not what was sent with
// its ID_msg (empty when there is none).
struct SessionDeliveries {
    std::vector<std::uint64_t> frames;
    std::vector<std::int64_t> offsets;
    std::string wrong;
};

SessionDeliveries deliveredFrom(const CommandSession& session, const Collected& c, std::uint64_t sent)
{
    SessionDeliveries d;
    for (const ReceivedFrame& f : c.frames) {
        if (!f.delivered())
            continue;
        const auto id = std::uint32_t(f.decoded.message.header.number(ItemId::ID_msg));
        const std::optional<std::uint64_t> i = session.indexOf(id, sent);
        if (!i || !(f.decoded.message == session.messageAt(*i))) {
            if (d.wrong.empty())
                d.wrong = "ID_msg " + std::to_string(id) + " at offset " + std::to_string(f.offset) + " is not as sent";
            continue;
        }
        d.frames.push_back(*i);
        d.offsets.push_back(f.offset);
    }
    return d;
}

// A command as the console sends it at kNoon + `second`.
Message command(std::uint32_t id, std::int64_t second = 0)
{
    const std::int64_t t = (kNoon + second) % 86400;
    Message m;
    m.header.set(ItemId::ID_msg, id);
    m.header.set(ItemId::ID_UA_source, Value::station({44, 133}));
    m.header.set(ItemId::time_UTC, t / 3600 * 10000 + t / 60 % 60 * 100 + t % 60);
    m.header.set(ItemId::date_UTC, 261231);
    Unit& e = m.addEngine(1);
    e.set(ItemId::eng_status, 0x90);
    e.set(ItemId::eng_carb_SET, 137);
    m.flaps.set(ItemId::FLAP_status, 0x90);
    m.flaps.set(ItemId::F_elev_set, -5);
    return m;
}

// `base` sent at kNoon + `second`, its counter `second`.
Message stampedAt(const Message& base, std::uint32_t second)
{
    Message m = base;
    m.header.set(ItemId::ID_msg, second);
    const std::int64_t t = (kNoon + second) % 86400;
    m.header.set(ItemId::time_UTC, t / 3600 * 10000 + t / 60 % 60 * 100 + t % 60);
    m.header.set(ItemId::date_UTC, 261231);
    return m;
}

EncodedBlocks encoded(const Message& m)
{
    Diagnostics errors;
    const std::optional<EncodedBlocks> b = encodeBlocks(m, errors);
    if (!b)
        qFatal("command does not encode: %s", errors.front().toString().c_str());
    return *b;
}

Bytes datagramOf(const Block& b1, const Block& b2)
{
    const DatagramBytes d = makeDatagram(b1, b2);
    return Bytes(d.begin(), d.end());
}

Bytes datagramOf(const Message& m)
{
    const EncodedBlocks b = encoded(m);
    return datagramOf(b.block1, b.block2);
}

// BLOCK 1 of `items`, led by padding as the encoder writes it.
Block block1Of(std::initializer_list<std::uint8_t> items)
{
    Block b;
    b.fill(kPad55);
    std::copy(items.begin(), items.end(), b.end() - static_cast<std::ptrdiff_t>(items.size()));
    return b;
}

Block emptyBlock2() { return encoded(command(1)).block2; }

// ID_msg 1, time_UTC 12:00:00, date_UTC 261231.
#define HEADER 0x03, 0x00, 0x00, 0x01, 0x05, 0x01, 0xD4, 0xC0, 0x06, 0x03, 0xFC, 0x6F

Refusal refusalOf(const Bytes& datagram, FrameReceiver::Options options = {})
{
    Collected c(std::move(options));
    c.receiver.receive(datagram);
    if (c.frames.size() != 1 || !c.frames[0].refusal)
        return static_cast<Refusal>(0xFF);
    return *c.frames[0].refusal;
}

}  // namespace

Q_DECLARE_METATYPE(rcm::Refusal)
Q_DECLARE_METATYPE(rcm::test::Bytes)

class TestReceive : public QObject {
    Q_OBJECT

private slots:
    void noWrongFrameDelivered_data();
    void noWrongFrameDelivered();
    void sixteenByteErrorsDelivered();
    void randomBytesDeliverNothing();
    void errorAtEitherEndOfCodeword1_data();
    void errorAtEitherEndOfCodeword1();
    void preambleThenConstant_data();
    void preambleThenConstant();
    void exactnessRules_data();
    void exactnessRules();
    void plausibility();
    void senderRestartConfirmedByNextFrame();
    void recordingIgnoresClock();
    void flightPlanSections();
    void planDescriptorBindsItsSections();
    void keyedLink();
    void wrongSizeDatagram();
    void replayedFramesNeverDelivered_data();
    void replayedFramesNeverDelivered();
    void oldFramesThatAgreeAreNoRestart();
    void splicesRefusedWhereTheProfileTells_data();
    void splicesRefusedWhereTheProfileTells();
    void noIntactFrameLostToAnEarlierReading_data();
    void noIntactFrameLostToAnEarlierReading();
    void slipsInARowThenAFrameWithoutItsMark_data();
    void slipsInARowThenAFrameWithoutItsMark();
    void trueFrameJustAfterARefusedRotation();
    void slipInsideBlock1PaddingNotDeliveredShifted();
    void slipInsideBlock1PaddingReadFromBytesEarly();
    void slipInsideBlock1ParityNotDeliveredShifted();
    void firstFrameAfterAnOutageDelivered();
    void predictionsPaidFromABudget();
    void sendersForgottenBeyondTheTable();
    void ownCommandPredictsTheStatus_data();
    void ownCommandPredictsTheStatus();
    void planSectionFromTwoPassesCopies();
    void severalCommandsChangedOnTheFirstFrame();
    void changedCommandsThroughSingleBitErrors();
};

void TestReceive::noWrongFrameDelivered_data()
{
    QTest::addColumn<int>("kind");
    QTest::addColumn<double>("ber");
    QTest::addColumn<int>("minimumCorrect");
    using K = Channel::Kind;
    QTest::newRow("clean") << int(K::Clean) << 0.0 << 10000;
    QTest::newRow("slip 1-3 bytes") << int(K::Slip) << 0.0 << 0;
    QTest::newRow("overwrite burst") << int(K::OverwriteBurst) << 0.0 << 3000;
    QTest::newRow("insertion burst") << int(K::InsertBurst) << 0.0 << 0;
    QTest::newRow("BER 1e-3") << int(K::BitErrors) << 1e-3 << 9990;
    QTest::newRow("BER 3e-3") << int(K::BitErrors) << 3e-3 << 9990;
    // Plain RS reads about 5 % of these frames and none at 3e-2: the rest
    // are read with the receiver's predictions.
    QTest::newRow("BER 1e-2") << int(K::BitErrors) << 1e-2 << 9700;
    QTest::newRow("BER 2e-2") << int(K::BitErrors) << 2e-2 << 9000;
    QTest::newRow("BER 3e-2") << int(K::BitErrors) << 3e-2 << 8000;
    // Every sent frame is there whole: none may be lost to the fakes.
    QTest::newRow("preamble + constant") << int(K::ConstantFollower) << 0.0 << 10000;
    QTest::newRow("preamble + random") << int(K::RandomFollower) << 0.0 << 10000;
}

void TestReceive::noWrongFrameDelivered()
{
    QFETCH(int, kind);
    QFETCH(double, ber);
    QFETCH(int, minimumCorrect);
    const RowResult r = runRow(CommandSession{}, Channel(Channel::Kind(kind), ber, ""), 10000, 7 + kind);
    qInfo("%llu of 10000 delivered correct, %llu of them read with a prediction",
          static_cast<unsigned long long>(r.correct), static_cast<unsigned long long>(r.fromPrediction));
    QVERIFY2(r.wrong == 0, r.firstWrong.c_str());
    QVERIFY2(r.correct >= std::uint64_t(minimumCorrect), qPrintable(QString::number(r.correct)));
    QCOMPARE(r.correct + r.lost, r.sent);
}

void TestReceive::sixteenByteErrorsDelivered()
{
    const RowResult r = runRow(CommandSession{}, Channel(Channel::Kind::ByteErrors16, 0, ""), 1000, 16);
    QCOMPARE(r.wrong, std::uint64_t{0});
    QCOMPARE(r.correct, std::uint64_t{1000});
}

// A megabyte of random bytes, read as a recording with the predictions on:
// nothing in it is a frame anybody sent.
void TestReceive::randomBytesDeliverNothing()
{
    const RowResult r = runRandomBytes(1, 99);
    QVERIFY2(r.wrong == 0, r.firstWrong.c_str());
}

void TestReceive::errorAtEitherEndOfCodeword1_data()
{
    QTest::addColumn<int>("place");
    QTest::newRow("first byte") << 0;
    QTest::newRow("last byte") << int(kCodewordSize - 1);
}

void TestReceive::errorAtEitherEndOfCodeword1()
{
    // 16 random byte errors in each codeword, preamble intact, one of them at
    // the given end of codeword 1: libfec corrects it, so it must be delivered.
    QFETCH(int, place);
    const CommandSession session;
    Collected c;
    std::mt19937_64 rng(std::uint64_t(place) + 99);
    for (std::uint64_t i = 0; i < 300; ++i) {
        FrameBytes f = session.frameAt(i);
        Channel::corruptBytes(&f[kPreambleSize], rng, place);
        Channel::corruptBytes(&f[kPreambleSize + kCodewordSize], rng, place);
        c.nowMicros = session.secondsAt(i) * 1'000'000;
        c.receiver.feed(f);
    }
    c.receiver.flush();
    QCOMPARE(c.frames.size(), std::size_t{300});
    for (std::size_t i = 0; i < c.frames.size(); ++i) {
        const ReceivedFrame& f = c.frames[i];
        QVERIFY2(f.delivered(), qPrintable(QStringLiteral("frame %1: %2").arg(i).arg(QString::fromStdString(f.detail))));
        QCOMPARE(f.offset, std::int64_t(i * kFrameSize));
        QCOMPARE(f.blocks.corrected.block1, 16);
        QCOMPARE(f.blocks.corrected.block2, 16);
        QVERIFY(f.decoded.message == session.messageAt(i));
    }
}

void TestReceive::preambleThenConstant_data()
{
    QTest::addColumn<int>("byte");
    QTest::addColumn<Refusal>("refusal");
    QTest::addColumn<QString>("detail");
    // Every constant word is an RS codeword: these decode with 0 corrections.
    QTest::newRow("00") << 0x00 << Refusal::UnknownItem << "block 1 offset 0: unknown Item_ID 0x00";
    QTest::newRow("55") << 0x55 << Refusal::BadPadding << "block 2 offset 222: End_Of_String: byte 0x55";
    QTest::newRow("AA") << 0xAA << Refusal::BadPadding << "block 2 offset 177: flight plan padding: byte 0xAA";
    QTest::newRow("0F") << 0x0F << Refusal::UnknownItem << "block 1 offset 0: unknown Item_ID 0x0F";
    QTest::newRow("FF") << 0xFF << Refusal::UnknownItem << "block 1 offset 0: unknown Item_ID 0xFF";
}

void TestReceive::preambleThenConstant()
{
    QFETCH(int, byte);
    QFETCH(Refusal, refusal);
    QFETCH(QString, detail);
    Bytes bytes(preamble().begin(), preamble().end());
    bytes.insert(bytes.end(), kDatagramSize, std::uint8_t(byte));
    Collected c;
    c.receiver.feed(bytes);
    c.receiver.flush();
    QCOMPARE(c.frames.size(), std::size_t{1});
    const ReceivedFrame& f = c.frames[0];
    QCOMPARE(f.blocks.corrected.block1, 0);
    QCOMPARE(f.blocks.corrected.block2, 0);
    QCOMPARE(f.refusal, std::optional<Refusal>(refusal));
    QVERIFY2(QString::fromStdString(f.detail).startsWith(detail), f.detail.c_str());
    QCOMPARE(c.receiver.stats().refused[std::size_t(refusal)], std::uint64_t{1});
    QCOMPARE(c.receiver.stats().delivered, std::uint64_t{0});
}

void TestReceive::exactnessRules_data()
{
    QTest::addColumn<Bytes>("datagram");
    QTest::addColumn<Refusal>("refusal");
    const Block b2 = emptyBlock2();
    QTest::newRow("as the encoder writes it") << datagramOf(block1Of({HEADER}), b2) << Refusal(0xFF);
    QTest::newRow("no date_UTC") << datagramOf(block1Of({0x03, 0x00, 0x00, 0x01, 0x05, 0x01, 0xD4, 0xC0}), b2)
                                 << Refusal::MissingHeaderItem;
    {
        Message m = command(1);
        m.header.erase(ItemId::ID_msg);
        QTest::newRow("no ID_msg") << datagramOf(m) << Refusal::MissingHeaderItem;
    }
    {
        Block b = block1Of({HEADER, 0x55, 0x40, 0x90});  // padding between items
        QTest::newRow("padding between items") << datagramOf(b, b2) << Refusal::BadPadding;
        Block after = block1Of({HEADER, 0x40, 0x90, 0x55});
        QTest::newRow("padding after the items") << datagramOf(after, b2) << Refusal::BadPadding;
        Block begin = block1Of({0x01, 0x09, HEADER});
        QTest::newRow("BEGIN before the items") << datagramOf(begin, b2) << Refusal::BadPadding;
    }
    {
        Block pad = b2;
        pad[100] = 0x54;
        QTest::newRow("BLOCK 2 padding") << datagramOf(block1Of({HEADER}), pad) << Refusal::BadPadding;
        Block eos = b2;
        eos[222] = 0x01;
        QTest::newRow("End_Of_String") << datagramOf(block1Of({HEADER}), eos) << Refusal::BadPadding;
    }
    QTest::newRow("corrupt two-bit field") << datagramOf(block1Of({HEADER, 0x40, 0x00}), b2) << Refusal::InvalidField;
    QTest::newRow("reserved bits") << datagramOf(block1Of({HEADER, 0x40, 0x91}), b2) << Refusal::InvalidField;
    QTest::newRow("-128 degrees") << datagramOf(block1Of({HEADER, 0x45, 0x80}), b2) << Refusal::InvalidField;
    QTest::newRow("time 24:00:00") << datagramOf(block1Of({0x03, 0x00, 0x00, 0x01, 0x05, 0x03, 0xA9, 0x80, 0x06, 0x03,
                                                          0xFC, 0x6F}),
                                                b2)
                                   << Refusal::InvalidField;
    QTest::newRow("unknown item") << datagramOf(block1Of({HEADER, 0x10, 0x00}), b2) << Refusal::UnknownItem;
    QTest::newRow("item cut off") << datagramOf(block1Of({HEADER, 0x04, 0x00, 0x2C}), b2) << Refusal::UnknownItem;
    QTest::newRow("flaps before engine")
        << datagramOf(block1Of({HEADER, 0x40, 0x90, 0x31, 0x01, 0x30, 0x90}), b2) << Refusal::NotCanonical;
    QTest::newRow("time before ID_msg") << datagramOf(block1Of({0x05, 0x01, 0xD4, 0xC0, 0x03, 0x00, 0x00, 0x01, 0x06,
                                                               0x03, 0xFC, 0x6F}),
                                                     b2)
                                        << Refusal::NotCanonical;
    QTest::newRow("repeated item") << datagramOf(block1Of({HEADER, 0x45, 0x01, 0x45, 0x01}), b2) << Refusal::Warning;
    QTest::newRow("orphan item") << datagramOf(block1Of({HEADER, 0x33, 0x10}), b2) << Refusal::Warning;
    {
        Message m = command(1);
        m.flightPlan.sectionId = 1;
        m.flightPlan.data = {1, 2, 3};
        QTest::newRow("flight_plan_ID 0 with data") << datagramOf(m) << Refusal::InvalidField;
    }
    {
        // What a keyed sender puts on the wire, to a receiver without the key.
        secure::SecretKey key;
        key.mutableBytes()[0] = 7;
        secure::SecureCodec codec(key, secure::Direction::GcsToUa);
        Diagnostics errors;
        const std::optional<EncodedBlocks> b = codec.encode(command(1), errors);
        QVERIFY(b);
        QTest::newRow("enciphered") << datagramOf(b->block1, b->block2) << Refusal::Enciphered;
    }
}

void TestReceive::exactnessRules()
{
    QFETCH(Bytes, datagram);
    QFETCH(Refusal, refusal);
    FrameReceiver::Options o;
    o.mode = FrameReceiver::Mode::Recording;
    QCOMPARE(int(refusalOf(datagram, o)), int(refusal));
}

void TestReceive::plausibility()
{
    Collected c;
    const auto send = [&](const Message& m) {
        c.receiver.receive(datagramOf(m));
        return c.frames.back();
    };
    QVERIFY(send(command(100, 0)).delivered());
    QVERIFY(send(command(101, 1)).delivered());

    ReceivedFrame f = send(command(101, 2));
    QCOMPARE(f.refusal, std::optional<Refusal>(Refusal::Replayed));
    QCOMPARE(f.detail, std::string("ID_msg 101 is not ahead of the last accepted 101"));
    QCOMPARE(send(command(90, 2)).refusal, std::optional<Refusal>(Refusal::Replayed));

    f = send(command(101 + kMaxMessageIdStep + 1, 2));
    QCOMPARE(f.refusal, std::optional<Refusal>(Refusal::MessageIdStep));
    QCOMPARE(f.detail, std::string("ID_msg 402 is 301 ahead of the last accepted; at most 300"));

    QCOMPARE(send(command(102, 0)).refusal, std::optional<Refusal>(Refusal::TimeStep));  // before the last
    f = send(command(102, 5));  // 4 s after the last, one message later: at most 1 + 2 s
    QCOMPARE(f.refusal, std::optional<Refusal>(Refusal::TimeStep));
    QCOMPARE(f.detail, std::string("time_UTC is 4 s after the last accepted, 1 message later"));

    c.nowMicros += 40'000'000;  // the receiver's clock 40 s on: outside the 30 s window
    f = send(command(102, 2));
    QCOMPARE(f.refusal, std::optional<Refusal>(Refusal::TimeWindow));
    QCOMPARE(f.detail, std::string("time_UTC/date_UTC is 38 s behind the receiver's clock; the window is 30 s"));
    c.nowMicros -= 40'000'000;

    // Three frames lost: ID + 4, time + 4 s.
    QVERIFY(send(command(105, 5)).delivered());
    QCOMPARE(c.receiver.stats().delivered, std::uint64_t{3});
    QCOMPARE(c.receiver.stats().refused[std::size_t(Refusal::Replayed)], std::uint64_t{2});
    QCOMPARE(c.receiver.stats().refusedTotal(), std::uint64_t{6});

    // Another sender has its own history.
    Message other = command(7, 5);
    other.header.set(ItemId::ID_UA_source, Value::station({44, 134}));
    QVERIFY(send(other).delivered());
    QCOMPARE(c.receiver.senders().size(), std::size_t{2});
    QCOMPARE(c.receiver.lastAccepted()->messageId, 7u);
}

void TestReceive::senderRestartConfirmedByNextFrame()
{
    // A console restarted counts from 0 again: its first frame is refused,
    // and the next one, following it, is delivered.
    Collected c;
    c.receiver.receive(datagramOf(command(5000, 0)));
    c.receiver.receive(datagramOf(command(0, 1)));
    c.receiver.receive(datagramOf(command(1, 2)));
    QCOMPARE(c.frames.size(), std::size_t{3});
    QVERIFY(c.frames[0].delivered());
    QCOMPARE(c.frames[1].refusal, std::optional<Refusal>(Refusal::Replayed));
    QVERIFY(c.frames[2].delivered());
    QCOMPARE(c.receiver.lastAccepted()->messageId, 1u);
    // Only a frame that follows the refused one confirms it.
    c.receiver.receive(datagramOf(command(9000, 3)));
    c.receiver.receive(datagramOf(command(9500, 4)));
    QCOMPARE(c.frames[3].refusal, std::optional<Refusal>(Refusal::MessageIdStep));
    QCOMPARE(c.frames[4].refusal, std::optional<Refusal>(Refusal::MessageIdStep));
}

void TestReceive::recordingIgnoresClock()
{
    FrameReceiver::Options o;
    o.mode = FrameReceiver::Mode::Recording;
    Collected c(o);
    c.nowMicros = 0;  // 1970: a live receiver would refuse every frame
    c.receiver.receive(datagramOf(command(1, 0)));
    c.receiver.receive(datagramOf(command(2, 1)));
    c.receiver.receive(datagramOf(command(2, 2)));
    QVERIFY(c.frames[0].delivered());
    QVERIFY(c.frames[1].delivered());
    QCOMPARE(c.frames[2].refusal, std::optional<Refusal>(Refusal::Replayed));  // continuity still holds

    Collected live;
    live.nowMicros = 0;
    live.receiver.receive(datagramOf(command(1, 0)));
    QCOMPARE(live.frames[0].refusal, std::optional<Refusal>(Refusal::TimeWindow));
}

// Sections of a plan of 6 sections of 12 bytes (the last 5): 10 + 55 plan
// bytes. Section 0 starts with the descriptor.
FlightPlanSection sixSectionPlan(std::uint32_t plan, std::uint16_t section)
{
    FlightPlanSection s;
    s.planId = plan;
    s.sectionId = section;
    s.data.assign(section == 5 ? 5 : 12, std::uint8_t(0x30 + section));
    if (section == 0) {
        const FlightPlanDescriptor d{6, 55, 0x12345678};
        d.write(std::span<std::uint8_t, FlightPlanDescriptor::kSize>(s.data.data(), FlightPlanDescriptor::kSize));
    }
    return s;
}

void TestReceive::flightPlanSections()
{
    Collected c;
    std::uint32_t id = 1;
    const auto sendSection = [&](const FlightPlanSection& s, std::uint32_t step = 1) {
        id += step;
        Message m = command(id, id);
        m.flightPlan = s;
        c.receiver.receive(datagramOf(m));
        return c.frames.back().refusal;
    };
    const auto send = [&](std::uint32_t plan, std::uint16_t section, std::uint32_t step = 1) {
        return sendSection(sixSectionPlan(plan, section), step);
    };
    QVERIFY(!send(0xA, 2));  // the first frame from a sender: joins a pass in progress
    QVERIFY(!send(0xA, 3));
    QVERIFY(!send(0xA, 4));
    QVERIFY(!send(0xA, 0, 2));  // the next pass, section 5 lost
    QCOMPARE(send(0xA, 5), std::optional<Refusal>(Refusal::PlanSection));
    QCOMPARE(c.frames.back().detail, std::string("flight plan 0x0000000A section 5 does not follow section 0 1 message later"));
    QCOMPARE(send(0xA, 0), std::optional<Refusal>(Refusal::PlanSection));  // the same section again
    QVERIFY(!send(0xA, 3, 1));  // three messages after section 0: sections 1 .. 3 may have been sent
    QCOMPARE(send(0xB, 1), std::optional<Refusal>(Refusal::PlanSection));
    QCOMPARE(c.frames.back().detail,
             std::string("flight plan 0x0000000B section 1 does not follow any plan being sent 1 message later"));
    QVERIFY(!send(0xB, 0));  // a new plan starts at 0
    QVERIFY(!send(0xC, 1, 2));  // ... which may have been lost
    QVERIFY(!send(0xC, kAcknowledgementSectionId));  // link control fits anywhere
    QVERIFY(!send(0xC, 2));  // two messages after section 1
    QVERIFY(!sendSection({}));  // a frame may carry no section
    QVERIFY(!send(0xC, 3, 3));  // the sender took a pause, and starts again where it was
    QVERIFY(!send(0xC, 0, 5));  // ... or at the start: frames between carried none
}

void TestReceive::planDescriptorBindsItsSections()
{
    Collected c;
    std::uint32_t id = 1;
    const auto send = [&](FlightPlanSection s) {
        ++id;
        Message m = command(id, id);
        m.flightPlan = std::move(s);
        c.receiver.receive(datagramOf(m));
        return c.frames.back().refusal;
    };
    QVERIFY(!send(sixSectionPlan(0xA, 0)));
    QVERIFY(!send(sixSectionPlan(0xA, 1)));
    FlightPlanSection longer = sixSectionPlan(0xA, 2);
    longer.data.push_back(0);
    QCOMPARE(send(longer), std::optional<Refusal>(Refusal::PlanSection));
    QCOMPARE(c.frames.back().detail,
             std::string("flight plan 0x0000000A section 2 carries 13 bytes; its plan's descriptor makes it 12"));
    QVERIFY(!send(sixSectionPlan(0xA, 2)));
    QVERIFY(!send(sixSectionPlan(0xA, 3)));
    QVERIFY(!send(sixSectionPlan(0xA, 4)));
    FlightPlanSection shortLast = sixSectionPlan(0xA, 5);
    shortLast.data.pop_back();
    QCOMPARE(send(shortLast), std::optional<Refusal>(Refusal::PlanSection));
    QVERIFY(!send(sixSectionPlan(0xA, 5)));
    FlightPlanSection beyond = sixSectionPlan(0xA, 6);
    QCOMPARE(send(beyond), std::optional<Refusal>(Refusal::PlanSection));
    QCOMPARE(c.frames.back().detail, std::string("flight plan 0x0000000A section 6: the plan has 6 sections"));
    QVERIFY(!send(sixSectionPlan(0xA, 0)));  // the next pass

    // A section 0 whose descriptor its own size contradicts: 6 sections of
    // 12 bytes cannot hold 10 + 100 bytes.
    FlightPlanSection wrong = sixSectionPlan(0xD, 0);
    FlightPlanDescriptor{6, 100, 0}.write(
        std::span<std::uint8_t, FlightPlanDescriptor::kSize>(wrong.data.data(), FlightPlanDescriptor::kSize));
    QCOMPARE(send(wrong), std::optional<Refusal>(Refusal::PlanSection));
    QCOMPARE(c.frames.back().detail,
             std::string("flight plan 0x0000000D section 0: its descriptor does not fit a section of 12 bytes"));
}

void TestReceive::keyedLink()
{
    secure::SecretKey key;
    key.mutableBytes()[5] = 42;
    const secure::SecureCodec toAircraft(key, secure::Direction::GcsToUa);
    const secure::SecureCodec toConsole(key, secure::Direction::UaToGcs);
    secure::SecretKey otherKey;
    const secure::SecureCodec stranger(otherKey, secure::Direction::GcsToUa);
    const auto keyed = [](const secure::SecureCodec& codec, const Message& m) {
        Diagnostics errors;
        const std::optional<EncodedBlocks> b = codec.encode(m, errors);
        return datagramOf(b->block1, b->block2);
    };

    secure::ReplayGuard guard(secure::ReplayGuard::Options{30, {}, {}, [] { return kNoon; }});
    FrameReceiver::Options o;
    o.keys.codecs = {&toAircraft};
    o.keys.guard = &guard;
    Collected c(o);
    c.receiver.receive(keyed(toAircraft, command(10, 0)));
    c.receiver.receive(keyed(toConsole, command(11, 1)));
    c.receiver.receive(keyed(stranger, command(12, 2)));
    c.receiver.receive(datagramOf(command(13, 3)));
    c.receiver.receive(keyed(toAircraft, command(10, 4)));
    c.receiver.receive(keyed(toAircraft, command(14, 4)));
    QCOMPARE(c.frames.size(), std::size_t{6});
    QVERIFY(c.frames[0].delivered());
    QCOMPARE(c.frames[0].direction, std::optional<secure::Direction>(secure::Direction::GcsToUa));
    QVERIFY(c.frames[0].decoded.message == command(10, 0));
    QCOMPARE(c.frames[1].refusal, std::optional<Refusal>(Refusal::Forged));  // the other direction
    QCOMPARE(c.frames[2].refusal, std::optional<Refusal>(Refusal::Forged));
    QCOMPARE(c.frames[3].refusal, std::optional<Refusal>(Refusal::Plaintext));
    QCOMPARE(c.frames[4].refusal, std::optional<Refusal>(Refusal::Replayed));
    for (int i = 1; i <= 4; ++i)
        QVERIFY(c.frames[std::size_t(i)].decoded.message == Message{});  // nothing of a refused frame is read
    QVERIFY(c.frames[5].delivered());
    QCOMPARE(guard.lastAccepted(), std::optional<std::uint32_t>(14));

    // `rcm decode --key` without a direction: either, named.
    FrameReceiver::Options both;
    both.mode = FrameReceiver::Mode::Recording;
    both.keys.codecs = {&toAircraft, &toConsole};
    Collected d(both);
    d.receiver.receive(keyed(toConsole, command(11, 1)));
    QVERIFY(d.frames[0].delivered());
    QCOMPARE(d.frames[0].direction, std::optional<secure::Direction>(secure::Direction::UaToGcs));
}

void TestReceive::wrongSizeDatagram()
{
    Collected c;
    const Bytes d = datagramOf(command(1));
    c.receiver.receive(std::span<const std::uint8_t>(d.data(), d.size() - 1));
    QCOMPARE(c.frames.size(), std::size_t{1});
    QCOMPARE(c.frames[0].refusal, std::optional<Refusal>(Refusal::WrongSize));
    QCOMPARE(c.frames[0].detail, std::string("509 bytes; a datagram is 510 and a frame 600"));
    // A whole frame, as a frame log row holds it, is read too.
    const FrameBytes f = makeFrame(encoded(command(1)).block1, encoded(command(1)).block2);
    c.receiver.receive(f, 600);
    QVERIFY(c.frames[1].delivered());
    QCOMPARE(c.frames[1].offset, std::int64_t{600});
}

void TestReceive::replayedFramesNeverDelivered_data()
{
    QTest::addColumn<bool>("live");
    QTest::newRow("live") << true;
    QTest::newRow("recording") << false;
}

// Old frames of the session replayed into it, one to five in a row, half of
// them from the last 30 s: none is delivered again or after a newer one, and
// every frame sent once is delivered.
void TestReceive::replayedFramesNeverDelivered()
{
    QFETCH(bool, live);
    const AttackResult r = runReplay(CommandSession{}, 5000, 0.5, live ? 31 : 32,
                                     live ? FrameReceiver::Mode::Live : FrameReceiver::Mode::Recording);
    QVERIFY(r.attacks > 5000);
    QVERIFY2(r.row.stale == 0, r.row.firstStale.c_str());
    QVERIFY2(r.row.wrong == 0, r.row.firstWrong.c_str());
    QCOMPARE(r.row.correct, std::uint64_t{5000});
    QCOMPARE(r.row.refused[std::size_t(Refusal::Replayed)] + r.row.refused[std::size_t(Refusal::TimeWindow)],
             r.attacks);
}

// Two consecutive old frames agree with each other, and used to pass for a
// sender's restart; a restart is recognised by a later stamp instead.
void TestReceive::oldFramesThatAgreeAreNoRestart()
{
    FrameReceiver::Options o;
    o.mode = FrameReceiver::Mode::Recording;
    Collected c(o);
    for (std::uint32_t id = 5000; id < 5003; ++id)
        c.receiver.receive(datagramOf(command(id, id - 4900)));  // stamps 100 .. 102 s
    c.receiver.receive(datagramOf(command(10, 0)));  // replayed: sent earlier
    c.receiver.receive(datagramOf(command(11, 1)));
    QCOMPARE(c.frames[3].refusal, std::optional<Refusal>(Refusal::Replayed));
    QCOMPARE(c.frames[4].refusal, std::optional<Refusal>(Refusal::Replayed));
    // The sender restarted: its counter from 0, its clock on.
    c.receiver.receive(datagramOf(command(0, 104)));
    c.receiver.receive(datagramOf(command(1, 105)));
    QCOMPARE(c.frames[5].refusal, std::optional<Refusal>(Refusal::Replayed));
    QVERIFY(c.frames[6].delivered());
    // ... and the frames of before the restart stay refused.
    c.receiver.receive(datagramOf(command(5003, 103)));
    c.receiver.receive(datagramOf(command(5004, 104)));
    QCOMPARE(c.frames[7].refusal, std::optional<Refusal>(Refusal::MessageIdStep));
    QCOMPARE(c.frames[8].refusal, std::optional<Refusal>(Refusal::MessageIdStep));
    QCOMPARE(c.receiver.lastAccepted()->messageId, 1u);
}

void TestReceive::splicesRefusedWhereTheProfileTells_data()
{
    QTest::addColumn<bool>("keyed");
    QTest::newRow("plain") << false;
    QTest::newRow("keyed") << true;
}

// Codeword 1 of one frame, codeword 2 of one 1 .. 3 frames later (3 % of
// frames), in a session uploading plans back to back. The keyed link binds the blocks
// (BLOCK 2's tweak holds BLOCK 1's counter and clock): every splice is
// refused. The plain profile binds nothing; what a splice delivers is only
// a BLOCK 2 that is empty or starts a plan where the frame's own was another.
void TestReceive::splicesRefusedWhereTheProfileTells()
{
    QFETCH(bool, keyed);
    secure::SecretKey key;
    key.mutableBytes()[3] = 9;
    const secure::SecureCodec codec(key, secure::Direction::GcsToUa);
    CommandSession session;
    session.uploadEvery = 40;
    session.uploadStart = 2;
    session.planBytes = 1500;
    if (keyed)
        session.codec = &codec;
    const AttackResult r = runSplices(session, 10000, 0.03, 33);
    qInfo("%llu splices, %llu delivered wrong, %llu the profile cannot tell",
          static_cast<unsigned long long>(r.attacks), static_cast<unsigned long long>(r.row.wrong),
          static_cast<unsigned long long>(r.undetectable));
    QVERIFY(r.attacks > 250);
    if (keyed) {
        QCOMPARE(r.row.wrong, std::uint64_t{0});
        QCOMPARE(r.row.refused[std::size_t(Refusal::Forged)], r.attacks);
    } else {
        QVERIFY(r.row.wrong <= r.undetectable);
        QVERIFY(r.row.refused[std::size_t(Refusal::PlanSection)] > r.attacks / 3);
    }
    QCOMPARE(r.row.stale, std::uint64_t{0});
}

void TestReceive::noIntactFrameLostToAnEarlierReading_data()
{
    QTest::addColumn<int>("damage");
    QTest::newRow("cut then intact") << int(StreamDamage::CutThenIntact);
    QTest::newRow("overlap") << int(StreamDamage::Overlap);
    QTest::newRow("garbage between") << int(StreamDamage::GarbageBetween);
    QTest::newRow("byte slips 1-8") << int(StreamDamage::ByteSlips);
    QTest::newRow("mixed") << int(StreamDamage::Mixed);
    QTest::newRow("two byte slips a frame") << int(StreamDamage::TwoByteSlips);
}

// Every frame that libfec reads at its true place in the damaged stream is
// delivered, and nothing wrong.
void TestReceive::noIntactFrameLostToAnEarlierReading()
{
    QFETCH(int, damage);
    const AttackResult r = runStreamDamage(CommandSession{}, StreamDamage(damage), 5000, 40 + std::uint64_t(damage));
    qInfo("%llu frames libfec reads, %llu delivered in all", static_cast<unsigned long long>(r.recoverable),
          static_cast<unsigned long long>(r.row.correct));
    QVERIFY(r.recoverable > 200);
    QVERIFY2(r.falseRefusals == 0, r.firstFalseRefusal.c_str());
    QVERIFY2(r.row.wrong == 0, r.row.firstWrong.c_str());
}

// Slips in frames in a row, then a frame whose slip took its preamble's mark
// (its last bytes): its codewords are intact, libfec reads them where they
// are, but no window qualifies there; only the search for a frame due a few
// bytes either side finds it. Seen in soak_receive --attacks, "byte slips 1-8".
// Frames 18100-18104 (20,000 a row): B lost 4 bytes in codeword 2 (read where
// it was due, codeword 2 beyond correction), C 7 inside codeword 1 (read a
// byte early into a rotation, refused as not exact), D its last 4 preamble
// bytes: D lies 10 bytes before 600 after C's reading, 15 before the start
// due, and nothing looked for it.
void TestReceive::slipsInARowThenAFrameWithoutItsMark_data()
{
    // frame, first byte slipped, bytes deleted (negative: bytes of C3 inserted); ...
    QTest::addColumn<QList<int>>("slips");
    QTest::addColumn<int>("lost");  // the frame that lost its mark
    QTest::newRow("18100-18104") << QList<int>{18100, 0, 0, 18101, 402, 4, 18102, 100, 7, 18103, 86, 4, 18104, 0, 0}
                                 << 18103;
    // soak_receive --attacks 1000000 "byte slips": 2 bytes inserted in
    // codeword 1 (refused where it was due, beyond correction), then the
    // next frame's mark lost, which puts its codewords back where they were
    // due: found there only by looking whatever its window shows.
    QTest::newRow("334305-334308") << QList<int>{334305, 0, 0, 334306, 308, -2, 334307, 88, 2, 334308, 0, 0}
                                   << 334307;
    // soak_receive --attacks 100000 "mixed": three frames cut short, then
    // one whose mark was lost, nowhere near a frame due.
    QTest::newRow("78698-78703") << QList<int>{78698, 0,  0,   78699, 495, 105, 78700, 240, 360,
                                               78701, 59, 541, 78702, 84,  6,   78703, 0,   0}
                                 << 78702;
}

void TestReceive::slipsInARowThenAFrameWithoutItsMark()
{
    QFETCH(QList<int>, slips);
    QFETCH(int, lost);
    const CommandSession session;
    Collected c;
    std::int64_t streamSize = 0;
    std::int64_t lostAt = -1;  // codeword 1 of the frame that lost its mark
    std::vector<std::uint64_t> intact;
    const auto first = std::uint64_t(slips[0]);
    feedSession(session, c, first, std::uint64_t(slips[slips.size() - 3]), [&](std::uint64_t frame, Bytes& b) {
        const qsizetype i = qsizetype(frame - first) * 3;
        const auto at = std::size_t(slips[i + 1]);
        const bool inserted = slips[i + 2] < 0;
        const auto n = std::size_t(std::abs(slips[i + 2]));
        const Bytes sent = b;
        if (inserted)
            b.insert(b.begin() + std::ptrdiff_t(at), n, std::uint8_t{0xC3});
        else
            b.erase(b.begin() + std::ptrdiff_t(at), b.begin() + std::ptrdiff_t(at + n));
        if (frame == std::uint64_t(lost)) {
            lostAt = streamSize + std::int64_t(at);
            // As libfec reads it there: both codewords, as sent.
            QVERIFY(std::equal(sent.begin() + kPreambleSize, sent.end(), b.begin() + std::ptrdiff_t(at)));
        }
        if ((inserted ? at : at + n) <= kPreambleSize)  // codewords intact
            intact.push_back(frame);
        streamSize += std::int64_t(b.size());
    });

    const SessionDeliveries d = deliveredFrom(session, c, first + std::uint64_t(slips.size() / 3));
    QVERIFY2(d.wrong.empty(), d.wrong.c_str());
    // Frames whose codewords were slipped inside may be read too (from a few
    // bytes off, where one codeword is whole and the other within RS's
    // reach); every frame with both codewords intact must be.
    std::vector<std::uint64_t> delivered;
    for (std::size_t k = 0; k < d.frames.size(); ++k) {
        if (d.frames[k] == std::uint64_t(lost))
            QCOMPARE(d.offsets[k], lostAt - std::int64_t(kPreambleSize));
        if (std::find(intact.begin(), intact.end(), d.frames[k]) != intact.end())
            delivered.push_back(d.frames[k]);
    }
    QCOMPARE(delivered, intact);
}

// soak_receive --attacks "mixed": frame 10673 has its last 31 bytes
// overwritten by 10674's start and is read where it was due, not exact;
// 10674, its last 6 bytes overwritten by 10675, is first read a byte early,
// a rotation refused as not exact; the frame 600 bytes on from that reading
// is 10675, 5 bytes early. Taking 10675 there (once 10676's bytes were
// in) before scanning on from the rotation skipped 10674, which libfec
// reads a byte after it.
void TestReceive::trueFrameJustAfterARefusedRotation()
{
    const CommandSession session;
    Collected c;
    feedSession(session, c, 10672, 10676, [](std::uint64_t frame, Bytes& b) {
        b.resize(frame == 10673 ? 569 : frame == 10674 ? 594 : kFrameSize);  // overwritten by the next
    });
    const SessionDeliveries d = deliveredFrom(session, c, 10677);
    QVERIFY2(d.wrong.empty(), d.wrong.c_str());
    QCOMPARE(d.frames, (std::vector<std::uint64_t>{10672, 10674, 10675, 10676}));
}

// Two slips in one frame (a soak of byte slips, two a frame, frame 39539):
// 2 bytes lost inside BLOCK 1's leading padding, 2 inserted at codeword 2's
// start. Read where it starts, codeword 1 is then within 2 bytes of its own
// rotation by 2 (the padding lines up with itself), and RS "corrects" it
// into BLOCK 1 shifted, whose last item is 2 parity bytes (B0 52): a command
// never sent. Codeword 2 is back in place and decodes. Not delivered.
void TestReceive::slipInsideBlock1PaddingNotDeliveredShifted()
{
    const CommandSession session;
    Collected c;
    feedSession(session, c, 39537, 39541, [](std::uint64_t frame, Bytes& b) {
        if (frame != 39539)
            return;
        QCOMPARE(b[kPreambleSize + 9], kPreambleFillByte);  // inside the padding
        QCOMPARE(b[kPreambleSize + 10], kPreambleFillByte);
        b.erase(b.begin() + 99, b.begin() + 101);
        b.insert(b.begin() + 344, 2, std::uint8_t{0xC3});
    });
    const SessionDeliveries d = deliveredFrom(session, c, 39542);
    QVERIFY2(d.wrong.empty(), d.wrong.c_str());
    QCOMPARE(d.frames, (std::vector<std::uint64_t>{39537, 39538, 39540, 39541}));
}

// 7 bytes lost inside BLOCK 1's leading padding: read 7 bytes early,
// codeword 2 is whole, and codeword 1 differs from the one sent only in its
// first bytes (the preamble's tail where padding was; the rest of the
// padding lines up with itself): RS restores it. Delivered as sent, though
// libfec cannot read it where it starts.
void TestReceive::slipInsideBlock1PaddingReadFromBytesEarly()
{
    const CommandSession session;
    Collected c;
    feedSession(session, c, 18101, 18103, [](std::uint64_t frame, Bytes& b) {
        if (frame != 18102)
            return;
        QVERIFY(std::all_of(b.begin() + 100, b.begin() + 107, [](std::uint8_t x) { return x == kPreambleFillByte; }));
        b.erase(b.begin() + 100, b.begin() + 107);
    });
    const SessionDeliveries d = deliveredFrom(session, c, 18104);
    QVERIFY2(d.wrong.empty(), d.wrong.c_str());
    QCOMPARE(d.frames, (std::vector<std::uint64_t>{18101, 18102, 18103}));
    QCOMPARE(d.offsets[1], std::int64_t(kFrameSize - 7));
}

// soak_receive --seed 1 --attacks 1000000 "byte slips", frame 106996: 2
// bytes inserted at codeword 1's byte 240. Read 2 bytes late, codeword 2 is
// whole and codeword 1 is within 16 bytes of its rotation by 2 (BLOCK 1
// shifted, parity bytes as its last item). Only one of the two 55s the
// rotation wraps round to its end was corrected: this codeword's own last
// parity byte is 55.
void TestReceive::slipInsideBlock1ParityNotDeliveredShifted()
{
    const CommandSession session;
    QCOMPARE(session.frameAt(106996)[kFrameSize - kCodewordSize - 1], kPreambleFillByte);
    Collected c;
    feedSession(session, c, 106994, 106998, [](std::uint64_t frame, Bytes& b) {
        if (frame == 106996)
            b.insert(b.begin() + 330, 2, std::uint8_t{0xC3});
    });
    const SessionDeliveries d = deliveredFrom(session, c, 106999);
    QVERIFY2(d.wrong.empty(), d.wrong.c_str());
    QCOMPARE(d.frames, (std::vector<std::uint64_t>{106994, 106995, 106997, 106998}));
}

// A sender that falls silent and comes back with its counter where it was
// (a satellite phone redialling): its first frame is judged against how long
// the receiver heard nothing.
void TestReceive::firstFrameAfterAnOutageDelivered()
{
    const AttackResult r = runOutages(CommandSession{}, 3000, 0.02, 34);
    QVERIFY(r.attacks > 30);
    QCOMPARE(r.falseRefusals, std::uint64_t{0});
    QCOMPARE(r.row.correct, std::uint64_t{3000});
    QCOMPARE(r.row.wrong, std::uint64_t{0});

    Collected c;
    c.receiver.receive(datagramOf(command(100, 0)));
    c.nowMicros += 16'000'000;  // 16 s without a frame
    c.receiver.receive(datagramOf(command(103, 16)));
    QVERIFY(c.frames[1].delivered());
    c.receiver.receive(datagramOf(command(104, 22)));  // 6 s later, 1 message: too far
    QCOMPARE(c.frames[2].refusal, std::optional<Refusal>(Refusal::TimeStep));
    QCOMPARE(c.frames[2].detail, std::string("time_UTC is 6 s after the last accepted, 1 message later"));
}

// The predictions' work is paid from a budget that refills with the clock:
// a flood of datagrams no prediction fits cannot spend more, and a genuine
// frame among them is still delivered.
void TestReceive::predictionsPaidFromABudget()
{
    secure::SecretKey key;
    key.mutableBytes()[2] = 5;
    const secure::SecureCodec codec(key, secure::Direction::GcsToUa);
    FrameReceiver::Options o;
    o.keys.codecs = {&codec};
    o.prediction.unitsPerSecond = 2000;
    o.prediction.maxUnits = 4000;
    Collected c(o);
    const auto keyed = [&](const Message& m) {
        Diagnostics errors;
        const std::optional<EncodedBlocks> b = codec.encode(m, errors);
        return datagramOf(b->block1, b->block2);
    };
    c.receiver.receive(keyed(command(10, 0)));
    QVERIFY(c.frames[0].delivered());
    std::mt19937_64 rng(5);
    Bytes junk(kDatagramSize);
    for (int i = 0; i < 200; ++i) {
        for (std::uint8_t& b : junk)
            b = static_cast<std::uint8_t>(rng());
        c.receiver.receive(junk);
    }
    const FrameReceiver::Stats& st = c.receiver.stats();
    QCOMPARE(st.refused[std::size_t(Refusal::Uncorrectable)], std::uint64_t{200});
    QVERIFY(st.predictionUnits <= 4000);
    QVERIFY(st.predictionsCut > 100);
    c.receiver.receive(keyed(command(11, 1)));
    QVERIFY(c.frames.back().delivered());
    // A second later the budget has refilled by 2,000 units, no more.
    c.nowMicros += 1'000'000;
    const std::uint64_t before = st.predictionUnits;
    for (int i = 0; i < 200; ++i) {
        for (std::uint8_t& b : junk)
            b = static_cast<std::uint8_t>(rng());
        c.receiver.receive(junk);
    }
    QVERIFY(st.predictionUnits > before);
    QVERIFY(st.predictionUnits <= before + 2000);
}

// At most kMaxSenders senders are kept: a flood of one-frame senders
// replaces its own kind, not the sender heard every second, and a sender
// forgotten cannot come back with frames older than its last.
void TestReceive::sendersForgottenBeyondTheTable()
{
    FrameReceiver::Options o;
    o.mode = FrameReceiver::Mode::Recording;
    Collected c(o);
    for (std::uint32_t id = 1; id <= 10; ++id)
        c.receiver.receive(datagramOf(command(id, id)));
    Message early = command(50, 50);
    early.header.set(ItemId::ID_UA_source, Value::station({44, 999}));
    c.receiver.receive(datagramOf(early));
    for (std::uint16_t s = 0; s < 40; ++s) {
        Message m = command(1000 + s, 100 + s);
        m.header.set(ItemId::ID_UA_source, Value::station({44, std::uint16_t(2000 + s)}));
        c.receiver.receive(datagramOf(m));
    }
    QCOMPARE(c.receiver.senders().size(), kMaxSenders);
    QCOMPARE(c.receiver.stats().sendersForgotten, std::uint64_t{41 - (kMaxSenders - 1)});
    QVERIFY(c.receiver.senders().count((44u << 16) | 133u));  // the aircraft heard every second stays
    QVERIFY(!c.receiver.senders().count((44u << 16) | 999u));
    // Sender 999 again, with its frame of 100 s before the latest forgotten one.
    c.receiver.receive(datagramOf(early));
    QCOMPARE(c.frames.back().refusal, std::optional<Refusal>(Refusal::Replayed));
    QVERIFY(c.receiver.senders().count((44u << 16) | 133u));
    c.receiver.receive(datagramOf(command(11, 11)));
    QVERIFY(c.frames.back().delivered());
}

void TestReceive::ownCommandPredictsTheStatus_data()
{
    QTest::addColumn<bool>("keyed");
    QTest::newRow("plain") << false;
    QTest::newRow("keyed") << true;
}

// The console's own command is its prediction of the aircraft's next status:
// a change of four commands at once (a radio retuned, engine and flaps) is
// read through 24 byte errors in each codeword, beyond Reed-Solomon alone,
// 8 of them in the parity (a prediction without the change is 6 bytes off,
// and 14 is beyond the trial's margin).
void TestReceive::ownCommandPredictsTheStatus()
{
    QFETCH(bool, keyed);
    secure::SecretKey key;
    key.mutableBytes()[4] = 77;
    const secure::SecureCodec codec(key, secure::Direction::UaToGcs);
    FrameReceiver::Options o;
    if (keyed)
        o.keys.codecs = {&codec};
    Collected c(o);
    const auto send = [&](Message m, bool damaged) {
        Diagnostics errors;
        const std::optional<EncodedBlocks> b = keyed ? codec.encode(m, errors) : encodeBlocks(m, errors);
        FrameBytes f = makeFrame(b->block1, b->block2);
        // 16 bad data bytes and 8 bad parity bytes in each codeword.
        if (damaged)
            for (std::size_t cw = 0; cw < 2; ++cw)
                for (std::size_t e = 0; e < 24; ++e)
                    f[kPreambleSize + cw * kCodewordSize + (e < 16 ? e * 13 + 2 : kBlockSize + (e - 16) * 4)] ^= 0x3C;
        c.nowMicros = (kNoon + m.header.number(ItemId::ID_msg)) * 1'000'000;
        c.receiver.feed(f);
        c.receiver.flush();
        return c.frames.back();
    };
    Message status = test::sessionStartMessage();
    status.header.set(ItemId::ID_UA_source, Value::station({44, 133}));
    const auto at = [&](std::uint32_t second) { return stampedAt(status, second); };
    QVERIFY(send(at(1), false).delivered());
    Message command = status;
    command.radios[0].set(ItemId::Rx_freq, 124250);
    command.radios[0].set(ItemId::Tx_freq, 124250);
    command.engines[0].set(ItemId::eng_carb_SET, 200);
    command.flaps.set(ItemId::F_elev_set, 12);
    // Before the console says what it commanded, the changed status is lost.
    status = withCommanded(status, command);
    QCOMPARE(send(at(2), true).refusal, std::optional<Refusal>(Refusal::Uncorrectable));
    c.receiver.expect(command);
    const ReceivedFrame f = send(at(3), true);
    QVERIFY2(f.delivered(), f.detail.c_str());
    QVERIFY(f.fromPrediction);
    QVERIFY(f.decoded.message == at(3));
    QCOMPARE(f.decoded.message.radios[0].number(ItemId::Rx_freq), 124250);
}

// A plan section whose codeword 2 is beyond RS in pass 1 (18 byte errors)
// and again in pass 2 (18 others): pass 1 is refused, pass 2 read from the
// two copies combined, exactly as sent; pass 1's frame replayed afterwards
// is never delivered (older than the last delivered), though its section is
// now known.
void TestReceive::planSectionFromTwoPassesCopies()
{
    Collected c;
    std::uint32_t id = 1;
    const auto send = [&](std::uint16_t section, int damageFrom) {
        ++id;
        c.nowMicros = (kNoon + id) * 1'000'000;
        Message m = command(id, id);
        m.flightPlan = sixSectionPlan(0xA, section);
        Bytes d = datagramOf(m);
        if (damageFrom >= 0)
            for (int e = 0; e < 18; ++e)
                d[kCodewordSize + static_cast<std::size_t>(damageFrom + 13 * e)] ^= static_cast<std::uint8_t>(0x11 + 7 * e);
        c.receiver.receive(d);
        return std::make_pair(c.frames.back(), std::make_pair(m, d));
    };
    c.nowMicros = (kNoon + id) * 1'000'000;
    c.receiver.receive(datagramOf(command(id, id)));
    QVERIFY(c.frames.back().delivered());
    Bytes passOne;
    Message passOneSent;
    for (std::uint16_t section = 0; section < 6; ++section) {
        const auto [frame, sent] = send(section, section == 3 ? 1 : -1);
        if (section == 3) {
            QCOMPARE(frame.refusal, std::optional<Refusal>(Refusal::Uncorrectable));
            passOne = sent.second;
            passOneSent = sent.first;
        } else {
            QVERIFY2(frame.delivered(), frame.detail.c_str());
        }
    }
    for (std::uint16_t section = 0; section < 6; ++section) {
        const auto [frame, sent] = send(section, section == 3 ? 6 : -1);
        QVERIFY2(frame.delivered(), frame.detail.c_str());
        QVERIFY(frame.decoded.message == sent.first);
        if (section == 3) {
            QVERIFY(frame.fromPrediction);
            QCOMPARE(frame.blocks.corrected.block2 >= 0, true);
        }
    }
    QCOMPARE(c.receiver.predictions()->stats().block2FromCopies, std::uint64_t{1});
    // Replayed: as damaged (its section not predicted backwards), and intact.
    c.receiver.receive(passOne);
    QCOMPARE(c.frames.back().refusal, std::optional<Refusal>(Refusal::Uncorrectable));
    c.receiver.receive(datagramOf(passOneSent));
    QCOMPARE(c.frames.back().refusal, std::optional<Refusal>(Refusal::Replayed));
}

namespace {

// The session's start with four commands changed at once (a radio retuned,
// the camera turned and raised): 9 bytes of BLOCK 1, each in 2 bits or more.
Message fourCommandsChanged(const Message& status)
{
    Message changed = status;
    changed.radios[0].set(ItemId::Rx_freq, 136975);  // 0x01DA9C -> 0x02170F
    changed.radios[0].set(ItemId::Tx_freq, 136975);
    changed.cameras[0].set(ItemId::cam_mag_compass, 27123);  // 0x2328 -> 0x69F3
    changed.cameras[0].set(ItemId::cam_elev, -1501);          // one byte: 24 -> 23
    return changed;
}

// status sent at second 1 intact, then `changed` at second 2 with 20 byte
// errors in its data (the padding before the items), 5 in its parity and one
// bit flipped at each of `oneBitErrors`: what the receiver made of the second.
ReceivedFrame firstFrameOfChange(Collected& c, const Message& status, const Message& changed,
                                 const std::vector<std::size_t>& oneBitErrors)
{
    const auto send = [&](const Message& m, bool damaged) {
        const EncodedBlocks b = encoded(m);
        Bytes d = datagramOf(b.block1, b.block2);
        if (damaged) {
            for (std::size_t e = 0; e < 20; ++e)
                d[e * 3 + 1] ^= static_cast<std::uint8_t>(0x21 + e);
            for (std::size_t e = 0; e < 5; ++e)
                d[kBlockSize + e * 6] ^= 0x5C;
            for (std::size_t place : oneBitErrors)
                d[place] ^= 0x10;
        }
        c.nowMicros = (kNoon + m.header.number(ItemId::ID_msg)) * 1'000'000;
        c.receiver.receive(d);
        return c.frames.back();
    };
    if (!send(stampedAt(status, 1), false).delivered())
        return {};
    return send(stampedAt(changed, 2), true);
}

}  // namespace

// Plain link: the first frame of a change of four commands (9 bytes) with 20
// byte errors in its data and 5 in its parity: beyond RS, and beyond a trial
// (9 bytes off the prediction + 5 > 12), read with those 9 command bytes
// erased (2 x 5 + 9 <= 20).
void TestReceive::severalCommandsChangedOnTheFirstFrame()
{
    Collected c;
    const Message status = test::sessionStartMessage();
    const Message changed = fourCommandsChanged(status);
    const ReceivedFrame f = firstFrameOfChange(c, status, changed, {});
    QVERIFY2(f.delivered(), f.detail.c_str());
    QVERIFY(f.fromPrediction);
    QVERIFY(f.decoded.message == stampedAt(changed, 2));
    QCOMPARE(c.receiver.predictions()->stats().block1FromChangedCommands, std::uint64_t{1});
}

// As above, and three unchanged command bytes took one bit error each: with
// every differing command byte erased, 2 x 5 + 12 > 20. A changed value
// differs from the last in several bits where one channel error flips one,
// so the second try leaves the one-bit differences to the prediction and
// erases the 9 changed bytes alone (2 x 5 + 9 <= 20).
void TestReceive::changedCommandsThroughSingleBitErrors()
{
    Collected c;
    const Message status = test::sessionStartMessage();
    const Message changed = fourCommandsChanged(status);
    // Where three unchanged one-byte commands are in BLOCK 1.
    const EncodedBlocks sent = encoded(stampedAt(changed, 2));
    std::vector<std::size_t> oneBit;
    for (const auto& set : std::vector<std::function<void(Message&)>>{
             [](Message& m) { m.engines[0].set(ItemId::eng_carb_SET, 138); },
             [](Message& m) { m.engines[1].set(ItemId::eng_prop_pitch, 121); },
             [](Message& m) { m.sense.set(ItemId::SA_zoom_FWD_cam, 11); }}) {
        Message other = stampedAt(changed, 2);
        set(other);
        const EncodedBlocks b = encoded(other);
        const auto diff = std::mismatch(sent.block1.begin(), sent.block1.end(), b.block1.begin());
        oneBit.push_back(static_cast<std::size_t>(diff.first - sent.block1.begin()));
        QVERIFY(oneBit.back() > 60 && oneBit.back() < kBlockSize);  // after the damaged padding
    }
    const ReceivedFrame f = firstFrameOfChange(c, status, changed, oneBit);
    QVERIFY2(f.delivered(), f.detail.c_str());
    QVERIFY(f.fromPrediction);
    QVERIFY(f.decoded.message == stampedAt(changed, 2));
    QCOMPARE(c.receiver.predictions()->stats().block1FromChangedCommands, std::uint64_t{1});
}

QTEST_GUILESS_MAIN(TestReceive)
#include "tst_receive.moc"
