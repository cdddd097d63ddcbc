// The link layer end to end: a LinkController's worker thread against a far
// end in the test's thread, over UDP on loopback and over pseudo-terminals.
// Time only enters through QTRY's patience: the cadence runs at 50 ms so the
// tests are quick, and nothing asserts how long anything took. The silence
// timeout, the worker's own logic, runs against the simulated aircraft in
// simulated time instead.

// First: it names a member emit(), which Qt's headers define as a macro.
#include "codec/frame/StreamSync.h"

#include "codec/message/MessageDecoder.h"
#include "codec/message/MessageEncoder.h"
#include "link/clock/VirtualClock.h"
#include "link/framelog/FrameLog.h"
#include "link/framelog/FrameLogReader.h"
#include "link/session/LinkController.h"
#include "link/session/LinkWorker.h"
#include "link/transport/SerialLink.h"
#include "link/transport/UdpLink.h"

#include "AircraftFixture.h"

#include <QDate>
#include <QDateTime>
#include <QFile>
#include <QSignalSpy>
#include <QSocketNotifier>
#include <QTemporaryDir>
#include <QTest>
#include <QUdpSocket>

#include <atomic>
#include <cerrno>
#include <map>
#include <fcntl.h>
#include <pty.h>
#include <unistd.h>

using namespace std::chrono_literals;

namespace {

constexpr auto kFastTick = 50ms;
constexpr int kPatience = 10000;  // ms QTRY waits for what a loaded machine may delay

rcm::Message command(int gcsUnit)
{
    rcm::Message m;
    m.header.set(rcm::ItemId::ID_UA_source, rcm::Value::pair(44, 133));
    m.header.set(rcm::ItemId::ID_GCS_destination, rcm::Value::pair(44, gcsUnit));
    return m;
}

// When the test function began (init()): the receive path refuses a frame
// outside the window of its clock (docs/protocol.md section 8), and these
// tests run on the system clock. One stamp for all of a test's frames, so
// that a frame built twice is the same bytes.
QDateTime g_stamp;

rcm::Message aircraftMessage(std::uint32_t id)
{
    const QDateTime now = g_stamp;
    const QDate d = now.date();
    const QTime t = now.time();
    rcm::Message m;
    m.header.set(rcm::ItemId::ID_msg, std::int64_t(id));
    m.header.set(rcm::ItemId::ID_UA_source, rcm::Value::pair(44, 133));
    m.header.set(rcm::ItemId::time_UTC, std::int64_t(t.hour() * 10000 + t.minute() * 100 + t.second()));
    m.header.set(rcm::ItemId::date_UTC, std::int64_t((d.year() % 100) * 10000 + d.month() * 100 + d.day()));
    return m;
}

template <std::size_t N>
QByteArray toByteArray(const std::array<std::uint8_t, N>& bytes)
{
    return QByteArray(reinterpret_cast<const char*>(bytes.data()), qsizetype(N));
}

QByteArray aircraftDatagram(std::uint32_t id)
{
    rcm::Diagnostics errors;
    return toByteArray(rcm::encodeDatagram(aircraftMessage(id), errors).value());
}

QByteArray aircraftFrame(std::uint32_t id)
{
    rcm::Diagnostics errors;
    return toByteArray(rcm::encodeFrame(aircraftMessage(id), errors).value());
}

rcm::DecodeResult decode(const QByteArray& bytes)
{
    return rcm::decodeFrame({reinterpret_cast<const std::uint8_t*>(bytes.constData()), std::size_t(bytes.size())});
}

std::int64_t messageId(const rcm::Message& m)
{
    return m.header.number(rcm::ItemId::ID_msg, -1);
}

// yymmdd of today in UTC.
std::int64_t todayYymmdd()
{
    const QDate d = QDateTime::currentDateTimeUtc().date();
    return (d.year() % 100) * 10000 + d.month() * 100 + d.day();
}

// Items the worker fills in: present, and the time a real hhmmss.
void verifyStamped(const rcm::Message& m)
{
    QVERIFY(m.header.has(rcm::ItemId::ID_msg));
    QVERIFY(m.header.has(rcm::ItemId::time_UTC));
    QVERIFY(m.header.has(rcm::ItemId::date_UTC));
    const std::int64_t t = m.header.number(rcm::ItemId::time_UTC);
    QVERIFY(t / 10000 < 24 && t / 100 % 100 < 60 && t % 100 < 60);
}

ReceivedMessage receivedAt(const QSignalSpy& spy, int i)
{
    return spy.at(i).at(0).value<ReceivedMessage>();
}

LoggedFrame loggedAt(const QSignalSpy& spy, int i)
{
    return spy.at(i).at(0).value<LoggedFrame>();
}

void compareEntries(const FrameIndexEntry& a, const FrameIndexEntry& b)
{
    QCOMPARE(a.offset, b.offset);
    QCOMPARE(a.utcMicros, b.utcMicros);
    QCOMPARE(a.length, b.length);
    QCOMPARE(a.direction, b.direction);
    QCOMPARE(a.transport, b.transport);
    QCOMPARE(a.status, b.status);
}

QVector<FrameRecord> readLog(const QString& path)
{
    FrameLogReader reader;
    if (!reader.open(path))
        qWarning() << reader.errorString();
    return reader.readAll();
}

QVector<FrameRecord> only(const QVector<FrameRecord>& records, FrameDirection direction)
{
    QVector<FrameRecord> out;
    for (const FrameRecord& r : records) {
        if (r.direction == direction)
            out.append(r);
    }
    return out;
}

std::unique_ptr<FrameLog> openLog(const QString& path)
{
    auto log = std::make_unique<FrameLog>();
    QString error;
    if (!log->open(path, &error))
        qWarning() << error;
    return log;
}

LinkWorker::Options fastOptions()
{
    LinkWorker::Options options;
    options.interval = kFastTick;
    options.statisticsInterval = 20ms;
    return options;
}

// The aircraft's end of a pseudo-terminal: the master side. Reads what the
// GCS sends through its own synchroniser, and can answer every frame.
class PtyFarEnd {
public:
    PtyFarEnd() : m_sync([this](const rcm::SyncedFrame& f) { onFrame(f); }) {}
    ~PtyFarEnd() { close(); }

