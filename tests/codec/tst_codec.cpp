// Binary codec: the item table, encoder, decoder, RS(255,223) and framing,
// against the source document's examples and a separate implementation's frames.
#include "RandomMessage.h"

#include "codec/message/Airframe.h"
#include "codec/frame/Frame.h"
#include "codec/message/MessageDecoder.h"
#include "codec/message/MessageEncoder.h"
#include "codec/frame/ReedSolomon.h"
#include "codec/receive/LoggedFrameReading.h"
#include "codec/secure/SecureCodec.h"
#include "codec/send/FrameBuilder.h"

#include <QtTest>

#include <algorithm>
#include <limits>
#include <numeric>
#include <random>
#include <set>

using namespace rcm;

namespace {

QByteArray readVector(const char* name)
{
    QFile f(QStringLiteral(RCM_VECTORS_DIR "/rcm/") + QLatin1String(name));
    if (!f.open(QIODevice::ReadOnly))
        qFatal("cannot open vector %s", name);
    return f.readAll();
}

std::span<const std::uint8_t> bytesOf(const QByteArray& a)
{
    return {reinterpret_cast<const std::uint8_t*>(a.constData()), static_cast<std::size_t>(a.size())};
}

QByteArray hex(std::span<const std::uint8_t> b)
{
    return QByteArray(reinterpret_cast<const char*>(b.data()), static_cast<qsizetype>(b.size())).toHex(' ').toUpper();
}

// The item bytes (Item_ID + value) that follow BLOCK 1's leading padding.
QByteArray block1Items(const Message& m)
{
    Diagnostics errors;
    const auto blocks = encodeBlocks(m, errors);
    if (!blocks)
        return "ENCODE FAILED: " + QByteArray::fromStdString(errors.front().toString());
    const std::size_t start = kBlockSize - block1ItemBytes(m);
    return hex(std::span<const std::uint8_t>(blocks->block1).subspan(start));
}

Block randomBlock(std::mt19937_64& rng)
{
    Block b;
    for (auto& x : b)
        x = static_cast<std::uint8_t>(rng());
    return b;
}

// Changes `count` distinct bytes of a codeword to different values.
void corrupt(std::mt19937_64& rng, std::uint8_t* codeword, int count)
{
    std::vector<int> positions(kCodewordSize);
    std::iota(positions.begin(), positions.end(), 0);
    std::shuffle(positions.begin(), positions.end(), rng);
    for (int i = 0; i < count; ++i)
        codeword[positions[i]] ^= static_cast<std::uint8_t>(1 + rng() % 255);
}

QByteArray dump(const Diagnostics& ds)
{
    QByteArray out;
    for (const auto& d : ds)
        out += QByteArray::fromStdString(d.toString()) + '\n';
    return out;
}

}  // namespace

class TestCodec : public QObject {
    Q_OBJECT
private slots:
    void itemTableIsConsistent();
    void seedExamples_data();
    void seedExamples();
    void unitsInCanonicalOrder();
    void frameLayout();
    void vectorsDecode_data();
    void vectorsDecode();
    void vectorsReencodeExactly_data();
    void vectorsReencodeExactly();
    void sendPathBuildsVectorsExactly_data();
    void sendPathBuildsVectorsExactly();
    void sendPathStampsAndEnciphers();
    void blockDecoderStaysInsideTheCodec();
    void randomRoundTrip();
    void datagramRoundTrip();
    void restingCommandEncodes();
    void encoderRefusesOutOfRange_data();
    void encoderRefusesOutOfRange();
    void encoderRefusesWhatDoesNotFit();
    void encoderRefusesUnitWithoutKey();
    void encoderKeepsRequiredPadding();
    void decoderReportsCorruptFields();
    void decoderReportsUnknownItemAndKeepsEarlier();
    void decoderReportsTruncatedItem();
    void decoderReportsOutOfRangeAndContinues();
    void decoderReportsOrphanAndRepeated();
    void decoderAcceptsAnyOrderPaddingAndBeginEnd();
    void decoderChecksBlock2();
    void decodeFrameRejectsWrongSize();
    void rsCorrectsUpTo16_data();
    void rsCorrectsUpTo16();
    void rsRefuses17AndMore_data();
    void rsRefuses17AndMore();
    void rsCleanCheckAgreesWithLibfec();
    void uncorrectableBlockIsReportedAndOtherKept();
};

void TestCodec::itemTableIsConsistent()
{
    std::set<std::uint8_t> ids;
    int previousRank = -1;
    for (const ItemInfo& item : itemTable()) {
        QVERIFY2(ids.insert(static_cast<std::uint8_t>(item.id)).second, item.name.data());
        QCOMPARE(findItem(item.id), &item);
        QCOMPARE(findItem(item.owner, item.name), &item);
        QVERIFY(canonicalRank(item.id) > previousRank);
        previousRank = canonicalRank(item.id);
        QVERIFY(item.size >= 1 && item.size <= 8);
        QCOMPARE(item.kind == ValueKind::Fields, !item.fields.empty());
        // Bytes that are not items must never be mistaken for one.
        QVERIFY(item.id != ItemId{kPad55} && item.id != ItemId{kPadAA});
    }
    QCOMPARE(ids.size(), std::size_t{37});
    for (std::uint8_t notItem : {0x00, 0x01, 0x02, 0x0A, 0x0F, 0x34, 0x55, 0xAA, 0xF0, 0xFF})
        QVERIFY(findItem(notItem) == nullptr);
    // The well-equipped aircraft of the source document takes 199 bytes (PROFILE.md).
    Message full = restingCommand(Airframe::wellEquipped());
    for (ItemId id : {ItemId::ID_msg, ItemId::ID_UA_source, ItemId::time_UTC, ItemId::date_UTC})
        full.header.set(id, itemInfo(id).kind == ValueKind::Station ? Value::pair(44, 1) : Value::of(1));
    full.header.set(ItemId::ID_BLK12_format, Value::pair(0, 0));
    full.header.set(ItemId::ID_GCS_destination, Value::pair(44, 2));
    full.header.set(ItemId::ID_GCS_backup, Value::pair(44, 3));
    for (Unit& cam : full.cameras) {
        cam.set(ItemId::cam_GCS_destination, Value::pair(44, 2));
        cam.set(ItemId::cam_GCS_backup, Value::pair(44, 3));
    }
    QCOMPARE(block1ItemBytes(full), std::size_t{199});
}

