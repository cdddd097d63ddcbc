// The console's session without a window: a live UDP link to a bare socket
// standing in for the aircraft, a rehearsal against the real uasim process, a
// frame log replayed, keys refused, actions replacing one another, and the
// link thread's bounded join. Every wait is a QSignalSpy or a QTRY_* on state
// the session exposes; the timeouts only bound a broken build.

#include "codec/message/Airframe.h"
#include "codec/message/MessageDecoder.h"
#include "codec/message/MessageEncoder.h"
#include "codec/receive/LoggedFrameReading.h"
#include "codec/secure/SecureCodec.h"
#include "link/framelog/FrameLog.h"
#include "link/framelog/FrameLogReader.h"
#include "link/session/ConsoleSession.h"
#include "link/session/LinkController.h"
#include "link/transport/UdpLink.h"

#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QRegularExpression>
#include <QSemaphore>
#include <QSignalSpy>
#include <QTemporaryDir>
#include <QTest>
#include <QThreadPool>

#include <atomic>

namespace {

constexpr int kTimeoutMs = 30000;
const QString kUasim = QStringLiteral(RCM_BIN_DIR "/uasim");

rcm::Message command(int elevator)
{
    rcm::Message m = rcm::restingCommand(rcm::Airframe::wellEquipped());
    m.flaps.set(rcm::ItemId::F_elev_set, elevator);
    return m;
}

rcm::Message decoded(const QByteArray& bytes)
{
    return rcm::decodeFrame(std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(bytes.constData()),
                                                          std::size_t(bytes.size())))
        .message;
}

// A transport whose destruction blocks until released: a serial driver stuck in close().
class StuckLink : public Link {
public:
    StuckLink(QSemaphore* release, std::atomic<bool>* gone) : m_release(release), m_gone(gone) {}
    ~StuckLink() override
    {
        m_release->acquire();
        *m_gone = true;
    }
    FrameTransport transport() const override { return FrameTransport::Serial; }
    bool isStream() const override { return true; }
    bool isOpen() const override { return m_open; }
    QString description() const override { return QStringLiteral("stuck"); }
    void open() override { m_open = true; }
    void close() override { m_open = false; }
    bool write(const QByteArray&) override { return false; }

private:
    QSemaphore* m_release;
    std::atomic<bool>* m_gone;
    bool m_open = false;
};

// Another station's session, as an observation tells it: here its frames are
// emitted by the test.
class ScriptedObservation : public Observation {
public:
    void start() override { running = true; }
    void stop() override { running = false; }
    QString observed() const override { return QStringLiteral("GB_133"); }
    bool running = false;
};

LoggedFrame loggedFrame(const rcm::Message& message, FrameDirection direction, const rcm::secure::SecureCodec& codec,
                        qint64 utcMicros)
{
    rcm::Diagnostics errors;
    const std::optional<rcm::EncodedBlocks> blocks = codec.encode(message, errors);
    const rcm::DatagramBytes datagram = rcm::makeDatagram(blocks->block1, blocks->block2);
    LoggedFrame frame;
    frame.entry.direction = direction;
    frame.entry.utcMicros = utcMicros;
    frame.entry.enciphered = true;
    frame.entry.offset = -1;
    frame.bytes = QByteArray(reinterpret_cast<const char*>(datagram.data()), qsizetype(datagram.size()));
    return frame;
}

}  // namespace

class TestConsoleSession : public QObject {
    Q_OBJECT

private slots:
    void initTestCase();
    void connectsOverUdpAndLogsTheSession();
    void refusedKeyLeavesTheRunningLinkAsItWas();
    void incompleteSettingsSayWhy();
    void replaysALogIndexedOffTheGuiThread();
    void replayOfAFileThatIsNotALogSaysWhy();
    void keyedLogReplaysWithItsKey();
    void aLaterActionReplacesOneBeingPrepared();
    void rehearsalAgainstUasim();
    void rehearsalWithoutUasimSaysWhy();
    void joinOfAStuckLinkThreadIsBounded();
    void stoppedLinksAreJoinedOnRequest();
    void observationIsAKindOfSession();

private:
    QString logDirectory(const QString& name) const { return m_dir.filePath(name); }
    // Twenty received status frames half a second apart.
    // 20 status frames, 2 a second; with `key`, enciphered as the aircraft
    // sends them and marked so in the log.
    QString writeLog(const QString& name, const rcm::secure::SecureCodec* key = nullptr) const;
    QTemporaryDir m_dir;
};