    bool open()
    {
        char name[256] = {};
        if (::openpty(&m_master, &m_slave, name, nullptr, nullptr) != 0)
            return false;
        ::fcntl(m_master, F_SETFL, ::fcntl(m_master, F_GETFL) | O_NONBLOCK);
        m_slavePath = QString::fromLocal8Bit(name);
        m_notifier = std::make_unique<QSocketNotifier>(m_master, QSocketNotifier::Read);
        QObject::connect(m_notifier.get(), &QSocketNotifier::activated, [this] { readMaster(); });
        return true;
    }

    // Closing the master hangs the slave up: to the port, the modem is gone.
    void close()
    {
        m_notifier.reset();
        if (m_master >= 0)
            ::close(m_master);
        if (m_slave >= 0)
            ::close(m_slave);
        m_master = m_slave = -1;
    }

    QString slavePath() const { return m_slavePath; }
    const std::vector<rcm::DecodeResult>& received() const { return m_received; }
    void setReplying(bool on) { m_replying = on; }

    void write(const QByteArray& bytes)
    {
        qsizetype done = 0;
        while (done < bytes.size()) {
            const ssize_t n = ::write(m_master, bytes.constData() + done, std::size_t(bytes.size() - done));
            if (n < 0 && errno != EINTR && errno != EAGAIN)
                return;
            done += n > 0 ? n : 0;
        }
    }

private:
    void readMaster()
    {
        char buffer[4096];
        const ssize_t n = ::read(m_master, buffer, sizeof buffer);
        if (n > 0)
            m_sync.feed({reinterpret_cast<const std::uint8_t*>(buffer), std::size_t(n)});
    }

    void onFrame(const rcm::SyncedFrame& frame)
    {
        m_received.push_back(rcm::decodeBlocks(frame.blocks));
        if (m_replying)
            write(aircraftFrame(m_replies++));
    }

    int m_master = -1;
    int m_slave = -1;  // held so the master never sees "no slave" before the port opens
    QString m_slavePath;
    std::unique_ptr<QSocketNotifier> m_notifier;
    rcm::StreamSync m_sync;
    std::vector<rcm::DecodeResult> m_received;
    bool m_replying = false;
    std::uint32_t m_replies = 0;
};

// The aircraft's end of a UDP link: answers whoever sent the last datagram.
struct UdpFarEnd {
    UdpLink link{QHostAddress::LocalHost, 0};
    QSignalSpy datagrams{&link, &Link::datagramReceived};

    UdpFarEnd()
    {
        link.setReplyToSender(true);
        link.open();
    }
    quint16 port() const { return link.boundPort(); }
    QByteArray datagram(int i) const { return datagrams.at(i).at(0).toByteArray(); }
};

std::unique_ptr<UdpLink> udpTo(quint16 port)
{
    return std::make_unique<UdpLink>(QHostAddress::LocalHost, 0, QHostAddress::LocalHost, port);
}

}  // namespace

class TestLink : public QObject {
    Q_OBJECT

private slots:
    void initTestCase() { LinkWorker::registerMetaTypes(); }
    void init() { g_stamp = QDateTime::currentDateTimeUtc(); }

    void defaults();
    void udpFramesArriveDecodeAndCountUp();
    void udpDatagramsFromStrangersAreDroppedUnread();
    void messageIdWrapsAt24Bits();
    void wrongSizeAndUndecodableDatagramsAreCountedNotFatal();
    void everyLoggedFrameIsSignalledWithItsOffset();
    void withoutALogTheSignalCarriesTheBytes();
    void commandFromGuiThreadReachesTheFrames();
    void silenceReportsLostOnceThenRegained();
    void silenceBeforeAnyFrameIsLost();
    void block2HooksCarryTheFlightPlan();
    void stopClosesAndReportsClosed();
    void serialFramesSynchronisedAcrossChunks();
    void serialPortVanishesAndComesBack();
};

void TestLink::defaults()
{
    const LinkWorker::Options options;
    QCOMPARE(options.interval, 1000ms);
    QCOMPARE(options.silenceTimeout, 3000ms);
    QVERIFY(options.statisticsInterval >= 200ms);  // "a few times a second" at most
    QCOMPARE(LinkWorker::kMessageIdModulus, 1u << 24);

    SerialLink serial(QStringLiteral("ttyS0"));
    QCOMPARE(serial.baudRate(), 9600);
    QCOMPARE(serial.reopenInterval(), 1000ms);
    QCOMPARE(serial.transport(), FrameTransport::Serial);
    QVERIFY(serial.isStream());
    QVERIFY(!serial.isOpen());
    QCOMPARE(serial.description(), QStringLiteral("ttyS0 9600 8N1"));
    for (const QSerialPortInfo& info : SerialLink::availablePorts())
        QVERIFY(!info.portName().isEmpty());

    UdpLink udp(QHostAddress::LocalHost, 0);
    QCOMPARE(udp.transport(), FrameTransport::Udp);
    QVERIFY(!udp.isStream());
    QCOMPARE(udp.boundPort(), quint16(0));
    QVERIFY(!udp.write(QByteArray(510, 'x')));  // closed
    udp.open();
    QVERIFY(udp.isOpen());
    QVERIFY(udp.boundPort() != 0);
    QVERIFY(!udp.write(QByteArray(510, 'x')));  // nobody to send to
}

