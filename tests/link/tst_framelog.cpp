// The pcapng frame log: round trips, exact bytes, torn tails, corruption,
// seeking, write failures, and what Wireshark's tshark makes of the file.

#include "link/framelog/FrameLog.h"
#include "link/framelog/FrameLogReader.h"

#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QProcess>
#include <QRandomGenerator>
#include <QScopeGuard>
#include <QStandardPaths>
#include <QTemporaryDir>
#include <QTest>
#include <QtEndian>

#ifdef Q_OS_UNIX
#include <csignal>
#include <sys/resource.h>
#endif

namespace {

FrameRecord makeRecord(quint32 seed, int length, qint64 utcMicros, FrameDirection direction, FrameTransport transport,
                       FrameStatus status, QList<int> correctedSymbols = {})
{
    FrameRecord r;
    r.bytes.resize(length);
    QRandomGenerator rng(seed);
    for (char& c : r.bytes)
        c = char(rng.bounded(256));
    r.utcMicros = utcMicros;
    r.direction = direction;
    r.transport = transport;
    r.status = status;
    r.correctedSymbols = std::move(correctedSymbols);
    return r;
}

// A mix of everything a session produces, in time order.
QVector<FrameRecord> sessionRecords(int n, qint64 t0 = 1795332720000000)
{
    QVector<FrameRecord> records;
    for (int i = 0; i < n; ++i) {
        const auto transport = FrameTransport(i % 4);
        const auto direction = (i / 4) % 2 ? FrameDirection::Sent : FrameDirection::Received;
        const auto status = FrameStatus(i % 5);
        const int length = transport == FrameTransport::Udp ? 510 : 600;
        QList<int> symbols;
        if (status == FrameStatus::Corrected)
            symbols = {i % 17, (i * 7) % 17};
        if (status == FrameStatus::Decoded)
            symbols = {0, 0};
        records.append(
            makeRecord(quint32(i), length, t0 + qint64(i) * 1000000 + i % 1000, direction, transport, status, symbols));
    }
    return records;
}

bool writeLog(const QString& path, const QVector<FrameRecord>& records)
{
    FrameLog log;
    QString error;
    if (!log.open(path, &error)) {
        qWarning() << error;
        return false;
    }
    for (const FrameRecord& r : records) {
        if (!log.append(r))
            return false;
    }
    return log.recordsWritten() == records.size();
}

QByteArray fileBytes(const QString& path)
{
    QFile f(path);
    return f.open(QIODevice::ReadOnly) ? f.readAll() : QByteArray();
}

bool putFile(const QString& path, const QByteArray& bytes)
{
    QFile f(path);
    return f.open(QIODevice::WriteOnly | QIODevice::Truncate) && f.write(bytes) == bytes.size();
}

// Builds pcapng blocks by hand, in either byte order, for files the writer
// would never produce.
struct Blocks {
    bool bigEndian = false;
    QByteArray out;