void TestConsoleSession::initTestCase()
{
    QVERIFY(m_dir.isValid());
}

QString TestConsoleSession::writeLog(const QString& name, const rcm::secure::SecureCodec* key) const
{
    const QString path = m_dir.filePath(name);
    FrameLog log;
    if (!log.open(path))
        return {};
    rcm::Message status = command(5);
    for (int i = 0; i < 20; ++i) {
        status.header.set(rcm::ItemId::ID_msg, i);
        // 2026-11-22T07:32:00Z + i/2 s, as the record's time says.
        status.header.set(rcm::ItemId::time_UTC, std::int64_t(73200 + i / 2));
        status.header.set(rcm::ItemId::date_UTC, std::int64_t(261122));
        rcm::Diagnostics errors;
        std::optional<rcm::DatagramBytes> datagram;
        if (!key) {
            datagram = rcm::encodeDatagram(status, errors);
        } else if (const auto blocks = key->encode(status, errors)) {
            datagram = rcm::makeDatagram(blocks->block1, blocks->block2);
        }
        if (!datagram)
            return {};
        FrameRecord r;
        r.enciphered = key != nullptr;
        r.bytes = QByteArray(reinterpret_cast<const char*>(datagram->data()), qsizetype(datagram->size()));
        r.utcMicros = 1795332720000000 + i * 500'000;
        r.direction = FrameDirection::Received;
        r.transport = FrameTransport::Udp;
        r.status = FrameStatus::Decoded;
        r.correctedSymbols = {0, 0};
        log.append(r);
    }
    return path;
}

void TestConsoleSession::connectsOverUdpAndLogsTheSession()
{
    UdpLink aircraft(QHostAddress::LocalHost, 0);
    aircraft.open();
    QSignalSpy arrived(&aircraft, &Link::datagramReceived);

    ConsoleSession session(logDirectory(QStringLiteral("udp")));
    QSignalSpy started(&session, &ConsoleSession::linkStarted);
    QSignalSpy stopped(&session, &ConsoleSession::linkStopped);
    session.setCommand(command(7));
    LinkSettings s;
    s.localAddress = QStringLiteral("127.0.0.1");
    s.remoteAddress = QStringLiteral("127.0.0.1");
    s.remotePort = aircraft.boundPort();
    session.connectWith(s);
    // The frame log is created in the thread pool: nothing runs yet.
    QCOMPARE(session.preparing(), ConsoleSession::Kind::Live);
    QVERIFY(!session.isRunning());
    QVERIFY(session.isActive());
    QTRY_COMPARE_WITH_TIMEOUT(started.count(), 1, kTimeoutMs);
    QCOMPARE(started.at(0).at(0).value<const LinkController*>(), session.controller());
    QCOMPARE(session.kind(), ConsoleSession::Kind::Live);
    QCOMPARE(session.description(), s.summary());
    QVERIFY(session.isDatagram());
    QCOMPARE(session.keyFingerprint(), QString());

    // Held until the operator resumes: 510-byte datagrams that command
    // nothing (issue 24; tst_commandhold has the whole story).
    QTRY_VERIFY_WITH_TIMEOUT(arrived.count() >= 1, kTimeoutMs);
    const QByteArray datagram = arrived.at(0).at(0).toByteArray();
    QCOMPARE(datagram.size(), 510);
    QVERIFY(decoded(datagram).flaps.empty());
    QVERIFY(!session.commanding());
    // Resumed with nothing heard from the far end: the command as it was set.
    QVERIFY(session.resumeCommanding());
    QTRY_VERIFY_WITH_TIMEOUT(decoded(arrived.last().at(0).toByteArray()).flaps.number(rcm::ItemId::F_elev_set) == 7,
                             kTimeoutMs);
    // A new command reaches the running link.
    session.setCommand(command(-3));
    QTRY_VERIFY_WITH_TIMEOUT(decoded(arrived.last().at(0).toByteArray()).flaps.number(rcm::ItemId::F_elev_set) == -3,
                             kTimeoutMs);
    QTRY_VERIFY_WITH_TIMEOUT(session.statistics().framesSent >= 2, kTimeoutMs);

    const QString logPath = session.sessionLogPath();
    QVERIFY(logPath.startsWith(logDirectory(QStringLiteral("udp"))));
    session.stop();
    QCOMPARE(stopped.count(), 1);
    QVERIFY(!session.isActive());
    QCOMPARE(session.kind(), ConsoleSession::Kind::None);
    QCOMPARE(session.statistics().framesSent, quint64(0));
    QCOMPARE(session.sessionLogPath(), QString());
    // The session's log holds what was sent, as sent.
    FrameLogReader reader;
    QVERIFY2(reader.open(logPath), qPrintable(reader.errorString()));
    QVERIFY(reader.count() >= 2);
    QCOMPARE(reader.recordAt(0).bytes, datagram);
    QCOMPARE(reader.recordAt(0).direction, FrameDirection::Sent);
}

