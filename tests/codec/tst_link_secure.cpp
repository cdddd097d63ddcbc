// The secure link end to end: the console's worker and the simulated
// aircraft with keys, in simulated time (AircraftFixture); a refused datagram
// over real UDP loopback; then the console's worker against the built
// `uasim --key`. Matching keys fly a session; different keys, a plaintext
// sender, replays and stale frames are rejected, and the statistics say why;
// a refused datagram does not move where the aircraft answers. Waits on the
// real sockets and process are on conditions (QTRY), never on a time.

// First: it names a member emit(), which Qt's headers define as a macro.
#include "codec/receive/LoggedFrameReading.h"
#include "codec/frame/StreamSync.h"

#include "codec/message/Airframe.h"
#include "codec/message/MessageDecoder.h"
#include "codec/message/MessageEncoder.h"
#include "codec/secure/SecureCodec.h"
#include "link/framelog/FrameLog.h"
#include "link/framelog/FrameLogCsv.h"
#include "link/framelog/FrameLogReader.h"
#include "link/session/LinkWorker.h"
#include "link/transport/UdpLink.h"

#include "AircraftFixture.h"
#include "UasimProcess.h"

#include <QBuffer>
#include <QSignalSpy>
#include <QTemporaryDir>
#include <QTest>
#include <QUdpSocket>

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

// Its time window on `clock`; the system clock when null.
std::shared_ptr<SecureEndpoint> endpoint(const QString& keyPath, Direction sends,
                                         const std::shared_ptr<Clock>& clock = nullptr)
{
    std::string error;
    SecureEndpoint::Options options;
    if (clock)
        options.clock = test::utcSecondsOf(clock);
    std::shared_ptr<SecureEndpoint> e = SecureEndpoint::open(keyPath.toStdString(), sends, error, options);
    if (!e)
        qFatal("%s", error.c_str());
    return e;
}

