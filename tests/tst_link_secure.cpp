// The secure link end to end over UDP loopback: two LinkWorkers with keys,
// then the console's worker against the built `uasim --key`. Matching keys fly
// a session; different keys, a plaintext sender, replays and stale frames
// are rejected, and the statistics say why; a refused datagram does not move
// where the aircraft answers. Waits are on conditions (QTRY), never on time;
// in-process workers tick every 50 ms so the tests are quick.

// First: it names a member emit(), which Qt's headers define as a macro.
#include "codec/frame/StreamSync.h"

#include "codec/message/Airframe.h"
#include "codec/message/MessageDecoder.h"
#include "codec/message/MessageEncoder.h"
#include "codec/secure/SecureCodec.h"
#include "link/framelog/FrameLog.h"
#include "link/framelog/FrameLogReader.h"
#include "link/session/LinkWorker.h"
#include "link/transport/UdpLink.h"

#include <QDateTime>
#include <QProcess>
#include <QSignalSpy>
#include <QTemporaryDir>
#include <QTest>
#include <QUdpSocket>

#include <csignal>
#include <random>

using namespace std::chrono_literals;
using namespace rcm;
using namespace rcm::secure;

namespace {

constexpr int kPatience = 20000;  // ms; generous for a loaded machine, never a measured time

QString makeKey(const QTemporaryDir& dir, const char* name)
{
    const QString path = dir.filePath(QLatin1String(name));
    std::string error;
    if (!writeKeyFile(path.toStdString(), generateKey(), error))
        qFatal("%s", error.c_str());
    return path;
}

std::shared_ptr<SecureEndpoint> endpoint(const QString& keyPath, Direction sends)
{
    std::string error;
    std::shared_ptr<SecureEndpoint> e = SecureEndpoint::open(keyPath.toStdString(), sends, error);
    if (!e)
        qFatal("%s", error.c_str());
    return e;
}

LinkWorker::Options options(std::shared_ptr<SecureEndpoint> secure)
{
    LinkWorker::Options o;
    o.interval = 50ms;
    o.statisticsInterval = 20ms;
    o.secure = std::move(secure);
    return o;
}

Message command(int gcsUnit)
{
    Message m = restingCommand(Airframe::wellEquipped());
    m.header.set(ItemId::ID_UA_source, Value::pair(44, 133));
    m.header.set(ItemId::ID_GCS_destination, Value::pair(44, gcsUnit));
    return m;
}

Message status()
{
    Message m;
    m.header.set(ItemId::ID_UA_source, Value::pair(44, 133));
    m.sense.set(ItemId::SA_zoom_FWD_cam, 77);
    return m;
}

std::span<const std::uint8_t> bytesOf(const QByteArray& a)
{
    return {reinterpret_cast<const std::uint8_t*>(a.constData()), std::size_t(a.size())};
}

DecodedBlocks blocksOf(const QByteArray& datagram)
{
    return decodeCodewords(std::span<const std::uint8_t, kDatagramSize>(
        reinterpret_cast<const std::uint8_t*>(datagram.constData()), kDatagramSize));
}

// The UTC clock as time_UTC and date_UTC, `offset` seconds from now.
void stampNow(Message& m, int offsetSeconds = 0)
{
    const QDateTime t = QDateTime::currentDateTimeUtc().addSecs(offsetSeconds);
    m.header.set(ItemId::time_UTC, t.time().hour() * 10000 + t.time().minute() * 100 + t.time().second());
    m.header.set(ItemId::date_UTC, (t.date().year() % 100) * 10000 + t.date().month() * 100 + t.date().day());
}

quint16 portOf(const LinkWorker& worker) { return static_cast<UdpLink*>(worker.link())->boundPort(); }

quint16 freePort()
{
    QUdpSocket probe;
    probe.bind(QHostAddress::LocalHost, 0);
    return probe.localPort();
}

QVector<FrameRecord> readLog(const QString& path)
{
    FrameLogReader reader;
    if (!reader.open(path))
        qWarning() << reader.errorString();
    return reader.readAll();
}

// Two in-process ends: the console's worker (sends GCS->UA) and an aircraft's
// worker answering whoever spoke last (sends UA->GCS).
struct Session {
    std::unique_ptr<LinkWorker> ua;
    std::unique_ptr<LinkWorker> gcs;
    std::unique_ptr<QSignalSpy> uaReceived, gcsReceived, uaRejected, gcsRejected;