    template <typename T>
    void put(T v)
    {
        char c[sizeof(T)];
        if (bigEndian) {
            qToBigEndian(v, c);
        } else {
            qToLittleEndian(v, c);
        }
        out.append(c, sizeof(T));
    }
    void pad()
    {
        while (out.size() % 4)
            out.append('\0');
    }
    void option(quint16 code, const QByteArray& value)
    {
        put<quint16>(code);
        put<quint16>(quint16(value.size()));
        out.append(value);
        pad();
    }
    void option32(quint16 code, quint32 value)
    {
        put<quint16>(code);
        put<quint16>(4);
        put<quint32>(value);
    }
    void endOfOptions() { put<quint32>(0); }
    qsizetype begin(quint32 type)
    {
        const qsizetype start = out.size();
        put<quint32>(type);
        put<quint32>(0);
        return start;
    }
    void end(qsizetype start)
    {
        const quint32 total = quint32(out.size() - start + 4);
        put<quint32>(total);
        if (bigEndian) {
            qToBigEndian(total, out.data() + start + 4);
        } else {
            qToLittleEndian(total, out.data() + start + 4);
        }
    }
    void sectionHeader()
    {
        const qsizetype s = begin(pcapng::kSectionHeader);
        put<quint32>(pcapng::kByteOrderMagic);
        put<quint16>(1);
        put<quint16>(0);
        put<quint64>(~quint64(0));
        endOfOptions();
        end(s);
    }
    void interface(quint16 linkType, const QByteArray& name)
    {
        const qsizetype s = begin(pcapng::kInterfaceDescription);
        put<quint16>(linkType);
        put<quint16>(0);
        put<quint32>(0);
        option(pcapng::kOptIfName, name);
        option(pcapng::kOptIfTsResol, QByteArray(1, '\x06'));
        endOfOptions();
        end(s);
    }
    void packet(quint32 interfaceId, const FrameRecord& r)
    {
        const qsizetype s = begin(pcapng::kEnhancedPacket);
        put<quint32>(interfaceId);
        put<quint32>(quint32(quint64(r.utcMicros) >> 32));
        put<quint32>(quint32(r.utcMicros));
        put<quint32>(quint32(r.bytes.size()));
        put<quint32>(quint32(r.bytes.size()));
        out.append(r.bytes);
        pad();
        option32(pcapng::kOptEpbFlags, r.direction == FrameDirection::Sent ? 2 : 1);
        option(pcapng::kOptComment, frameStatusComment(r.status, r.correctedSymbols));
        endOfOptions();
        end(s);
    }
    void opaque(quint32 type, int bodyBytes)
    {
        const qsizetype s = begin(type);
        out.append(QByteArray(bodyBytes, '\x5a'));
        end(s);
    }
};

QByteArray hex(const char* digits)
{
    return QByteArray::fromHex(digits);  // skips the spaces that group the fields
}

void patch32(QByteArray& bytes, qint64 offset, quint32 value)
{
    qToLittleEndian(value, bytes.data() + offset);
}

}  // namespace

class TestFrameLog : public QObject {
    Q_OBJECT

private slots:
    void sessionFileName();
    void statusComment_data();
    void statusComment();
    void roundTrip();
    void exactHeaderBytes();
    void openCreatesDirectoriesAndKeepsExistingFiles();
    void refusesOversizeFrame();
    void syncEveryRecord();
    void truncatedAtEveryOffsetOfLastRecord_data();
    void truncatedAtEveryOffsetOfLastRecord();
    void truncatedInsideSectionHeader();
    void corruptBlockInMiddle_data();
    void corruptBlockInMiddle();
    void notPcapng();
    void seekByTime();
    void seekWhenClockStepsBack();
    void bigEndianSectionThenLittleEndianSection();
    void unknownBlocksAndForeignInterfacesSkipped();
    void writeFailureReportedOnce();
    void tsharkReadsLog();

private:
    QTemporaryDir m_dir;
    QString path(const QString& name) const { return m_dir.filePath(name); }
};

void TestFrameLog::sessionFileName()
{
    const QDateTime utc(QDate(2026, 11, 22), QTime(7, 32, 0), Qt::UTC);
    QCOMPARE(FrameLog::sessionFileName(utc), QStringLiteral("rcm-2026-11-22T07-32-00Z.pcapng"));
    const QDateTime plus2 = utc.toOffsetFromUtc(2 * 3600);
    QCOMPARE(FrameLog::sessionFileName(plus2), QStringLiteral("rcm-2026-11-22T07-32-00Z.pcapng"));
    QVERIFY(FrameLog::defaultDirectory().endsWith(QStringLiteral("/framelogs")));
}

void TestFrameLog::statusComment_data()
{
    QTest::addColumn<int>("status");
    QTest::addColumn<QList<int>>("symbols");
    QTest::addColumn<QByteArray>("text");
    QTest::addColumn<bool>("enciphered");
    QTest::newRow("decoded") << int(FrameStatus::Decoded) << QList<int>{0, 0} << QByteArray("rcm decoded symbols=0/0")
                             << false;
    QTest::newRow("keyed") << int(FrameStatus::Corrected) << QList<int>{2, 0}
                           << QByteArray("rcm corrected symbols=2/0 enciphered") << true;
    QTest::newRow("keyed, sent") << int(FrameStatus::NotChecked) << QList<int>{}
                                 << QByteArray("rcm not-checked enciphered") << true;
    QTest::newRow("corrected") << int(FrameStatus::Corrected) << QList<int>{3, 0}
                               << QByteArray("rcm corrected symbols=3/0") << false;
    QTest::newRow("uncorrectable") << int(FrameStatus::Uncorrectable) << QList<int>{16, -1}
                                   << QByteArray("rcm uncorrectable symbols=16/-1") << false;
    QTest::newRow("rejected") << int(FrameStatus::Rejected) << QList<int>{} << QByteArray("rcm rejected") << false;
    QTest::newRow("not-checked") << int(FrameStatus::NotChecked) << QList<int>{} << QByteArray("rcm not-checked")
                                 << false;
    QTest::newRow("one codeword") << int(FrameStatus::Corrected) << QList<int>{7}
                                  << QByteArray("rcm corrected symbols=7") << false;
}

