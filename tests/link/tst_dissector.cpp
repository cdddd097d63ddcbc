// The generated Wireshark dissector: the checked-in copy is the generator's
// output byte for byte, and tshark, running it over a frame log of the sample
// frames, reads the values the samples were made with.

#include "codec/frame/Frame.h"
#include "codec/message/ItemTable.h"
#include "codec/dissector/WiresharkDissector.h"
#include "link/framelog/FrameLog.h"

#include <QFile>
#include <QFileInfo>
#include <QProcess>
#include <QRegularExpression>
#include <QSet>
#include <QTemporaryDir>
#include <QTest>

#include <cstring>

namespace {

const QString kCheckedIn = QStringLiteral(RCM_SOURCE_DIR "/resources/wireshark/rcm.lua");
const QString kVectors = QStringLiteral(RCM_VECTORS_DIR "/rcm/");
const QString kTshark = QStringLiteral("/usr/bin/tshark");

QByteArray readFile(const QString& path)
{
    QFile f(path);
    return f.open(QIODevice::ReadOnly) ? f.readAll() : QByteArray();
}

QByteArray generated()
{
    return QByteArray::fromStdString(rcm::wiresharkDissectorLua());
}

// The Item_IDs a sample carries, in order, as tshark prints a hex uint8.
QStringList itemIdsOf(const QString& itemsTxt)
{
    QStringList ids;
    static const QRegularExpression line(QStringLiteral("^  ([0-9A-F]{2}) "));
    for (const QByteArray& l : readFile(itemsTxt).split('\n')) {
        const auto m = line.match(QString::fromLatin1(l));
        if (m.hasMatch())
            ids.append(QStringLiteral("0x") + m.captured(1).toLower());
    }
    return ids;
}

rcm::Block paddedBlock()
{
    rcm::Block b;
    b.fill(rcm::kPad55);
    return b;
}

QByteArray frameOf(const rcm::Block& b1, const rcm::Block& b2)
{
    const rcm::FrameBytes f = rcm::makeFrame(b1, b2);
    return QByteArray(reinterpret_cast<const char*>(f.data()), qsizetype(f.size()));
}

constexpr int kFaultyUnknownOffset = 36;

// Everything the dissector must flag, one of each, in one frame.
QByteArray faultyFrame()
{
    using rcm::ItemId;
    rcm::Block b1 = paddedBlock();
    // clang-format off
    const std::uint8_t items[] = {
        0xAA, 0xAA, 0x55,                                   // a mixed padding run, after the 55s before it
        std::uint8_t(ItemId::eng_prop_pitch), 7,            // before any eng_ID: an orphan
        rcm::kBegin, 0x10, rcm::kEnd,                       // never sent, skipped
        std::uint8_t(ItemId::eng_ID), 5,
        std::uint8_t(ItemId::eng_status), 0x00,             // both fields corrupt
        std::uint8_t(ItemId::FLAP_status), 0x93,            // reserved bits set
        std::uint8_t(ItemId::F_lift_set), 0x80,             // -128 is below the minimum
        std::uint8_t(ItemId::land_wheels), 0x57,            // TAIL = 11, corrupt
        std::uint8_t(ItemId::cam_ID), 'N', 'I', 'K', 3,
        std::uint8_t(ItemId::cam_mag_compass), 0x8C, 0xA0,  // 36000 is above 359.99
        0xFF,                                               // unknown: the rest is not read
        std::uint8_t(ItemId::ID_msg), 0, 0, 1,
    };
    // clang-format on
    std::memcpy(b1.data() + 10, items, sizeof items);
    Q_ASSERT(b1[kFaultyUnknownOffset] == 0xFF);
    rcm::Block b2 = paddedBlock();
    b2[0] = 216;
    return frameOf(b1, b2);
}

// An item cut by the end of the block, and a bad End_Of_String.
QByteArray truncatedFrame()
{
    rcm::Block b1 = paddedBlock();
    b1[rcm::kBlockSize - 3] = std::uint8_t(rcm::ItemId::Rx_freq);
    rcm::Block b2 = paddedBlock();
    b2[0] = 2;
    b2[1] = 0;
    b2[2] = 0;
    b2[3] = 0;
    b2[4] = 9;
    b2[5] = 0;
    b2[6] = 1;
    b2[7] = 0xAB;
    b2[8] = 0xCD;
    b2[rcm::kBlockSize - 1] = 0x55;
    return frameOf(b1, b2);
}

struct ValueRow {
    int packet;
    const char* field;
    const char* expected;
};

// What tshark must print for a field of a packet (1-based), from the samples' items.txt.
QVector<ValueRow> valueRows()
{
    QVector<ValueRow> rows;
    auto row = [&rows](int packet, const char* field, const char* expected) { rows.append({packet, field, expected}); };
    // seed-example.items.txt
    row(1, "rcm.form", "frame");
    row(1, "rcm.item.ID_msg", "133");
    row(1, "rcm.item.ID_UA_source", "GB_133");
    row(1, "rcm.item.ID_UA_source.country", "44");
    row(1, "rcm.item.ID_UA_source.unit", "133");
    row(1, "rcm.item.time_UTC", "16:35:23");
    row(1, "rcm.item.date_UTC", "071114");
    row(1, "rcm.item.ID_BLK12_format", "5 15");
    row(1, "rcm.item.ID_GCS_destination", "GB_30226");
    row(1, "rcm.item.ID_GCS_backup", "GB_41251");
    row(1, "rcm.item.SA_zoom_LHS_cam", "35");
    row(1, "rcm.item.SA_zoom_FWD_cam", "105");
    row(1, "rcm.item.eng_ID", "");
    row(1, "rcm.block2.x", "0");
    row(1, "rcm.block2.flight_plan_ID", "0x00000000");
    // well-equipped.items.txt: ID_msg 44 CB 63
    row(2, "rcm.item.ID_msg", "4508515");
    row(2, "rcm.item.ID_UA_source", "1166_8271");
    row(2, "rcm.item.time_UTC", "08:07:31");
    row(2, "rcm.item.date_UTC", "970816");
    row(2, "rcm.item.ID_GCS_destination", "193_63944");
    row(2, "rcm.item.eng_ID", "1,2,3");
    row(2, "rcm.item.eng_status", "0x90,0xd0,0x50");
    row(2, "rcm.item.eng_status.control", "2,3,1");
    row(2, "rcm.item.eng_prop_pitch", "228,52,13");
    row(2, "rcm.item.eng_carb_SET", "136,162,4");
    row(2, "rcm.item.F_aileron_LHS_set", "121");
    row(2, "rcm.item.F_aileron_RHS_set", "-19");
    row(2, "rcm.item.F_rudder_set", "-120");
    row(2, "rcm.item.ENABLE_fuel_dump.tank3", "2");
    row(2, "rcm.item.land_wheels", "0x55");
    row(2, "rcm.item.land_wheels.LHS", "1");
    row(2, "rcm.item.land_wheels.TAIL", "1");
    row(2, "rcm.item.lights.wing_RHS", "2");
    row(2, "rcm.item.lights.wing_LHS", "1");
    row(2, "rcm.item.system_ID", "VHF1,VHF2,VHF3");
    row(2, "rcm.item.receiver_control.receiver", "1,1,2");
    row(2, "rcm.item.Rx_freq", "127712,134410,134363");
    row(2, "rcm.item.Tx_OP_power", "170,97,201");
    row(2, "rcm.item.cam_ID", "SNY 1,SNY 2");
    row(2, "rcm.item.cam_ID.number", "1,2");
    row(2, "rcm.item.cam_mag_compass", "264.95,333.2");
    row(2, "rcm.item.cam_elev", "45.76,-54.64");
    row(2, "rcm.item.take_one_photo.photo", "1,1");
    row(2, "rcm.item.camera.ID_GCS_destination", "1808_49113,806_48565");
    row(2, "rcm.item.camera.ID_GCS_backup", "178_57535,1003_3876");
    row(2, "rcm.unit",
        "Header,Engine 1,Engine 2,Engine 3,Flaps,Fuel dump,Settings,Radio VHF1,Radio VHF2,Radio VHF3,"
        "Sense and avoid,Camera SNY 1,Camera SNY 2");
    // flight-plan.items.txt, as a frame and as a datagram
    for (int packet : {3, 4}) {
        row(packet, "rcm.item.ID_msg", "15747770");
        row(packet, "rcm.item.ID_UA_source", "TR_40439");
        row(packet, "rcm.item.eng_status.control", "3");
        row(packet, "rcm.item.F_aileron_LHS_set", "-10");
        row(packet, "rcm.item.cam_ID", "NIK 1");
        row(packet, "rcm.item.cam_elev", "86.98");
        row(packet, "rcm.block2.x", "40");
        row(packet, "rcm.block2.flight_plan_ID", "0xdeadbeef");
        row(packet, "rcm.block2.flight_plan_section_ID", "3");
        row(packet, "rcm.block2.flight_plan_data",
            "000102030405060708090a0b0c0d0e0f101112131415161718191a1b1c1d1e1f2021222324252627");
        row(packet, "rcm.block2.End_Of_String", "0x00");
    }
    row(2, "_ws.col.Info", "Received frame ID_msg 4508515, 61 items");
    row(3, "_ws.col.Info", "Sent frame ID_msg 15747770, 34 items, flight plan 0xDEADBEEF section 3, 40 bytes");
    row(4, "_ws.col.Info", "Received datagram ID_msg 15747770, 34 items, flight plan 0xDEADBEEF section 3, 40 bytes");
    row(5, "_ws.col.Info", "Received frame, 8 items [9 problems]");
    row(8, "_ws.col.Info", "100 bytes: a frame is 600 bytes and a datagram 510");
    row(3, "rcm.form", "frame");
    row(4, "rcm.form", "datagram");
    row(4, "rcm.preamble", "");
    return rows;
}

}  // namespace