    Session(std::shared_ptr<SecureEndpoint> uaKey, std::shared_ptr<SecureEndpoint> gcsKey,
            std::unique_ptr<FrameLog> gcsLog = {})
    {
        auto uaLink = std::make_unique<UdpLink>(QHostAddress::LocalHost, 0);
        uaLink->setReplyToSender(true);
        ua = std::make_unique<LinkWorker>(std::move(uaLink), nullptr, options(std::move(uaKey)));
        ua->setCommand(status());
        ua->start();
        gcs = std::make_unique<LinkWorker>(
            std::make_unique<UdpLink>(QHostAddress::LocalHost, 0, QHostAddress::LocalHost, portOf(*ua)),
            std::move(gcsLog), options(std::move(gcsKey)));
        gcs->setCommand(command(30226));
        uaReceived = std::make_unique<QSignalSpy>(ua.get(), &LinkWorker::messageReceived);
        gcsReceived = std::make_unique<QSignalSpy>(gcs.get(), &LinkWorker::messageReceived);
        uaRejected = std::make_unique<QSignalSpy>(ua.get(), &LinkWorker::frameRejected);
        gcsRejected = std::make_unique<QSignalSpy>(gcs.get(), &LinkWorker::frameRejected);
        gcs->start();
    }
    ~Session()
    {
        gcs->stop();
        ua->stop();
    }
};

quint64 rejectedTotal(const LinkStatistics& s)
{
    return s.rejectedForged + s.rejectedReplayed + s.rejectedStaleTime + s.rejectedPlaintext;
}

// `uasim --udp PORT --verbose --key FILE`, collecting what it says.
class Uasim {
public:
    explicit Uasim(const QString& keyFile) : m_port(freePort())
    {
        m_process.setProgram(QStringLiteral(RCM_BIN_DIR "/uasim"));
        m_process.setArguments({QStringLiteral("--udp"), QString::number(m_port), QStringLiteral("--verbose"),
                                QStringLiteral("--key"), keyFile});
        QObject::connect(&m_process, &QProcess::readyReadStandardError,
                         [this] { m_stderr += m_process.readAllStandardError(); });
    }
    ~Uasim()
    {
        if (m_process.state() != QProcess::NotRunning) {
            m_process.kill();
            m_process.waitForFinished();
        }
    }
    bool start()
    {
        m_process.start();
        return m_process.waitForStarted();
    }
    bool listening() const { return m_stderr.contains("on udp"); }
    // SIGTERM: uasim stops and prints its rejection counts.
    bool stop()
    {
        ::kill(static_cast<pid_t>(m_process.processId()), SIGTERM);
        const bool done = m_process.waitForFinished(kPatience);
        m_stderr += m_process.readAllStandardError();
        return done;
    }
    quint16 port() const { return m_port; }
    const QByteArray& stderrText() const { return m_stderr; }

private:
    quint16 m_port;
    QProcess m_process;
    QByteArray m_stderr;
};

}  // namespace

class TestLinkSecure : public QObject {
    Q_OBJECT

private slots:
    void initTestCase() { LinkWorker::registerMetaTypes(); }

    void matchingKeysFlyASession();
    void differentKeysRejectEveryFrame();
    void plaintextSenderIsRejected();
    void replayedAndStaleFramesAreRejected();
    void refusedDatagramsDoNotRedirectTheReplies();
    void commandMustLeaveRoomForTheRedundancy();
    void uasimWithMatchingKey();
    void uasimWithDifferentKey();
};

