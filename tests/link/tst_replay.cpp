// Replay of a frame log: the same frames in the same order, pause, speed,
// seeking by time, the end of the log, and the worker taking a replay as it
// takes any transport. Each replay runs on a VirtualClock the test steps:
// the logs hold a frame a second, so a second of simulated time plays one
// through at 10x, and ten show that a paused or closed one stays silent.

#include "codec/frame/Frame.h"
#include "link/clock/VirtualClock.h"
#include "link/framelog/FrameLog.h"
#include "link/replay/ReplayLink.h"
#include "link/session/LinkWorker.h"

#include <QFile>
#include <QSignalSpy>
#include <QTemporaryDir>
#include <QTest>

#include <memory>

namespace {

const QString kVectors = QStringLiteral(RCM_VECTORS_DIR "/rcm/");
using namespace std::chrono_literals;

constexpr qint64 kT0 = 1795332720000123;

QByteArray readFile(const QString& path)
{
    QFile f(path);
    return f.open(QIODevice::ReadOnly) ? f.readAll() : QByteArray();
}

// A session as the console logs one: a frame a second, sends and receipts,
// serial frames and UDP datagrams, one uncorrectable frame, one wrong-size
// datagram; `backStep` puts in a wall clock step backwards.
QList<FrameRecord> session(int n, bool backStep = false)
{
    const QByteArray frames[] = {readFile(kVectors + QStringLiteral("seed-example.bin")),
                                 readFile(kVectors + QStringLiteral("well-equipped.bin")),
                                 readFile(kVectors + QStringLiteral("flight-plan.bin"))};
    QList<FrameRecord> records;
    for (int i = 0; i < n; ++i) {
        FrameRecord r;
        r.bytes = frames[i % 3];
        r.utcMicros = kT0 + qint64(i) * 1000000 + i;
        r.direction = i % 4 == 1 ? FrameDirection::Sent : FrameDirection::Received;
        r.transport = i % 5 == 2 ? FrameTransport::Udp : FrameTransport::Serial;
        r.status = r.direction == FrameDirection::Sent ? FrameStatus::NotChecked : FrameStatus::Decoded;
        if (r.transport == FrameTransport::Udp)
            r.bytes = r.bytes.mid(int(rcm::kPreambleSize));
        if (i == 3) {
            r.bytes[200] = char(r.bytes[200] ^ 0xFF);
            r.status = FrameStatus::Corrected;
            r.correctedSymbols = {1, 0};
        }
        if (i == 8) {
            r.bytes = QByteArray(17, 0x55);
            r.transport = FrameTransport::Udp;
            r.status = FrameStatus::Rejected;
        }
        records.append(r);
    }
    if (backStep && n > 6)
        records[6].utcMicros = records[5].utcMicros - 500000;
    return records;
}

// What the worker must be handed for the received records.
QList<QByteArray> receivedDatagrams(const QList<FrameRecord>& records)
{
    QList<QByteArray> out;
    for (const FrameRecord& r : records)
        if (r.direction == FrameDirection::Received)
            out.append(r.bytes.size() == qsizetype(rcm::kFrameSize) ? r.bytes.mid(int(rcm::kPreambleSize)) : r.bytes);
    return out;
}

QList<FrameRecord> replayed(const QSignalSpy& spy)
{
    QList<FrameRecord> out;
    for (const QList<QVariant>& args : spy)
        out.append(args.at(0).value<FrameRecord>());
    return out;
}

QList<QByteArray> datagrams(const QSignalSpy& spy)
{
    QList<QByteArray> out;
    for (const QList<QVariant>& args : spy)
        out.append(args.at(0).toByteArray());
    return out;
}

}  // namespace

class TestReplay : public QObject {
    Q_OBJECT

private slots:
    void initTestCase();
    void init();
    void replaysFrameForFrameAt10x();
    void pauseStopsDelivery();
    void seekByTime();
    void endOfLogIsSignalledOnce();
    void emptyLogEndsAtOnce();
    void speedIsClamped();
    void writesAreRefused();
    void unreadableLog();
    void closeStopsPlayback();
    void workerDecodesReplayedFrames();

private:
    QString writeLog(const QList<FrameRecord>& records);