void TestConsoleSession::refusedKeyLeavesTheRunningLinkAsItWas()
{
    UdpLink aircraft(QHostAddress::LocalHost, 0);
    aircraft.open();
    ConsoleSession session(logDirectory(QStringLiteral("key")));
    QSignalSpy started(&session, &ConsoleSession::linkStarted);
    QSignalSpy failed(&session, &ConsoleSession::failed);
    LinkSettings s;
    s.localAddress = QStringLiteral("127.0.0.1");
    s.remoteAddress = QStringLiteral("127.0.0.1");
    s.remotePort = aircraft.boundPort();
    session.connectWith(s);
    QTRY_COMPARE_WITH_TIMEOUT(started.count(), 1, kTimeoutMs);
    const LinkController* running = session.controller();

    const QString key = m_dir.filePath(QStringLiteral("open.key"));
    std::string error;
    QVERIFY(rcm::secure::writeKeyFile(key.toStdString(), rcm::secure::generateKey(), error));
    QVERIFY(QFile::setPermissions(key, QFile::ReadOwner | QFile::WriteOwner | QFile::ReadOther));
    s.keyPath = key;
    session.connectWith(s);
    QTRY_COMPARE_WITH_TIMEOUT(failed.count(), 1, kTimeoutMs);
    const QString reason = failed.at(0).at(0).toString();
    QVERIFY2(reason.startsWith(QStringLiteral("Not connected: the key file is refused: ")), qPrintable(reason));
    QVERIFY2(reason.contains(QStringLiteral("chmod 600 ") + key), qPrintable(reason));
    QCOMPARE(session.controller(), running);
    QCOMPARE(session.kind(), ConsoleSession::Kind::Live);
    QCOMPARE(session.preparing(), ConsoleSession::Kind::None);
    QCOMPARE(started.count(), 1);

    // The same key, made private, is taken: a new link replaces the old one.
    QVERIFY(QFile::setPermissions(key, QFile::ReadOwner | QFile::WriteOwner));
    session.connectWith(s);
    QTRY_COMPARE_WITH_TIMEOUT(started.count(), 2, kTimeoutMs);
    QCOMPARE(session.keyFingerprint().size(), 16);
    QVERIFY(session.description().endsWith(QStringLiteral(", encrypted")));
}

void TestConsoleSession::incompleteSettingsSayWhy()
{
    ConsoleSession session(logDirectory(QStringLiteral("incomplete")));
    QSignalSpy failed(&session, &ConsoleSession::failed);
    LinkSettings s;
    s.transport = LinkSettings::Transport::Serial;
    session.connectWith(s);
    QCOMPARE(failed.count(), 1);
    QCOMPARE(failed.at(0).at(0).toString(), QStringLiteral("Choose a serial port"));
    QVERIFY(!session.isActive());
}