void TestCodec::seedExamples_data()
{
    QTest::addColumn<int>("item");
    QTest::addColumn<qint64>("a");
    QTest::addColumn<qint64>("b");
    QTest::addColumn<QByteArray>("bytes");
    QTest::newRow("ID_msg 133") << 0x03 << qint64(133) << qint64(0) << QByteArray("03 00 00 85");
    QTest::newRow("time_UTC 16:35:23") << 0x05 << qint64(163523) << qint64(0) << QByteArray("05 02 7E C3");
    QTest::newRow("date_UTC 071114") << 0x06 << qint64(71114) << qint64(0) << QByteArray("06 01 15 CA");
    QTest::newRow("ID_BLK12_format 5 15") << 0x07 << qint64(5) << qint64(15) << QByteArray("07 05 0F");
    QTest::newRow("SA_zoom_LHS_cam 35") << 0xB0 << qint64(35) << qint64(0) << QByteArray("B0 23");
    QTest::newRow("SA_zoom_FWD_cam 105") << 0xB1 << qint64(105) << qint64(0) << QByteArray("B1 69");
    // PROFILE.md's correction of the seed's swapped country bytes.
    QTest::newRow("ID_UA_source GB_133") << 0x04 << qint64(44) << qint64(133) << QByteArray("04 00 2C 00 85");
    QTest::newRow("ID_GCS_destination GB_30226") << 0x08 << qint64(44) << qint64(0x7612) << QByteArray("08 00 2C 76 12");
    QTest::newRow("F_rudder_set -19") << 0x44 << qint64(-19) << qint64(0) << QByteArray("44 ED");
    QTest::newRow("F_rudder_set 127") << 0x44 << qint64(127) << qint64(0) << QByteArray("44 7F");
    QTest::newRow("cam_elev -54.64") << 0xC2 << qint64(-5464) << qint64(0) << QByteArray("C2 EA A8");
    QTest::newRow("Rx_freq 134850") << 0x82 << qint64(134850) << qint64(0) << QByteArray("82 00 02 0E C2");
}

void TestCodec::seedExamples()
{
    QFETCH(int, item);
    QFETCH(qint64, a);
    QFETCH(qint64, b);
    QFETCH(QByteArray, bytes);
    const ItemInfo& info = *findItem(static_cast<std::uint8_t>(item));
    Message m;
    Unit* unit = m.single(info.owner);
    if (!unit) {  // repeated units need their key first
        unit = &m.repeated(info.owner)->emplace_back(info.owner);
        const ItemInfo& key = itemInfo(*unitKey(info.owner));
        unit->set(key.id, key.kind == ValueKind::Text ? Value::string("VHF1") : Value::string("NIK", 1));
    }
    unit->set(info.id, Value::pair(a, b));
    QByteArray items = block1Items(m);
    QVERIFY2(items.endsWith(bytes), items);
    // The header alone: the example in the seed, read as PROFILE.md says.
    if (info.owner == UnitKind::Header)
        QCOMPARE(items, bytes);
}

void TestCodec::unitsInCanonicalOrder()
{
    Message m;
    Unit& e = m.addEngine(2);
    e.set(ItemId::eng_carb_SET, 4);
    e.set(ItemId::eng_status, 0x90);
    e.set(ItemId::eng_prop_pitch, 3);
    m.sense.set(ItemId::SA_zoom_RHS_cam, 1);
    m.header.set(ItemId::ID_msg, 7);
    m.flaps.set(ItemId::F_elev_set, -1);
    // Header, engine key first then ascending IDs, flaps, sense: as PROFILE.md orders them.
    QCOMPARE(block1Items(m), QByteArray("03 00 00 07 31 02 30 90 32 03 33 04 45 FF B2 01"));
    Diagnostics errors;
    const auto blocks = encodeBlocks(m, errors);
    QVERIFY(blocks);
    QVERIFY(std::all_of(blocks->block1.begin(), blocks->block1.begin() + (223 - 16),
                        [](std::uint8_t x) { return x == 0x55; }));
}

void TestCodec::frameLayout()
{
    Message m;
    m.header.set(ItemId::ID_msg, 133);
    Diagnostics errors;
    const auto frame = encodeFrame(m, errors);
    QVERIFY(frame);
    for (std::size_t i = 0; i < 88; ++i)
        QCOMPARE(int((*frame)[i]), 0x55);
    QCOMPARE(int((*frame)[88]), 0x0F);
    QCOMPARE(int((*frame)[89]), 0x0F);
    // Systematic code: data unchanged right after the preamble, parity after it.
    const auto blocks = encodeBlocks(m, errors);
    QVERIFY(std::equal(blocks->block1.begin(), blocks->block1.end(), frame->begin() + 90));
    QVERIFY(std::equal(blocks->block2.begin(), blocks->block2.end(), frame->begin() + 90 + 255));
    // BLOCK 2 with no update: x = 0, both IDs 0, padding, End_Of_String 00.
    QCOMPARE(hex(std::span<const std::uint8_t>(blocks->block2).first(9)), QByteArray("00 00 00 00 00 00 00 55 55"));
    QCOMPARE(int(blocks->block2[222]), 0);
    const auto datagram = encodeDatagram(m, errors);
    QVERIFY(datagram);
    QVERIFY(std::equal(datagram->begin(), datagram->end(), frame->begin() + 90));
}