class TestDissector : public QObject {
    Q_OBJECT

private slots:
    void initTestCase();
    void checkedInCopyIsGenerated();
    void installedCopyIsTheSame();
    void fieldNamesAreUnique();
    void everyItemHasAField();
    void tsharkValues_data();
    void tsharkValues();
    void tsharkItemIds_data();
    void tsharkItemIds();
    void tsharkTree();
    void tsharkFlagsProblems();

private:
    bool haveTshark() const { return QFile::exists(kTshark); }
    QString runTshark(const QStringList& args);
    // Per packet (1-based), field -> tshark's text for it.
    QVector<QHash<QString, QString>> tsharkFields(const QStringList& fields);

    static constexpr int kPackets = 8;
    QTemporaryDir m_dir;
    QString m_log;
    QString m_verbose;  // tshark -V of the whole log, made once
    QVector<QHash<QString, QString>> m_values;
};

void TestDissector::initTestCase()
{
    QVERIFY(m_dir.isValid());
    m_log = m_dir.filePath(QStringLiteral("dissector.pcapng"));
    FrameLog log;
    QString error;
    QVERIFY2(log.open(m_log, &error), qPrintable(error));
    qint64 t = 1795332720000000;
    auto append = [&](const QByteArray& bytes, FrameDirection direction, FrameTransport transport) {
        FrameRecord r;
        r.bytes = bytes;
        r.utcMicros = t += 1000000;
        r.direction = direction;
        r.transport = transport;
        r.status = FrameStatus::Decoded;
        r.correctedSymbols = {0, 0};
        return log.append(r);
    };
    const QByteArray flightPlan = readFile(kVectors + QStringLiteral("flight-plan.bin"));
    QCOMPARE(flightPlan.size(), 600);
    // Packets 1..8, in the order the tests below number them.
    QVERIFY(append(readFile(kVectors + QStringLiteral("seed-example.bin")), FrameDirection::Received,
                   FrameTransport::Serial));
    QVERIFY(append(readFile(kVectors + QStringLiteral("well-equipped.bin")), FrameDirection::Received,
                   FrameTransport::Serial));
    QVERIFY(append(flightPlan, FrameDirection::Sent, FrameTransport::Serial));
    QVERIFY(append(flightPlan.mid(int(rcm::kPreambleSize)), FrameDirection::Received, FrameTransport::Udp));
    QVERIFY(append(faultyFrame(), FrameDirection::Received, FrameTransport::Serial));
    QVERIFY(append(truncatedFrame(), FrameDirection::Received, FrameTransport::Serial));
    QVERIFY(append(readFile(kVectors + QStringLiteral("well-equipped.errors.bin")), FrameDirection::Received,
                   FrameTransport::Serial));
    QVERIFY(append(QByteArray(100, 0x55), FrameDirection::Received, FrameTransport::Udp));
    log.close();

    if (haveTshark())
        m_verbose = runTshark({QStringLiteral("-V")});
}