// A console's link listens to its aircraft only: datagrams from any other
// address or port are dropped before they are read, counted, and reported
// once; the aircraft's own still arrive.
void TestLink::udpDatagramsFromStrangersAreDroppedUnread()
{
    UdpFarEnd far;
    UdpLink console(QHostAddress::LocalHost, 0, QHostAddress::LocalHost, far.port());
    QSignalSpy datagrams(&console, &Link::datagramReceived);
    QSignalSpy errors(&console, &Link::errorOccurred);
    console.open();
    QVERIFY(console.isOpen());

    QUdpSocket stranger;
    QVERIFY(stranger.bind(QHostAddress::LocalHost, 0));
    for (int i = 0; i < 3; ++i)
        QCOMPARE(stranger.writeDatagram(aircraftDatagram(200 + i), QHostAddress::LocalHost, console.boundPort()), 510);
    far.link.setRemote(QHostAddress::LocalHost, console.boundPort());
    QVERIFY(far.link.write(aircraftDatagram(100)));

    QTRY_COMPARE_WITH_TIMEOUT(datagrams.count(), 1, kPatience);
    QCOMPARE(datagrams.at(0).at(0).toByteArray(), aircraftDatagram(100));
    QCOMPARE(console.strangerDatagrams(), quint64(3));
    QCOMPARE(errors.count(), 1);
    QCOMPARE(errors.at(0).at(0).toString(),
             QStringLiteral("udp: datagrams from 127.0.0.1:%1 dropped unread: only 127.0.0.1:%2 is listened to "
                            "(every further one is counted, not reported)")
                 .arg(stranger.localPort())
                 .arg(far.port()));
}

void TestLink::udpFramesArriveDecodeAndCountUp()
{
    QTemporaryDir dir;
    const QString logPath = dir.filePath(QStringLiteral("session.pcapng"));
    UdpFarEnd far;
    QVector<ReceivedMessage> fromAircraft;
    int framesSent = 0;
    {
        LinkController controller(udpTo(far.port()), openLog(logPath), fastOptions());
        QSignalSpy received(&controller, &LinkController::messageReceived);
        QSignalSpy errors(&controller, &LinkController::errorOccurred);
        controller.setCommand(command(2));
        controller.start();

        QTRY_VERIFY_WITH_TIMEOUT(far.datagrams.count() >= 5, kPatience);
        for (int i = 0; i < far.datagrams.count(); ++i) {
            const QByteArray bytes = far.datagram(i);
            QCOMPARE(bytes.size(), 510);
            const rcm::DecodeResult r = decode(bytes);
            QVERIFY(r.ok());
            QCOMPARE(r.corrected.block1, 0);
            QCOMPARE(r.corrected.block2, 0);
            QVERIFY(r.diagnostics.empty());
            QCOMPARE(messageId(r.message), i);
            verifyStamped(r.message);
            const std::int64_t date = r.message.header.number(rcm::ItemId::date_UTC);
            QVERIFY(date == todayYymmdd() || date + 1 >= todayYymmdd());  // midnight may have passed since
            QCOMPARE(*r.message.header.find(rcm::ItemId::ID_GCS_destination), rcm::Value::pair(44, 2));
            QCOMPARE(*r.message.header.find(rcm::ItemId::ID_UA_source), rcm::Value::pair(44, 133));
        }

        // The aircraft answers: once clean, once with 3 + 2 bytes to correct.
        QVERIFY(far.link.write(aircraftDatagram(100)));
        QByteArray damaged = aircraftDatagram(101);
        for (int at : {3, 77, 200, 255 + 9, 255 + 250})
            damaged[at] = char(damaged[at] ^ 0x5A);
        QVERIFY(far.link.write(damaged));
        QTRY_COMPARE_WITH_TIMEOUT(received.count(), 2, kPatience);
        fromAircraft = {receivedAt(received, 0), receivedAt(received, 1)};
        QCOMPARE(fromAircraft[0].message, aircraftMessage(100));
        QCOMPARE(fromAircraft[0].corrected.block1, 0);
        QCOMPARE(fromAircraft[0].corrected.block2, 0);
        QCOMPARE(fromAircraft[0].transport, FrameTransport::Udp);
        QVERIFY(fromAircraft[0].utcMicros > 0);
        QCOMPARE(fromAircraft[1].message, aircraftMessage(101));
        QCOMPARE(fromAircraft[1].corrected.block1, 3);
        QCOMPARE(fromAircraft[1].corrected.block2, 2);

        QTRY_VERIFY_WITH_TIMEOUT(controller.statistics().framesReceived == 2, kPatience);
        QTRY_VERIFY_WITH_TIMEOUT(controller.statistics().framesSent >= quint64(far.datagrams.count()), kPatience);
        const LinkStatistics s = controller.statistics();
        QCOMPARE(s.state, LinkState::Connected);
        QCOMPARE(s.correctedBytesBlock1, quint64(3));
        QCOMPARE(s.correctedBytesBlock2, quint64(2));
        QCOMPARE(s.refusedFor(rcm::Refusal::Uncorrectable), quint64(0));
        QCOMPARE(s.refusedFor(rcm::Refusal::WrongSize), quint64(0));
        QCOMPARE(s.bytesSkipped, quint64(0));
        QVERIFY(s.lastGoodFrameUtcMicros >= fromAircraft[1].utcMicros);
        QCOMPARE(s.sendDelaySamples, s.framesSent);
        QVERIFY(s.sendDelayMinMicros >= 0);
        QVERIFY(s.sendDelayMinMicros <= s.sendDelayMeanMicros() && s.sendDelayMeanMicros() <= s.sendDelayMaxMicros);
        QCOMPARE(errors.count(), 0);
    }
    // Everything sent reached the far end and the log, byte for byte.
    const QVector<FrameRecord> log = readLog(logPath);
    const QVector<FrameRecord> sent = only(log, FrameDirection::Sent);
    framesSent = int(sent.size());
    QTRY_COMPARE_WITH_TIMEOUT(int(far.datagrams.count()), framesSent, kPatience);
    for (int i = 0; i < framesSent; ++i) {
        QCOMPARE(sent[i].bytes, far.datagram(i));
        QCOMPARE(sent[i].transport, FrameTransport::Udp);
        QCOMPARE(sent[i].status, FrameStatus::NotChecked);
    }
    const QVector<FrameRecord> got = only(log, FrameDirection::Received);
    QCOMPARE(got.size(), 2);
    QCOMPARE(got[0].bytes, aircraftDatagram(100));
    QCOMPARE(got[0].status, FrameStatus::Decoded);
    QCOMPARE(got[0].correctedSymbols, QList<int>({0, 0}));
    QCOMPARE(got[1].status, FrameStatus::Corrected);
    QCOMPARE(got[1].correctedSymbols, QList<int>({3, 2}));
}