void TestConsoleSession::replaysALogIndexedOffTheGuiThread()
{
    const QString path = writeLog(QStringLiteral("replay.pcapng"));
    QVERIFY(!path.isEmpty());
    ConsoleSession session(logDirectory(QStringLiteral("replay")));
    QSignalSpy indexed(&session, &ConsoleSession::replayIndexed);
    QSignalSpy started(&session, &ConsoleSession::linkStarted);
    session.setReplaySpeed(10.0);
    session.openReplay(path);
    // The call returns before the log is indexed.
    QCOMPARE(indexed.count(), 0);
    QCOMPARE(session.preparing(), ConsoleSession::Kind::Replay);
    QTRY_COMPARE_WITH_TIMEOUT(indexed.count(), 1, kTimeoutMs);
    QCOMPARE(indexed.at(0).at(0).toString(), path);
    std::unique_ptr<FrameLogReader> index = session.takeReplayIndex();
    QVERIFY(index);
    QCOMPARE(index->count(), 20);
    QCOMPARE(index->index().first().utcMicros, 1795332720000000);
    QVERIFY(!session.takeReplayIndex());  // handed over once
    // The link starts in a pass of the event loop after the index is shown.
    QTRY_COMPARE_WITH_TIMEOUT(started.count(), 1, kTimeoutMs);
    QCOMPARE(session.kind(), ConsoleSession::Kind::Replay);
    QVERIFY(session.replay());
    QCOMPARE(session.description(), QStringLiteral("replay of replay.pcapng"));
    QCOMPARE(session.sessionLogPath(), QString());  // a replay writes no log

    QSignalSpy ended(session.replay(), &ReplayLink::endOfLog);
    QTRY_COMPARE_WITH_TIMEOUT(ended.count(), 1, kTimeoutMs);
    QTRY_COMPARE_WITH_TIMEOUT(session.statistics().framesReceived, quint64(20), kTimeoutMs);
    QCOMPARE(session.statistics().framesSent, quint64(0));
    QVERIFY(!QFileInfo::exists(logDirectory(QStringLiteral("replay"))));

    // What a view builds from the index is built off the GUI thread too,
    // with the whole index, before replayIndexed().
    std::atomic<int> recordsSeen = -1;
    std::atomic<bool> onGuiThread = true;
    indexed.clear();
    QObject::connect(&session, &ConsoleSession::replayIndexed, &session,
                     [&] { QCOMPARE(recordsSeen.load(), 20); });
    session.openReplay(path, QString(), [&](const FrameLogReader& reader) {
        recordsSeen = reader.count();
        onGuiThread = QThread::currentThread() == qApp->thread();
    });
    QTRY_COMPARE_WITH_TIMEOUT(indexed.count(), 1, kTimeoutMs);
    QCOMPARE(recordsSeen.load(), 20);
    QVERIFY(!onGuiThread);
}

// A keyed session's log: with its key the replay reads every status frame
// and the log key reads the rows; without it nothing is delivered.
void TestConsoleSession::keyedLogReplaysWithItsKey()
{
    const QString keyPath = m_dir.filePath(QStringLiteral("replay.key"));
    std::string error;
    const rcm::secure::SecretKey psk = rcm::secure::generateKey();
    QVERIFY(rcm::secure::writeKeyFile(keyPath.toStdString(), psk, error));
    const rcm::secure::SecureCodec aircraft(psk, rcm::secure::Direction::UaToGcs);
    const QString path = writeLog(QStringLiteral("keyed.pcapng"), &aircraft);
    QVERIFY(!path.isEmpty());
    const QStringList stateFiles = QDir(m_dir.path()).entryList(QDir::Files);

    for (const bool withKey : {true, false}) {
        ConsoleSession session(logDirectory(QStringLiteral("keyed")));
        QSignalSpy started(&session, &ConsoleSession::linkStarted);
        session.setReplaySpeed(10.0);
        session.openReplay(path, withKey ? keyPath : QString());
        QTRY_COMPARE_WITH_TIMEOUT(started.count(), 1, kTimeoutMs);
        QCOMPARE(bool(session.logKey()), withKey);
        QSignalSpy ended(session.replay(), &ReplayLink::endOfLog);
        QTRY_COMPARE_WITH_TIMEOUT(ended.count(), 1, kTimeoutMs);
        if (withKey) {
            QTRY_COMPARE_WITH_TIMEOUT(session.statistics().framesReceived, quint64(20), kTimeoutMs);
            QCOMPARE(session.logKey()->fingerprint(), rcm::secure::fingerprint(psk));
        } else {
            QTRY_COMPARE_WITH_TIMEOUT(session.statistics().refusedTotal(), quint64(20), kTimeoutMs);
            QCOMPARE(session.statistics().framesReceived, quint64(0));
        }
    }
    // Replaying touched no replay state beside the key.
    QCOMPARE(QDir(m_dir.path()).entryList(QDir::Files), stateFiles);
}

void TestConsoleSession::replayOfAFileThatIsNotALogSaysWhy()
{
    const QString path = m_dir.filePath(QStringLiteral("not-a-log.pcapng"));
    {
        QFile f(path);
        QVERIFY(f.open(QIODevice::WriteOnly));
        f.write(QByteArray(64, 'x'));
    }
    ConsoleSession session(logDirectory(QStringLiteral("bad")));
    QSignalSpy failed(&session, &ConsoleSession::failed);
    session.openReplay(path);
    QTRY_COMPARE_WITH_TIMEOUT(failed.count(), 1, kTimeoutMs);
    const QString reason = failed.at(0).at(0).toString();
    QVERIFY2(reason.startsWith(QStringLiteral("Cannot open the frame log: ")), qPrintable(reason));
    QVERIFY2(reason.contains(QStringLiteral("offset 0")), qPrintable(reason));
    QVERIFY(!session.isActive());
}