void TestCodec::vectorsDecode_data()
{
    QTest::addColumn<QString>("file");
    QTest::addColumn<int>("corrected");
    QTest::newRow("seed-example") << "seed-example.bin" << 0;
    QTest::newRow("well-equipped") << "well-equipped.bin" << 0;
    QTest::newRow("well-equipped.errors") << "well-equipped.errors.bin" << 16;
    QTest::newRow("flight-plan") << "flight-plan.bin" << 0;
}

void TestCodec::vectorsDecode()
{
    QFETCH(QString, file);
    QFETCH(int, corrected);
    const QByteArray raw = readVector(file.toLatin1().constData());
    QCOMPARE(raw.size(), 600);
    const DecodeResult r = decodeFrame(bytesOf(raw));
    QVERIFY2(r.diagnostics.empty(), dump(r.diagnostics));
    QCOMPARE(r.corrected.block1, corrected);
    QCOMPARE(r.corrected.block2, corrected);
    const Message& m = r.message;
    if (file == "seed-example.bin") {
        QCOMPARE(m.header.number(ItemId::ID_msg), 133);
        QCOMPARE(m.header.find(ItemId::ID_UA_source)->number, 44);
        QCOMPARE(m.header.find(ItemId::ID_UA_source)->second, 133);
        QCOMPARE(m.header.number(ItemId::time_UTC), 163523);
        QCOMPARE(m.header.number(ItemId::date_UTC), 71114);
        QCOMPARE(m.header.find(ItemId::ID_GCS_destination)->second, 0x7612);
        QCOMPARE(m.sense.number(ItemId::SA_zoom_FWD_cam), 105);
        QVERIFY(m.engines.empty() && m.flightPlan.empty());
    } else if (file.startsWith("well-equipped")) {
        QCOMPARE(m.engines.size(), std::size_t{3});
        QCOMPARE(m.radios.size(), std::size_t{3});
        QCOMPARE(m.cameras.size(), std::size_t{2});
        QCOMPARE(m.header.number(ItemId::ID_msg), 0x44CB63);
        QCOMPARE(m.engines[1].number(ItemId::eng_ID), 2);
        QCOMPARE(m.engines[1].number(ItemId::eng_status), 0xD0);
        QCOMPARE(m.engines[1].fieldCode(ItemId::eng_status, 0), 3u);  // RC transmitter
        QCOMPARE(m.flaps.number(ItemId::F_aileron_RHS_set), -19);   // ED
        QCOMPARE(m.flaps.number(ItemId::F_rudder_set), -120);       // 88
        QCOMPARE(m.radios[2].find(ItemId::system_ID)->text, std::string("VHF3"));
        QCOMPARE(m.radios[0].number(ItemId::Rx_freq), 0x01F2E0);
        QCOMPARE(m.cameras[1].find(ItemId::cam_ID)->text, std::string("SNY"));
        QCOMPARE(m.cameras[1].find(ItemId::cam_ID)->number, 2);
        QCOMPARE(m.cameras[1].number(ItemId::cam_elev), -5464);     // EA A8
        QCOMPARE(m.cameras[1].find(ItemId::cam_GCS_backup)->number, 0x03EB);
        QCOMPARE(m.cameras[0].number(ItemId::cam_mag_compass), 0x677F);
    } else {
        QCOMPARE(m.flightPlan.planId, 0xDEADBEEFu);
        QCOMPARE(m.flightPlan.sectionId, 3);
        QCOMPARE(m.flightPlan.data.size(), std::size_t{40});
        for (std::size_t i = 0; i < 40; ++i)
            QCOMPARE(int(m.flightPlan.data[i]), int(i));
        QCOMPARE(m.cameras[0].number(ItemId::cam_mag_compass), 0x89D9);
    }
}

void TestCodec::vectorsReencodeExactly_data() { vectorsDecode_data(); }

void TestCodec::vectorsReencodeExactly()
{
    QFETCH(QString, file);
    const QByteArray raw = readVector(file.toLatin1().constData());
    const DecodeResult r = decodeFrame(bytesOf(raw));
    Diagnostics errors;
    const auto frame = encodeFrame(r.message, errors);
    QVERIFY2(frame, dump(errors));
    const QByteArray clean = readVector(file == "well-equipped.errors.bin" ? "well-equipped.bin" : file.toLatin1().constData());
    QCOMPARE(hex(*frame), hex(bytesOf(clean)));
}

void TestCodec::sendPathBuildsVectorsExactly_data() { vectorsDecode_data(); }