// On a VirtualClock the worker's thread runs exactly the ticks the test
// steps: three frames, on the second.
void TestLink::messageIdWrapsAt24Bits()
{
    UdpFarEnd far;
    const auto clock = std::make_shared<VirtualClock>(rcm::test::kFixtureStartUtcMicros);
    LinkWorker::Options options;
    options.clock = clock;
    options.firstMessageId = 0xFFFFFE;
    LinkController controller(udpTo(far.port()), nullptr, options);
    QCOMPARE(controller.firstMessageId(), 0xFFFFFEu);
    QSignalSpy started(&controller, &LinkController::started);
    controller.setCommand(command(2));
    controller.start();
    QTRY_COMPARE_WITH_TIMEOUT(started.count(), 1, kPatience);
    clock->advance(3s);
    QTRY_COMPARE_WITH_TIMEOUT(far.datagrams.count(), 3, kPatience);
    for (int i = 0; i < 3; ++i) {
        const rcm::Message m = decode(far.datagram(i)).message;
        QCOMPARE(messageId(m), std::int64_t(i == 2 ? 0 : 0xFFFFFE + i));
        QCOMPARE(m.header.number(rcm::ItemId::time_UTC), 73201 + i);
        QCOMPARE(m.header.number(rcm::ItemId::date_UTC), 261122);
    }
}

void TestLink::wrongSizeAndUndecodableDatagramsAreCountedNotFatal()
{
    QTemporaryDir dir;
    const QString logPath = dir.filePath(QStringLiteral("session.pcapng"));
    UdpFarEnd far;
    const QByteArray shortOne(100, '\x55');
    const QByteArray serialFrame = aircraftFrame(1);  // 600 bytes: right for serial, wrong for UDP
    QByteArray garbage(510, '\0');
    for (int i = 0; i < garbage.size(); ++i)
        garbage[i] = char((i * 97 + 13) & 0xFF);
    {
        LinkController controller(udpTo(far.port()), openLog(logPath), fastOptions());
        QSignalSpy received(&controller, &LinkController::messageReceived);
        QSignalSpy errors(&controller, &LinkController::errorOccurred);
        QSignalSpy rejected(&controller, &LinkController::frameRejected);
        controller.setCommand(command(2));
        controller.start();
        QTRY_VERIFY_WITH_TIMEOUT(far.datagrams.count() >= 1, kPatience);  // the far end knows where to answer

        QVERIFY(far.link.write(shortOne));
        QVERIFY(far.link.write(serialFrame));
        QVERIFY(far.link.write(garbage));
        QVERIFY(far.link.write(aircraftDatagram(7)));
        QTRY_COMPARE_WITH_TIMEOUT(received.count(), 1, kPatience);
        QCOMPARE(receivedAt(received, 0).message, aircraftMessage(7));
        QTRY_VERIFY_WITH_TIMEOUT(controller.statistics().framesReceived == 1, kPatience);
        const LinkStatistics s = controller.statistics();
        QCOMPARE(s.refusedFor(rcm::Refusal::WrongSize), quint64(2));
        QCOMPARE(s.refusedFor(rcm::Refusal::Uncorrectable), quint64(1));
        QCOMPARE(s.refusedTotal(), quint64(3));
        QCOMPARE(s.state, LinkState::Connected);
        QCOMPARE(rejected.count(), 3);
        QCOMPARE(rejected.at(0).at(0).toString(), QStringLiteral("wrong size: 100 bytes; a datagram is 510"));
        QCOMPARE(rejected.at(1).at(0).toString(), QStringLiteral("wrong size: 600 bytes; a datagram is 510"));
        QCOMPARE(rejected.at(2).at(0).toString(),
                 QStringLiteral("uncorrectable: block 1 beyond correction, block 2 not read"));
        QCOMPARE(errors.count(), 0);

        // And frames keep going out.
        const int before = int(far.datagrams.count());
        QTRY_VERIFY_WITH_TIMEOUT(far.datagrams.count() > before, kPatience);
    }
    const QVector<FrameRecord> got = only(readLog(logPath), FrameDirection::Received);
    QCOMPARE(got.size(), 4);
    QCOMPARE(got[0].bytes, shortOne);
    QCOMPARE(got[0].status, FrameStatus::Rejected);
    QCOMPARE(got[1].bytes, serialFrame);
    QCOMPARE(got[1].status, FrameStatus::Rejected);
    QCOMPARE(got[2].bytes, garbage);
    QCOMPARE(got[2].status, FrameStatus::Uncorrectable);
    QVERIFY(got[2].correctedSymbols.contains(-1));
    QCOMPARE(got[3].status, FrameStatus::Decoded);
}