LinkWorker::Options options(std::shared_ptr<SecureEndpoint> secure, std::shared_ptr<Clock> clock = nullptr)
{
    LinkWorker::Options o;
    o.secure = std::move(secure);
    o.clock = std::move(clock);
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

std::shared_ptr<VirtualClock> virtualClock()
{
    return std::make_shared<VirtualClock>(test::kFixtureStartUtcMicros);
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

// `clock`'s time as time_UTC and date_UTC, `offset` seconds from now.
void stampNow(Message& m, const Clock& clock, int offsetSeconds = 0)
{
    using namespace std::chrono;
    const sys_seconds t{seconds(clock.utcMicros() / 1'000'000 + offsetSeconds)};
    const sys_days day = floor<days>(t);
    const year_month_day date{day};
    const hh_mm_ss time{t - day};
    m.header.set(ItemId::time_UTC, time.hours().count() * 10000 + time.minutes().count() * 100 + time.seconds().count());
    m.header.set(ItemId::date_UTC,
                 (int(date.year()) % 100) * 10000 + int(unsigned(date.month())) * 100 + int(unsigned(date.day())));
}

quint16 portOf(const LinkWorker& worker) { return static_cast<UdpLink*>(worker.link())->boundPort(); }

QVector<FrameRecord> readLog(const QString& path)
{
    FrameLogReader reader;
    if (!reader.open(path))
        qWarning() << reader.errorString();
    return reader.readAll();
}

// The console (sends GCS->UA) and the simulated aircraft (sends UA->GCS)
// in simulated time, each with its key (null: plain), their time windows on
// the fixture's clock.
struct Session {
    std::shared_ptr<VirtualClock> clock = virtualClock();
    std::unique_ptr<test::AircraftFixture> fixture;
    LinkWorker* ua = nullptr;
    LinkWorker* gcs = nullptr;
    std::unique_ptr<QSignalSpy> uaReceived, gcsReceived, uaRejected, gcsRejected;

    Session(const QString& uaKey, const QString& gcsKey, std::unique_ptr<FrameLog> gcsLog = {})
    {
        test::AircraftFixture::Options o;
        o.clock = clock;
        if (!uaKey.isEmpty())
            o.aircraft.secure = endpoint(uaKey, Direction::UaToGcs, clock);
        if (!gcsKey.isEmpty())
            o.console.secure = endpoint(gcsKey, Direction::GcsToUa, clock);
        o.consoleLog = std::move(gcsLog);
        fixture = std::make_unique<test::AircraftFixture>(std::move(o));
        ua = fixture->aircraftWorker.get();
        gcs = fixture->console.get();
        gcs->setCommand(command(30226));
        uaReceived = std::make_unique<QSignalSpy>(ua, &LinkWorker::messageReceived);
        gcsReceived = std::make_unique<QSignalSpy>(gcs, &LinkWorker::messageReceived);
        uaRejected = std::make_unique<QSignalSpy>(ua, &LinkWorker::frameRejected);
        gcsRejected = std::make_unique<QSignalSpy>(gcs, &LinkWorker::frameRejected);
        fixture->start();
    }
};

quint64 rejectedTotal(const LinkStatistics& s)
{
    return s.refusedTotal() - s.refusedFor(rcm::Refusal::Uncorrectable);
}

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
        Session s(key, key, std::move(log));
        s.fixture->run(5s);
        // One frame each way on each second from 07:32:01.
        QCOMPARE(s.uaReceived->count(), 5);
        QCOMPARE(s.gcsReceived->count(), 5);
        s.gcs->stop();
        s.ua->stop();

        for (const LinkWorker* w : {s.gcs, s.ua}) {
            QVERIFY(w->statistics().secure);
            QCOMPARE(w->statistics().state, LinkState::Closed);
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
                QCOMPARE(id, (lastId + 1) % std::int64_t(kMessageIdModulus));
            lastId = id;
        }
        const Message first = s.gcsReceived->at(0).at(0).value<ReceivedMessage>().message;
        QCOMPARE(first.header.number(ItemId::time_UTC), 73201);
        QCOMPARE(first.engines.size(), std::size_t(3));
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
        // The log says so, and a reader of it shows no items without the key
        // and the real ones, authenticated, with it.
        QVERIFY(r.enciphered);
        const LoggedFrameReading without = readLoggedFrame(bytesOf(r.bytes), r.enciphered, {});
        QCOMPARE(int(without.outcome), int(LoggedFrameReading::Outcome::Enciphered));
        QVERIFY(without.decoded.message.header.items().empty());
        const LoggedFrameReading with = readLoggedFrame(bytesOf(r.bytes), r.enciphered, {&up, &down});
        QVERIFY2(with.read(), with.detail.c_str());
        QCOMPARE(*with.direction, r.direction == FrameDirection::Sent ? Direction::GcsToUa : Direction::UaToGcs);
        QVERIFY(with.decoded.message.header.has(ItemId::ID_msg));
        (r.direction == FrameDirection::Sent ? sent : received)++;
    }
    QCOMPARE(sent, 5);
    QCOMPARE(received, 5);

    // CSV export: without the key every row says enciphered and no item has
    // a value; with it every row is read, its ID_msg there.
    const auto csvRows = [&](const LogKey* logKey) {
        QBuffer out;
        out.open(QIODevice::WriteOnly);
        QString error;
        if (!exportFrameLogCsv(logPath, out, &error, logKey))
            qWarning() << error;
        return QString::fromLatin1(out.data()).split(QStringLiteral("\r\n"), Qt::SkipEmptyParts);
    };
    const QStringList plainRows = csvRows(nullptr);
    QCOMPARE(plainRows.size(), 11);
    QCOMPARE(plainRows.first(),
             QStringLiteral("utc,direction,transport,status,corrected_block1,corrected_block2,reading"));
    for (const QString& row : plainRows.mid(1))
        QVERIFY2(row.endsWith(QStringLiteral(",enciphered")), qPrintable(row));
    std::string keyError;
    const std::unique_ptr<LogKey> logKey = LogKey::open(key.toStdString(), keyError);
    QVERIFY2(logKey, keyError.c_str());
    const QStringList keyedRows = csvRows(logKey.get());
    QCOMPARE(keyedRows.size(), 11);
    const QStringList header = keyedRows.first().split(QLatin1Char(','));
    const qsizetype reading = header.indexOf(QStringLiteral("reading"));
    const qsizetype id = header.indexOf(QStringLiteral("HEADER.ID_msg"));
    QVERIFY(reading > 0 && id > 0);
    for (const QString& row : keyedRows.mid(1)) {
        const QStringList cells = row.split(QLatin1Char(','));
        QCOMPARE(cells.value(reading), QStringLiteral("read"));
        QVERIFY2(!cells.value(id).isEmpty(), qPrintable(row));
    }
}

