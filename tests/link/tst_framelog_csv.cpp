// A frame log as CSV: the columns, their order and names, the values as the
// text format prints them, RFC 4180 quoting, and the failures.

#include "codec/frame/Frame.h"
#include "codec/message/MessageDecoder.h"
#include "codec/message/MessageEncoder.h"
#include "codec/message/TextFormat.h"
#include "link/framelog/FrameLog.h"
#include "link/framelog/FrameLogCsv.h"
#include "link/framelog/FrameLogReader.h"

#include <QBuffer>
#include <QFile>
#include <QRandomGenerator>
#include <QTemporaryDir>
#include <QTest>
#include <QtEndian>

namespace {

const QString kVectors = QStringLiteral(RCM_VECTORS_DIR "/rcm/");
constexpr qint64 kT0 = 1795332720000001;  // 2026-11-22T07:32:00.000001Z

QByteArray readFile(const QString& path)
{
    QFile f(path);
    return f.open(QIODevice::ReadOnly) ? f.readAll() : QByteArray();
}

FrameRecord record(const QByteArray& bytes, qint64 utcMicros, FrameDirection direction = FrameDirection::Received,
                   FrameTransport transport = FrameTransport::Serial, FrameStatus status = FrameStatus::Decoded,
                   QList<int> symbols = {0, 0})
{
    FrameRecord r;
    r.bytes = bytes;
    r.utcMicros = utcMicros;
    r.direction = direction;
    r.transport = transport;
    r.status = status;
    r.correctedSymbols = std::move(symbols);
    return r;
}

QByteArray frameOf(const rcm::Message& m)
{
    rcm::Diagnostics errors;
    const auto f = rcm::encodeFrame(m, errors);
    if (!f) {
        qWarning() << "encode failed:" << QString::fromStdString(errors.front().toString());
        return {};
    }
    return QByteArray(reinterpret_cast<const char*>(f->data()), qsizetype(f->size()));
}

bool writeLog(const QString& path, const QList<FrameRecord>& records)
{
    FrameLog log;
    QString error;
    if (!log.open(path, &error)) {
        qWarning() << error;
        return false;
    }
    for (const FrameRecord& r : records)
        if (!log.append(r))
            return false;
    return true;
}

// A strict RFC 4180 reader: CRLF after every record, quotes only around a
// whole field, quotes inside doubled. Anything else fails the parse.
bool parseCsv(const QByteArray& csv, QList<QStringList>* rows)
{
    QStringList row;
    QByteArray field;
    int i = 0;
    const int n = int(csv.size());
    while (i < n) {
        field.clear();
        if (csv[i] == '"') {
            ++i;
            for (;;) {
                if (i >= n)
                    return false;
                if (csv[i] == '"') {
                    if (i + 1 < n && csv[i + 1] == '"') {
                        field += '"';
                        i += 2;
                        continue;
                    }
                    ++i;
                    break;
                }
                field += csv[i++];
            }
        } else {
            while (i < n && csv[i] != ',' && csv[i] != '\r' && csv[i] != '\n' && csv[i] != '"')
                field += csv[i++];
        }
        row.append(QString::fromUtf8(field));
        if (i < n && csv[i] == ',') {
            ++i;
            continue;
        }
        if (i + 1 < n && csv[i] == '\r' && csv[i + 1] == '\n') {
            i += 2;
            rows->append(row);
            row.clear();
            continue;
        }
        return false;
    }
    return row.isEmpty();
}

struct Table {
    QStringList header;
    QList<QStringList> rows;
    QString cell(int row, const QString& column) const
    {
        const int c = header.indexOf(column);
        return c < 0 ? QStringLiteral("<no column %1>").arg(column) : rows.value(row).value(c);
    }
};

}  // namespace

class TestFrameLogCsv : public QObject {
    Q_OBJECT

private slots:
    void samples();
    void valuesAreTheTextFormats();
    void quoting();
    void columnOrderIsCanonical();
    void repeatedKeyInOneFrame();
    void failures();
    void corruptLogExportsRecordsBeforeTheFault();

private:
    // Exports `records` and parses the result; false if either step fails.
    bool exportRecords(const QList<FrameRecord>& records, Table* table, QByteArray* raw = nullptr);