QString TestDissector::runTshark(const QStringList& args)
{
    QProcess p;
    // tshark warns on stderr about running as root and the like: only the
    // exit code and stdout count.
    p.setProcessChannelMode(QProcess::SeparateChannels);
    p.start(kTshark, QStringList{QStringLiteral("-n"), QStringLiteral("-X"), QStringLiteral("lua_script:") + kCheckedIn,
                                 QStringLiteral("-r"), m_log} +
                         args);
    if (!p.waitForFinished(120000) || p.exitStatus() != QProcess::NormalExit || p.exitCode() != 0) {
        qWarning().noquote() << "tshark" << args.join(QLatin1Char(' ')) << "failed:" << p.exitCode()
                             << p.readAllStandardError();
        return {};
    }
    const QByteArray err = p.readAllStandardError();
    if (err.contains("Lua") || err.contains("lua"))
        qWarning().noquote() << "tshark stderr:" << err;
    return QString::fromUtf8(p.readAllStandardOutput());
}

QVector<QHash<QString, QString>> TestDissector::tsharkFields(const QStringList& fields)
{
    QStringList args{QStringLiteral("-T"), QStringLiteral("fields"), QStringLiteral("-E"),
                     QStringLiteral("separator=/t")};
    for (const QString& f : fields)
        args << QStringLiteral("-e") << f;
    QVector<QHash<QString, QString>> packets;
    const QString out = runTshark(args);
    QStringList lines = out.split(QLatin1Char('\n'));
    if (!lines.isEmpty() && lines.last().isEmpty())
        lines.removeLast();
    // A packet without any of the fields prints an empty line: still a packet.
    for (const QString& line : std::as_const(lines)) {
        const QStringList values = line.split(QLatin1Char('\t'));
        QHash<QString, QString> packet;
        for (int i = 0; i < fields.size() && i < values.size(); ++i)
            packet.insert(fields[i], values[i]);
        packets.append(packet);
    }
    return packets;
}