    QTemporaryDir m_dir;
    std::shared_ptr<VirtualClock> m_clock;  // a new one for each test
    int m_logs = 0;
};

void TestReplay::initTestCase()
{
    QVERIFY(m_dir.isValid());
}

void TestReplay::init()
{
    m_clock = std::make_shared<VirtualClock>(0);
}

QString TestReplay::writeLog(const QList<FrameRecord>& records)
{
    const QString path = m_dir.filePath(QStringLiteral("replay%1.pcapng").arg(++m_logs));
    FrameLog log;
    QString error;
    if (!log.open(path, &error)) {
        qWarning() << error;
        return {};
    }
    for (const FrameRecord& r : records)
        if (!log.append(r))
            return {};
    return path;
}

void TestReplay::replaysFrameForFrameAt10x()
{
    const QList<FrameRecord> records = session(10, true);
    const QString path = writeLog(records);
    QVERIFY(!path.isEmpty());

    ReplayLink link(path, m_clock);
    QSignalSpy frames(&link, &ReplayLink::frameReplayed);
    QSignalSpy received(&link, &Link::datagramReceived);
    QSignalSpy bytes(&link, &Link::bytesReceived);
    QSignalSpy opened(&link, &Link::opened);
    QSignalSpy position(&link, &ReplayLink::positionChanged);
    QSignalSpy states(&link, &ReplayLink::stateChanged);
    QSignalSpy end(&link, &ReplayLink::endOfLog);
    link.setSpeed(10);
    QCOMPARE(link.speed(), 10.0);
    link.open();
    QVERIFY(link.isOpen());
    QCOMPARE(opened.count(), 1);
    QCOMPARE(link.transport(), FrameTransport::Replay);
    QVERIFY(!link.isStream());
    QCOMPARE(link.frameCount(), records.size());
    QCOMPARE(link.startMicros(), records.first().utcMicros);
    QCOMPARE(link.endMicros(), records.last().utcMicros);

    // The last record is due 9 s (and 9 us) of log after the first: 900 ms at 10x.
    m_clock->advance(899ms);
    QCOMPARE(frames.count(), records.size() - 1);
    QCOMPARE(end.count(), 0);
    m_clock->advance(2ms);
    QCOMPARE(end.count(), 1);
    QCOMPARE(replayed(frames), records);
    QCOMPARE(datagrams(received), receivedDatagrams(records));
    QCOMPARE(bytes.count(), 0);
    QCOMPARE(link.state(), ReplayLink::State::Finished);
    QCOMPARE(link.nextIndex(), records.size());
    QCOMPARE(position.last().at(0).toLongLong(), records.last().utcMicros);
    QCOMPARE(position.last().at(1).toInt(), records.size());
    QCOMPARE(link.positionMicros(), records.last().utcMicros);
    QCOMPARE(states.count(), 2);
    QCOMPARE(states.at(0).at(0).value<ReplayLink::State>(), ReplayLink::State::Playing);
    QCOMPARE(states.at(1).at(0).value<ReplayLink::State>(), ReplayLink::State::Finished);
}

void TestReplay::pauseStopsDelivery()
{
    const QList<FrameRecord> records = session(8);
    const QString path = writeLog(records);
    ReplayLink link(path, m_clock);
    QSignalSpy frames(&link, &ReplayLink::frameReplayed);
    QSignalSpy end(&link, &ReplayLink::endOfLog);
    // Paused from a slot, as a GUI button would: exactly after the second frame.
    connect(&link, &ReplayLink::frameReplayed, this, [&link, n = 0]() mutable {
        if (++n == 2)
            link.pause();
    });
    link.setSpeed(10);
    link.open();
    m_clock->advance(1s);
    QCOMPARE(link.state(), ReplayLink::State::Paused);
    QVERIFY(link.isPaused());
    const int atPause = 2;
    QCOMPARE(frames.count(), atPause);
    const qint64 frozen = link.positionMicros();

    m_clock->advance(10s);
    QCOMPARE(frames.count(), atPause);
    QCOMPARE(end.count(), 0);
    QCOMPARE(link.positionMicros(), frozen);

    link.resume();
    QCOMPARE(link.state(), ReplayLink::State::Playing);
    m_clock->advance(1s);
    QCOMPARE(end.count(), 1);
    QCOMPARE(replayed(frames), records);  // nothing lost or repeated across the pause
}