    QTemporaryDir m_dir;
    int m_files = 0;
};

bool TestFrameLogCsv::exportRecords(const QList<FrameRecord>& records, Table* table, QByteArray* raw)
{
    const QString path = m_dir.filePath(QStringLiteral("log%1.pcapng").arg(++m_files));
    if (!writeLog(path, records))
        return false;
    QBuffer out;
    out.open(QIODevice::WriteOnly);
    QString error;
    if (!exportFrameLogCsv(path, out, &error)) {
        qWarning() << "export failed:" << error;
        return false;
    }
    if (raw)
        *raw = out.data();
    QList<QStringList> rows;
    if (!parseCsv(out.data(), &rows) || rows.isEmpty()) {
        qWarning() << "not RFC 4180:" << out.data().left(400);
        return false;
    }
    table->header = rows.takeFirst();
    table->rows = rows;
    for (const QStringList& r : rows)
        if (r.size() != table->header.size())
            return false;
    return true;
}

void TestFrameLogCsv::samples()
{
    const QByteArray wellEquipped = readFile(kVectors + QStringLiteral("well-equipped.bin"));
    QByteArray garbage(600, 0);
    QRandomGenerator rng(7);
    for (char& c : garbage)
        c = char(rng.bounded(256));
    const QList<FrameRecord> records = {
        record(readFile(kVectors + QStringLiteral("seed-example.bin")), kT0),
        record(wellEquipped, kT0 + 1000000, FrameDirection::Sent, FrameTransport::Serial, FrameStatus::NotChecked, {}),
        record(readFile(kVectors + QStringLiteral("flight-plan.bin")).mid(int(rcm::kPreambleSize)), kT0 + 2000000,
               FrameDirection::Received, FrameTransport::Udp, FrameStatus::Corrected, {3, 0}),
        record(readFile(kVectors + QStringLiteral("well-equipped.errors.bin")), kT0 + 3000000, FrameDirection::Received,
               FrameTransport::Serial, FrameStatus::Corrected, {16, 16}),
        record(garbage, kT0 + 4000000, FrameDirection::Received, FrameTransport::Serial, FrameStatus::Uncorrectable,
               {-1, -1}),
        record("7 bytes", kT0 + 5000000, FrameDirection::Received, FrameTransport::Simulated, FrameStatus::Rejected,
               {}),
    };
    Table t;
    QByteArray raw;
    QVERIFY(exportRecords(records, &t, &raw));
    QCOMPARE(t.rows.size(), records.size());
    QVERIFY(raw.endsWith("\r\n"));
    QCOMPARE(raw.count('\n'), raw.count("\r\n"));

    QCOMPARE(t.header.mid(0, 8), (QStringList{"utc", "direction", "transport", "status", "corrected_block1",
                                              "corrected_block2", "reading", "HEADER.ID_msg"}));
    // header 7, engines 3 x 4, flaps 7, fuel dump 1, settings 2, radios 3 x 5,
    // sense 3, cameras NIK 1 (5), SNY 1 and SNY 2 (7 each), flight plan 3
    QCOMPARE(t.header.size(), 7 + 7 + 12 + 7 + 1 + 2 + 15 + 3 + 19 + 3);
    const QStringList order = {"HEADER.ID_GCS_backup",        "engine 1.eng_ID",
                               "engine 1.eng_status",         "engine 3.eng_carb_SET",
                               "flaps.FLAP_status",           "FCU_general.ENABLE_fuel_dump",
                               "SETTINGS.land_wheels",        "radio VHF1.system_ID",
                               "radio VHF3.Tx_OP_power",      "SENSE.SA_zoom_LHS_cam",
                               "camera NIK 1.cam_ID",         "camera SNY 1.cam_ID",
                               "camera SNY 2.ID_GCS_backup",  "FLIGHT_PLAN.flight_plan_ID",
                               "FLIGHT_PLAN.flight_plan_data"};
    for (int i = 1; i < order.size(); ++i) {
        QVERIFY2(t.header.indexOf(order[i - 1]) >= 0, qPrintable(order[i - 1]));
        QVERIFY2(t.header.indexOf(order[i - 1]) < t.header.indexOf(order[i]), qPrintable(order[i]));
    }
    QCOMPARE(t.header.last(), QStringLiteral("FLIGHT_PLAN.flight_plan_data"));

    // seed-example: received, logged clean
    QCOMPARE(t.rows[0].mid(0, 6),
             (QStringList{"2026-11-22T07:32:00.000001Z", "received", "serial", "decoded", "0", "0"}));
    QCOMPARE(t.cell(0, "HEADER.ID_msg"), QStringLiteral("133"));
    QCOMPARE(t.cell(0, "HEADER.ID_UA_source"), QStringLiteral("GB_133"));
    QCOMPARE(t.cell(0, "HEADER.time_UTC"), QStringLiteral("16:35:23"));
    QCOMPARE(t.cell(0, "HEADER.date_UTC"), QStringLiteral("071114"));
    QCOMPARE(t.cell(0, "SENSE.SA_zoom_FWD_cam"), QStringLiteral("105"));
    QCOMPARE(t.cell(0, "engine 1.eng_prop_pitch"), QString());
    QCOMPARE(t.cell(0, "FLIGHT_PLAN.flight_plan_ID"), QString());

    // well-equipped, our own send: no corrections logged, so the decode's
    QCOMPARE(t.rows[1].mid(0, 6),
             (QStringList{"2026-11-22T07:32:01.000001Z", "sent", "serial", "not-checked", "0", "0"}));
    QCOMPARE(t.cell(1, "HEADER.ID_msg"), QStringLiteral("4508515"));
    QCOMPARE(t.cell(1, "engine 2.eng_prop_pitch"), QStringLiteral("52"));
    QCOMPARE(t.cell(1, "engine 2.eng_status"), QStringLiteral("control=RC slave=NO_SLAVE"));
    QCOMPARE(t.cell(1, "flaps.F_aileron_RHS_set"), QStringLiteral("-19"));
    QCOMPARE(t.cell(1, "SETTINGS.land_wheels"), QStringLiteral("LHS=OUT RHS=OUT NOSE=OUT TAIL=OUT"));
    QCOMPARE(t.cell(1, "radio VHF1.Rx_freq"), QStringLiteral("127712"));
    QCOMPARE(t.cell(1, "radio VHF3.receiver_control"), QStringLiteral("receiver=ON transmitter=OFF"));
    QCOMPARE(t.cell(1, "camera SNY 1.cam_mag_compass"), QStringLiteral("264.95"));
    QCOMPARE(t.cell(1, "camera SNY 2.cam_elev"), QStringLiteral("-54.64"));
    QCOMPARE(t.cell(1, "camera SNY 2.cam_ID"), QStringLiteral("SNY 2"));
    QCOMPARE(t.cell(1, "camera NIK 1.cam_ID"), QString());

    // flight-plan as a datagram
    QCOMPARE(t.rows[2].mid(0, 6),
             (QStringList{"2026-11-22T07:32:02.000001Z", "received", "udp", "corrected", "3", "0"}));
    QCOMPARE(t.cell(2, "camera NIK 1.cam_ID"), QStringLiteral("NIK 1"));
    QCOMPARE(t.cell(2, "FLIGHT_PLAN.flight_plan_ID"), QStringLiteral("0xDEADBEEF"));
    QCOMPARE(t.cell(2, "FLIGHT_PLAN.flight_plan_section_ID"), QStringLiteral("3"));
    QCOMPARE(t.cell(2, "FLIGHT_PLAN.flight_plan_data"),
             QStringLiteral("000102030405060708090A0B0C0D0E0F101112131415161718191A1B1C1D1E1F2021222324252627"));

    // 16 errors in each codeword: corrected to the very values of the clean frame
    QCOMPARE(t.rows[3].mid(3, 3), (QStringList{"corrected", "16", "16"}));
    QCOMPARE(t.rows[3].mid(7), t.rows[1].mid(7));

    // What the receive path makes of each on its own.
    QCOMPARE(t.cell(0, "reading"), QStringLiteral("read"));
    QCOMPARE(t.cell(1, "reading"), QStringLiteral("read"));
    QCOMPARE(t.cell(2, "reading"), QStringLiteral("read"));
    QCOMPARE(t.cell(3, "reading"), QStringLiteral("read"));
    QCOMPARE(t.cell(4, "reading"), QStringLiteral("refused as uncorrectable"));
    QCOMPARE(t.cell(5, "reading"), QStringLiteral("not a frame"));

    // beyond correction, and not a frame at all: no values
    QCOMPARE(t.rows[4].mid(3, 3), (QStringList{"uncorrectable", "-1", "-1"}));
    QCOMPARE(t.rows[4].mid(7), QStringList(t.header.size() - 7, QString()));
    QCOMPARE(t.rows[5].mid(0, 6),
             (QStringList{"2026-11-22T07:32:05.000001Z", "received", "simulated", "rejected", "", ""}));
    QCOMPARE(t.rows[5].mid(7), QStringList(t.header.size() - 7, QString()));
}