void TestLink::everyLoggedFrameIsSignalledWithItsOffset()
{
    QTemporaryDir dir;
    const QString logPath = dir.filePath(QStringLiteral("session.pcapng"));
    UdpFarEnd far;
    QByteArray corrected = aircraftDatagram(6);
    for (int at : {5, 300})
        corrected[at] = char(corrected[at] ^ 0x33);
    QByteArray garbage(510, '\0');
    for (int i = 0; i < garbage.size(); ++i)
        garbage[i] = char((i * 89 + 7) & 0xFF);
    const QByteArray shortOne(100, '\x55');

    LinkController controller(udpTo(far.port()), openLog(logPath), fastOptions());
    QSignalSpy logged(&controller, &LinkController::frameLogged);
    QSignalSpy stopped(&controller, &LinkController::stopped);
    controller.setCommand(command(2));
    controller.start();
    QTRY_VERIFY_WITH_TIMEOUT(far.datagrams.count() >= 1, kPatience);
    for (const QByteArray& datagram : {aircraftDatagram(5), corrected, garbage, shortOne})
        QVERIFY(far.link.write(datagram));
    QTRY_VERIFY_WITH_TIMEOUT(controller.statistics().refusedFor(rcm::Refusal::WrongSize) == 1, kPatience);

    // While the link is still writing the log, the last frame signalled is
    // already there to read at its offset.
    {
        const LoggedFrame last = loggedAt(logged, int(logged.count()) - 1);
        QVERIFY(last.inLog());
        FrameLogReader live;
        QVERIFY2(live.openLive(logPath), qPrintable(live.errorString()));
        const std::optional<FrameRecord> record = live.recordAt(last.entry);
        QVERIFY2(record, qPrintable(live.errorString()));
        QCOMPARE(record->bytes.size(), qsizetype(last.entry.length));
        // The bytes travel with the signal too (for the broker), the same as in the file.
        QCOMPARE(last.bytes, record->bytes);
        QCOMPARE(record->direction, last.entry.direction);
        QCOMPARE(record->correctedSymbols, last.correctedSymbols);
        // An offset where no such frame starts is refused, not misread.
        FrameIndexEntry wrong = last.entry;
        wrong.offset += 4;
        QVERIFY(!live.recordAt(wrong));
        QVERIFY(!live.errorString().isEmpty());
    }

    // Every signal before stopped() has arrived once stopped() has: same sender, same receiver.
    controller.stop();
    QTRY_COMPARE_WITH_TIMEOUT(stopped.count(), 1, kPatience);
    FrameLogReader reader;
    QVERIFY2(reader.open(logPath), qPrintable(reader.errorString()));
    QCOMPARE(int(logged.count()), reader.count());
    // Every frame sent has reached the far end.
    QTRY_COMPARE_WITH_TIMEOUT(far.datagrams.count(), only(reader.readAll(), FrameDirection::Sent).size(), kPatience);
    std::map<FrameStatus, int> statuses;
    int sent = 0;
    for (int i = 0; i < reader.count(); ++i) {
        const LoggedFrame frame = loggedAt(logged, i);
        compareEntries(frame.entry, reader.index()[i]);
        const std::optional<FrameRecord> record = reader.recordAt(frame.entry);
        QVERIFY2(record, qPrintable(reader.errorString()));
        QCOMPARE(frame.bytes, record->bytes);  // in the file, and in the signal as well
        QCOMPARE(*record, reader.recordAt(i));
        QCOMPARE(frame.correctedSymbols, record->correctedSymbols);
        ++statuses[frame.entry.status];
        if (frame.entry.direction == FrameDirection::Sent) {
            QCOMPARE(record->bytes, far.datagram(sent++));
            QVERIFY(frame.messageId);
            QCOMPARE(std::int64_t(*frame.messageId), messageId(decode(record->bytes).message));
        }
        switch (frame.entry.status) {
            case FrameStatus::Decoded:
                QCOMPARE(record->bytes, aircraftDatagram(5));
                QCOMPARE(frame.messageId, std::optional<quint32>(5));
                break;
            case FrameStatus::Corrected:
                QCOMPARE(record->bytes, corrected);
                QCOMPARE(frame.messageId, std::optional<quint32>(6));
                QCOMPARE(frame.correctedSymbols, QList<int>({1, 1}));
                break;
            case FrameStatus::Uncorrectable:
                QCOMPARE(record->bytes, garbage);
                QVERIFY(frame.correctedSymbols.contains(-1));
                QCOMPARE(frame.messageId, std::nullopt);
                break;
            case FrameStatus::Rejected:
                QCOMPARE(record->bytes, shortOne);
                QCOMPARE(frame.messageId, std::nullopt);
                break;
            case FrameStatus::NotChecked:
                QCOMPARE(frame.entry.direction, FrameDirection::Sent);
                break;
        }
    }
    for (FrameStatus s :
         {FrameStatus::Decoded, FrameStatus::Corrected, FrameStatus::Uncorrectable, FrameStatus::Rejected})
        QCOMPARE(statuses[s], 1);
    QCOMPARE(statuses[FrameStatus::NotChecked], sent);
}