void TestLinkSecure::matchingKeysFlyASession()
{
    QTemporaryDir dir;
    const QString key = makeKey(dir, "aircraft.key");
    const QString logPath = dir.filePath("gcs.pcapng");
    auto log = std::make_unique<FrameLog>();
    QString error;
    QVERIFY2(log->open(logPath, &error), qPrintable(error));
    {
        Session s(endpoint(key, Direction::UaToGcs), endpoint(key, Direction::GcsToUa), std::move(log));
        QTRY_VERIFY_WITH_TIMEOUT(s.uaReceived->count() >= 5 && s.gcsReceived->count() >= 5, kPatience);
        s.gcs->stop();
        s.ua->stop();

        for (const LinkWorker* w : {s.gcs.get(), s.ua.get()}) {
            QVERIFY(w->statistics().secure);
            QCOMPARE(rejectedTotal(w->statistics()), quint64(0));
        }
        QCOMPARE(s.uaRejected->count(), 0);
        QCOMPARE(s.gcsRejected->count(), 0);
        std::int64_t lastId = -1;
        for (const QList<QVariant>& args : *s.uaReceived) {
            const ReceivedMessage r = args.at(0).value<ReceivedMessage>();
            QCOMPARE(r.message.header.find(ItemId::ID_GCS_destination)->second, 30226);
            QVERIFY(r.diagnostics.empty());
            const std::int64_t id = r.message.header.number(ItemId::ID_msg);
            if (lastId >= 0)
                QVERIFY(messageIdAhead(std::uint32_t(id), std::uint32_t(lastId)));
            lastId = id;
        }
        QCOMPARE(s.gcsReceived->at(0).at(0).value<ReceivedMessage>().message.sense.number(ItemId::SA_zoom_FWD_cam),
                 77);
    }
    // State beside the key, one file per direction and role.
    for (const char* suffix : {".replay-gcs-to-ua", ".replay-ua-to-gcs", ".sent-gcs-to-ua", ".sent-ua-to-gcs"})
        QVERIFY2(QFile::exists(key + QLatin1String(suffix)), suffix);

    // The frame log holds the ciphertext as sent and received.
    std::string e;
    const std::optional<SecretKey> psk = readKeyFile(key.toStdString(), e);
    const SecureCodec up(*psk, Direction::GcsToUa), down(*psk, Direction::UaToGcs);
    const QVector<FrameRecord> records = readLog(logPath);
    int sent = 0, received = 0;
    for (const FrameRecord& r : records) {
        QCOMPARE(r.bytes.size(), qsizetype(kDatagramSize));
        const SecureCodec& codec = r.direction == FrameDirection::Sent ? up : down;
        QVERIFY(codec.decryptBlocks(blocksOf(r.bytes)).authentic);
        QVERIFY(!decodeFrame(bytesOf(r.bytes)).diagnostics.empty());  // not readable without the key
        (r.direction == FrameDirection::Sent ? sent : received)++;
    }
    QVERIFY(sent >= 5 && received >= 5);
}

void TestLinkSecure::differentKeysRejectEveryFrame()
{
    QTemporaryDir dir;
    const QString keyA = makeKey(dir, "a.key"), keyB = makeKey(dir, "b.key");
    const QString logPath = dir.filePath("gcs.pcapng");
    auto log = std::make_unique<FrameLog>();
    QVERIFY(log->open(logPath));
    Session s(endpoint(keyA, Direction::UaToGcs), endpoint(keyB, Direction::GcsToUa), std::move(log));
    // The aircraft accepts nothing from this console, so it would never learn
    // where to answer (refusedDatagramsDoNotRedirectTheReplies): told here.
    static_cast<UdpLink*>(s.ua->link())->setRemote(QHostAddress::LocalHost, portOf(*s.gcs));
    QTRY_VERIFY_WITH_TIMEOUT(s.gcs->statistics().rejectedForged >= 5 && s.ua->statistics().rejectedForged >= 5,
                             kPatience);
    // A rejected frame does not make or keep the link connected.
    QVERIFY(s.gcs->statistics().state != LinkState::Connected);
    QVERIFY(s.ua->statistics().state != LinkState::Connected);
    s.gcs->stop();
    s.ua->stop();
    for (const LinkWorker* w : {s.gcs.get(), s.ua.get()}) {
        const LinkStatistics& st = w->statistics();
        QCOMPARE(st.framesReceived, quint64(0));
        QCOMPARE(st.rejectedForged, rejectedTotal(st));
        QCOMPARE(st.uncorrectableFrames, quint64(0));
    }
    QCOMPARE(s.uaReceived->count(), 0);
    QCOMPARE(s.gcsReceived->count(), 0);
    QCOMPARE(quint64(s.gcsRejected->count()), s.gcs->statistics().rejectedForged);
    QVERIFY(s.gcsRejected->at(0).at(0).toString().startsWith(QStringLiteral("forged: ")));

    int rejectedInLog = 0;
    for (const FrameRecord& r : readLog(logPath)) {
        if (r.direction == FrameDirection::Received) {
            QCOMPARE(r.status, FrameStatus::Rejected);
            ++rejectedInLog;
        }
    }
    QCOMPARE(quint64(rejectedInLog), s.gcs->statistics().rejectedForged);
}

