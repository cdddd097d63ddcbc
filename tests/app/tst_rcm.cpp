// The rcm command-line tool, run as a user runs it: bytes in, bytes and text
// out, exit status and error messages.
#include "codec/message/MessageDecoder.h"
#include "codec/message/MessageEncoder.h"
#include "codec/message/TextFormat.h"

#include "RunProgram.h"
#include "ReceiveChannel.h"

#include <QtTest>

namespace {

using Run = rcm::test::ProgramRun;

Run runRcm(const QStringList& args, const QByteArray& input = {})
{
    return rcm::test::runProgram(QStringLiteral("rcm"), args, input);
}

QByteArray vector(const char* name)
{
    QFile f(QStringLiteral(RCM_VECTORS_DIR "/rcm/") + QLatin1String(name));
    return f.open(QIODevice::ReadOnly) ? f.readAll() : QByteArray();
}

std::span<const std::uint8_t> bytesOf(const QByteArray& a)
{
    return {reinterpret_cast<const std::uint8_t*>(a.constData()), static_cast<std::size_t>(a.size())};
}

}  // namespace

class TestRcm : public QObject {
    Q_OBJECT
private slots:
    void encodeGivesTheSeedsBytes();
    void encodeKeepsGivenFieldsAndFillsOnlyTheHeaderClock();
    void encodeDatagram();
    void encodeReportsLineAndColumn();
    void encodeRefusesWhatDoesNotFit();
    void encodeCapsTheErrors();
    void encodeReportsControlBytesWhole();
    void encodeSkipsAByteOrderMark();
    void decodeVectorsToText();
    void decodeStreamAmidGarbage();
    void decodeFrameBeginningBeforeTheStream();
    void decodeReportsUncorrectable();
    void decodeReadsWithPredictions();
    void decodeFindsNothing();
    void decodeSummary();
    void decodeRefusesWhatIsNotExact();
    void decodeDatagram();
    void roundTripThroughTheTool();
    void misuse_data();
    void misuse();
    void helpExplainsWithAnExample();
    void dissectorMatchesTheShippedCopy();
};

void TestRcm::encodeGivesTheSeedsBytes()
{
    const Run r = runRcm({"encode"}, "ID_msg 133\nID_UA_source GB_133\ntime_UTC 16:35:23\ndate_UTC 071114\n"
                                  "ID_BLK12_format 5 15\nSA_zoom_LHS_cam 35\n");
    QCOMPARE(r.exitCode, 0);
    QCOMPARE(r.err, QByteArray());
    QCOMPARE(r.out.size(), 600);
    QCOMPARE(r.out.left(90), QByteArray(88, '\x55') + QByteArray(2, '\x0F'));
    // BLOCK 1 ends with the items in canonical order, after padding.
    const QByteArray items = QByteArray::fromHex("0300008504002C008505027EC3060115CA07050FB023");
    QCOMPARE(r.out.mid(90, 223).right(items.size()), items);
    QCOMPARE(r.out.mid(90, 223 - items.size()), QByteArray(223 - items.size(), '\x55'));
}