void TestLink::withoutALogTheSignalCarriesTheBytes()
{
    UdpFarEnd far;
    LinkController controller(udpTo(far.port()), nullptr, fastOptions());
    QSignalSpy logged(&controller, &LinkController::frameLogged);
    QSignalSpy stopped(&controller, &LinkController::stopped);
    controller.setCommand(command(2));
    controller.start();
    QTRY_VERIFY_WITH_TIMEOUT(far.datagrams.count() >= 2, kPatience);
    QVERIFY(far.link.write(aircraftDatagram(9)));
    QTRY_VERIFY_WITH_TIMEOUT(controller.statistics().framesReceived == 1, kPatience);
    controller.stop();
    QTRY_COMPARE_WITH_TIMEOUT(stopped.count(), 1, kPatience);
    QTRY_COMPARE_WITH_TIMEOUT(quint64(far.datagrams.count()), controller.statistics().framesSent, kPatience);

    int sent = 0, received = 0;
    for (int i = 0; i < logged.count(); ++i) {
        const LoggedFrame frame = loggedAt(logged, i);
        QVERIFY(!frame.inLog());
        QCOMPARE(frame.entry.offset, qint64(-1));
        QCOMPARE(qsizetype(frame.entry.length), frame.bytes.size());
        if (frame.entry.direction == FrameDirection::Sent) {
            QCOMPARE(frame.bytes, far.datagram(sent++));
        } else {
            QCOMPARE(frame.bytes, aircraftDatagram(9));
            QCOMPARE(frame.entry.status, FrameStatus::Decoded);
            ++received;
        }
    }
    QCOMPARE(quint64(sent), controller.statistics().framesSent);
    QCOMPARE(received, 1);
}

void TestLink::commandFromGuiThreadReachesTheFrames()
{
    UdpFarEnd far;
    LinkController controller(udpTo(far.port()), nullptr, fastOptions());
    QSignalSpy rejected(&controller, &LinkController::commandRejected);
    const auto destinationOf = [&](int i) {
        return far.datagram(i).isEmpty()
                   ? -1
                   : decode(far.datagram(i)).message.header.find(rcm::ItemId::ID_GCS_destination)->second;
    };
    controller.setCommand(command(2));
    controller.start();
    QTRY_VERIFY_WITH_TIMEOUT(far.datagrams.count() >= 2, kPatience);
    QCOMPARE(destinationOf(0), 2);

    controller.setCommand(command(3));
    const auto firstWith3 = [&] {
        for (int i = 0; i < far.datagrams.count(); ++i) {
            if (destinationOf(i) == 3)
                return i;
        }
        return -1;
    };
    QTRY_VERIFY_WITH_TIMEOUT(firstWith3() >= 0, kPatience);

    // Out of range: refused with the reason, and the last good command stays.
    rcm::Message bad = command(4);
    bad.header.set(rcm::ItemId::ID_UA_source, rcm::Value::pair(0, 133));
    controller.setCommand(bad);
    QTRY_COMPARE_WITH_TIMEOUT(rejected.count(), 1, kPatience);
    QVERIFY(rejected.at(0).at(0).toString().contains(QStringLiteral("ID_UA_source")));
    const int afterRejection = int(far.datagrams.count());
    QTRY_VERIFY_WITH_TIMEOUT(far.datagrams.count() >= afterRejection + 2, kPatience);

    // From the first frame with the new command on, every frame has it, and
    // the IDs never skipped.
    const int first = firstWith3();
    QVERIFY(first > 0);
    for (int i = 0; i < far.datagrams.count(); ++i) {
        QCOMPARE(destinationOf(i), i < first ? 2 : 3);
        QCOMPARE(messageId(decode(far.datagram(i)).message), i);
    }
}

// Silence is the worker's own affair, so these run against the simulated
// aircraft in simulated time (AircraftFixture), to the microsecond.
void TestLink::silenceReportsLostOnceThenRegained()
{
    rcm::test::AircraftFixture f;
    QSignalSpy lost(f.console.get(), &LinkWorker::linkLost);
    QSignalSpy regained(f.console.get(), &LinkWorker::linkRegained);
    QSignalSpy states(f.console.get(), &LinkWorker::stateChanged);
    f.console->setCommand(command(2));
    f.start();
    f.run(3s);  // 07:32:03.250: the aircraft's frames of 07:32:01, :02 and :03 heard
    QCOMPARE(f.console->statistics().framesReceived, quint64(3));
    QCOMPARE(f.console->statistics().state, LinkState::Connected);

    // The aircraft falls silent; lost 3 s after the last frame heard, not before.
    f.aircraftWorker->stop();
    f.run(2749ms);
    QCOMPARE(lost.count(), 0);
    f.run(1ms);
    QCOMPARE(lost.count(), 1);
    QCOMPARE(f.console->statistics().state, LinkState::Lost);
    // Silence goes on for several more timeouts: still one report.
    f.run(10s);
    QCOMPARE(lost.count(), 1);
    QCOMPARE(regained.count(), 0);

    // Back on the air, its ID_msg one on but its time 14 s on: the console
    // heard nothing for 14 s, which allows it, so its first frame is
    // delivered (a satellite phone redialled: the aircraft sent nothing meanwhile).
    QSignalSpy rejected(f.console.get(), &LinkWorker::frameRejected);
    f.aircraftWorker->start();
    f.run(1000ms);
    QCOMPARE(regained.count(), 1);
    QCOMPARE(rejected.count(), 0);
    QCOMPARE(f.console->statistics().refusedTotal(), quint64(0));
    QCOMPARE(f.console->statistics().framesReceived, quint64(4));
    f.run(3s);
    QCOMPARE(lost.count(), 1);
    QCOMPARE(regained.count(), 1);
    QCOMPARE(f.console->statistics().state, LinkState::Connected);

    QList<LinkState> seen;
    for (const QList<QVariant>& args : states)
        seen << args.at(0).value<LinkState>();
    QCOMPARE(seen, QList<LinkState>({LinkState::Waiting, LinkState::Connected, LinkState::Lost, LinkState::Connected}));
}