void TestLinkSecure::plaintextSenderIsRejected()
{
    QTemporaryDir dir;
    const QString key = makeKey(dir, "aircraft.key");
    Session s(endpoint(key, Direction::UaToGcs), nullptr);
    QTRY_VERIFY_WITH_TIMEOUT(s.ua->statistics().rejectedPlaintext >= 3, kPatience);
    QCOMPARE(s.uaReceived->count(), 0);
    QCOMPARE(s.ua->statistics().rejectedForged, quint64(0));
    QVERIFY(s.uaRejected->at(0).at(0).toString().startsWith(QStringLiteral("plaintext: ")));
}

// The console's worker against a far end the test drives frame by frame.
void TestLinkSecure::replayedAndStaleFramesAreRejected()
{
    QTemporaryDir dir;
    const QString key = makeKey(dir, "aircraft.key");
    UdpLink far(QHostAddress::LocalHost, 0);
    far.setReplyToSender(true);
    far.open();
    QSignalSpy heard(&far, &Link::datagramReceived);
    LinkWorker gcs(std::make_unique<UdpLink>(QHostAddress::LocalHost, 0, QHostAddress::LocalHost, far.boundPort()),
                   nullptr, options(endpoint(key, Direction::GcsToUa)));
    QSignalSpy received(&gcs, &LinkWorker::messageReceived);
    QSignalSpy rejected(&gcs, &LinkWorker::frameRejected);
    gcs.setCommand(command(1));
    gcs.start();
    QTRY_VERIFY_WITH_TIMEOUT(heard.count() >= 1, kPatience);  // the far end knows where to answer

    std::string error;
    const SecureCodec down(*readKeyFile(key.toStdString(), error), Direction::UaToGcs);
    auto datagram = [&](std::uint32_t id, int offsetSeconds) {
        Message m = status();
        m.header.set(ItemId::ID_msg, id);
        stampNow(m, offsetSeconds);
        Diagnostics errors;
        const EncodedBlocks b = *down.encode(m, errors);
        const DatagramBytes d = makeDatagram(b.block1, b.block2);
        return QByteArray(reinterpret_cast<const char*>(d.data()), qsizetype(d.size()));
    };
    const QByteArray first = datagram(100, 0);
    far.write(first);
    QTRY_COMPARE_WITH_TIMEOUT(received.count(), 1, kPatience);
    far.write(first);  // replayed
    QTRY_COMPARE_WITH_TIMEOUT(gcs.statistics().rejectedReplayed, quint64(1), kPatience);
    far.write(datagram(101, -600));  // ten minutes old, never delivered
    QTRY_COMPARE_WITH_TIMEOUT(gcs.statistics().rejectedStaleTime, quint64(1), kPatience);
    far.write(datagram(102, 0));  // the next fresh one
    QTRY_COMPARE_WITH_TIMEOUT(received.count(), 2, kPatience);
    QCOMPARE(received.at(1).at(0).value<ReceivedMessage>().message.header.number(ItemId::ID_msg), 102);
    QCOMPARE(rejected.count(), 2);
    QVERIFY(rejected.at(0).at(0).toString().startsWith(QStringLiteral("replayed: ID_msg 100")));
    QVERIFY(rejected.at(1).at(0).toString().startsWith(QStringLiteral("stale time: ")));
    QCOMPARE(gcs.statistics().rejectedForged, quint64(0));
    gcs.stop();
}