void TestFrameLog::statusComment()
{
    QFETCH(int, status);
    QFETCH(QList<int>, symbols);
    QFETCH(QByteArray, text);
    QFETCH(bool, enciphered);
    QCOMPARE(frameStatusComment(FrameStatus(status), symbols, enciphered), text);
    FrameStatus parsed = FrameStatus::Decoded;
    QList<int> parsedSymbols{99};
    bool parsedEnciphered = !enciphered;
    QVERIFY(parseFrameStatusComment(text, &parsed, &parsedSymbols, &parsedEnciphered));
    QCOMPARE(int(parsed), status);
    QCOMPARE(parsedSymbols, symbols);
    QCOMPARE(parsedEnciphered, enciphered);

    for (const char* bad :
         {"decoded", "rcm", "rcm fine", "rcm decoded extra", "rcm decoded symbols=", "rcm decoded symbols=1/",
          "rcm decoded symbols=x", "rcm decoded enciphered extra", "rcm decoded symbols=1/2 ciphered"}) {
        QVERIFY2(!parseFrameStatusComment(QByteArrayView(bad), nullptr, nullptr), bad);
    }
}

void TestFrameLog::roundTrip()
{
    QVector<FrameRecord> records = sessionRecords(40);
    // Lengths and times at the edges of what the format carries.
    records.prepend(makeRecord(1001, 0, -5, FrameDirection::Sent, FrameTransport::Simulated, FrameStatus::NotChecked));
    records.append(makeRecord(1002, 1, records.last().utcMicros + 1, FrameDirection::Received, FrameTransport::Udp,
                              FrameStatus::Rejected));
    records.append(makeRecord(1003, 3, records.last().utcMicros + 1, FrameDirection::Sent, FrameTransport::Replay,
                              FrameStatus::Corrected, {1, 2}));
    records.append(makeRecord(1004, FrameLog::kMaxFrameBytes, records.last().utcMicros + 1, FrameDirection::Received,
                              FrameTransport::Serial, FrameStatus::Uncorrectable, {17, 17}));
    const QString file = path(QStringLiteral("roundtrip.pcapng"));
    QVERIFY(writeLog(file, records));

    FrameLogReader reader;
    QVERIFY2(reader.open(file), qPrintable(reader.errorString()));
    QVERIFY(!reader.truncatedTail());
    QCOMPARE(reader.foreignPackets(), 0);
    QCOMPARE(reader.count(), records.size());
    for (int i = 0; i < records.size(); ++i) {
        const FrameRecord got = reader.recordAt(i);
        const FrameRecord& want = records[i];
        QCOMPARE(got.bytes, want.bytes);
        QCOMPARE(got.utcMicros, want.utcMicros);
        QCOMPARE(got.direction, want.direction);
        QCOMPARE(got.transport, want.transport);
        QCOMPARE(got.status, want.status);
        QCOMPARE(got.correctedSymbols, want.correctedSymbols);
        QVERIFY(got == want);

        const FrameIndexEntry& e = reader.index()[i];
        QCOMPARE(e.utcMicros, want.utcMicros);
        QCOMPARE(qsizetype(e.length), want.bytes.size());
        QCOMPARE(e.direction, want.direction);
        QCOMPARE(e.transport, want.transport);
        QCOMPARE(e.status, want.status);
        if (i > 0)
            QVERIFY(e.offset > reader.index()[i - 1].offset);
    }
    QCOMPARE(reader.readAll(), records);
    QCOMPARE(reader.recordAt(-1), FrameRecord());
    QCOMPARE(reader.recordAt(reader.count()), FrameRecord());
}

