// rcm with --key, run as a user runs it: keygen, encode and decode on the
// secure link, rejections on standard error, the replay state, misuse.
#include "codec/secure/SecureCodec.h"
#include "link/framelog/FrameLog.h"

#include "RunProgram.h"

#include <QtTest>

#include <sys/stat.h>

namespace {

using Run = rcm::test::ProgramRun;

Run runRcm(const QStringList& args, const QByteArray& input = {})
{
    return rcm::test::runProgram(QStringLiteral("rcm"), args, input);
}

// The key file's hex digits, to check that no output ever contains them.
QByteArray keyText(const QString& path)
{
    QFile f(path);
    return f.open(QIODevice::ReadOnly) ? f.readAll().trimmed() : QByteArray();
}

// The UTC clock as the text format writes it, so frames fall in the window.
QByteArray nowHeader(int id, int offsetSeconds = 0)
{
    const QDateTime t = QDateTime::currentDateTimeUtc().addSecs(offsetSeconds);
    return "ID_msg " + QByteArray::number(id) + "\ntime_UTC " + t.toString("HH:mm:ss").toLatin1() + "\ndate_UTC " +
           t.toString("yyMMdd").toLatin1() + "\n";
}

const QByteArray kCommand = "ID_UA_source GB_133\nSA_zoom_FWD_cam 105\n";

}  // namespace

class TestRcmSecure : public QObject {
    Q_OBJECT

private slots:
    void init();
    void keygen();
    void encodeDecodeRoundTrip();
    void wrongKeyIsForged();
    void plaintextFrameIsRefused();
    void encipheredFrameWithoutKey();
    void keyedFrameLog();
    void keyFileReadableByOthers();
    void replayStateRefusesReplayAndStaleTime();
    void encodeRefusesWhatTheSecureLinkCannotCarry();
    void misuse_data();
    void misuse();
    void helpExplainsKey();

private:
    QTemporaryDir m_dir;
    QString path(const char* name) const { return m_dir.filePath(QLatin1String(name)); }
    QString m_key;
};

void TestRcmSecure::init()
{
    QVERIFY(m_dir.isValid());
    m_key = path("aircraft.key");
    if (!QFile::exists(m_key)) {
        const Run r = runRcm({"keygen", m_key});
        QCOMPARE(r.exitCode, 0);
    }
}

void TestRcmSecure::keygen()
{
    const QString k = path("new.key");
    const Run r = runRcm({"keygen", k});
    QCOMPARE(r.exitCode, 0);
    QVERIFY(r.out.startsWith("fingerprint "));
    QCOMPARE(r.out.trimmed().size(), 12 + 16);
    struct stat st {};
    QCOMPARE(::stat(k.toLocal8Bit().constData(), &st), 0);
    QCOMPARE(st.st_mode & 0777, mode_t(0600));
    QCOMPARE(keyText(k).size(), 64);
    QVERIFY(!r.out.contains(keyText(k)));

    // The fingerprint is the one the codec computes for the key.
    std::string error;
    const auto key = rcm::secure::readKeyFile(k.toStdString(), error);
    QVERIFY2(key, error.c_str());
    QCOMPARE(r.out.trimmed().mid(12).toStdString(), rcm::secure::fingerprint(*key));

    const Run again = runRcm({"keygen", k});
    QCOMPARE(again.exitCode, 1);
    QVERIFY(again.err.contains("exists already"));
}