// Every item cell is the value half of the item's line in formatMessage.
void TestFrameLogCsv::valuesAreTheTextFormats()
{
    const QByteArray frame = readFile(kVectors + QStringLiteral("well-equipped.bin"));
    Table t;
    QVERIFY(exportRecords({record(frame, kT0)}, &t));
    const auto decoded = rcm::decodeFrame(
        std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(frame.constData()), frame.size()));
    const QStringList lines = QString::fromStdString(rcm::formatMessage(decoded.message)).split(QLatin1Char('\n'));
    QStringList values;
    for (const QString& line : lines)
        if (!line.startsWith(QLatin1String("BEGIN ")) && line != QLatin1String("END") && !line.isEmpty())
            values.append(line.section(QLatin1Char(' '), 1));
    QCOMPARE(t.rows.first().mid(7), values);
}

void TestFrameLogCsv::quoting()
{
    rcm::Message m;
    m.header.set(rcm::ItemId::ID_msg, 1);
    m.addRadio("A,\"B");
    m.addRadio("C D");
    Table t;
    QByteArray raw;
    QVERIFY(exportRecords({record(frameOf(m), kT0)}, &t, &raw));
    QVERIFY(t.header.contains(QStringLiteral("radio A,\"B.system_ID")));
    QCOMPARE(t.cell(0, QStringLiteral("radio A,\"B.system_ID")), QStringLiteral("\"A,\\\"B\""));
    QCOMPARE(t.cell(0, QStringLiteral("radio C D.system_ID")), QStringLiteral("\"C D\""));
    QVERIFY(raw.contains("\"radio A,\"\"B.system_ID\""));
    QVERIFY(raw.contains(",\"\"\"A,\\\"\"B\"\"\""));
    QVERIFY(raw.contains(",radio C D.system_ID"));  // a space alone needs no quotes
}