void TestRcm::encodeKeepsGivenFieldsAndFillsOnlyTheHeaderClock()
{
    Run r = runRcm({"encode"}, "SA_zoom_FWD_cam 105\n");
    QCOMPARE(r.exitCode, 0);
    rcm::DecodeResult d = rcm::decodeFrame(bytesOf(r.out));
    QVERIFY(d.ok());
    QCOMPARE(d.message.header.number(rcm::ItemId::ID_msg, -1), 0);
    QVERIFY(d.message.header.has(rcm::ItemId::time_UTC));
    QVERIFY(d.message.header.has(rcm::ItemId::date_UTC));
    const QDate today = QDateTime::currentDateTimeUtc().date();
    const qint64 yymmdd = (today.year() % 100) * 10000 + today.month() * 100 + today.day();
    // Midnight may pass between the tool's clock and ours.
    QVERIFY(std::abs(d.message.header.number(rcm::ItemId::date_UTC) - yymmdd) <= 100);
    QVERIFY(!d.message.header.has(rcm::ItemId::ID_UA_source));
    QCOMPARE(d.message.header.items().size(), std::size_t{3});
    QVERIFY(d.message.engines.empty() && d.message.radios.empty() && d.message.cameras.empty());
    QCOMPARE(d.message.sense.items().size(), std::size_t{1});

    r = runRcm({"encode"}, "ID_msg 7\ntime_UTC 01:02:03\ndate_UTC 991231\n");
    d = rcm::decodeFrame(bytesOf(r.out));
    QCOMPARE(d.message.header.number(rcm::ItemId::ID_msg), 7);
    QCOMPARE(d.message.header.number(rcm::ItemId::time_UTC), 10203);
    QCOMPARE(d.message.header.number(rcm::ItemId::date_UTC), 991231);
}

void TestRcm::encodeDatagram()
{
    const Run frame = runRcm({"encode"}, "ID_msg 1\ntime_UTC 00:00:00\ndate_UTC 261122\n");
    const Run datagram = runRcm({"encode", "--datagram", "-"}, "ID_msg 1\ntime_UTC 00:00:00\ndate_UTC 261122\n");
    QCOMPARE(datagram.exitCode, 0);
    QCOMPARE(datagram.out.size(), 510);
    QCOMPARE(datagram.out, frame.out.mid(90));
}

void TestRcm::encodeReportsLineAndColumn()
{
    QTemporaryDir dir;
    const QString path = dir.filePath("bad.txt");
    QFile f(path);
    QVERIFY(f.open(QIODevice::WriteOnly));
    f.write("ID_msg 133\nF_rudder_set 300\nlights wing_RHS=ON\nno_such_item 1\n");
    f.close();
    const Run r = runRcm({"encode", path});
    QCOMPARE(r.exitCode, 1);
    QCOMPARE(r.out, QByteArray());
    const QList<QByteArray> lines = r.err.trimmed().split('\n');
    // Every error in the text, each at its line and column; three for the
    // three fields missing from `lights`.
    QCOMPARE(lines.size(), 5);
    QCOMPARE(lines[0], (path + ":2:14: F_rudder_set: 300 is above the maximum 127 by 173").toUtf8());
    QVERIFY2(lines[1].startsWith((path + ":3:20: lights: ").toUtf8()) && lines[1].contains("wing_LHS"), lines[1]);
    QVERIFY2(lines[4].startsWith((path + ":4:1: no_such_item: ").toUtf8()), lines[4]);
}

void TestRcm::encodeRefusesWhatDoesNotFit()
{
    QByteArray text;
    for (int i = 0; i < 10; ++i)
        text += "system_ID R" + QByteArray::number(i) + "\nRx_freq 1\nTx_freq 1\nTx_OP_power 1\nreceiver_control "
                "receiver=ON transmitter=ON\n";
    const Run r = runRcm({"encode"}, text);
    QCOMPARE(r.exitCode, 1);
    QCOMPARE(r.out, QByteArray());
    // Named at the first item that no longer fits: the tenth radio's
    // system_ID, as ID_msg, time_UTC and date_UTC take 12 bytes.
    QCOMPARE(r.err, QByteArray("<stdin>:46:1: system_ID: BLOCK 1 is full here: the items need 242 bytes, 19 more than "
                               "the 223 a block holds (counting ID_msg, time_UTC and date_UTC, filled in when not "
                               "given)\n"));
}

void TestRcm::encodeCapsTheErrors()
{
    QByteArray text;
    for (int i = 0; i < 1000000; ++i)
        text += "foo 1\n";
    const Run r = runRcm({"encode"}, text);
    QCOMPARE(r.exitCode, 1);
    QCOMPARE(r.out, QByteArray());
    QByteArray expected;
    for (int line = 1; line <= 20; ++line)
        expected += "<stdin>:" + QByteArray::number(line) + ":1: foo: unknown item 'foo'\n";
    expected += "<stdin>: 999980 more errors not listed\n";
    QCOMPARE(r.err, expected);
}