void TestLink::silenceBeforeAnyFrameIsLost()
{
    rcm::test::AircraftFixture f;  // the aircraft is never started
    QSignalSpy lost(f.console.get(), &LinkWorker::linkLost);
    f.console->setCommand(command(2));
    f.console->start();
    f.run(2999ms);
    QCOMPARE(lost.count(), 0);
    f.run(1ms);
    QCOMPARE(lost.count(), 1);
    QCOMPARE(f.console->statistics().state, LinkState::Lost);
    QCOMPARE(f.console->statistics().lastGoodFrameAgeMicros(0), qint64(-1));
}

void TestLink::block2HooksCarryTheFlightPlan()
{
    UdpFarEnd far;
    const rcm::FlightPlanSection section{7, 0, {1, 2, 3, 4, 5, 6, 7, 8, 9, 10}};
    std::atomic<int> asked{0};
    std::atomic<int> replies{0};
    LinkWorker::Options options = fastOptions();
    options.block2Source = [&]() -> std::optional<rcm::FlightPlanSection> {
        return ++asked % 2 ? std::optional(section) : std::nullopt;
    };
    options.block2Reply = [&](const rcm::FlightPlanSection& reply) {
        if (reply.planId == 9)
            ++replies;
    };
    LinkController controller(udpTo(far.port()), nullptr, options);
    controller.setCommand(command(2));
    controller.start();
    QTRY_VERIFY_WITH_TIMEOUT(far.datagrams.count() >= 2, kPatience);
    QCOMPARE(decode(far.datagram(0)).message.flightPlan, section);
    QVERIFY(decode(far.datagram(1)).message.flightPlan.empty());

    rcm::Message answer = aircraftMessage(1);
    answer.flightPlan = {9, 0xFFFF, std::vector<std::uint8_t>(10, 0)};
    rcm::Diagnostics errors;
    far.link.write(toByteArray(rcm::encodeDatagram(answer, errors).value()));
    QTRY_COMPARE_WITH_TIMEOUT(replies.load(), 1, kPatience);
}

void TestLink::stopClosesAndReportsClosed()
{
    UdpFarEnd far;
    LinkController controller(udpTo(far.port()), nullptr, fastOptions());
    QSignalSpy started(&controller, &LinkController::started);
    QSignalSpy stopped(&controller, &LinkController::stopped);
    QSignalSpy lost(&controller, &LinkController::linkLost);
    controller.setCommand(command(2));
    controller.start();
    QTRY_COMPARE_WITH_TIMEOUT(started.count(), 1, kPatience);
    QTRY_VERIFY_WITH_TIMEOUT(far.datagrams.count() >= 1, kPatience);
    controller.stop();
    QTRY_COMPARE_WITH_TIMEOUT(stopped.count(), 1, kPatience);
    QTRY_COMPARE_WITH_TIMEOUT(controller.statistics().state, LinkState::Closed, kPatience);
    QCOMPARE(lost.count(), 0);  // stopping is not losing

    // Restartable, and the IDs go on.
    const int before = int(far.datagrams.count());
    controller.start();
    QTRY_VERIFY_WITH_TIMEOUT(far.datagrams.count() > before, kPatience);
    QCOMPARE(messageId(decode(far.datagram(before)).message), before);
}

void TestLink::serialFramesSynchronisedAcrossChunks()
{
    QTemporaryDir dir;
    const QString logPath = dir.filePath(QStringLiteral("session.pcapng"));
    PtyFarEnd far;
    QVERIFY(far.open());
    const QByteArray junk(37, '\x3C');
    QByteArray stream = junk;
    for (std::uint32_t id = 0; id < 6; ++id) {
        QByteArray frame = aircraftFrame(id);
        if (id == 2) {
            for (int at : {90 + 10, 90 + 20, 90 + 30, 90 + 255 + 5})
                frame[at] = char(frame[at] ^ 0xFF);
        }
        stream += frame;
    }
    {
        LinkController controller(std::make_unique<SerialLink>(far.slavePath()), openLog(logPath), fastOptions());
        QSignalSpy received(&controller, &LinkController::messageReceived);
        QSignalSpy errors(&controller, &LinkController::errorOccurred);
        QSignalSpy lost(&controller, &LinkController::linkLost);
        controller.setCommand(command(2));
        controller.start();
        // A frame out means the port is open and in raw mode.
        QTRY_VERIFY_WITH_TIMEOUT(far.received().size() >= 2, kPatience);
        for (std::size_t i = 0; i < far.received().size(); ++i) {
            QVERIFY(far.received()[i].ok());
            QCOMPARE(messageId(far.received()[i].message), std::int64_t(i));
            verifyStamped(far.received()[i].message);
        }

        // Each piece is read by the port before the next is written, so the
        // synchroniser really gets them one at a time. (Counted by the worker:
        // polling FIONREAD on the slave instead stalled this kernel's pty for
        // seconds at a time under load.)
        const int pieces[] = {1, 7, 90, 13, 255, 2, 64, 150, 33, 5, 511, 3, 599, 600, 601};
        qsizetype at = 0;
        for (int i = 0; at < stream.size(); ++i) {
            const qsizetype n = std::min<qsizetype>(pieces[i % std::size(pieces)], stream.size() - at);
            far.write(stream.mid(at, n));
            at += n;
            QTRY_COMPARE_WITH_TIMEOUT(controller.statistics().bytesReceived, quint64(at), kPatience);
        }
        QTRY_VERIFY_WITH_TIMEOUT(received.count() >= 5, kPatience);
        for (int i = 0; i < received.count(); ++i) {
            const ReceivedMessage r = receivedAt(received, i);
            QCOMPARE(r.message, aircraftMessage(std::uint32_t(i)));
            QCOMPARE(r.transport, FrameTransport::Serial);
            QCOMPARE(r.corrected.block1, i == 2 ? 3 : 0);
            QCOMPARE(r.corrected.block2, i == 2 ? 1 : 0);
        }
        QTRY_VERIFY_WITH_TIMEOUT(controller.statistics().framesReceived >= 5, kPatience);
        const LinkStatistics s = controller.statistics();
        QCOMPARE(s.bytesSkipped, quint64(junk.size()));
        QCOMPARE(s.correctedBytesBlock1, quint64(3));
        QCOMPARE(s.correctedBytesBlock2, quint64(1));
        QCOMPARE(s.refusedFor(rcm::Refusal::Uncorrectable), quint64(0));
        QCOMPARE(s.state, LinkState::Connected);
        QCOMPARE(errors.count(), 0);

        // The modem goes away: reported lost once, however many ticks pass.
        far.close();
        QTRY_COMPARE_WITH_TIMEOUT(lost.count(), 1, kPatience);
        QTRY_COMPARE_WITH_TIMEOUT(errors.count(), 1, kPatience);
        QVERIFY(errors.at(0).at(0).toString().contains(QStringLiteral("port lost")));
        QTRY_COMPARE_WITH_TIMEOUT(controller.statistics().state, LinkState::Lost, kPatience);
    }
    const QVector<FrameRecord> log = readLog(logPath);
    const QVector<FrameRecord> sent = only(log, FrameDirection::Sent);
    QVERIFY(sent.size() >= qsizetype(far.received().size()));
    for (std::size_t i = 0; i < far.received().size(); ++i) {
        QCOMPARE(sent[qsizetype(i)].bytes.size(), 600);
        QCOMPARE(sent[qsizetype(i)].transport, FrameTransport::Serial);
        QCOMPARE(decode(sent[qsizetype(i)].bytes).message, far.received()[i].message);
    }
    const QVector<FrameRecord> got = only(log, FrameDirection::Received);
    QVERIFY(got.size() >= 5);
    for (qsizetype i = 0; i < got.size(); ++i) {
        QCOMPARE(got[i].bytes.size(), 600);
        QCOMPARE(got[i].status, i == 2 ? FrameStatus::Corrected : FrameStatus::Decoded);
        QCOMPARE(got[i].correctedSymbols, i == 2 ? QList<int>({3, 1}) : QList<int>({0, 0}));
        QCOMPARE(got[i].bytes, stream.mid(junk.size() + i * 600, 600));
    }
}