void TestConsoleSession::aLaterActionReplacesOneBeingPrepared()
{
    const QString first = writeLog(QStringLiteral("first.pcapng"));
    const QString second = writeLog(QStringLiteral("second.pcapng"));
    ConsoleSession session(logDirectory(QStringLiteral("replaced")));
    QSignalSpy indexed(&session, &ConsoleSession::replayIndexed);
    session.openReplay(first);
    session.openReplay(second);
    // Both indexes are built; only the later one counts.
    QThreadPool::globalInstance()->waitForDone();
    QTRY_COMPARE_WITH_TIMEOUT(indexed.count(), 1, kTimeoutMs);
    QCoreApplication::sendPostedEvents();
    QCOMPARE(indexed.count(), 1);
    QCOMPARE(indexed.at(0).at(0).toString(), second);

    // And stop() ends one being prepared before it starts.
    QSignalSpy started(&session, &ConsoleSession::linkStarted);
    session.openReplay(first);
    session.stop();
    QThreadPool::globalInstance()->waitForDone();
    QCoreApplication::sendPostedEvents();
    QCOMPARE(started.count(), 0);
    QVERIFY(!session.isActive());
}

void TestConsoleSession::rehearsalAgainstUasim()
{
    QVERIFY2(QFileInfo(kUasim).isExecutable(), "build the uasim target first");
    ConsoleSession session(logDirectory(QStringLiteral("rehearsal")));
    QSignalSpy starting(&session, &ConsoleSession::starting);
    QSignalSpy started(&session, &ConsoleSession::linkStarted);
    session.setCommand(command(0));
    session.startRehearsal(rcm::Airframe::wellEquipped(), QString(), kUasim);
    QTRY_VERIFY_WITH_TIMEOUT(started.count() >= 1, kTimeoutMs);
    QCOMPARE(starting.at(0).at(0).toString(), QStringLiteral("Starting uasim\u2026"));
    QCOMPARE(session.kind(), ConsoleSession::Kind::Rehearsal);
    QVERIFY(session.description().startsWith(QStringLiteral("rehearsal with uasim on 127.0.0.1:")));
    // uasim answers every command with a status frame.
    QTRY_VERIFY_WITH_TIMEOUT(session.statistics().framesReceived >= 2, kTimeoutMs);
    QCOMPARE(session.statistics().refusedFor(rcm::Refusal::Uncorrectable), quint64(0));
    QVERIFY(QFileInfo::exists(session.sessionLogPath()));
    session.stop();
    QVERIFY(!session.isActive());
}

void TestConsoleSession::rehearsalWithoutUasimSaysWhy()
{
    ConsoleSession session(logDirectory(QStringLiteral("nouasim")));
    QSignalSpy failed(&session, &ConsoleSession::failed);
    const QString missing = m_dir.filePath(QStringLiteral("no-such-uasim"));
    session.startRehearsal(rcm::Airframe::wellEquipped(), QString(), missing);
    QTRY_COMPARE_WITH_TIMEOUT(failed.count(), 1, kTimeoutMs);
    QCOMPARE(failed.at(0).at(0).toString(),
             QStringLiteral("Rehearsal: The simulated aircraft %1 is not there; build the uasim target").arg(missing));
    QVERIFY(!session.isActive());
}

void TestConsoleSession::joinOfAStuckLinkThreadIsBounded()
{
    QSemaphore release;
    std::atomic<bool> gone = false;
    auto controller = std::make_unique<LinkController>(std::make_unique<StuckLink>(&release, &gone));
    QTest::ignoreMessage(QtWarningMsg,
                         QRegularExpression(QStringLiteral("^LinkController: waited 6000 ms for the link thread to "
                                                           "close its transport and end; it has not")));
    controller.reset();  // returns, the link thread still stuck in the link's destructor
    QVERIFY(!gone);
    // Unstuck, the thread goes on and destroys the link after all.
    release.release();
    QTRY_VERIFY_WITH_TIMEOUT(gone, kTimeoutMs);
}