void TestDissector::checkedInCopyIsGenerated()
{
    const QByteArray text = generated();
    if (qEnvironmentVariableIsSet("RCM_REGENERATE_DISSECTOR")) {
        QFile f(kCheckedIn);
        QVERIFY2(f.open(QIODevice::WriteOnly | QIODevice::Truncate), qPrintable(f.errorString()));
        QCOMPARE(f.write(text), text.size());
    }
    const QByteArray checkedIn = readFile(kCheckedIn);
    if (checkedIn == text)
        return;
    const QList<QByteArray> a = checkedIn.split('\n');
    const QList<QByteArray> b = text.split('\n');
    int line = 0;
    while (line < a.size() && line < b.size() && a[line] == b[line])
        ++line;
    const QString message =
        QStringLiteral(
            "resources/wireshark/rcm.lua is not what the item table generates (first difference at line "
            "%1). The file is generated, never edited: regenerate it with\n"
            "    build/bin/rcm dissector > resources/wireshark/rcm.lua\n"
            "or RCM_REGENERATE_DISSECTOR=1 build/bin/tst_dissector, and commit it with the table change.\n"
            "checked in: %2\ngenerated:  %3")
            .arg(line + 1)
            .arg(QString::fromUtf8(a.value(line)), QString::fromUtf8(b.value(line)));
    QFAIL(qPrintable(message));
}

// tshark loads an installed rcm.lua (the rcm-gcs package puts one in
// Wireshark's plugin folder) before the -X lua_script copy, which then cannot
// register the protocol again: the tshark tests below check the installed
// copy, and say something of this tree only when it is the same text.
void TestDissector::installedCopyIsTheSame()
{
    if (!haveTshark())
        QSKIP("/usr/bin/tshark is not installed");
    QProcess p;
    p.start(kTshark, {QStringLiteral("-G"), QStringLiteral("plugins")});
    QVERIFY(p.waitForFinished(60000) && p.exitStatus() == QProcess::NormalExit);
    const QByteArray checkedIn = readFile(kCheckedIn);
    for (const QByteArray& line : p.readAllStandardOutput().split('\n')) {
        const QString path = QString::fromUtf8(line.split('\t').constLast()).trimmed();
        if (QFileInfo(path).fileName() != QLatin1String("rcm.lua"))
            continue;
        QVERIFY2(readFile(path) == checkedIn,
                 qPrintable(QStringLiteral("tshark loads %1 before this tree's resources/wireshark/rcm.lua, and it "
                                           "is not the same: the tshark tests would check it instead. Remove it, "
                                           "or install this tree's package (scripts/package).")
                                .arg(path)));
    }
}