void TestLinkSecure::differentKeysRejectEveryFrame()
{
    QTemporaryDir dir;
    const QString keyA = makeKey(dir, "a.key"), keyB = makeKey(dir, "b.key");
    const QString logPath = dir.filePath("gcs.pcapng");
    auto log = std::make_unique<FrameLog>();
    QVERIFY(log->open(logPath));
    Session s(keyA, keyB, std::move(log));
    s.fixture->run(5s);
    QCOMPARE(s.gcs->statistics().refusedFor(rcm::Refusal::Forged), quint64(5));
    QCOMPARE(s.ua->statistics().refusedFor(rcm::Refusal::Forged), quint64(5));
    // A rejected frame does not make or keep the link connected: silent for
    // 3 s, each side has lost it.
    QCOMPARE(s.gcs->statistics().state, LinkState::Lost);
    QCOMPARE(s.ua->statistics().state, LinkState::Lost);
    s.gcs->stop();
    s.ua->stop();
    for (const LinkWorker* w : {s.gcs, s.ua}) {
        const LinkStatistics& st = w->statistics();
        QCOMPARE(st.framesReceived, quint64(0));
        QCOMPARE(st.refusedFor(rcm::Refusal::Forged), rejectedTotal(st));
        QCOMPARE(st.refusedFor(rcm::Refusal::Uncorrectable), quint64(0));
    }
    QCOMPARE(s.uaReceived->count(), 0);
    QCOMPARE(s.gcsReceived->count(), 0);
    QCOMPARE(s.gcsRejected->count(), 5);
    QVERIFY(s.gcsRejected->at(0).at(0).toString().startsWith(QStringLiteral("forged: ")));

    int rejectedInLog = 0;
    for (const FrameRecord& r : readLog(logPath)) {
        if (r.direction == FrameDirection::Received) {
            QCOMPARE(r.status, FrameStatus::Rejected);
            ++rejectedInLog;
        }
    }
    QCOMPARE(rejectedInLog, 5);
}

void TestLinkSecure::plaintextSenderIsRejected()
{
    QTemporaryDir dir;
    const QString key = makeKey(dir, "aircraft.key");
    Session s(key, QString());
    s.fixture->run(3s);
    QCOMPARE(s.ua->statistics().refusedFor(rcm::Refusal::Plaintext), quint64(3));
    QCOMPARE(s.uaReceived->count(), 0);
    QCOMPARE(s.ua->statistics().refusedFor(rcm::Refusal::Forged), quint64(0));
    QVERIFY(s.uaRejected->at(0).at(0).toString().startsWith(QStringLiteral("plaintext: ")));
}