void TestRcm::encodeReportsControlBytesWhole()
{
    const Run r = runRcm({"encode"}, QByteArray("ID_msg 1\nID\000msg 2\nSA_zoom_LHS_cam 35\n", 37));
    QCOMPARE(r.exitCode, 1);
    QCOMPARE(r.err, QByteArray("<stdin>:2:3: control byte \\x00 in the text; the format is printable text (inside "
                               "quotes write any byte as \\xHH)\n"));
}

void TestRcm::encodeSkipsAByteOrderMark()
{
    const QByteArray text = "ID_msg 1\ntime_UTC 00:00:00\ndate_UTC 261122\n";
    const Run plain = runRcm({"encode"}, text);
    const Run marked = runRcm({"encode"}, "\xEF\xBB\xBF" + text);
    QCOMPARE(marked.exitCode, 0);
    QCOMPARE(marked.err, QByteArray());
    QCOMPARE(marked.out, plain.out);
}

void TestRcm::decodeVectorsToText()
{
    QTemporaryDir dir;
    const QString path = dir.filePath("we.bin");
    QFile f(path);
    QVERIFY(f.open(QIODevice::WriteOnly));
    f.write(vector("well-equipped.errors.bin"));
    f.close();
    const Run r = runRcm({"decode", path});
    QCOMPARE(r.exitCode, 0);
    QCOMPARE(r.err, QByteArray());
    QVERIFY(r.out.startsWith("# frame 1 at byte offset 0\n# block1 corrected 16\n# block2 corrected 16\nBEGIN HEADER\n"
                             "ID_msg 4508515\n"));
    QVERIFY(r.out.contains("\nF_aileron_RHS_set -19\n"));
    QVERIFY(r.out.contains("\nsystem_ID VHF3\n"));
    QVERIFY(r.out.contains("\ncam_elev -54.64\n"));
}

void TestRcm::decodeStreamAmidGarbage()
{
    const Run r = runRcm({"decode"}, vector("stream.bin"));
    QCOMPARE(r.exitCode, 0);
    QCOMPARE(r.out.count("# frame "), 3);
    QCOMPARE(r.out.count("# block1 corrected 0\n"), 3);
    QVERIFY(r.out.contains("flight_plan_ID 0xDEADBEEF\n"));
}

void TestRcm::decodeFrameBeginningBeforeTheStream()
{
    // The stream begins 50 bytes into the frame's 90-byte preamble.
    const Run r = runRcm({"decode"}, vector("seed-example.bin").mid(50));
    QCOMPARE(r.exitCode, 0);
    QVERIFY2(r.out.startsWith("# frame 1 at byte offset -50 (50 bytes before the start of the stream)\n"
                              "# block1 corrected 0\n"),
             r.out.constData());
}

void TestRcm::decodeReportsUncorrectable()
{
    // 20 bad bytes in the first frame's BLOCK 1: beyond Reed-Solomon, and
    // with no frame before it, nothing to predict it from.
    QByteArray bytes = vector("seed-example.bin") + vector("well-equipped.bin");
    for (int i = 0; i < 20; ++i)
        bytes[90 + i * 12] = static_cast<char>(bytes[90 + i * 12] ^ 0x5A);
    const Run r = runRcm({"decode"}, bytes);
    QCOMPARE(r.exitCode, 1);
    QCOMPARE(r.out.count("# frame "), 1);
    QVERIFY(r.out.startsWith("# frame 2 at byte offset 600\n"));
    QCOMPARE(r.err, QByteArray("rcm: frame 1 at byte offset 0: refused as uncorrectable: block 1 beyond correction, "
                               "block 2 good\n"));
}