void TestDissector::fieldNamesAreUnique()
{
    static const QRegularExpression protoField(QStringLiteral("ProtoField\\.\\w+\\(\"([^\"]+)\""));
    QSet<QString> seen;
    auto it = protoField.globalMatch(QString::fromUtf8(generated()));
    while (it.hasNext()) {
        const QString abbr = it.next().captured(1);
        QVERIFY2(!seen.contains(abbr), qPrintable(abbr + QStringLiteral(" is registered twice")));
        seen.insert(abbr);
    }
    QVERIFY(seen.contains(QStringLiteral("rcm.item.ID_GCS_destination")));
    QVERIFY(seen.contains(QStringLiteral("rcm.item.camera.ID_GCS_destination")));
}

void TestDissector::everyItemHasAField()
{
    const QString text = QString::fromUtf8(generated());
    for (const rcm::ItemInfo& item : rcm::itemTable()) {
        const QString name = QString::fromUtf8(item.name.data(), qsizetype(item.name.size()));
        QVERIFY2(text.contains(QStringLiteral("\"rcm.item.%1\"").arg(name)) ||
                     text.contains(QStringLiteral(".%1\", \"%1\"").arg(name)),
                 qPrintable(name));
        for (const rcm::FieldInfo& f : item.fields)
            QVERIFY(text.contains(
                QStringLiteral(".%1.%2\"").arg(name, QString::fromUtf8(f.name.data(), qsizetype(f.name.size())))));
    }
}

void TestDissector::tsharkValues_data()
{
    QTest::addColumn<int>("packet");
    QTest::addColumn<QString>("field");
    QTest::addColumn<QString>("expected");
    for (const ValueRow& r : valueRows())
        QTest::addRow("%d %s", r.packet, r.field)
            << r.packet << QString::fromLatin1(r.field) << QString::fromLatin1(r.expected);
}

void TestDissector::tsharkValues()
{
    if (!haveTshark())
        QSKIP("/usr/bin/tshark is not installed");
    QFETCH(int, packet);
    QFETCH(QString, field);
    QFETCH(QString, expected);
    // One tshark run for all rows: each run loads Wireshark anew.
    if (m_values.isEmpty()) {
        QStringList fields;
        for (const ValueRow& r : valueRows())
            if (!fields.contains(QLatin1String(r.field)))
                fields.append(QString::fromLatin1(r.field));
        m_values = tsharkFields(fields);
    }
    QCOMPARE(m_values.size(), kPackets);
    QCOMPARE(m_values[packet - 1].value(field), expected);
}

void TestDissector::tsharkItemIds_data()
{
    QTest::addColumn<int>("packet");
    QTest::addColumn<QString>("items");
    QTest::newRow("seed-example") << 1 << QStringLiteral("seed-example.items.txt");
    QTest::newRow("well-equipped") << 2 << QStringLiteral("well-equipped.items.txt");
    QTest::newRow("flight-plan frame") << 3 << QStringLiteral("flight-plan.items.txt");
    QTest::newRow("flight-plan datagram") << 4 << QStringLiteral("flight-plan.items.txt");
}

// Every item of the samples is found, in order, and none is invented.
void TestDissector::tsharkItemIds()
{
    if (!haveTshark())
        QSKIP("/usr/bin/tshark is not installed");
    QFETCH(int, packet);
    QFETCH(QString, items);
    const QStringList expected = itemIdsOf(kVectors + items);
    QVERIFY(expected.size() > 5);
    const auto packets = tsharkFields({QStringLiteral("rcm.item_id")});
    QCOMPARE(packets.size(), kPackets);
    QCOMPARE(packets[packet - 1].value(QStringLiteral("rcm.item_id")).split(QLatin1Char(',')), expected);
}

