// FrameReceiver: no wrong frame delivered through any damage the soak
// (tests/bench/soak_receive.cpp) applies, here at 10^4 frames a row; every
// frame within RS's reach delivered; and each refusal with its reason.
#include "codec/receive/FrameReceiver.h"
#include "codec/secure/SecureCodec.h"
#include "tests/ReceiveChannel.h"

#include <QtTest>

#include <initializer_list>

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
    void keyedLink();
    void wrongSizeDatagram();
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

void TestReceive::flightPlanSections()
{
    Collected c;
    std::uint32_t id = 1;
    const auto send = [&](std::uint32_t plan, std::uint16_t section, std::uint32_t step = 1) {
        id += step;
        Message m = command(id, id);
        m.flightPlan.planId = plan;
        m.flightPlan.sectionId = section;
        m.flightPlan.data = {1, 2, 3};
        c.receiver.receive(datagramOf(m));
        return c.frames.back().refusal;
    };
    QVERIFY(!send(0xA, 2));  // the first frame from a sender: joins a pass in progress
    QVERIFY(!send(0xA, 3));
    QVERIFY(!send(0xA, 0));  // the next pass
    QCOMPARE(send(0xA, 5), std::optional<Refusal>(Refusal::PlanSection));
    QVERIFY(!send(0xA, 4, 3));  // four messages after section 0: sections 1..4 may have been sent
    QCOMPARE(send(0xB, 1), std::optional<Refusal>(Refusal::PlanSection));
    QCOMPARE(c.frames.back().detail,
             std::string("flight plan 0x0000000B section 1 does not follow any plan being sent 1 message later"));
    QVERIFY(!send(0xB, 0));  // a new plan starts at 0
    QVERIFY(!send(0xC, 1, 2));  // ... which may have been lost
    QVERIFY(!send(0xC, kAcknowledgementSectionId));  // link control fits anywhere
    QVERIFY(!send(0xC, 2));
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

QTEST_GUILESS_MAIN(TestReceive)
#include "tst_receive.moc"