void TestFrameLog::exactHeaderBytes()
{
    const QString file = path(QStringLiteral("exact.pcapng"));
    FrameRecord r;
    r.bytes = QByteArray::fromHex("010203");
    r.utcMicros = 1795332720123456;  // 2026-11-22T07:32:00.123456Z = 0x000660d8'79095e40
    r.direction = FrameDirection::Sent;
    r.transport = FrameTransport::Serial;
    r.status = FrameStatus::Corrected;
    r.correctedSymbols = {3, 0};
    QVERIFY(writeLog(file, {r}));

    // clang-format off
    const QByteArray shb =
        hex("0a0d0d0a 2c000000")            // type, total length 44
        + hex("4d3c2b1a")                   // byte-order magic, little-endian
        + hex("0100 0000")                  // version 1.0
        + hex("ffffffff ffffffff")          // section length unknown
        + hex("0400 0700") + "rcm-gcs" + hex("00")  // shb_userappl, padded
        + hex("0000 0000")                  // opt_endofopt
        + hex("2c000000");
    const QByteArray idb =
        hex("01000000 64000000")            // type 1, total length 100
        + hex("9300 0000")                  // LINKTYPE_USER0 (147), reserved
        + hex("ffff0000")                   // snaplen 65535
        + hex("0200 0600") + "serial" + hex("0000")  // if_name
        + hex("0300 3200") + "Remote Control Message frames over the serial link" + hex("0000")
        + hex("0900 0100 06000000")         // if_tsresol = 6: microseconds
        + hex("0000 0000")
        + hex("64000000");
    const QByteArray epb =
        hex("06000000 50000000")            // type 6, total length 80
        + hex("00000000")                   // interface 0: serial
        + hex("d8600600 405e0979")          // timestamp high, low
        + hex("03000000 03000000")          // captured, original length
        + hex("01020300")                   // frame, padded
        + hex("0200 0400 02000000")         // epb_flags: outbound
        + hex("0100 1900") + "rcm corrected symbols=3/0" + hex("000000")  // opt_comment
        + hex("0000 0000")
        + hex("50000000");
    // clang-format on
    const QByteArray got = fileBytes(file);
    QCOMPARE(got.size(), shb.size() + idb.size() + epb.size());
    QCOMPARE(got.left(shb.size()).toHex(' '), shb.toHex(' '));
    QCOMPARE(got.mid(shb.size(), idb.size()).toHex(' '), idb.toHex(' '));
    QCOMPARE(got.mid(shb.size() + idb.size()).toHex(' '), epb.toHex(' '));

    FrameLogReader reader;
    QVERIFY(reader.open(file));
    QCOMPARE(reader.count(), 1);
    QCOMPARE(reader.index()[0].offset, qint64(shb.size() + idb.size()));
    QCOMPARE(reader.recordAt(0), r);
}

void TestFrameLog::openCreatesDirectoriesAndKeepsExistingFiles()
{
    const QString file = path(QStringLiteral("a/b/c/session.pcapng"));
    FrameLog log;
    QString error;
    QVERIFY2(log.open(file, &error), qPrintable(error));
    QVERIFY(log.isOpen());
    QVERIFY(log.append(sessionRecords(1).first()));
    log.close();
    const QByteArray before = fileBytes(file);

    FrameLog second;
    QVERIFY(!second.open(file, &error));
    QVERIFY(error.contains(file));
    QCOMPARE(second.errorString(), error);
    QCOMPARE(fileBytes(file), before);
    QVERIFY(!second.append(sessionRecords(1).first()));
}

void TestFrameLog::refusesOversizeFrame()
{
    const QString file = path(QStringLiteral("oversize.pcapng"));
    FrameLog log;
    QVERIFY(log.open(file));
    int reports = 0;
    log.setErrorHandler([&](const QString&) { ++reports; });
    FrameRecord big = sessionRecords(1).first();
    big.bytes.resize(FrameLog::kMaxFrameBytes + 1);
    QVERIFY(!log.append(big));
    QVERIFY(log.errorString().contains(QString::number(FrameLog::kMaxFrameBytes + 1)));
    // Only that frame is refused: the file is still sound.
    QVERIFY(!log.hasFailed());
    QCOMPARE(reports, 0);
    QVERIFY(log.append(sessionRecords(1).first()));
    QCOMPARE(log.recordsWritten(), 1);
}

void TestFrameLog::syncEveryRecord()
{
    const QString file = path(QStringLiteral("synced.pcapng"));
    const QVector<FrameRecord> records = sessionRecords(5);
    FrameLog log;
    QVERIFY(log.open(file));
    log.setSyncEveryRecord(true);
    for (const FrameRecord& r : records)
        QVERIFY2(log.append(r), qPrintable(log.errorString()));
    log.close();
    FrameLogReader reader;
    QVERIFY(reader.open(file));
    QCOMPARE(reader.readAll(), records);
}