void TestReplay::seekByTime()
{
    const QList<FrameRecord> records = session(10);
    const QString path = writeLog(records);
    ReplayLink link(path, m_clock);
    QSignalSpy frames(&link, &ReplayLink::frameReplayed);
    QSignalSpy received(&link, &Link::datagramReceived);
    QSignalSpy position(&link, &ReplayLink::positionChanged);
    QSignalSpy end(&link, &ReplayLink::endOfLog);
    link.setPaused(true);
    link.setSpeed(10);
    link.open();
    QCOMPARE(link.state(), ReplayLink::State::Paused);
    QCOMPARE(link.nextIndex(), 0);

    auto seekTo = [&](qint64 t) {
        link.seek(t);
        return position.last().at(1).toInt();
    };
    QCOMPARE(seekTo(records[5].utcMicros), 5);
    QCOMPARE(position.last().at(0).toLongLong(), records[5].utcMicros);
    QCOMPARE(seekTo(records[5].utcMicros - 1), 5);
    QCOMPARE(seekTo(records[5].utcMicros + 1), 6);
    QCOMPARE(seekTo(records[2].utcMicros - 400000), 2);
    QCOMPARE(seekTo(0), 0);
    QCOMPARE(link.positionMicros(), records.first().utcMicros);  // not 56 years before it
    QCOMPARE(end.count(), 0);
    QCOMPARE(seekTo(records.last().utcMicros + 1), records.size());
    QCOMPARE(link.state(), ReplayLink::State::Finished);
    QCOMPARE(end.count(), 1);

    // Back from the end, still paused; then played from exactly there.
    QCOMPARE(seekTo(records[7].utcMicros - 1000), 7);
    QCOMPARE(link.state(), ReplayLink::State::Paused);
    QCOMPARE(frames.count(), 0);
    link.resume();
    m_clock->advance(1s);
    QCOMPARE(end.count(), 2);
    QCOMPARE(replayed(frames), records.mid(7));
    QCOMPARE(datagrams(received), receivedDatagrams(records.mid(7)));

    // A seek while playing goes on playing from the new place.
    frames.clear();
    QCOMPARE(seekTo(records[8].utcMicros), 8);
    QCOMPARE(link.state(), ReplayLink::State::Playing);
    m_clock->advance(1s);
    QCOMPARE(end.count(), 3);
    QCOMPARE(replayed(frames), records.mid(8));
}

void TestReplay::endOfLogIsSignalledOnce()
{
    const QList<FrameRecord> records = session(4);
    const QString path = writeLog(records);
    ReplayLink link(path, m_clock);
    QSignalSpy end(&link, &ReplayLink::endOfLog);
    QSignalSpy frames(&link, &ReplayLink::frameReplayed);
    link.setSpeed(10);
    link.open();
    m_clock->advance(1s);
    QCOMPARE(end.count(), 1);
    link.pause();
    link.resume();
    link.setSpeed(2);
    link.seek(records.last().utcMicros + 5000000);
    m_clock->advance(10s);
    QCOMPARE(end.count(), 1);
    QCOMPARE(frames.count(), records.size());
    QCOMPARE(link.state(), ReplayLink::State::Finished);
}

void TestReplay::emptyLogEndsAtOnce()
{
    const QString path = writeLog({});
    ReplayLink link(path, m_clock);
    QSignalSpy end(&link, &ReplayLink::endOfLog);
    QSignalSpy opened(&link, &Link::opened);
    link.open();
    QCOMPARE(opened.count(), 1);
    QCOMPARE(end.count(), 1);
    QCOMPARE(link.state(), ReplayLink::State::Finished);
    QCOMPARE(link.frameCount(), 0);
}

void TestReplay::speedIsClamped()
{
    ReplayLink link(m_dir.filePath(QStringLiteral("never-opened.pcapng")), m_clock);
    QSignalSpy speed(&link, &ReplayLink::speedChanged);
    QCOMPARE(link.speed(), 1.0);
    link.setSpeed(100);
    QCOMPARE(link.speed(), ReplayLink::kMaxSpeed);
    link.setSpeed(0);
    QCOMPARE(link.speed(), ReplayLink::kMinSpeed);
    link.setSpeed(-3);
    link.setSpeed(std::nan(""));
    QCOMPARE(link.speed(), ReplayLink::kMinSpeed);
    link.setSpeed(2.5);
    QCOMPARE(link.speed(), 2.5);
    QCOMPARE(speed.count(), 3);
    QCOMPARE(speed.last().at(0).toDouble(), 2.5);
    QVERIFY(link.description().contains(QLatin1String("never-opened.pcapng at 2.5x")));
}