void TestDissector::tsharkTree()
{
    if (!haveTshark())
        QSKIP("/usr/bin/tshark is not installed");
    QVERIFY(!m_verbose.isEmpty());
    QVERIFY2(!m_verbose.contains(QStringLiteral("Lua Error")), "the dissector raised a Lua error");
    const QStringList expected = {
        QStringLiteral("Remote Control Message, frame (600 bytes)"),
        QStringLiteral("Remote Control Message, datagram (510 bytes)"),
        QStringLiteral("Reed-Solomon RS(255,223) is not applied by this dissector"),
        QStringLiteral("Padding: 24 bytes of 55 at offset 0"),
        QStringLiteral("ID_msg: 4508515"),
        QStringLiteral("Engine 2\n"),
        QStringLiteral("eng_status: control=RC slave=NO_SLAVE (0xD0)"),
        QStringLiteral("11.. .... = control: RC (3)"),
        QStringLiteral("F_aileron_RHS_set: -19 deg"),
        QStringLiteral("land_wheels: LHS=OUT RHS=OUT NOSE=OUT TAIL=OUT (0x55)"),
        QStringLiteral("01.. .... = LHS: OUT (1)"),
        QStringLiteral(".... ..01 = TAIL: OUT (1)"),
        QStringLiteral("lights: wing_RHS=ON wing_LHS=OFF tail=OFF wheel_brake=ON (0x96)"),
        QStringLiteral("Radio VHF3\n"),
        QStringLiteral("Rx_freq: 127712 kHz"),
        QStringLiteral("Tx_OP_power: 170 dBm"),
        QStringLiteral("cam_elev: -54.64 deg"),
        QStringLiteral("cam_mag_compass: 333.20 deg"),
        QStringLiteral("date_UTC: 970816 (2097-08-16)"),
        QStringLiteral("time_UTC: 16:35:23"),
        QStringLiteral("ID_UA_source: GB_133"),
        QStringLiteral("country: GB (44)"),
        QStringLiteral("Padding: 175 bytes of 55 at offset 47"),
        QStringLiteral("End_Of_String: 0x00"),
    };
    for (const QString& s : expected)
        QVERIFY2(m_verbose.contains(s), qPrintable(s));
}

void TestDissector::tsharkFlagsProblems()
{
    if (!haveTshark())
        QSKIP("/usr/bin/tshark is not installed");
    QVERIFY(!m_verbose.isEmpty());
    const QStringList expected = {
        QStringLiteral("Padding: 13 bytes (11 of 55, 2 of AA) at offset 0"),
        QStringLiteral("eng_prop_pitch at block 1 offset 13 comes before any eng_ID; the console ignores it"),
        QStringLiteral("BEGIN at offset 15: skipped"),
        QStringLiteral("END at offset 17: skipped"),
        QStringLiteral("Engine 5 eng_status control: code 00 means data corruption; ignored"),
        QStringLiteral("Engine 5 eng_status slave: code 00 means data corruption; ignored"),
        QStringLiteral("00.. .... = control: corrupt (0)"),
        QStringLiteral("Flaps FLAP_status: reserved bits are not 0 (byte 0x93)"),
        QStringLiteral("Flaps F_lift_set: value -128 is below the minimum -127"),
        QStringLiteral("Settings land_wheels TAIL: code 11 means data corruption; ignored"),
        QStringLiteral("Camera NIK 3 cam_mag_compass: value 360.00 is above the maximum 359.99"),
        QStringLiteral("Unknown Item_ID 0xFF at block 1 offset %1 (packet offset %2)")
            .arg(kFaultyUnknownOffset)
            .arg(kFaultyUnknownOffset + int(rcm::kPreambleSize)),
        QStringLiteral("x = 216 is above the maximum 215 by 1; the section is not read"),
        QStringLiteral("Rx_freq at block 1 offset 220 needs 4 value bytes, only 2 left in the block"),
        QStringLiteral("flight_plan_data: abcd"),
        QStringLiteral("End_Of_String is 0x55 at block 2 offset 222"),
        QStringLiteral("100 bytes: a frame is 600 bytes and a datagram 510"),
        // well-equipped.errors.bin: 16 wrong bytes per codeword, shown uncorrected
        QStringLiteral("Unknown Item_ID 0x5C at block 1 offset 7"),
    };
    for (const QString& s : expected)
        QVERIFY2(m_verbose.contains(s), qPrintable(s));
    // No item after the unknown ID is shown: the faulty frame's ID_msg 1 stays unread.
    const auto packets = tsharkFields({QStringLiteral("rcm.item.ID_msg"), QStringLiteral("rcm.item.eng_ID")});
    QCOMPARE(packets.size(), kPackets);
    QCOMPARE(packets[4].value(QStringLiteral("rcm.item.ID_msg")), QString());
    QCOMPARE(packets[4].value(QStringLiteral("rcm.item.eng_ID")), QStringLiteral("5"));
}

QTEST_GUILESS_MAIN(TestDissector)
#include "tst_dissector.moc"