void TestRcmSecure::encodeDecodeRoundTrip()
{
    const QByteArray text = nowHeader(7) + kCommand;
    for (const char* dir : {"gcs-to-ua", "ua-to-gcs"}) {
        const Run e = runRcm({"encode", "--key", m_key, "--direction", dir}, text);
        QCOMPARE(e.exitCode, 0);
        QCOMPARE(e.out.size(), 600);
        QVERIFY(!e.out.mid(90, 223).contains(QByteArray(16, '\x55')));  // enciphered

        // Both directions are tried without --direction; the frame names its own.
        const Run d = runRcm({"decode", "--key", m_key}, e.out);
        QCOMPARE(d.exitCode, 0);
        QCOMPARE(d.err, QByteArray());
        const QByteArray line = QByteArray("# secure ") + (dir[0] == 'g' ? "GCS->UA" : "UA->GCS") + ", authenticated";
        QVERIFY2(d.out.contains(line), d.out.constData());
        QVERIFY(d.out.contains("SA_zoom_FWD_cam 105"));
        QVERIFY(d.out.contains("ID_msg 7"));

        // The other direction only: forged.
        const Run w = runRcm({"decode", "--key", m_key, "--direction", dir[0] == 'g' ? "ua-to-gcs" : "gcs-to-ua"},
                             e.out);
        QCOMPARE(w.exitCode, 1);
        QVERIFY(w.err.contains("refused as forged"));
        QVERIFY(!w.out.contains("SA_zoom_FWD_cam"));

        // Datagrams too.
        const Run ed = runRcm({"encode", "--key", m_key, "--direction", dir, "--datagram"}, text);
        QCOMPARE(ed.out.size(), 510);
        QCOMPARE(ed.out, e.out.mid(90));
        const Run dd = runRcm({"decode", "--key", m_key, "--datagram", "--summary"}, ed.out);
        QCOMPARE(dd.exitCode, 0);
        QVERIFY(dd.out.contains("delivered 1\n"));
        QVERIFY(dd.out.contains("refused forged 0\n"));
    }
}

void TestRcmSecure::wrongKeyIsForged()
{
    const QString other = path("other.key");
    QCOMPARE(runRcm({"keygen", other}).exitCode, 0);
    const Run e = runRcm({"encode", "--key", m_key}, nowHeader(1) + kCommand);
    QByteArray stream;
    for (int i = 0; i < 3; ++i)
        stream += e.out;
    const Run d = runRcm({"decode", "--key", other, "--summary"}, stream);
    QCOMPARE(d.exitCode, 1);
    QVERIFY(d.out.contains("frames 3\n"));
    QVERIFY(d.out.contains("delivered 0\n"));
    QVERIFY(d.out.contains("refused forged 3\n"));
    QCOMPARE(d.err.count("refused as forged: sent in none of the directions given with this key"), 3);
    QVERIFY(!d.err.contains(keyText(m_key)) && !d.err.contains(keyText(other)));
}

// No downgrade: a keyed decoder refuses an unencrypted frame, and says so.
void TestRcmSecure::plaintextFrameIsRefused()
{
    const Run e = runRcm({"encode"}, nowHeader(1) + kCommand);
    QCOMPARE(e.exitCode, 0);
    const Run d = runRcm({"decode", "--key", m_key}, e.out);
    QCOMPARE(d.exitCode, 1);
    QVERIFY(d.err.contains("frame 1 at byte offset 0: refused as plaintext: an unencrypted message on a keyed link"));
    QCOMPARE(d.out, QByteArray());
}

// Without the key a secure frame is said to be enciphered, never decoded
// into nonsense items.
void TestRcmSecure::encipheredFrameWithoutKey()
{
    const Run e = runRcm({"encode", "--key", m_key}, nowHeader(1) + kCommand);
    QCOMPARE(e.exitCode, 0);
    const Run d = runRcm({"decode"}, e.out);
    QCOMPARE(d.exitCode, 1);
    QCOMPARE(d.out, QByteArray());
    QCOMPARE(d.err, QByteArray("rcm: frame 1 at byte offset 0: refused as enciphered: the blocks look enciphered, and "
                               "no key was given\n"));
    const Run s = runRcm({"decode", "--summary"}, e.out + e.out);
    QVERIFY2(s.out.contains("frames 2\ndelivered 0\nrefused 2\n"), s.out.constData());
    QVERIFY(s.out.contains("\nrefused enciphered 2\n"));
}