void TestFrameLog::truncatedAtEveryOffsetOfLastRecord_data()
{
    QTest::addColumn<bool>("newTransport");
    QTest::newRow("known transport") << false;
    QTest::newRow("first frame of a transport") << true;
}

void TestFrameLog::truncatedAtEveryOffsetOfLastRecord()
{
    QFETCH(bool, newTransport);
    const QString file = path(QStringLiteral("torn-source.pcapng"));
    QFile::remove(file);
    QVector<FrameRecord> early;
    for (const FrameRecord& r : sessionRecords(8)) {
        if (r.transport != FrameTransport::Simulated)
            early.append(r);
    }
    // The first frame of a transport carries its interface block in the same
    // write, so the cuts go through that block too.
    const FrameRecord last =
        makeRecord(77, 600, early.last().utcMicros + 1, FrameDirection::Sent,
                   newTransport ? FrameTransport::Simulated : FrameTransport::Udp, FrameStatus::NotChecked);
    qint64 lastStart = 0;
    {
        FrameLog log;
        QVERIFY(log.open(file));
        for (const FrameRecord& r : early)
            QVERIFY(log.append(r));
        lastStart = QFileInfo(file).size();
        QVERIFY(log.append(last));
    }
    const QByteArray full = fileBytes(file);
    QVERIFY(full.size() > lastStart + 600);
    const qint64 packetStart =
        lastStart + (newTransport ? qFromLittleEndian<quint32>(full.constData() + lastStart + 4) : 0);
    QCOMPARE(qFromLittleEndian<quint32>(full.constData() + packetStart), pcapng::kEnhancedPacket);

    const QString cutFile = path(QStringLiteral("torn.pcapng"));
    for (qint64 cut = lastStart; cut <= full.size(); ++cut) {
        QVERIFY(putFile(cutFile, full.left(cut)));
        FrameLogReader reader;
        const QByteArray where = "cut at " + QByteArray::number(cut);
        QVERIFY2(reader.open(cutFile), qPrintable(reader.errorString()));
        QVERIFY2(reader.errorString().isEmpty(), where);
        // A cut exactly after the interface block leaves a sound file that
        // merely describes an interface no packet uses: nothing is torn.
        const bool torn = cut > lastStart && cut < full.size() && cut != packetStart;
        QVERIFY2(reader.truncatedTail() == torn, where);
        QCOMPARE(reader.count(), int(early.size()) + (cut == full.size() ? 1 : 0));
        for (int i = 0; i < early.size(); ++i)
            QVERIFY2(reader.recordAt(i) == early[i], where);
    }
}

void TestFrameLog::truncatedInsideSectionHeader()
{
    const QString file = path(QStringLiteral("torn-header-source.pcapng"));
    {
        FrameLog log;
        QVERIFY(log.open(file));
    }
    const QByteArray header = fileBytes(file);
    QCOMPARE(header.size(), 44);
    const QString cutFile = path(QStringLiteral("torn-header.pcapng"));
    for (int cut = 0; cut <= header.size(); ++cut) {
        QVERIFY(putFile(cutFile, header.left(cut)));
        FrameLogReader reader;
        QVERIFY2(reader.open(cutFile), qPrintable(reader.errorString()));
        QCOMPARE(reader.count(), 0);
        QCOMPARE(reader.truncatedTail(), cut < header.size());
    }
}

void TestFrameLog::corruptBlockInMiddle_data()
{
    QTest::addColumn<bool>("atEnd");
    QTest::addColumn<qint64>("delta");
    QTest::addColumn<quint32>("value");
    QTest::addColumn<QString>("complaint");
    QTest::newRow("4 bytes longer") << false << qint64(4) << 0u << "at its end";
    QTest::newRow("4 bytes shorter") << false << qint64(-4) << 0u << "at its end";
    QTest::newRow("not a multiple of 4") << false << qint64(1) << 0u << "invalid total length";
    QTest::newRow("shorter than a block") << false << qint64(0) << 8u << "invalid total length 8";
    QTest::newRow("far past the end") << false << qint64(0) << 0x40000000u << "bytes are left";
    QTest::newRow("trailing length") << true << qint64(4) << 0u << "at its end";
}