// The aircraft's worker answers whoever sent the last frame it accepted. An
// injector on another socket sends a forged frame and replays the console's
// genuine one; both are refused, and the aircraft's next frames still reach
// the console. The console here is a socket the test drives, which speaks
// once: a worker would keep sending and so win the address back within a
// tick, hiding a redirection.
void TestLinkSecure::refusedDatagramsDoNotRedirectTheReplies()
{
    QTemporaryDir dir;
    const QString key = makeKey(dir, "aircraft.key");
    auto uaLink = std::make_unique<UdpLink>(QHostAddress::LocalHost, 0);
    uaLink->setReplyToSender(true);
    LinkWorker ua(std::move(uaLink), nullptr, options(endpoint(key, Direction::UaToGcs)));
    QSignalSpy received(&ua, &LinkWorker::messageReceived);
    QSignalSpy sent(&ua, &LinkWorker::frameSent);
    ua.setCommand(status());
    ua.start();

    QUdpSocket console, injector;
    QVERIFY(console.bind(QHostAddress::LocalHost, 0));
    QVERIFY(injector.bind(QHostAddress::LocalHost, 0));
    std::string error;
    const std::optional<SecretKey> psk = readKeyFile(key.toStdString(), error);
    const SecureCodec up(*psk, Direction::GcsToUa), down(*psk, Direction::UaToGcs);

    Message m = command(30226);
    m.header.set(ItemId::ID_msg, 1);
    stampNow(m);
    Diagnostics errors;
    const EncodedBlocks genuine = *up.encode(m, errors);
    const DatagramBytes genuineBytes = makeDatagram(genuine.block1, genuine.block2);
    const QByteArray genuineDatagram(reinterpret_cast<const char*>(genuineBytes.data()), qsizetype(kDatagramSize));
    console.writeDatagram(genuineDatagram, QHostAddress::LocalHost, portOf(ua));
    QTRY_COMPARE_WITH_TIMEOUT(received.count(), 1, kPatience);

    // True once the console has heard the aircraft's frame with this ID_msg,
    // or a later one. Stays true: QTRY evaluates it again after it held.
    std::optional<std::uint32_t> lastHeard;
    auto consoleHeard = [&](quint32 id) {
        while (console.hasPendingDatagrams()) {
            QByteArray d(qsizetype(console.pendingDatagramSize()), '\0');
            console.readDatagram(d.data(), d.size());
            const Authenticated a =
                d.size() == qsizetype(kDatagramSize) ? down.decryptBlocks(blocksOf(d)) : Authenticated{};
            if (a.authentic)
                lastHeard = a.stamp.messageId;
        }
        return lastHeard && (*lastHeard == id || messageIdAhead(*lastHeard, id));
    };
    QTRY_VERIFY_WITH_TIMEOUT(sent.count() >= 1, kPatience);
    QTRY_VERIFY_WITH_TIMEOUT(consoleHeard(sent.last().at(0).toUInt()), kPatience);

    // Two codewords that decode, around bytes no key holder enciphered.
    Block forged1, forged2;
    std::mt19937 rng(5);
    for (Block* b : {&forged1, &forged2})
        for (std::uint8_t& byte : *b)
            byte = static_cast<std::uint8_t>(rng());
    const DatagramBytes forgedBytes = makeDatagram(forged1, forged2);
    injector.writeDatagram(QByteArray(reinterpret_cast<const char*>(forgedBytes.data()), qsizetype(kDatagramSize)),
                           QHostAddress::LocalHost, portOf(ua));
    QTRY_COMPARE_WITH_TIMEOUT(ua.statistics().rejectedForged, quint64(1), kPatience);
    injector.writeDatagram(genuineDatagram, QHostAddress::LocalHost, portOf(ua));
    QTRY_COMPARE_WITH_TIMEOUT(ua.statistics().rejectedReplayed, quint64(1), kPatience);

    // A frame the aircraft sends after both refusals reaches the console...
    const qsizetype before = sent.count();
    QTRY_VERIFY_WITH_TIMEOUT(sent.count() > before, kPatience);
    QTRY_VERIFY_WITH_TIMEOUT(consoleHeard(sent.at(before).at(0).toUInt()), kPatience);
    // ...and the injector, which would have had it instead, has nothing.
    QVERIFY(!injector.hasPendingDatagrams());
    QCOMPARE(received.count(), 1);
    ua.stop();
}

// A command that fills BLOCK 1 beyond 223 - 16 bytes is refused when set on
// a keyed link (it would go out on a plain one).
void TestLinkSecure::commandMustLeaveRoomForTheRedundancy()
{
    QTemporaryDir dir;
    const QString key = makeKey(dir, "aircraft.key");
    Message big;
    big.header.set(ItemId::ID_UA_source, Value::pair(44, 133));
    for (int e = 0; block1ItemBytes(big) + 12 + 4 <= kBlockSize - 10; ++e)
        big.addEngine(static_cast<std::uint8_t>(e)).set(ItemId::eng_prop_pitch, 1);
    for (const bool keyed : {false, true}) {
        LinkWorker w(std::make_unique<UdpLink>(QHostAddress::LocalHost, 0), nullptr,
                     options(keyed ? endpoint(key, Direction::GcsToUa) : nullptr));
        QSignalSpy refused(&w, &LinkWorker::commandRejected);
        w.setCommand(big);
        QCOMPARE(refused.count(), keyed ? 1 : 0);
        if (keyed)
            QVERIFY(refused.at(0).at(0).toString().contains(QStringLiteral("16 bytes of required padding")));
    }
}