// A keyed session's frame log, as the console writes it (pcapng, each frame
// marked enciphered): without the key every frame is said to be enciphered
// and none decoded; with it, both directions' frames, authenticated.
void TestRcmSecure::keyedFrameLog()
{
    const Run up = runRcm({"encode", "--key", m_key, "--direction", "gcs-to-ua"}, nowHeader(1) + kCommand);
    const Run down = runRcm({"encode", "--key", m_key, "--direction", "ua-to-gcs"}, nowHeader(2) + kCommand);
    QCOMPARE(up.exitCode, 0);
    QCOMPARE(down.exitCode, 0);
    QCOMPARE(up.out.size(), 600);
    const QString logPath = m_dir.filePath(QStringLiteral("keyed.pcapng"));
    {
        FrameLog log;
        QVERIFY(log.open(logPath));
        for (const Run* r : {&up, &down}) {
            FrameRecord f;
            f.bytes = r->out;
            f.utcMicros = QDateTime::currentMSecsSinceEpoch() * 1000;
            f.direction = r == &up ? FrameDirection::Sent : FrameDirection::Received;
            f.status = r == &up ? FrameStatus::NotChecked : FrameStatus::Decoded;
            f.enciphered = true;
            QVERIFY(log.append(f));
        }
    }
    const Run without = runRcm({"decode", logPath});
    QCOMPARE(without.exitCode, 1);
    QCOMPARE(without.out, QByteArray());
    const QList<QByteArray> lines = without.err.split('\n');
    QCOMPARE(lines.size(), 3);
    QVERIFY2(lines[0].startsWith("rcm: frame 1 (sent) at byte offset ") &&
                 lines[0].endsWith(" of the log: enciphered (a keyed link's frame): give --key to read it"),
             lines[0].constData());
    QVERIFY2(lines[1].startsWith("rcm: frame 2 (received) at byte offset "), lines[1].constData());

    const Run with = runRcm({"decode", "--key", m_key, logPath});
    QCOMPARE(with.err, QByteArray());
    QCOMPARE(with.exitCode, 0);
    QVERIFY2(with.out.contains("# secure GCS->UA, authenticated\n"), with.out.constData());
    QVERIFY(with.out.contains("# secure UA->GCS, authenticated\n"));
    QCOMPARE(with.out.count("SA_zoom_FWD_cam 105\n"), 2);
    QVERIFY(!with.out.contains(keyText(m_key)));

    const Run summary = runRcm({"decode", "--summary", logPath});
    QVERIFY2(summary.out.startsWith("frames 2\nread 0\nrefused 0\nenciphered 2\n"), summary.out.constData());
}

void TestRcmSecure::keyFileReadableByOthers()
{
    const QString k = path("shared.key");
    QCOMPARE(runRcm({"keygen", k}).exitCode, 0);
    QVERIFY(::chmod(k.toLocal8Bit().constData(), 0644) == 0);
    for (const QStringList& args : {QStringList{"encode", "--key", k}, QStringList{"decode", "--key", k}}) {
        const Run r = runRcm(args, nowHeader(1) + kCommand);
        QCOMPARE(r.exitCode, 1);
        QVERIFY2(r.err.contains("has mode 0644"), r.err.constData());
        QVERIFY(r.err.contains(("chmod 600 " + k).toLocal8Bit()));
        QVERIFY(!r.err.contains(keyText(k)));
        QCOMPARE(r.out, QByteArray());
    }
}

void TestRcmSecure::replayStateRefusesReplayAndStaleTime()
{
    const QString state = path("aircraft.key.replay-gcs-to-ua");
    const QStringList decode{"decode", "--key", m_key, "--direction", "gcs-to-ua", "--replay-state", state};
    const Run e10 = runRcm({"encode", "--key", m_key}, nowHeader(10) + kCommand);
    const Run e11 = runRcm({"encode", "--key", m_key}, nowHeader(11) + kCommand);

    Run d = runRcm(decode, e10.out);
    QCOMPARE(d.exitCode, 0);
    QVERIFY(d.out.contains("ID_msg 10"));
    QFile f(state);
    QVERIFY(f.open(QIODevice::ReadOnly));
    QVERIFY(f.readAll().contains("last_accepted_id 10\n"));

    // The same frame again, in a later run: the state remembered it.
    d = runRcm(decode, e10.out);
    QCOMPARE(d.exitCode, 1);
    QVERIFY(d.err.contains("refused as replayed: ID_msg 10 is not ahead of the last accepted 10"));
    QCOMPARE(d.out, QByteArray());

    // Replay and the next fresh one in one stream.
    d = runRcm(QStringList(decode) << "--summary", e10.out + e11.out);
    QCOMPARE(d.exitCode, 1);
    QVERIFY(d.out.contains("delivered 1\n"));
    QVERIFY(d.out.contains("refused replayed 1\n"));

    // Ten minutes old: stale time, with the default window and with --window.
    const Run old = runRcm({"encode", "--key", m_key}, nowHeader(12, -600) + kCommand);
    d = runRcm(decode, old.out);
    QCOMPARE(d.exitCode, 1);
    QVERIFY2(d.err.contains("refused as stale time"), d.err.constData());
    QVERIFY(d.err.contains("behind the receiver's clock; the window is 30 s"));
    d = runRcm(QStringList(decode) << "--window" << "3600", old.out);
    QCOMPARE(d.exitCode, 0);
}