void TestFrameLog::corruptBlockInMiddle()
{
    QFETCH(bool, atEnd);
    QFETCH(qint64, delta);
    QFETCH(quint32, value);
    QFETCH(QString, complaint);

    const QString file = path(QStringLiteral("corrupt-source.pcapng"));
    QFile::remove(file);
    const QVector<FrameRecord> records = sessionRecords(10);
    QVERIFY(writeLog(file, records));
    FrameLogReader clean;
    QVERIFY(clean.open(file));
    const qint64 victim = clean.index()[5].offset;
    clean.close();

    QByteArray bytes = fileBytes(file);
    const quint32 length = qFromLittleEndian<quint32>(bytes.constData() + victim + 4);
    const qint64 field = atEnd ? victim + length - 4 : victim + 4;
    patch32(bytes, field, value ? value : quint32(qint64(length) + delta));
    const QString broken = path(QStringLiteral("corrupt.pcapng"));
    QVERIFY(putFile(broken, bytes));

    FrameLogReader reader;
    QVERIFY(!reader.open(broken));
    const QString error = reader.errorString();
    QVERIFY2(error.contains(QStringLiteral("byte offset %1").arg(victim)), qPrintable(error));
    QVERIFY2(error.contains(complaint), qPrintable(error));
    QVERIFY(!reader.truncatedTail());
    // Everything before the damage stays readable.
    QCOMPARE(reader.count(), 5);
    for (int i = 0; i < 5; ++i)
        QCOMPARE(reader.recordAt(i), records[i]);
}

void TestFrameLog::notPcapng()
{
    const QString file = path(QStringLiteral("not.pcapng"));
    QVERIFY(putFile(file, QByteArray::fromHex("d4c3b2a102000400") + QByteArray(100, '\0')));
    FrameLogReader reader;
    QVERIFY(!reader.open(file));
    QVERIFY2(reader.errorString().contains(QStringLiteral("not a pcapng file")), qPrintable(reader.errorString()));
    QVERIFY2(reader.errorString().contains(QStringLiteral("byte offset 0")), qPrintable(reader.errorString()));

    QVERIFY(!reader.open(path(QStringLiteral("missing.pcapng"))));
    QVERIFY(reader.errorString().contains(QStringLiteral("missing.pcapng")));
}

void TestFrameLog::seekByTime()
{
    const qint64 t0 = 1795332720000000;
    QVector<FrameRecord> records;
    for (int i = 0; i < 1000; ++i) {
        records.append(makeRecord(quint32(i), 8, t0 + qint64(i) * 1000000,
                                  i % 2 ? FrameDirection::Sent : FrameDirection::Received, FrameTransport::Serial,
                                  FrameStatus::Decoded));
    }
    const QString file = path(QStringLiteral("seek.pcapng"));
    QVERIFY(writeLog(file, records));
    FrameLogReader reader;
    QVERIFY(reader.open(file));
    QCOMPARE(reader.count(), 1000);

    QCOMPARE(reader.indexAtOrAfter(t0 - 1), 0);
    QCOMPARE(reader.indexAtOrAfter(t0), 0);
    QCOMPARE(reader.indexAtOrAfter(t0 + 1), 1);
    QCOMPARE(reader.indexAtOrAfter(t0 + 500 * 1000000), 500);
    QCOMPARE(reader.indexAtOrAfter(t0 + 500 * 1000000 + 500000), 501);
    QCOMPARE(reader.indexAtOrAfter(t0 + 999 * 1000000), 999);
    QCOMPARE(reader.indexAtOrAfter(t0 + 999 * 1000000 + 1), 1000);
    for (int i : {0, 1, 321, 998, 999}) {
        const int at = reader.indexAtOrAfter(t0 + qint64(i) * 1000000);
        QCOMPARE(reader.recordAt(at), records[i]);
        QCOMPARE(reader.index()[at].offset, reader.index()[i].offset);
    }
}

void TestFrameLog::seekWhenClockStepsBack()
{
    const QVector<qint64> times{10, 20, 30, 15, 40, 40, 50};
    QVector<FrameRecord> records;
    for (qint64 t : times) {
        records.append(
            makeRecord(quint32(t), 4, t, FrameDirection::Received, FrameTransport::Udp, FrameStatus::Decoded));
    }
    const QString file = path(QStringLiteral("stepback.pcapng"));
    QVERIFY(writeLog(file, records));
    FrameLogReader reader;
    QVERIFY(reader.open(file));
    QCOMPARE(reader.indexAtOrAfter(15), 1);  // the log first reached 15 at 20
    QCOMPARE(reader.indexAtOrAfter(25), 2);
    QCOMPARE(reader.indexAtOrAfter(31), 4);
    QCOMPARE(reader.indexAtOrAfter(40), 4);
    QCOMPARE(reader.indexAtOrAfter(41), 6);
    QCOMPARE(reader.indexAtOrAfter(51), 7);
}