void TestLinkSecure::uasimWithMatchingKey()
{
    QTemporaryDir dir;
    const QString key = makeKey(dir, "aircraft.key");
    Uasim uasim(key);
    QVERIFY(uasim.start());
    QTRY_VERIFY_WITH_TIMEOUT(uasim.listening(), kPatience);
    std::string error;
    const std::string print = fingerprint(*readKeyFile(key.toStdString(), error));
    QVERIFY2(uasim.stderrText().contains("secure link: encrypted and authenticated, key fingerprint " +
                                         QByteArray::fromStdString(print)),
             uasim.stderrText().constData());

    LinkWorker::Options o = options(endpoint(key, Direction::GcsToUa));
    o.interval = 1000ms;  // uasim's own cadence
    LinkWorker gcs(std::make_unique<UdpLink>(QHostAddress::LocalHost, 0, QHostAddress::LocalHost, uasim.port()),
                   nullptr, o);
    QSignalSpy received(&gcs, &LinkWorker::messageReceived);
    gcs.setCommand(command(30226));
    gcs.start();
    QTRY_VERIFY_WITH_TIMEOUT(received.count() >= 3, kPatience);
    gcs.stop();
    QCOMPARE(rejectedTotal(gcs.statistics()), quint64(0));
    // The status frames report the aircraft the commands reached.
    const ReceivedMessage last = received.last().at(0).value<ReceivedMessage>();
    QVERIFY(last.diagnostics.empty());
    QCOMPARE(last.message.engines.size(), std::size_t(3));

    QVERIFY(uasim.stop());
    QVERIFY2(uasim.stderrText().contains("command "), uasim.stderrText().constData());  // --verbose lines
    QVERIFY(!uasim.stderrText().contains("command rejected"));
    QVERIFY(uasim.stderrText().contains("rejected commands: 0 forged, 0 replayed, 0 stale time, 0 plaintext"));
}

void TestLinkSecure::uasimWithDifferentKey()
{
    QTemporaryDir dir;
    const QString uaKey = makeKey(dir, "ua.key"), gcsKey = makeKey(dir, "gcs.key");
    Uasim uasim(uaKey);
    QVERIFY(uasim.start());
    QTRY_VERIFY_WITH_TIMEOUT(uasim.listening(), kPatience);

    LinkWorker::Options o = options(endpoint(gcsKey, Direction::GcsToUa));
    o.interval = 1000ms;
    LinkWorker gcs(std::make_unique<UdpLink>(QHostAddress::LocalHost, 0, QHostAddress::LocalHost, uasim.port()),
                   nullptr, o);
    QSignalSpy received(&gcs, &LinkWorker::messageReceived);
    gcs.setCommand(command(30226));
    gcs.start();
    QTRY_VERIFY_WITH_TIMEOUT(uasim.stderrText().count("command rejected: forged: ") >= 3, kPatience);
    gcs.stop();
    // uasim answers only a sender whose frames it accepted: not this console.
    QCOMPARE(received.count(), 0);
    QCOMPARE(gcs.statistics().framesReceived, quint64(0));
    QCOMPARE(rejectedTotal(gcs.statistics()), quint64(0));

    QVERIFY(uasim.stop());
    const QByteArray said = uasim.stderrText();
    QVERIFY2(said.contains("command rejected: forged: "), said.constData());
    const qsizetype at = said.indexOf("rejected commands: ");
    QVERIFY(at >= 0);
    const int forged = said.mid(at + 19).split(' ').value(0).toInt();
    QVERIFY2(forged >= 3, said.constData());
    QVERIFY(said.mid(at).startsWith("rejected commands: " + QByteArray::number(forged) +
                                    " forged, 0 replayed, 0 stale time, 0 plaintext"));
}

QTEST_GUILESS_MAIN(TestLinkSecure)
#include "tst_link_secure.moc"