void TestFrameLogCsv::columnOrderIsCanonical()
{
    rcm::Message a;
    a.addEngine(10);
    a.addEngine(2).set(rcm::ItemId::eng_prop_pitch, 9);
    rcm::Message b;
    b.header.set(rcm::ItemId::ID_msg, 2);
    b.addRadio("B");
    b.addRadio("A");
    b.addEngine(1);
    rcm::Message c;
    c.addCamera("NIK", 2);
    c.addCamera("NIK", 1);
    c.addCamera("ABC", 9);
    const QStringList expected = {"HEADER.ID_msg",           "engine 1.eng_ID",     "engine 2.eng_ID",
                                  "engine 2.eng_prop_pitch", "engine 10.eng_ID",    "radio A.system_ID",
                                  "radio B.system_ID",       "camera ABC 9.cam_ID", "camera NIK 1.cam_ID",
                                  "camera NIK 2.cam_ID"};
    Table forward, backward;
    QVERIFY(
        exportRecords({record(frameOf(a), kT0), record(frameOf(b), kT0 + 1), record(frameOf(c), kT0 + 2)}, &forward));
    QVERIFY(
        exportRecords({record(frameOf(c), kT0), record(frameOf(b), kT0 + 1), record(frameOf(a), kT0 + 2)}, &backward));
    QCOMPARE(forward.header.mid(7), expected);
    QCOMPARE(backward.header, forward.header);
    QCOMPARE(forward.cell(0, "engine 2.eng_prop_pitch"), QStringLiteral("9"));
    QCOMPARE(backward.cell(2, "engine 2.eng_prop_pitch"), QStringLiteral("9"));
}