void TestReplay::writesAreRefused()
{
    const QString path = writeLog(session(2));
    ReplayLink link(path, m_clock);
    link.setPaused(true);
    link.open();
    QSignalSpy frames(&link, &ReplayLink::frameReplayed);
    QVERIFY(!link.write(QByteArray(510, 0x55)));
    QCOMPARE(frames.count(), 0);
    QCOMPARE(link.frameCount(), 2);
}

void TestReplay::unreadableLog()
{
    const QString missing = m_dir.filePath(QStringLiteral("missing.pcapng"));
    ReplayLink link(missing, m_clock);
    QSignalSpy errors(&link, &Link::errorOccurred);
    QSignalSpy opened(&link, &Link::opened);
    link.open();
    QCOMPARE(errors.count(), 1);
    QVERIFY(errors.first().at(0).toString().contains(missing));
    QCOMPARE(opened.count(), 0);
    QVERIFY(!link.isOpen());
    QCOMPARE(link.state(), ReplayLink::State::Closed);
    link.seek(kT0);  // harmless while closed
    QCOMPARE(link.state(), ReplayLink::State::Closed);
}

void TestReplay::closeStopsPlayback()
{
    const QList<FrameRecord> records = session(6);
    const QString path = writeLog(records);
    ReplayLink link(path, m_clock);
    QSignalSpy frames(&link, &ReplayLink::frameReplayed);
    QSignalSpy closed(&link, &Link::closed);
    QSignalSpy end(&link, &ReplayLink::endOfLog);
    auto closeOnce = connect(&link, &ReplayLink::frameReplayed, &link, &ReplayLink::close);
    link.setSpeed(10);
    link.open();
    m_clock->advance(1s);
    QCOMPARE(closed.count(), 1);
    disconnect(closeOnce);
    link.close();
    QCOMPARE(closed.count(), 1);
    QCOMPARE(link.state(), ReplayLink::State::Closed);
    const int atClose = 1;
    QCOMPARE(frames.count(), atClose);
    m_clock->advance(10s);
    QCOMPARE(frames.count(), atClose);
    QCOMPARE(end.count(), 0);

    // Opened again, it starts over.
    link.open();
    m_clock->advance(1s);
    QCOMPARE(end.count(), 1);
    QCOMPARE(replayed(frames).mid(atClose), records);
}

void TestReplay::workerDecodesReplayedFrames()
{
    const QList<FrameRecord> records = session(10);
    const QString path = writeLog(records);
    auto replay = std::make_unique<ReplayLink>(path, m_clock);
    ReplayLink* link = replay.get();
    link->setSpeed(10);
    QSignalSpy end(link, &ReplayLink::endOfLog);
    LinkWorker::Options options;
    options.clock = m_clock;
    LinkWorker worker(std::move(replay), nullptr, options);
    QSignalSpy messages(&worker, &LinkWorker::messageReceived);
    worker.start();
    m_clock->advance(1s);
    QCOMPARE(end.count(), 1);
    // The received records are the three sample frames over again (one
    // corrupted, and corrected) and a wrong-size datagram: each frame is
    // delivered once, and its repeats are refused as not following it
    // (docs/protocol.md section 8; a recording is judged by its own frames).
    QCOMPARE(int(messages.count()), 3);
    QCOMPARE(worker.statistics().refusedTotal(), quint64(4));
    const auto first = messages.first().at(0).value<ReceivedMessage>();
    QCOMPARE(first.transport, FrameTransport::Replay);
    QCOMPARE(first.message.header.number(rcm::ItemId::ID_msg), 133);
    QCOMPARE(worker.statistics().refusedFor(rcm::Refusal::WrongSize), 1);
    worker.stop();
}

QTEST_GUILESS_MAIN(TestReplay)
#include "tst_replay.moc"