// A recording reads as well as the live link read it: the same receiver,
// predictions included. Ten frames of a session, then ten more with 24 bad
// bytes in each codeword, far beyond Reed-Solomon alone.
void TestRcm::decodeReadsWithPredictions()
{
    const rcm::test::CommandSession session;
    QByteArray bytes;
    std::mt19937_64 rng(24);
    for (std::uint64_t i = 0; i < 20; ++i) {
        rcm::FrameBytes f = session.frameAt(i);
        if (i >= 10)
            for (std::size_t cw = 0; cw < 2; ++cw)
                for (int e = 0; e < 24; ++e)
                    f[rcm::kPreambleSize + cw * rcm::kCodewordSize + (e * 7 + i) % 223] ^= static_cast<std::uint8_t>(1 + rng() % 255);
        bytes.append(reinterpret_cast<const char*>(f.data()), qsizetype(f.size()));
    }
    const Run r = runRcm({"decode", "--summary"}, bytes);
    QCOMPARE(r.err, QByteArray());
    QCOMPARE(r.exitCode, 0);
    QVERIFY2(r.out.startsWith("frames 20\ndelivered 20\nrefused 0\n"), r.out.constData());
    QVERIFY2(r.out.contains("\nfrom a prediction 10\n"), r.out.constData());
}

void TestRcm::decodeFindsNothing()
{
    const Run r = runRcm({"decode"}, QByteArray(5000, '\x55'));
    QCOMPARE(r.exitCode, 1);
    QCOMPARE(r.out, QByteArray());
    QCOMPARE(r.err, QByteArray("rcm: no frame found\n"));
}

void TestRcm::decodeSummary()
{
    Run r = runRcm({"decode", "--summary"},
                   vector("well-equipped.errors.bin") + vector("seed-example.bin") + vector("flight-plan.bin"));
    QCOMPARE(r.exitCode, 0);
    QCOMPARE(r.err, QByteArray());
    QVERIFY2(r.out.startsWith("frames 3\ndelivered 3\nrefused 0\ncorrected block1 16\ncorrected block2 16\n"
                              "from a prediction 0\nbytes read 1800\nbytes skipped 0\nrefused uncorrectable 0\n"),
             r.out.constData());
    // A recording is checked for continuity between its own frames: the
    // well-equipped frame again (stream.bin holds it) is a replay, counted by
    // its reason.
    r = runRcm({"decode", "--summary"}, vector("stream.bin") + vector("well-equipped.errors.bin"));
    QCOMPARE(r.exitCode, 1);
    QCOMPARE(r.out, QByteArray("frames 4\ndelivered 3\nrefused 1\ncorrected block1 0\ncorrected block2 0\n"
                               "from a prediction 0\nbytes read 3100\nbytes skipped 700\n"
                               "refused uncorrectable 0\nrefused wrong size 0\nrefused enciphered 0\n"
                               "refused forged 0\nrefused plaintext 0\nrefused not exact: missing header item 0\n"
                               "refused not exact: bad padding 0\nrefused not exact: invalid field 0\n"
                               "refused not exact: unknown item 0\nrefused not exact: not canonical 0\n"
                               "refused not exact: warning 0\nrefused replayed 1\n"
                               "refused implausible: message id step 0\nrefused implausible: time step 0\n"
                               "refused stale time 0\nrefused implausible: plan section 0\n"));
    QCOMPARE(r.err, QByteArray("rcm: frame 4 at byte offset 2500: refused as replayed: ID_msg 4508515 is not ahead of "
                               "the last accepted 4508515\n"));
}