void TestFrameLogCsv::repeatedKeyInOneFrame()
{
    // Only a decoder meets this: two engines 1 in one block.
    rcm::Block b1;
    b1.fill(rcm::kPad55);
    const std::uint8_t items[] = {0x31, 1, 0x32, 5, 0x31, 1, 0x32, 6};
    std::copy(std::begin(items), std::end(items), b1.begin() + 100);
    rcm::Block b2;
    b2.fill(rcm::kPad55);
    b2[0] = 0;
    std::fill(b2.begin() + 1, b2.begin() + 7, 0);
    b2[rcm::kBlockSize - 1] = 0;
    const rcm::FrameBytes f = rcm::makeFrame(b1, b2);
    Table t;
    QVERIFY(exportRecords({record(QByteArray(reinterpret_cast<const char*>(f.data()), qsizetype(f.size())), kT0)}, &t));
    QCOMPARE(t.header.mid(7), (QStringList{"engine 1.eng_ID", "engine 1.eng_prop_pitch", "engine 1#2.eng_ID",
                                           "engine 1#2.eng_prop_pitch"}));
    QCOMPARE(t.rows.first().mid(7), (QStringList{"1", "5", "1", "6"}));
}

void TestFrameLogCsv::failures()
{
    QBuffer out;
    out.open(QIODevice::WriteOnly);
    QString error;
    QVERIFY(!exportFrameLogCsv(m_dir.filePath(QStringLiteral("absent.pcapng")), out, &error));
    QVERIFY(!error.isEmpty());
    QVERIFY(out.data().isEmpty());

    const QString path = m_dir.filePath(QStringLiteral("one.pcapng"));
    QVERIFY(writeLog(path, {record(readFile(kVectors + QStringLiteral("seed-example.bin")), kT0)}));
    QBuffer readOnly;
    readOnly.open(QIODevice::ReadOnly);
    error.clear();
    QVERIFY(!exportFrameLogCsv(path, readOnly, &error));
    QVERIFY(!error.isEmpty());

    // An empty log is a header and nothing else.
    const QString empty = m_dir.filePath(QStringLiteral("empty.pcapng"));
    QVERIFY(writeLog(empty, {}));
    QBuffer csv;
    csv.open(QIODevice::WriteOnly);
    QVERIFY(exportFrameLogCsv(empty, csv, &error));
    QCOMPARE(csv.data(), QByteArray("utc,direction,transport,status,corrected_block1,corrected_block2,reading\r\n"));
}

void TestFrameLogCsv::corruptLogExportsRecordsBeforeTheFault()
{
    const QByteArray frame = readFile(kVectors + QStringLiteral("seed-example.bin"));
    const QString path = m_dir.filePath(QStringLiteral("corrupt.pcapng"));
    QVERIFY(writeLog(path, {record(frame, kT0), record(frame, kT0 + 1), record(frame, kT0 + 2)}));
    qint64 second = 0;
    {
        FrameLogReader reader;
        QVERIFY(reader.open(path));
        second = reader.index()[1].offset;
    }
    QFile f(path);
    QVERIFY(f.open(QIODevice::ReadWrite));
    QVERIFY(f.seek(second + 4));  // the block's total length
    uchar length[4];
    qToLittleEndian<quint32>(5, length);
    QCOMPARE(f.write(reinterpret_cast<const char*>(length), 4), 4);
    f.close();

    QBuffer out;
    out.open(QIODevice::WriteOnly);
    QString error;
    QVERIFY(!exportFrameLogCsv(path, out, &error));
    QVERIFY2(error.contains(QLatin1String("after frame 1")), qPrintable(error));
    QList<QStringList> rows;
    QVERIFY(parseCsv(out.data(), &rows));
    QCOMPARE(rows.size(), 2);
    QCOMPARE(rows[1].value(7), QStringLiteral("133"));
}

QTEST_GUILESS_MAIN(TestFrameLogCsv)
#include "tst_framelog_csv.moc"