void TestFrameLog::bigEndianSectionThenLittleEndianSection()
{
    const FrameRecord a = makeRecord(1, 510, 1795332720000001, FrameDirection::Received, FrameTransport::Udp,
                                     FrameStatus::Decoded, {0, 0});
    const FrameRecord b =
        makeRecord(2, 510, 1795332721000001, FrameDirection::Sent, FrameTransport::Udp, FrameStatus::Rejected);
    Blocks be;
    be.bigEndian = true;
    be.sectionHeader();
    be.interface(pcapng::kLinkTypeUser0, "udp");
    be.packet(0, a);
    be.packet(0, b);
    QCOMPARE(be.out.mid(8, 4), QByteArray::fromHex("1a2b3c4d"));

    // A second section, as `cat` of two logs makes: interface ids restart.
    const QString little = path(QStringLiteral("little.pcapng"));
    const QVector<FrameRecord> tail = sessionRecords(6, 1795332722000000);
    QVERIFY(writeLog(little, tail));
    const QString file = path(QStringLiteral("big-endian.pcapng"));
    QVERIFY(putFile(file, be.out + fileBytes(little)));

    FrameLogReader reader;
    QVERIFY2(reader.open(file), qPrintable(reader.errorString()));
    QCOMPARE(reader.count(), 2 + int(tail.size()));
    QCOMPARE(reader.recordAt(0), a);
    QCOMPARE(reader.recordAt(1), b);
    for (int i = 0; i < tail.size(); ++i)
        QCOMPARE(reader.recordAt(2 + i), tail[i]);
    QVERIFY(!reader.truncatedTail());
}

void TestFrameLog::unknownBlocksAndForeignInterfacesSkipped()
{
    const QString file = path(QStringLiteral("plain.pcapng"));
    QVector<FrameRecord> records;
    for (int i = 0; i < 4; ++i) {
        records.append(makeRecord(quint32(i), 600, 1795332720000000 + i, FrameDirection::Received,
                                  FrameTransport::Serial, FrameStatus::Decoded));
    }
    QVERIFY(writeLog(file, records));
    FrameLogReader plain;
    QVERIFY(plain.open(file));
    const qint64 splice = plain.index()[2].offset;
    plain.close();

    Blocks extra;
    extra.opaque(0x00000BAD, 20);  // custom block type
    extra.opaque(4, 8);            // name resolution
    extra.interface(1, "eth0");    // Ethernet: not ours
    extra.packet(
        1, makeRecord(9, 60, 1795332720000002, FrameDirection::Received, FrameTransport::Serial, FrameStatus::Decoded));
    extra.interface(pcapng::kLinkTypeUser0, "radio");  // our link type, unknown name
    extra.packet(2, makeRecord(10, 60, 1795332720000002, FrameDirection::Received, FrameTransport::Serial,
                               FrameStatus::Decoded));
    QByteArray bytes = fileBytes(file);
    bytes.insert(splice, extra.out);
    const QString mixed = path(QStringLiteral("mixed.pcapng"));
    QVERIFY(putFile(mixed, bytes));

    FrameLogReader reader;
    QVERIFY2(reader.open(mixed), qPrintable(reader.errorString()));
    QCOMPARE(reader.foreignPackets(), 2);
    QCOMPARE(reader.readAll(), records);
}