void TestLink::serialPortVanishesAndComesBack()
{
    // A symlink we control stands for the device node: removing it is the
    // modem unplugged, pointing it at a new pty is the modem plugged back in.
    QTemporaryDir dir;
    const QString port = dir.filePath(QStringLiteral("modem"));
    auto first = std::make_unique<PtyFarEnd>();
    QVERIFY(first->open());
    first->setReplying(true);
    QVERIFY(QFile::link(first->slavePath(), port));

    // The port's reopening on simulated time, stepped by the test; the rest
    // of the link on the system's.
    const auto reopenClock = std::make_shared<VirtualClock>(rcm::test::kFixtureStartUtcMicros);
    auto serial = std::make_unique<SerialLink>(port, SerialLink::kDefaultBaudRate, nullptr, reopenClock);
    serial->setReopenInterval(50ms);
    const SerialLink* watched = serial.get();  // owned by the worker; reopenAttempts() is atomic
    LinkWorker::Options options = fastOptions();
    options.silenceTimeout = 2000ms;  // the port going away must be what reports the loss
    LinkController controller(std::move(serial), nullptr, options);
    QSignalSpy received(&controller, &LinkController::messageReceived);
    QSignalSpy errors(&controller, &LinkController::errorOccurred);
    QSignalSpy lost(&controller, &LinkController::linkLost);
    QSignalSpy regained(&controller, &LinkController::linkRegained);
    controller.setCommand(command(2));
    controller.start();
    QTRY_VERIFY_WITH_TIMEOUT(received.count() >= 2, kPatience);
    QCOMPARE(errors.count(), 0);

    QVERIFY(QFile::remove(port));
    first->close();
    QTRY_COMPARE_WITH_TIMEOUT(lost.count(), 1, kPatience);
    QTRY_COMPARE_WITH_TIMEOUT(errors.count(), 1, kPatience);
    QVERIFY(errors.at(0).at(0).toString().contains(QStringLiteral("port lost")));
    // An attempt to reopen every 50 ms, each failing, and not one more report.
    QTRY_COMPARE_WITH_TIMEOUT(reopenClock->activeTimers(), 1, kPatience);  // armed in the link's thread
    QCOMPARE(watched->reopenAttempts(), 0);
    reopenClock->advance(49ms);
    QCOMPARE(watched->reopenAttempts(), 0);
    reopenClock->advance(1ms + 100ms);
    QCOMPARE(watched->reopenAttempts(), 3);
    QCOMPARE(reopenClock->activeTimers(), 1);
    QCOMPARE(errors.count(), 1);
    QCOMPARE(regained.count(), 0);

    PtyFarEnd second;
    QVERIFY(second.open());
    second.setReplying(true);
    QVERIFY(QFile::link(second.slavePath(), port));
    reopenClock->advance(50ms);
    QCOMPARE(watched->reopenAttempts(), 4);
    QCOMPARE(reopenClock->activeTimers(), 0);  // open: no more attempts
    QTRY_COMPARE_WITH_TIMEOUT(regained.count(), 1, kPatience);
    QTRY_VERIFY_WITH_TIMEOUT(second.received().size() >= 2, kPatience);
    QCOMPARE(lost.count(), 1);
    QCOMPARE(errors.count(), 1);
    QTRY_COMPARE_WITH_TIMEOUT(controller.statistics().state, LinkState::Connected, kPatience);
    // The worker's IDs went on across the outage.
    QVERIFY(messageId(second.received()[1].message) == messageId(second.received()[0].message) + 1);
}

QTEST_GUILESS_MAIN(TestLink)
#include "tst_link.moc"