void TestRcmSecure::encodeRefusesWhatTheSecureLinkCannotCarry()
{
    // 200 flight plan bytes fit a plain section (215) but not a secure one (199).
    const QByteArray plan = "BEGIN FLIGHT_PLAN\nflight_plan_ID 1\nflight_plan_section_ID 0\nflight_plan_data " +
                            QByteArray(200, '\x11').toHex() + "\nEND\n";
    QCOMPARE(runRcm({"encode"}, nowHeader(1) + plan).exitCode, 0);
    const Run r = runRcm({"encode", "--key", m_key}, nowHeader(1) + plan);
    QCOMPARE(r.exitCode, 1);
    QCOMPARE(r.err, QByteArray("<stdin>:7:18: flight_plan_data: 200 bytes is above the maximum 199 by 1\n"));
    QCOMPARE(r.out, QByteArray());
}

void TestRcmSecure::misuse_data()
{
    QTest::addColumn<QStringList>("args");
    QTest::addColumn<QByteArray>("message");
    QTest::newRow("key without value") << QStringList{"decode", "--key"} << QByteArray("--key needs a value");
    QTest::newRow("direction without key") << QStringList{"decode", "--direction", "gcs-to-ua"}
                                           << QByteArray("need --key");
    QTest::newRow("bad direction") << QStringList{"decode", "--key", "k", "--direction", "up"}
                                   << QByteArray("--direction is gcs-to-ua or ua-to-gcs");
    QTest::newRow("replay without direction") << QStringList{"decode", "--key", "k", "--replay-state", "s"}
                                              << QByteArray("--replay-state needs --direction");
    QTest::newRow("window without replay") << QStringList{"decode", "--key", "k", "--window", "5"}
                                           << QByteArray("--window applies with --replay-state only");
    QTest::newRow("bad window") << QStringList{"decode", "--key", "k", "--window", "5s"}
                                << QByteArray("--window takes a number of seconds");
    QTest::newRow("replay on encode") << QStringList{"encode", "--key", "k", "--direction", "gcs-to-ua",
                                                     "--replay-state", "s"}
                                      << QByteArray("--replay-state applies to decode only");
    QTest::newRow("key on dissector") << QStringList{"dissector", "--key", "k"}
                                      << QByteArray("--key applies to encode and decode");
    QTest::newRow("keygen without file") << QStringList{"keygen"} << QByteArray("keygen takes one argument");
}

void TestRcmSecure::misuse()
{
    QFETCH(QStringList, args);
    QFETCH(QByteArray, message);
    const Run r = runRcm(args);
    QCOMPARE(r.exitCode, 2);
    QVERIFY2(r.err.contains(message), r.err.constData());
}

void TestRcmSecure::helpExplainsKey()
{
    const Run r = runRcm({"--help"});
    QCOMPARE(r.exitCode, 0);
    for (const char* s : {"--key KEYFILE", "--direction", "--replay-state STATE", "--window SECONDS", "rcm keygen",
                          "chmod 600", "forged", "plaintext", "replayed", "stale time"})
        QVERIFY2(r.out.contains(s), s);
}

QTEST_APPLESS_MAIN(TestRcmSecure)
#include "tst_rcm_secure.moc"