void TestFrameLog::writeFailureReportedOnce()
{
#ifndef Q_OS_UNIX
    QSKIP("needs RLIMIT_FSIZE to make the file unwritable");
#else
    const QString file = path(QStringLiteral("full.pcapng"));
    const QVector<FrameRecord> records = sessionRecords(8);
    FrameLog log;
    QVERIFY(log.open(file));
    QStringList reports;
    log.setErrorHandler([&](const QString& message) { reports.append(message); });
    for (int i = 0; i < 3; ++i)
        QVERIFY(log.append(records[i]));
    const qint64 size = QFileInfo(file).size();

    // Past this size write(2) fails with EFBIG, like a full disk but only for
    // this process, and only while the limit stands.
    rlimit saved{};
    QVERIFY(::getrlimit(RLIMIT_FSIZE, &saved) == 0);
    if (saved.rlim_cur != RLIM_INFINITY && saved.rlim_cur < rlim_t(size + 150)) {
        QSKIP("file size limit already too low");
    }
    const auto savedSignal = std::signal(SIGXFSZ, SIG_IGN);
    rlimit limit = saved;
    // Cuts the next write (interface block of 100 bytes, then the packet)
    // inside the packet.
    limit.rlim_cur = rlim_t(size + 150);
    QVERIFY(::setrlimit(RLIMIT_FSIZE, &limit) == 0);
    auto restore = qScopeGuard([&] {
        ::setrlimit(RLIMIT_FSIZE, &saved);
        std::signal(SIGXFSZ, savedSignal);
    });

    QVERIFY(!log.append(records[3]));
    QVERIFY(log.hasFailed());
    QCOMPARE(reports.size(), 1);
    QVERIFY2(reports[0].contains(file), qPrintable(reports[0]));
    QCOMPARE(log.errorString(), reports[0]);
    for (int i = 4; i < records.size(); ++i)
        QVERIFY(!log.append(records[i]));
    restore.dismiss();
    ::setrlimit(RLIMIT_FSIZE, &saved);
    std::signal(SIGXFSZ, savedSignal);
    // Writable again, but a torn block must stay the last one in the file.
    QVERIFY(!log.append(records[4]));
    QCOMPARE(reports.size(), 1);
    QCOMPARE(log.recordsWritten(), 3);
    log.close();

    QCOMPARE(QFileInfo(file).size(), size + 150);
    FrameLogReader reader;
    QVERIFY2(reader.open(file), qPrintable(reader.errorString()));
    QVERIFY(reader.truncatedTail());
    QCOMPARE(reader.readAll(), records.mid(0, 3));
#endif
}

void TestFrameLog::tsharkReadsLog()
{
    const QString tshark = QStandardPaths::findExecutable(QStringLiteral("tshark"));
    if (tshark.isEmpty())
        QSKIP("tshark is not installed");

    QVector<FrameRecord> records = sessionRecords(12);
    records.append(makeRecord(500, 7, records.last().utcMicros + 1, FrameDirection::Sent, FrameTransport::Simulated,
                              FrameStatus::NotChecked));
    const QString file = path(QStringLiteral("tshark.pcapng"));
    QVERIFY(writeLog(file, records));

    QProcess p;
    p.setProcessChannelMode(QProcess::SeparateChannels);  // tshark chats on stderr
    p.start(tshark, {QStringLiteral("-n"), QStringLiteral("-r"), file, QStringLiteral("-T"), QStringLiteral("fields"),
                     QStringLiteral("-E"), QStringLiteral("separator=|"), QStringLiteral("-e"),
                     QStringLiteral("frame.len"), QStringLiteral("-e"), QStringLiteral("frame.packet_flags_direction"),
                     QStringLiteral("-e"), QStringLiteral("frame.interface_name"), QStringLiteral("-e"),
                     QStringLiteral("frame.time_epoch"), QStringLiteral("-e"), QStringLiteral("frame.comment")});
    QVERIFY(p.waitForFinished(-1));
    const QByteArray err = p.readAllStandardError();
    QVERIFY2(p.exitStatus() == QProcess::NormalExit && p.exitCode() == 0, err.constData());
    const QList<QByteArray> lines = p.readAllStandardOutput().trimmed().split('\n');
    QCOMPARE(lines.size(), records.size());
    for (int i = 0; i < records.size(); ++i) {
        const FrameRecord& r = records[i];
        const QList<QByteArray> f = lines[i].trimmed().split('|');
        QCOMPARE(f.size(), 5);
        QCOMPARE(f[0].toLongLong(), r.bytes.size());
        QCOMPARE(f[1].toUInt(nullptr, 0), r.direction == FrameDirection::Sent ? 2u : 1u);
        QCOMPARE(QString::fromUtf8(f[2]), frameTransportName(r.transport));
        const QByteArray epoch = QByteArray::number(r.utcMicros / 1000000) + '.' +
                                 QByteArray::number(r.utcMicros % 1000000).rightJustified(6, '0');
        QVERIFY2(f[3].startsWith(epoch), f[3].constData());
        QCOMPARE(f[4], frameStatusComment(r.status, r.correctedSymbols));
    }
}

QTEST_APPLESS_MAIN(TestFrameLog)
#include "tst_framelog.moc"