// The console's worker against a far end the test drives frame by frame.
void TestLinkSecure::replayedAndStaleFramesAreRejected()
{
    QTemporaryDir dir;
    const QString key = makeKey(dir, "aircraft.key");
    const std::shared_ptr<VirtualClock> clock = virtualClock();
    auto [consoleEnd, far] = test::InProcessLink::pair(test::InProcessLink::Kind::Datagrams);
    far->open();
    LinkWorker gcs(std::move(consoleEnd), nullptr, options(endpoint(key, Direction::GcsToUa, clock), clock));
    QSignalSpy received(&gcs, &LinkWorker::messageReceived);
    QSignalSpy rejected(&gcs, &LinkWorker::frameRejected);
    gcs.setCommand(command(1));
    gcs.start();

    std::string error;
    const SecureCodec down(*readKeyFile(key.toStdString(), error), Direction::UaToGcs);
    auto datagram = [&](std::uint32_t id, int offsetSeconds) {
        Message m = status();
        m.header.set(ItemId::ID_msg, id);
        stampNow(m, *clock, offsetSeconds);
        Diagnostics errors;
        const EncodedBlocks b = *down.encode(m, errors);
        const DatagramBytes d = makeDatagram(b.block1, b.block2);
        return QByteArray(reinterpret_cast<const char*>(d.data()), qsizetype(d.size()));
    };
    const QByteArray first = datagram(100, 0);
    far->write(first);
    QCOMPARE(received.count(), 1);
    far->write(first);  // replayed
    QCOMPARE(gcs.statistics().refusedFor(rcm::Refusal::Replayed), quint64(1));
    far->write(datagram(101, -int(kDefaultWindowSeconds) - 1));  // a second outside the window, never delivered
    QCOMPARE(gcs.statistics().refusedFor(rcm::Refusal::TimeWindow), quint64(1));
    // The next fresh one, at the window's edge; as many IDs on as seconds,
    // or it would not follow the first (docs/protocol.md section 8).
    far->write(datagram(100 + kDefaultWindowSeconds, int(kDefaultWindowSeconds)));
    QCOMPARE(received.count(), 2);
    QCOMPARE(received.at(1).at(0).value<ReceivedMessage>().message.header.number(ItemId::ID_msg),
             100 + kDefaultWindowSeconds);
    QCOMPARE(rejected.count(), 2);
    QVERIFY(rejected.at(0).at(0).toString().startsWith(QStringLiteral("replayed: ID_msg 100")));
    QVERIFY(rejected.at(1).at(0).toString().startsWith(QStringLiteral("stale time: ")));
    QCOMPARE(gcs.statistics().refusedFor(rcm::Refusal::Forged), quint64(0));
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
    const std::shared_ptr<VirtualClock> clock = virtualClock();
    auto uaLink = std::make_unique<UdpLink>(QHostAddress::LocalHost, 0);
    uaLink->setReplyToSender(true);
    LinkWorker ua(std::move(uaLink), nullptr, options(endpoint(key, Direction::UaToGcs, clock), clock));
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
    stampNow(m, *clock);
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
    clock->advance(1s);
    QCOMPARE(sent.count(), 1);
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
    QTRY_COMPARE_WITH_TIMEOUT(ua.statistics().refusedFor(rcm::Refusal::Forged), quint64(1), kPatience);
    injector.writeDatagram(genuineDatagram, QHostAddress::LocalHost, portOf(ua));
    QTRY_COMPARE_WITH_TIMEOUT(ua.statistics().refusedFor(rcm::Refusal::Replayed), quint64(1), kPatience);

    // A frame the aircraft sends after both refusals reaches the console...
    clock->advance(1s);
    QCOMPARE(sent.count(), 2);
    QTRY_VERIFY_WITH_TIMEOUT(consoleHeard(sent.at(1).at(0).toUInt()), kPatience);
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

// The built uasim at its own 1 Hz: one status frame is enough.
void TestLinkSecure::uasimWithMatchingKey()
{
    QTemporaryDir dir;
    const QString key = makeKey(dir, "aircraft.key");
    test::UasimProcess uasim({QStringLiteral("--key"), key});
    QVERIFY(uasim.start());
    QTRY_VERIFY_WITH_TIMEOUT(uasim.listening(), kPatience);
    std::string error;
    const std::string print = fingerprint(*readKeyFile(key.toStdString(), error));
    QVERIFY2(uasim.stderrText().contains("secure link: encrypted and authenticated, key fingerprint " +
                                         QByteArray::fromStdString(print)),
             uasim.stderrText().constData());

    LinkWorker gcs(std::make_unique<UdpLink>(QHostAddress::LocalHost, 0, QHostAddress::LocalHost, uasim.port()),
                   nullptr, options(endpoint(key, Direction::GcsToUa)));
    QSignalSpy received(&gcs, &LinkWorker::messageReceived);
    gcs.setCommand(command(30226));
    gcs.start();
    QTRY_VERIFY_WITH_TIMEOUT(received.count() >= 1, kPatience);
    gcs.stop();
    QCOMPARE(rejectedTotal(gcs.statistics()), quint64(0));
    // The status frames report the aircraft the commands reached.
    const ReceivedMessage last = received.last().at(0).value<ReceivedMessage>();
    QVERIFY(last.diagnostics.empty());
    QCOMPARE(last.message.engines.size(), std::size_t(3));

    QVERIFY(uasim.stop(kPatience));
    QVERIFY2(uasim.stderrText().contains("command "), uasim.stderrText().constData());  // --verbose lines
    QVERIFY(!uasim.stderrText().contains("command rejected"));
    QVERIFY(uasim.stderrText().contains("rejected commands: 0 forged, 0 replayed, 0 stale time, 0 plaintext"));
}

void TestLinkSecure::uasimWithDifferentKey()
{
    QTemporaryDir dir;
    const QString uaKey = makeKey(dir, "ua.key"), gcsKey = makeKey(dir, "gcs.key");
    test::UasimProcess uasim({QStringLiteral("--key"), uaKey});
    QVERIFY(uasim.start());
    QTRY_VERIFY_WITH_TIMEOUT(uasim.listening(), kPatience);

    LinkWorker gcs(std::make_unique<UdpLink>(QHostAddress::LocalHost, 0, QHostAddress::LocalHost, uasim.port()),
                   nullptr, options(endpoint(gcsKey, Direction::GcsToUa)));
    QSignalSpy received(&gcs, &LinkWorker::messageReceived);
    gcs.setCommand(command(30226));
    gcs.start();
    QTRY_VERIFY_WITH_TIMEOUT(uasim.stderrText().contains("command rejected: forged: "), kPatience);
    gcs.stop();
    // uasim answers only a sender whose frames it accepted: not this console.
    QCOMPARE(received.count(), 0);
    QCOMPARE(gcs.statistics().framesReceived, quint64(0));
    QCOMPARE(rejectedTotal(gcs.statistics()), quint64(0));

    QVERIFY(uasim.stop(kPatience));
    const QByteArray said = uasim.stderrText();
    const qsizetype at = said.indexOf("rejected commands: ");
    QVERIFY(at >= 0);
    const int forged = said.mid(at + 19).split(' ').value(0).toInt();
    QVERIFY2(forged >= 1, said.constData());
    QVERIFY(said.mid(at).startsWith("rejected commands: " + QByteArray::number(forged) +
                                    " forged, 0 replayed, 0 stale time, 0 plaintext"));
}

QTEST_GUILESS_MAIN(TestLinkSecure)
#include "tst_link_secure.moc"