// A frame the acceptance decision finds inexact is refused with its reason,
// never printed as items.
void TestRcm::decodeRefusesWhatIsNotExact()
{
    rcm::Message m;
    m.sense.set(rcm::ItemId::SA_zoom_FWD_cam, 105);  // no ID_msg, time_UTC or date_UTC
    rcm::Diagnostics errors;
    const auto frame = rcm::encodeFrame(m, errors);
    QVERIFY(frame);
    const Run r = runRcm({"decode"}, QByteArray(reinterpret_cast<const char*>(frame->data()), 600));
    QCOMPARE(r.exitCode, 1);
    QCOMPARE(r.out, QByteArray());
    QCOMPARE(r.err, QByteArray("rcm: frame 1 at byte offset 0: refused as not exact: missing header item: block 1: "
                               "no ID_msg\n"));
}

void TestRcm::decodeDatagram()
{
    const Run ok = runRcm({"decode", "--datagram"}, vector("flight-plan.bin").mid(90));
    QCOMPARE(ok.exitCode, 0);
    QVERIFY(ok.out.contains("flight_plan_section_ID 3\n"));
    const Run wrong = runRcm({"decode", "--datagram"}, vector("flight-plan.bin"));
    QCOMPARE(wrong.exitCode, 1);
    QCOMPARE(wrong.err, QByteArray("rcm: a datagram is 510 bytes; read 600\n"));
}

void TestRcm::roundTripThroughTheTool()
{
    QFile sample(QStringLiteral(RCM_SOURCE_DIR "/resources/samples/well-equipped.txt"));
    QVERIFY(sample.open(QIODevice::ReadOnly));
    const Run encoded = runRcm({"encode"}, sample.readAll());
    QCOMPARE(encoded.exitCode, 0);
    const Run decoded = runRcm({"decode"}, encoded.out);
    QCOMPARE(decoded.exitCode, 0);
    // The decoder's text, with its comment lines, encodes back to the same frame.
    const Run again = runRcm({"encode"}, decoded.out);
    QCOMPARE(again.exitCode, 0);
    QCOMPARE(again.out, encoded.out);
}

void TestRcm::misuse_data()
{
    QTest::addColumn<QStringList>("args");
    QTest::addColumn<QByteArray>("message");
    QTest::newRow("no command") << QStringList{} << QByteArray("rcm: no command given\n");
    QTest::newRow("unknown command") << QStringList{"fly"} << QByteArray("rcm: unknown command fly\n");
    QTest::newRow("unknown option") << QStringList{"decode", "--fast"} << QByteArray("rcm: unknown option --fast\n");
    QTest::newRow("two files") << QStringList{"decode", "a", "b"} << QByteArray("rcm: too many arguments: b\n");
    QTest::newRow("summary on encode") << QStringList{"encode", "--summary"}
                                       << QByteArray("rcm: --summary applies to decode only\n");
}

void TestRcm::misuse()
{
    QFETCH(QStringList, args);
    QFETCH(QByteArray, message);
    const Run r = runRcm(args);
    QCOMPARE(r.exitCode, 2);
    QCOMPARE(r.err, message + "Try 'rcm --help'.\n");
}

void TestRcm::helpExplainsWithAnExample()
{
    const Run r = runRcm({"--help"});
    QCOMPARE(r.exitCode, 0);
    for (const char* needle : {"rcm encode [FILE] [--datagram]", "rcm decode [FILE] [--datagram] [--summary]",
                               "# block1 corrected N", "Exit status", "Example:", "rcm encode cmd.txt > cmd.bin"})
        QVERIFY2(r.out.contains(needle), needle);
}

void TestRcm::dissectorMatchesTheShippedCopy()
{
    QFile shipped(QStringLiteral(RCM_SOURCE_DIR "/resources/wireshark/rcm.lua"));
    QVERIFY(shipped.open(QIODevice::ReadOnly));
    const Run r = runRcm({"dissector"});
    QCOMPARE(r.exitCode, 0);
    QVERIFY2(r.out == shipped.readAll(), "regenerate: build/bin/rcm dissector > resources/wireshark/rcm.lua");
}

QTEST_GUILESS_MAIN(TestRcm)
#include "tst_rcm.moc"