// stop() does not wait for the link's thread; joinStoppedLinks() does, so
// that an owner can delete what the thread's hooks call (the main window's
// flight plan upload) once it returns.
void TestConsoleSession::stoppedLinksAreJoinedOnRequest()
{
    QSemaphore unstuck(1);  // its destruction does not block: it only says when it happened
    std::atomic<bool> gone = false;
    ConsoleSession session(logDirectory(QStringLiteral("join")));
    session.connectLink(std::make_unique<StuckLink>(&unstuck, &gone), QStringLiteral("stuck"));
    QTRY_VERIFY_WITH_TIMEOUT(session.isRunning(), kTimeoutMs);
    session.stop();
    QVERIFY(!session.isRunning());
    session.joinStoppedLinks();
    QVERIFY(gone);
    QVERIFY(session.findChildren<LinkController*>().isEmpty());
}

// An observation runs as a kind of session: read only (nothing is live,
// no link of ours runs), its keyed frames read with the keys given, what
// each frame sent commanded said by loggedCommand, and stop() ends it.
void TestConsoleSession::observationIsAKindOfSession()
{
    const rcm::secure::SecretKey psk = rcm::secure::generateKey();
    const auto key = std::make_shared<const rcm::LogKey>(psk);
    const rcm::secure::SecureCodec up(psk, rcm::secure::Direction::GcsToUa);
    const rcm::secure::SecureCodec down(psk, rcm::secure::Direction::UaToGcs);
    const rcm::secure::SecureCodec stranger(rcm::secure::generateKey(), rcm::secure::Direction::GcsToUa);
    rcm::Message sent = command(12);
    sent.header.set(rcm::ItemId::ID_msg, 7);
    sent.header.set(rcm::ItemId::time_UTC, std::int64_t(73200));
    sent.header.set(rcm::ItemId::date_UTC, std::int64_t(261122));

    ConsoleSession session(logDirectory(QStringLiteral("observed")));
    QSignalSpy started(&session, &ConsoleSession::observationStarted);
    QSignalSpy stopped(&session, &ConsoleSession::observationStopped);
    QSignalSpy linkStarted(&session, &ConsoleSession::linkStarted);
    QList<std::pair<qint64, std::optional<rcm::Message>>> commanded;
    connect(&session, &ConsoleSession::loggedCommand, this,
            [&](qint64 utc, const std::optional<rcm::Message>& m) { commanded.append({utc, m}); });
    auto owned = std::make_unique<ScriptedObservation>();
    ScriptedObservation* observation = owned.get();
    session.observe(std::move(owned), QStringLiteral("Observing GB_133 on the test"), {key});
    QCOMPARE(started.count(), 1);
    QCOMPARE(linkStarted.count(), 0);
    QVERIFY(observation->running);
    QCOMPARE(session.observation(), observation);
    QCOMPARE(session.kind(), ConsoleSession::Kind::Observation);
    QVERIFY(session.isActive());
    QVERIFY(!session.isLive());
    QVERIFY(!session.isRunning());
    QCOMPARE(session.description(), QStringLiteral("Observing GB_133 on the test"));
    QCOMPARE(session.logKey(), key);
    QCOMPARE(session.keyFingerprint(), QString::fromStdString(key->fingerprint()));

    emit observation->frameLogged(loggedFrame(sent, FrameDirection::Sent, up, 1000));
    emit observation->frameLogged(loggedFrame(sent, FrameDirection::Received, down, 2000));
    emit observation->frameLogged(loggedFrame(sent, FrameDirection::Sent, stranger, 3000));
    QCOMPARE(commanded.size(), 3);
    QCOMPARE(commanded.at(0).first, qint64(1000));
    QVERIFY(commanded.at(0).second);
    QCOMPARE(commanded.at(0).second->flaps.number(rcm::ItemId::F_elev_set), std::int64_t(12));
    QCOMPARE(commanded.at(0).second->header.number(rcm::ItemId::ID_msg), std::int64_t(7));
    // A report is no command; a frame no key of ours opens is not read.
    QCOMPARE(commanded.at(1).first, qint64(2000));
    QVERIFY(!commanded.at(1).second);
    QCOMPARE(commanded.at(2).first, qint64(3000));
    QVERIFY(!commanded.at(2).second);

    QPointer<Observation> gone(observation);
    session.stop();
    QCOMPARE(stopped.count(), 1);
    QVERIFY(!observation->running);
    QCOMPARE(session.kind(), ConsoleSession::Kind::None);
    QVERIFY(!session.isActive());
    QVERIFY(!session.observation());
    QVERIFY(session.description().isEmpty());
    QTRY_VERIFY_WITH_TIMEOUT(gone.isNull(), kTimeoutMs);
}

QTEST_MAIN(TestConsoleSession)
#include "tst_consolesession.moc"