// The one send path, given the vector's command and its stamp, builds the
// separate implementation's bytes: the frame, and the datagram within it.
void TestCodec::sendPathBuildsVectorsExactly()
{
    QFETCH(QString, file);
    const Message sent = decodeFrame(bytesOf(readVector(file.toLatin1().constData()))).message;
    // The damaged copy, once corrected, is the clean frame.
    const QByteArray raw = readVector(file == "well-equipped.errors.bin" ? "well-equipped.bin" : file.toLatin1().constData());
    const std::optional<std::int64_t> seconds = secure::stampSeconds(
        std::uint32_t(sent.header.number(ItemId::time_UTC)), std::uint32_t(sent.header.number(ItemId::date_UTC)));
    QVERIFY(seconds);
    Message command = sent;
    for (ItemId id : {ItemId::ID_msg, ItemId::time_UTC, ItemId::date_UTC})
        command.header.set(id, std::int64_t(0));
    // Any instant within the stamped second gives the same bytes.
    const SendStamp stamp{std::uint32_t(sent.header.number(ItemId::ID_msg)), *seconds * 1'000'000 + 999'999};
    QVERIFY(validateCommand(command, SendFormat{}).empty());
    Diagnostics errors;
    const std::vector<std::uint8_t> frame = buildFrame(command, stamp, SendFormat{false, nullptr}, errors);
    QVERIFY2(!frame.empty(), dump(errors));
    QCOMPARE(hex(frame), hex(bytesOf(raw)));
    const std::vector<std::uint8_t> datagram = buildFrame(command, stamp, SendFormat{true, nullptr}, errors);
    QCOMPARE(hex(datagram), hex(bytesOf(raw).subspan(kPreambleSize)));
}

// Keyed, the send path enciphers what it stamped; the receive path reads
// back exactly that message. Its checks follow the format: what leaves no
// room for the checked padding is refused on the secure link only.
void TestCodec::sendPathStampsAndEnciphers()
{
    QCOMPARE(nextSendMicros(1'795'334'400'250'000, std::chrono::seconds(1)), 1'795'334'401'000'000);
    QCOMPARE(nextSendMicros(1'795'334'401'000'000, std::chrono::seconds(1)), 1'795'334'402'000'000);

    const secure::SecretKey psk = secure::generateKey();
    const secure::SecureCodec up(psk, secure::Direction::GcsToUa);
    const Message command = restingCommand(Airframe::wellEquipped());
    const SendStamp stamp{0x123456, 1'795'334'401'000'000};  // 2026-11-22 08:00:01 UTC
    for (const bool datagram : {false, true}) {
        Diagnostics errors;
        const std::vector<std::uint8_t> bytes = buildFrame(command, stamp, SendFormat{datagram, &up}, errors);
        QVERIFY2(!bytes.empty(), dump(errors));
        QCOMPARE(bytes.size(), datagram ? kDatagramSize : kFrameSize);
        Message stamped = command;
        stampMessage(stamped, stamp);
        QCOMPARE(stamped.header.number(ItemId::ID_msg), 0x123456);
        QCOMPARE(stamped.header.number(ItemId::time_UTC), 80001);
        QCOMPARE(stamped.header.number(ItemId::date_UTC), 261122);
        const std::optional<EncodedBlocks> blocks = up.encode(stamped, errors);
        QVERIFY(blocks);
        const DatagramBytes d = makeDatagram(blocks->block1, blocks->block2);
        const FrameBytes f = makeFrame(blocks->block1, blocks->block2);
        const auto expected = datagram ? std::vector<std::uint8_t>(d.begin(), d.end())
                                       : std::vector<std::uint8_t>(f.begin(), f.end());
        QCOMPARE(hex(bytes), hex(expected));
        const LogKey key(psk);
        const LoggedFrameReading reading = readLoggedFrame(bytes, true, &key);
        QVERIFY2(reading.read(), reading.detail.c_str());
        QVERIFY(reading.decoded.message == stamped);
    }

    // 209 bytes of items: plain they fit, keyed the 16 checked bytes of
    // padding do not (as in encoderKeepsRequiredPadding).
    Message full = command;
    for (ItemId id : {ItemId::ID_UA_source, ItemId::ID_GCS_destination, ItemId::ID_GCS_backup})
        full.header.set(id, Value::pair(44, 1));
    full.header.set(ItemId::ID_BLK12_format, Value::pair(0, 0));
    for (Unit& cam : full.cameras)
        for (ItemId id : {ItemId::cam_GCS_destination, ItemId::cam_GCS_backup})
            cam.set(id, Value::pair(44, 2));
    Unit& fourth = full.addEngine(4);
    fourth.set(ItemId::eng_status, 0x50);
    fourth.set(ItemId::eng_prop_pitch, 1);
    fourth.set(ItemId::eng_carb_SET, 1);
    full.addEngine(5);
    QVERIFY(validateCommand(full, SendFormat{}).empty());
    const Diagnostics refused = validateCommand(full, SendFormat{true, &up});
    QCOMPARE(refused.size(), std::size_t{1});
    QCOMPARE(QString::fromStdString(refused[0].message),
             QString("the items need 209 bytes plus 16 bytes of required padding, 2 more than the 223 a block holds"));
    Diagnostics errors;
    QVERIFY(buildFrame(full, stamp, SendFormat{true, &up}, errors).empty());
    QVERIFY(!errors.empty());
}

// Outside codec/ a frame is read through codec/receive only, which also
// decides whether it is accepted: no source of link/, ui/ or app/ reaches the
// block decoder or deciphers on its own.
void TestCodec::blockDecoderStaysInsideTheCodec()
{
    static const char* const bypasses[] = {"MessageDecoder.h", "decodeFrame(", "decodeBlocks(", "decodeBlock1(",
                                           "decodeBlock2(", "decryptBlocks(", "openFrame("};
    QStringList found;
    int files = 0;
    for (const char* folder : {"link", "ui", "app"}) {
        QDirIterator it(QStringLiteral(RCM_SOURCE_DIR "/") + QLatin1String(folder), {"*.cpp", "*.h"}, QDir::Files,
                        QDirIterator::Subdirectories);
        while (it.hasNext()) {
            QFile f(it.next());
            QVERIFY(f.open(QIODevice::ReadOnly));
            ++files;
            const QByteArray text = f.readAll();
            for (const char* bypass : bypasses)
                if (text.contains(bypass))
                    found << QStringLiteral("%1: %2").arg(f.fileName(), QLatin1String(bypass));
        }
    }
    QVERIFY(files > 100);
    QVERIFY2(found.isEmpty(), qPrintable(found.join(QLatin1Char('\n'))));
}

void TestCodec::randomRoundTrip()
{
    std::mt19937_64 rng(20261122);
    for (int i = 0; i < 5000; ++i) {
        const Message m = test::randomMessage(rng);
        Diagnostics errors;
        const auto frame = encodeFrame(m, errors);
        QVERIFY2(frame, dump(errors));
        const DecodeResult r = decodeFrame(*frame);
        QVERIFY2(r.diagnostics.empty(), dump(r.diagnostics));
        QVERIFY2(r.message == m, qPrintable(QString("message %1 differs after a round trip").arg(i)));
        const auto again = encodeFrame(r.message, errors);
        QVERIFY(again && *again == *frame);
    }
}

void TestCodec::datagramRoundTrip()
{
    std::mt19937_64 rng(7);
    const Message m = test::randomMessage(rng);
    Diagnostics errors;
    auto datagram = encodeDatagram(m, errors);
    QVERIFY(datagram);
    QCOMPARE(datagram->size(), std::size_t{510});
    corrupt(rng, datagram->data(), 5);
    const DecodeResult r = decodeFrame(*datagram);
    QCOMPARE(r.corrected.block1, 5);
    QCOMPARE(r.corrected.block2, 0);
    QVERIFY(r.message == m);
}

void TestCodec::restingCommandEncodes()
{
    const Message m = restingCommand(Airframe::wellEquipped());
    QCOMPARE(m.engines.size(), std::size_t{3});
    QCOMPARE(m.radios.size(), std::size_t{3});
    QCOMPARE(m.cameras.size(), std::size_t{2});
    QVERIFY2(validate(m).empty(), dump(validate(m)));
    QCOMPARE(m.engines[0].fieldCode(ItemId::eng_status, 0), 1u);  // AUTO
    QCOMPARE(m.settings.fieldCode(ItemId::land_wheels, 2), 1u);   // nose wheel out
}

void TestCodec::encoderRefusesOutOfRange_data()
{
    QTest::addColumn<int>("item");
    QTest::addColumn<qint64>("a");
    QTest::addColumn<qint64>("b");
    QTest::addColumn<QString>("message");
    QTest::newRow("flap -128") << 0x41 << qint64(-128) << qint64(0)
                               << "flaps F_aileron_LHS_set: -128 is below the minimum -127 by 1";
    QTest::newRow("flap 200") << 0x46 << qint64(200) << qint64(0)
                              << "flaps F_airbrake_set: 200 is above the maximum 127 by 73";
    QTest::newRow("pitch 300") << 0x32 << qint64(300) << qint64(0)
                               << "engine 1 eng_prop_pitch: 300 is above the maximum 255 by 45";
    QTest::newRow("compass 360.00") << 0xC1 << qint64(36000) << qint64(0)
                                    << "camera NIK 1 cam_mag_compass: 360.00 is above the maximum 359.99 by 0.01";
    QTest::newRow("ID_msg 2^24") << 0x03 << qint64(1 << 24) << qint64(0)
                                 << "HEADER ID_msg: 16777216 is above the maximum 16777215 by 1";
    QTest::newRow("country 0") << 0x04 << qint64(0) << qint64(5)
                               << "HEADER ID_UA_source: country dialling code 0 is below the minimum 1 by 1";
    QTest::newRow("country 2000") << 0x08 << qint64(2000) << qint64(5)
                                  << "country dialling code 2000 is above the maximum 1929 by 71";
    QTest::newRow("unit 70000") << 0x09 << qint64(44) << qint64(70000)
                                << "unit number 70000 is above the maximum 65535 by 4465";
    QTest::newRow("time 24:00:00") << 0x05 << qint64(240000) << qint64(0) << "hours 24 is above the maximum 23 by 1";
    QTest::newRow("time 12:60:00") << 0x05 << qint64(126000) << qint64(0) << "minutes 60 is above the maximum 59 by 1";
    QTest::newRow("date month 13") << 0x06 << qint64(71314) << qint64(0) << "month 13 is above the maximum 12 by 1";
    QTest::newRow("date 30 Feb") << 0x06 << qint64(80230) << qint64(0) << "day 30 is above the maximum 29 by 1";
    QTest::newRow("corrupt field") << 0x71 << qint64(0x16) << qint64(0)
                                   << "SETTINGS lights: field wing_RHS: code 00 means data corruption";
    QTest::newRow("reserved bits") << 0x80 << qint64(0x51) << qint64(0)
                                   << "radio VHF1 receiver_control: field reserved bits: reserved bits are not 0";
    QTest::newRow("format 256") << 0x07 << qint64(256) << qint64(1) << "first format ID 256 is above the maximum 255 by 1";
    // The distance to the range need not fit in an int64.
    const qint64 lowest = std::numeric_limits<qint64>::min();
    const qint64 highest = std::numeric_limits<qint64>::max();
    QTest::newRow("ID_msg -2^63") << 0x03 << lowest << qint64(0)
                                  << "HEADER ID_msg: -9223372036854775808 is below the minimum 0 by 9223372036854775808";
    QTest::newRow("flap 2^63-1") << 0x45 << highest << qint64(0)
                                 << "flaps F_elev_set: 9223372036854775807 is above the maximum 127 by 9223372036854775680";
    QTest::newRow("compass -2^63") << 0xC1 << lowest << qint64(0)
                                   << "camera NIK 1 cam_mag_compass: -92233720368547758.08 is below the minimum 0.00 by "
                                      "92233720368547758.08";
    QTest::newRow("elevation -2^63") << 0xC2 << lowest << qint64(0)
                                     << "camera NIK 1 cam_elev: -92233720368547758.08 is below the minimum -327.67 by "
                                        "92233720368547430.41";
    QTest::newRow("unit -2^63") << 0x09 << qint64(44) << lowest
                                << "unit number -9223372036854775808 is below the minimum 0 by 9223372036854775808";
}

void TestCodec::encoderRefusesOutOfRange()
{
    QFETCH(int, item);
    QFETCH(qint64, a);
    QFETCH(qint64, b);
    QFETCH(QString, message);
    const ItemInfo& info = *findItem(static_cast<std::uint8_t>(item));
    Message m;
    m.addEngine(1);
    m.addRadio("VHF1");
    m.addCamera("NIK", 1);
    Unit* unit = m.single(info.owner) ? m.single(info.owner) : &m.repeated(info.owner)->front();
    unit->set(info.id, Value::pair(a, b));
    Diagnostics errors;
    QVERIFY(!encodeFrame(m, errors));
    QCOMPARE(errors.size(), std::size_t{1});
    QCOMPARE(errors[0].kind, Diagnostic::Kind::OutOfRange);
    QVERIFY2(errors[0].toString().find(message.toStdString()) != std::string::npos, errors[0].toString().c_str());
}

void TestCodec::encoderRefusesWhatDoesNotFit()
{
    Message m;
    for (int i = 0; i < 10; ++i) {  // 10 radios x 23 bytes = 230 bytes
        Unit& r = m.addRadio("R" + std::to_string(i));
        r.set(ItemId::receiver_control, 0x50);
        r.set(ItemId::Rx_freq, 1);
        r.set(ItemId::Tx_freq, 1);
        r.set(ItemId::Tx_OP_power, 1);
    }
    Diagnostics errors;
    QVERIFY(!encodeFrame(m, errors));
    QCOMPARE(errors.size(), std::size_t{1});
    QCOMPARE(errors[0].kind, Diagnostic::Kind::DoesNotFit);
    QCOMPARE(QString::fromStdString(errors[0].toString()),
             QString("block 1: BLOCK 1: the items need 230 bytes, 7 more than the 223 a block holds"));

    Message plan;
    plan.flightPlan.planId = 1;
    plan.flightPlan.data.assign(216, 0xAB);
    QVERIFY(!encodeFrame(plan, errors));
    QCOMPARE(QString::fromStdString(errors[0].toString()),
             QString("block 2: flight plan section: 216 data bytes, 1 more than the 215 a section carries"));
    plan.flightPlan.data.resize(215);
    QVERIFY(encodeFrame(plan, errors));
}

void TestCodec::encoderRefusesUnitWithoutKey()
{
    Message m;
    Unit& e = m.engines.emplace_back(UnitKind::Engine);
    e.set(ItemId::eng_prop_pitch, 10);
    Diagnostics errors;
    QVERIFY(!encodeFrame(m, errors));
    QCOMPARE(errors[0].kind, Diagnostic::Kind::MissingKey);
    QVERIFY(errors[0].toString().find("needs its key item eng_ID") != std::string::npos);
}

void TestCodec::encoderKeepsRequiredPadding()
{
    Message m = restingCommand(Airframe::wellEquipped());  // 149 bytes of items
    EncodeOptions secure;
    secure.minBlock1Padding = 16;
    secure.maxFlightPlanData = 199;
    QCOMPARE(block1ItemBytes(m), std::size_t{149});
    for (ItemId id : {ItemId::ID_UA_source, ItemId::ID_GCS_destination, ItemId::ID_GCS_backup})
        m.header.set(id, Value::pair(44, 1));
    for (ItemId id : {ItemId::ID_msg, ItemId::time_UTC, ItemId::date_UTC})
        m.header.set(id, 10101);
    m.header.set(ItemId::ID_BLK12_format, Value::pair(0, 0));
    for (Unit& cam : m.cameras)
        for (ItemId id : {ItemId::cam_GCS_destination, ItemId::cam_GCS_backup})
            cam.set(id, Value::pair(44, 2));
    Unit& fourth = m.addEngine(4);
    fourth.set(ItemId::eng_status, 0x50);
    fourth.set(ItemId::eng_prop_pitch, 1);
    fourth.set(ItemId::eng_carb_SET, 1);
    QCOMPARE(block1ItemBytes(m), std::size_t{207});  // 16 bytes of padding left: exactly enough
    QVERIFY(validate(m, secure).empty());
    m.addEngine(5);
    const Diagnostics errors = validate(m, secure);
    QCOMPARE(errors.size(), std::size_t{1});
    QCOMPARE(QString::fromStdString(errors[0].message),
             QString("the items need 209 bytes plus 16 bytes of required padding, 2 more than the 223 a block holds"));
    QVERIFY(validate(m).empty());
    m.flightPlan.data.assign(200, 1);
    QVERIFY(validate(m, secure).size() == 2);
}

namespace {
// A block holding the given item bytes after leading padding.
Block blockWith(std::initializer_list<std::uint8_t> items)
{
    Block b;
    b.fill(0x55);
    std::copy(items.begin(), items.end(), b.end() - static_cast<std::ptrdiff_t>(items.size()));
    return b;
}
Block emptyBlock2()
{
    Block b;
    b.fill(0x55);
    std::fill_n(b.begin(), 7, 0);
    b[222] = 0;
    return b;
}
DecodeResult decodeB1(const Block& b1)
{
    DecodedBlocks blocks;
    blocks.block1 = b1;
    blocks.block2 = emptyBlock2();
    return decodeBlocks(blocks);
}
}  // namespace

void TestCodec::decoderReportsCorruptFields()
{
    // lights: wing_RHS 00 (corrupt), wing_LHS ON, tail 11 (corrupt), brake OFF.
    // The item stays, so its valid fields can still be acted on.
    const DecodeResult r = decodeB1(blockWith({0x71, 0x2D, 0x80, 0x50}));
    QCOMPARE(r.diagnostics.size(), std::size_t{3});
    QCOMPARE(QString::fromStdString(r.diagnostics[0].toString()),
             QString("block 1 offset 219: SETTINGS lights wing_RHS: code 00 means data corruption; ignored"));
    QCOMPARE(QString::fromStdString(r.diagnostics[1].toString()),
             QString("block 1 offset 219: SETTINGS lights tail: code 11 means data corruption; ignored"));
    QCOMPARE(QString::fromStdString(r.diagnostics[2].toString()),
             QString("block 1 offset 221: receiver_control: comes before any system_ID; ignored"));
    QCOMPARE(r.message.settings.fieldCode(ItemId::lights, 1), 2u);
    QCOMPARE(r.message.settings.fieldCode(ItemId::lights, 3), 1u);
}

void TestCodec::decoderReportsUnknownItemAndKeepsEarlier()
{
    const DecodeResult r = decodeB1(blockWith({0x03, 0x00, 0x00, 0x85, 0x0F, 0xB0, 0x23}));
    QCOMPARE(r.diagnostics.size(), std::size_t{1});
    QCOMPARE(QString::fromStdString(r.diagnostics[0].toString()),
             QString("block 1 offset 220: unknown Item_ID 0x0F; the length of what follows is unknown, so the rest of "
                     "the block is not read"));
    QCOMPARE(r.message.header.number(ItemId::ID_msg), 133);
    QVERIFY(!r.message.sense.has(ItemId::SA_zoom_LHS_cam));
}

void TestCodec::decoderReportsTruncatedItem()
{
    const DecodeResult r = decodeB1(blockWith({0xB0, 0x01, 0x82, 0x00, 0x01}));
    QCOMPARE(r.diagnostics.size(), std::size_t{1});
    QCOMPARE(QString::fromStdString(r.diagnostics[0].toString()),
             QString("block 1 offset 220: Rx_freq: needs 4 value bytes, only 2 left in the block"));
    QCOMPARE(r.message.sense.number(ItemId::SA_zoom_LHS_cam), 1);
}

void TestCodec::decoderReportsOutOfRangeAndContinues()
{
    // F_lift_set 0x80 (-128 is invalid), then a valid zoom.
    const DecodeResult r = decodeB1(blockWith({0x43, 0x80, 0x44, 0x05, 0x05, 0x03, 0xA9, 0x80, 0xB1, 0x69}));
    QCOMPARE(r.diagnostics.size(), std::size_t{2});
    QCOMPARE(QString::fromStdString(r.diagnostics[0].toString()),
             QString("block 1 offset 213: flaps F_lift_set: -128 is below the minimum -127 by 1; ignored"));
    QCOMPARE(QString::fromStdString(r.diagnostics[1].toString()),
             QString("block 1 offset 217: HEADER time_UTC: hours 24 is above the maximum 23 by 1; ignored"));
    QVERIFY(!r.message.flaps.has(ItemId::F_lift_set));
    QVERIFY(!r.message.header.has(ItemId::time_UTC));
    QCOMPARE(r.message.flaps.number(ItemId::F_rudder_set), 5);
    QCOMPARE(r.message.sense.number(ItemId::SA_zoom_FWD_cam), 105);
}

void TestCodec::decoderReportsOrphanAndRepeated()
{
    const DecodeResult r = decodeB1(blockWith({0x32, 0x10, 0x31, 0x07, 0x32, 0x11, 0x32, 0x12}));
    QCOMPARE(r.diagnostics.size(), std::size_t{2});
    QCOMPARE(QString::fromStdString(r.diagnostics[0].toString()),
             QString("block 1 offset 215: eng_prop_pitch: comes before any eng_ID; ignored"));
    QCOMPARE(QString::fromStdString(r.diagnostics[1].toString()),
             QString("block 1 offset 221: engine 7 eng_prop_pitch: given twice; the later value is kept"));
    QCOMPARE(r.message.engines.size(), std::size_t{1});
    QCOMPARE(r.message.engines[0].number(ItemId::eng_prop_pitch), 0x12);
}

void TestCodec::decoderAcceptsAnyOrderPaddingAndBeginEnd()
{
    // Items out of canonical order, AA padding between them, BEGIN/END bytes,
    // and two engines whose items interleave with a radio.
    const DecodeResult r = decodeB1(blockWith({0x01, 0x04, 0xB2, 0x09, 0x02, 0xAA, 0x31, 0x01, 0x81, 'V', 'H', 'F', '9',
                                               ' ', ' ', ' ', ' ', 0x32, 0x44, 0x84, 0x0A, 0x55, 0x03, 0x00, 0x00, 0x01}));
    QVERIFY2(r.diagnostics.empty(), dump(r.diagnostics));
    QCOMPARE(r.message.sense.number(ItemId::SA_zoom_RHS_cam), 9);
    QCOMPARE(r.message.engines[0].number(ItemId::eng_prop_pitch), 0x44);
    QCOMPARE(r.message.radios[0].find(ItemId::system_ID)->text, std::string("VHF9"));
    QCOMPARE(r.message.radios[0].number(ItemId::Tx_OP_power), 10);
    QCOMPARE(r.message.header.number(ItemId::ID_msg), 1);
}

void TestCodec::decoderChecksBlock2()
{
    Block b2 = emptyBlock2();
    b2[0] = 216;
    DecodedBlocks blocks;
    blocks.block1.fill(0x55);
    blocks.block2 = b2;
    DecodeResult r = decodeBlocks(blocks);
    QCOMPARE(QString::fromStdString(r.diagnostics.at(0).toString()),
             QString("block 2 offset 0: flight plan data length: 216 is above the maximum 215 by 1; section ignored"));
    b2 = emptyBlock2();
    b2[0] = 2;
    b2[7] = 0xAB;
    b2[8] = 0xCD;
    b2[100] = 0x54;
    b2[222] = 0x01;
    blocks.block2 = b2;
    r = decodeBlocks(blocks);
    QCOMPARE(r.diagnostics.size(), std::size_t{2});
    QCOMPARE(QString::fromStdString(r.diagnostics[0].toString()),
             QString("block 2 offset 100: flight plan padding: byte 0x54 where padding 0x55 belongs"));
    QCOMPARE(QString::fromStdString(r.diagnostics[1].toString()),
             QString("block 2 offset 222: End_Of_String: byte 0x01 where 0x00 belongs"));
    QCOMPARE(r.message.flightPlan.data, (std::vector<std::uint8_t>{0xAB, 0xCD}));
}

void TestCodec::decodeFrameRejectsWrongSize()
{
    std::vector<std::uint8_t> bytes(509);
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, decodeFrame(bytes));
}

void TestCodec::rsCorrectsUpTo16_data()
{
    QTest::addColumn<int>("errors");
    for (int e : {1, 2, 8, 15, 16})
        QTest::addRow("%d", e) << e;
}

void TestCodec::rsCorrectsUpTo16()
{
    QFETCH(int, errors);
    std::mt19937_64 rng(errors);
    for (int trial = 0; trial < 200; ++trial) {
        const Block b1 = randomBlock(rng), b2 = randomBlock(rng);
        DatagramBytes d = makeDatagram(b1, b2);
        const DatagramBytes clean = d;
        corrupt(rng, d.data(), errors);
        corrupt(rng, d.data() + 255, errors);
        const DecodedBlocks out = decodeCodewords(d);
        QCOMPARE(out.corrected.block1, errors);
        QCOMPARE(out.corrected.block2, errors);
        QVERIFY(out.block1 == b1 && out.block2 == b2);
        QVERIFY(!rs::isCodeword(d.data()));
        QVERIFY(rs::isCodeword(clean.data()) && rs::isCodeword(clean.data() + 255));
    }
}

void TestCodec::rsRefuses17AndMore_data()
{
    QTest::addColumn<int>("errors");
    for (int e : {17, 18, 24, 40})
        QTest::addRow("%d", e) << e;
}

void TestCodec::rsRefuses17AndMore()
{
    QFETCH(int, errors);
    std::mt19937_64 rng(100 + errors);
    int refused = 0;
    const int trials = 200;
    for (int trial = 0; trial < trials; ++trial) {
        const Block b1 = randomBlock(rng), b2 = randomBlock(rng);
        DatagramBytes d = makeDatagram(b1, b2);
        corrupt(rng, d.data(), errors);
        const DatagramBytes received = d;
        const DecodedBlocks out = decodeCodewords(d);
        QCOMPARE(out.corrected.block2, 0);
        // Beyond 16 errors a decoder can only fail or miscorrect into another
        // codeword 17+ bytes away; it must never hand back the original.
        QVERIFY(out.block1 != b1);
        if (out.corrected.block1 < 0) {
            ++refused;
            QVERIFY(std::equal(out.block1.begin(), out.block1.end(), received.begin()));
        }
    }
    // Miscorrection of RS(255,223) beyond its capacity is rare (well under 1e-3).
    QCOMPARE(refused, trials);
}

void TestCodec::rsCleanCheckAgreesWithLibfec()
{
    std::mt19937_64 rng(99);
    for (int trial = 0; trial < 2000; ++trial) {
        const Block b1 = randomBlock(rng), b2 = randomBlock(rng);
        DatagramBytes d = makeDatagram(b1, b2);
        const int errors = trial % 3 == 0 ? 0 : 1 + static_cast<int>(rng() % 3);
        corrupt(rng, d.data(), errors);
        std::uint8_t copy[255];
        std::memcpy(copy, d.data(), 255);
        QCOMPARE(rs::isCodeword(d.data()), rs::decodeLibfec(copy) == 0);
    }
}

void TestCodec::uncorrectableBlockIsReportedAndOtherKept()
{
    std::mt19937_64 rng(5);
    Message m = restingCommand(Airframe::wellEquipped());
    m.flightPlan.planId = 9;
    m.flightPlan.data = {1, 2, 3};
    Diagnostics errors;
    auto d = encodeDatagram(m, errors);
    QVERIFY(d);
    corrupt(rng, d->data() + 255, 30);
    const DecodeResult r = decodeFrame(*d);
    QCOMPARE(r.corrected.block1, 0);
    QCOMPARE(r.corrected.block2, -1);
    QVERIFY(!r.ok());
    QCOMPARE(r.diagnostics.size(), std::size_t{1});
    QCOMPARE(QString::fromStdString(r.diagnostics[0].toString()),
             QString("block 2: more than 16 byte errors in the codeword; block not read"));
    QCOMPARE(r.message.engines.size(), std::size_t{3});
    QVERIFY(r.message.flightPlan.empty());
}

QTEST_APPLESS_MAIN(TestCodec)
#include "tst_codec.moc"
