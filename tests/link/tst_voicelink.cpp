// The voice links: commands and voice on one serial line, 1,200 bytes a
// second, C V C V ..., over a pseudo-terminal; voice in datagrams of its own
// beside the commands over UDP on loopback. What the far end receives is
// counted in bytes and frames, and the phrase it hears is compared by its
// band energies. Time enters only through QTRY's patience.

// First: it names a member emit(), which Qt's headers define as a macro.
#include "codec/frame/StreamSync.h"

#include "BandEnergy.h"
#include "CommandFrame.h"
#include "UasimProcess.h"

#include "codec/message/MessageDecoder.h"
#include "codec/message/MessageEncoder.h"
#include "codec/voice/VoiceCodec.h"
#include "codec/voice/VoiceMux.h"
#include "codec/voice/WavFile.h"
#include "link/clock/VirtualClock.h"
#include "link/session/LinkWorker.h"
#include "link/transport/SerialLink.h"
#include "link/transport/UdpLink.h"
#include "link/voice/VoiceDecoderSink.h"
#include "link/voice/VoiceEncoderSource.h"
#include "link/voice/VoiceSerialLink.h"
#include "link/voice/VoiceUdpLink.h"

#include <QProcess>
#include <QSignalSpy>
#include <QSocketNotifier>
#include <QTemporaryDir>
#include <QTest>

#include <cerrno>
#include <fcntl.h>
#include <poll.h>
#include <pty.h>
#include <termios.h>
#include <unistd.h>

using namespace std::chrono_literals;

namespace {

constexpr int kPatience = 20000;      // ms QTRY waits for what a loaded machine may delay
constexpr double kToleranceDb = 6.0;  // as tst_voicecodec's, which says why

using Pcm = std::vector<std::int16_t>;

Pcm phrase()
{
    std::string error;
    const auto audio = rcm::WavFile::read(RCM_SOURCE_DIR "/resources/voice/phrase.wav", error);
    if (!audio)
        qFatal("phrase.wav: %s", error.c_str());
    return audio->samples;
}

std::size_t phraseFrames()
{
    return (phrase().size() + rcm::voice::kFrameSamples - 1) / rcm::voice::kFrameSamples;
}

// The aircraft's end of a pseudo-terminal: the master side, keeping every
// byte the line carried.
class PtyLine {
public:
    ~PtyLine()
    {
        m_notifier.reset();
        if (m_master >= 0)
            ::close(m_master);
        if (m_slave >= 0)
            ::close(m_slave);
    }

    bool open()
    {
        char name[256] = {};
        if (::openpty(&m_master, &m_slave, name, nullptr, nullptr) != 0)
            return false;
        ::fcntl(m_master, F_SETFL, ::fcntl(m_master, F_GETFL) | O_NONBLOCK);
        m_slavePath = QString::fromLocal8Bit(name);
        m_notifier = std::make_unique<QSocketNotifier>(m_master, QSocketNotifier::Read);
        QObject::connect(m_notifier.get(), &QSocketNotifier::activated, [this] {
            char buffer[4096];
            for (ssize_t n; (n = ::read(m_master, buffer, sizeof buffer)) > 0;)
                m_bytes.append(buffer, n);
        });
        return true;
    }

    QString slavePath() const { return m_slavePath; }
    const QByteArray& bytes() const { return m_bytes; }

private:
    int m_master = -1;
    int m_slave = -1;  // held so the master never sees "no slave" before the port opens
    QString m_slavePath;
    std::unique_ptr<QSocketNotifier> m_notifier;
    QByteArray m_bytes;
};

// What the far end makes of the line: frames (with their line offsets) and
// the voice, decoded.
struct Heard {
    std::vector<std::int64_t> frameOffsets;  // line offset of each good frame's preamble
    std::vector<std::int64_t> frameIds;
    Pcm pcm;
    rcm::voice::VoiceDecoder::Stats voice;
    std::uint64_t phaseChanges = 0;
    int controlPhase = 0;
};

Heard hear(const QByteArray& line)
{
    Heard h;
    rcm::voice::VoiceDecoder decoder;
    rcm::StreamSync sync([&](const rcm::SyncedFrame& f) {
        if (!f.ok())
            return;
        // One control byte per line pair, control first: with no phase
        // change, control offset k is line offset 2k.
        h.frameOffsets.push_back(2 * f.offset);
        const rcm::DecodeResult r = rcm::decodeBlocks(f.blocks);
        h.frameIds.push_back(r.message.header.number(rcm::ItemId::ID_msg, -1));
    });
    rcm::VoiceDemultiplexer demux([&](std::span<const std::uint8_t> b) { sync.feed(b); },
                                  [&](std::span<const std::uint8_t> b) { decoder.decode(b, h.pcm); });
    demux.feed({reinterpret_cast<const std::uint8_t*>(line.constData()), std::size_t(line.size())});
    sync.flush();
    h.voice = decoder.stats();
    h.phaseChanges = demux.stats().phaseChanges;
    h.controlPhase = demux.controlPhase();
    return h;
}

// The 20 ms slots of `pcm` that are not all silence, as [first, last + 1).
std::pair<std::size_t, std::size_t> soundingSlots(const Pcm& pcm)
{
    constexpr std::size_t n = rcm::voice::kFrameSamples;
    std::size_t first = pcm.size() / n;
    std::size_t end = 0;
    for (std::size_t s = 0; s < pcm.size() / n; ++s) {
        if (std::any_of(pcm.begin() + std::ptrdiff_t(s * n), pcm.begin() + std::ptrdiff_t((s + 1) * n),
                        [](std::int16_t x) { return x != 0; })) {
            first = std::min(first, s);
            end = s + 1;
        }
    }
    return {first, std::max(first, end)};
}

// The phrase came out as long as it went in (whole frames), in one piece,
// with its energy in the same bands.
void verifyPhrase(const Pcm& out, const Pcm& in = phrase())
{
    const auto [first, end] = soundingSlots(out);
    QCOMPARE(end - first, phraseFrames());
    const Pcm speech(out.begin() + std::ptrdiff_t(first * rcm::voice::kFrameSamples),
                     out.begin() + std::ptrdiff_t(end * rcm::voice::kFrameSamples));
    const auto a = rcm::test::bandEnergyDb(in);
    const auto b = rcm::test::bandEnergyDb(speech);
    for (std::size_t i = 0; i < rcm::test::kBands; ++i)
        QVERIFY2(std::abs(a[i] - b[i]) <= kToleranceDb,
                 qPrintable(QStringLiteral("band %1: %2 dB in, %3 dB out").arg(i).arg(a[i]).arg(b[i])));
}

// Two pseudo-terminals joined master to master: a null-modem cable between
// two programs that each open a serial device.
class PtyBridge {
public:
    ~PtyBridge()
    {
        for (End& e : m_ends) {
            e.notifier.reset();
            if (e.master >= 0)
                ::close(e.master);
            if (e.slave >= 0)
                ::close(e.slave);
        }
    }

    bool open()
    {
        for (std::size_t i = 0; i < 2; ++i) {
            End& e = m_ends[i];
            char name[256] = {};
            // Raw from the start, as a cable is: a new pty echoes, and until
            // the console opened its end, uasim would hear its own bytes come
            // back, a stray byte of them enough to swap its demultiplexer's
            // phases until the console's first preamble, up to a second of
            // the phrase later.
            termios raw{};
            ::cfmakeraw(&raw);
            if (::openpty(&e.master, &e.slave, name, &raw, nullptr) != 0)
                return false;
            ::fcntl(e.master, F_SETFL, ::fcntl(e.master, F_GETFL) | O_NONBLOCK);
            e.path = QString::fromLocal8Bit(name);
            e.notifier = std::make_unique<QSocketNotifier>(e.master, QSocketNotifier::Read);
            QObject::connect(e.notifier.get(), &QSocketNotifier::activated, [this, i] { carry(i); });
        }
        return true;
    }

    QString path(std::size_t end) const { return m_ends[end].path; }
    // What the program on `end` sent.
    qsizetype bytesFrom(std::size_t end) const { return m_ends[end].carried; }

private:
    struct End {
        int master = -1;
        int slave = -1;  // held so the master never sees "no slave" before the program opens it
        QString path;
        std::unique_ptr<QSocketNotifier> notifier;
        qsizetype carried = 0;
    };

    void carry(std::size_t from)
    {
        const int to = m_ends[1 - from].master;
        char buffer[4096];
        for (ssize_t n; (n = ::read(m_ends[from].master, buffer, sizeof buffer)) > 0;) {
            m_ends[from].carried += n;
            for (ssize_t done = 0; done < n;) {
                const ssize_t w = ::write(to, buffer + done, std::size_t(n - done));
                if (w > 0) {
                    done += w;
                } else if (errno == EAGAIN) {
                    pollfd p{to, POLLOUT, 0};
                    ::poll(&p, 1, -1);
                } else if (errno != EINTR) {
                    return;
                }
            }
        }
    }

    std::array<End, 2> m_ends;
};

// How many 20 ms slots of a WAV file sound, and the samples of those slots.
Pcm soundingPart(const Pcm& pcm)
{
    const auto [first, end] = soundingSlots(pcm);
    return Pcm(pcm.begin() + std::ptrdiff_t(first * rcm::voice::kFrameSamples),
               pcm.begin() + std::ptrdiff_t(end * rcm::voice::kFrameSamples));
}

VoiceSerialLink::Options fastLine()
{
    VoiceSerialLink::Options o;
    o.bytesPerSecond = 12000;  // ten times the modem: a frame period is 100 ms
    o.lead = 240;
    return o;
}

}  // namespace

class TestVoiceLink : public QObject {
    Q_OBJECT

private slots:
    void framesQueuedTogetherGoBackToBack();
    void workerCadenceGives1200BytesASecond();
    void phraseOverTheSerialLine();
    void writesOnlyWholeFrames();
    void voiceDatagramFormat();
    void phraseOverUdpBesideCommands();
    void uasimRecordsThePhraseAndSpeaksBack();
    void uasimOverUdpSpeaksFromTheFirstCommand();
    void uasimEchoesWhatItHears();
};

// Four frames written at once go out back to back: their preambles stand
// exactly 1,200 line bytes apart, each frame interleaved with 600 voice
// bytes, and fill before the first.
void TestVoiceLink::framesQueuedTogetherGoBackToBack()
{
    PtyLine far;
    QVERIFY(far.open());
    VoiceSerialLink link(std::make_unique<SerialLink>(far.slavePath()), nullptr, nullptr, fastLine());
    QSignalSpy opened(&link, &Link::opened);
    link.open();
    QVERIFY(link.isOpen());
    QCOMPARE(opened.count(), 1);
    for (std::uint32_t id = 1; id <= 4; ++id)
        QVERIFY(link.write(rcm::test::commandFrame(id)));
    QTRY_COMPARE_WITH_TIMEOUT(hear(far.bytes()).frameIds.size(), std::size_t(4), kPatience);

    const Heard h = hear(far.bytes());
    QCOMPARE(h.phaseChanges, std::uint64_t(0));
    QCOMPARE(h.frameIds, (std::vector<std::int64_t>{1, 2, 3, 4}));
    for (std::size_t i = 1; i < h.frameOffsets.size(); ++i)
        QCOMPARE(h.frameOffsets[i] - h.frameOffsets[i - 1], std::int64_t(rcm::kMuxedFrameSize));
    // Voice (idle) all along, in step from the first byte.
    QCOMPARE(h.voice.resyncs, std::uint64_t(0));
    QCOMPARE(h.voice.lostFrames, std::uint64_t(0));
    QVERIFY(h.voice.idleFrames * rcm::voice::kFrameBytes + rcm::voice::kFrameBytes >=
            std::uint64_t(far.bytes().size() / 2));
    QCOMPARE(link.multiplexer().stats().framesStarted, std::uint64_t(4));
}

// The link worker at its real cadence, a frame a second, over the voice
// line at its real rate, both on one clock stepped by the test: the line
// carries exactly 1,200 bytes from one preamble to the next, every second.
void TestVoiceLink::workerCadenceGives1200BytesASecond()
{
    PtyLine far;
    QVERIFY(far.open());
    const auto clock = std::make_shared<VirtualClock>(0);
    VoiceSerialLink::Options line;
    line.clock = clock;
    auto link =
        std::make_unique<VoiceSerialLink>(std::make_unique<SerialLink>(far.slavePath()), nullptr, nullptr, line);
    LinkWorker::Options options;
    options.clock = clock;
    LinkWorker worker(std::move(link), nullptr, options);
    rcm::Message command;
    command.header.set(rcm::ItemId::ID_UA_source, rcm::Value::pair(44, 133));
    worker.setCommand(command);
    QSignalSpy sent(&worker, &LinkWorker::frameSent);
    worker.start();
    // A frame sent each second from 1 s on takes a second of line, the first
    // held 200 ms: by 5.5 s four have gone out whole and the fifth is on the line.
    // The event loop runs between ticks, as it does live, so that the port
    // takes each tick's bytes (the pacing holds back what it has not taken).
    for (int step = 0; step < 550; ++step) {
        clock->advance(10ms);
        QCoreApplication::processEvents();
    }
    QCOMPARE(sent.count(), 5);
    QTRY_COMPARE_WITH_TIMEOUT(hear(far.bytes()).frameOffsets.size(), std::size_t(4), kPatience);
    worker.stop();

    const Heard h = hear(far.bytes());
    QCOMPARE(h.phaseChanges, std::uint64_t(0));
    for (std::size_t i = 1; i < h.frameOffsets.size(); ++i)
        QCOMPARE(h.frameOffsets[i] - h.frameOffsets[i - 1], std::int64_t(rcm::kMuxedFrameSize));
    for (std::size_t i = 1; i < h.frameIds.size(); ++i)
        QCOMPARE(h.frameIds[i], h.frameIds[i - 1] + 1);
    QCOMPARE(h.voice.resyncs, std::uint64_t(0));
}

// Commands and the phrase at once: the far end finds the frames in the
// control phase and hears the phrase, whole, in the voice phase.
void TestVoiceLink::phraseOverTheSerialLine()
{
    PtyLine far;
    QVERIFY(far.open());
    auto source = std::make_shared<VoiceEncoderSource>(0ms);
    const Pcm in = phrase();
    source->pushPcm(in);
    source->endTalk();
    VoiceSerialLink link(std::make_unique<SerialLink>(far.slavePath()), source, nullptr, fastLine());
    link.open();
    QVERIFY(link.write(rcm::test::commandFrame(7)));
    QVERIFY(link.write(rcm::test::commandFrame(8)));
    QTRY_COMPARE_WITH_TIMEOUT(source->speechFramesSent(), std::uint64_t(phraseFrames()), kPatience);
    QTRY_COMPARE_WITH_TIMEOUT(hear(far.bytes()).frameIds.size(), std::size_t(2), kPatience);
    // Then a little idle, so the far end has the last voice frame whole.
    const qsizetype enough = far.bytes().size() + 4 * qsizetype(rcm::voice::kFrameBytes);
    QTRY_VERIFY_WITH_TIMEOUT(far.bytes().size() >= enough, kPatience);

    const Heard h = hear(far.bytes());
    QCOMPARE(h.frameIds, (std::vector<std::int64_t>{7, 8}));
    QCOMPARE(h.voice.speechFrames, std::uint64_t(phraseFrames()));
    QCOMPARE(h.voice.lostFrames, std::uint64_t(0));
    verifyPhrase(h.pcm);
}

void TestVoiceLink::writesOnlyWholeFrames()
{
    PtyLine far;
    QVERIFY(far.open());
    VoiceSerialLink link(std::make_unique<SerialLink>(far.slavePath()), nullptr, nullptr, fastLine());
    QVERIFY(!link.write(rcm::test::commandFrame(1)));  // closed
    link.open();
    QVERIFY(!link.write(QByteArray(599, 'x')));
    QVERIFY(!link.write(rcm::test::commandFrame(1).left(510)));
    QVERIFY(link.write(rcm::test::commandFrame(1)));
    QVERIFY(link.isStream());
    QCOMPARE(link.transport(), FrameTransport::Serial);
    QVERIFY(link.description().contains(QStringLiteral("voice multiplexed")));
}

// As a plain UDP peer sees it: "RCMV" and one 12-byte voice frame per
// datagram, beside the 510-byte command datagrams; and what the voice link
// takes for voice and what it passes on.
void TestVoiceLink::voiceDatagramFormat()
{
    UdpLink peer(QHostAddress::LocalHost, 0);
    QSignalSpy fromVoiceLink(&peer, &Link::datagramReceived);
    peer.open();
    QVERIFY(peer.isOpen());
    VoiceUdpLink link(std::make_unique<UdpLink>(QHostAddress::LocalHost, 0, QHostAddress::LocalHost, peer.boundPort()),
                      std::make_shared<VoiceEncoderSource>(), nullptr);
    QSignalSpy commands(&link, &Link::datagramReceived);
    link.open();
    QVERIFY(link.isOpen());
    QVERIFY(!link.isStream());
    const QByteArray command = rcm::test::commandFrame(3).mid(rcm::kPreambleSize);
    QVERIFY(link.write(command));
    QTRY_VERIFY_WITH_TIMEOUT(fromVoiceLink.count() >= 10, kPatience);
    int voice = 0;
    int commandsSeen = 0;
    for (const QList<QVariant>& args : fromVoiceLink) {
        const QByteArray d = args.at(0).toByteArray();
        if (d == command) {
            ++commandsSeen;
            continue;
        }
        QCOMPARE(d.size(), qsizetype(16));
        QVERIFY(d.startsWith("RCMV"));
        QVERIFY(VoiceUdpLink::isVoiceDatagram(d));
        rcm::voice::VoiceFrame f;
        QVERIFY(rcm::voice::parseFrame(
            std::span<const std::uint8_t, 12>(reinterpret_cast<const std::uint8_t*>(d.constData()) + 4, 12), f));
        QCOMPARE(f.kind, rcm::voice::FrameKind::Idle);
        ++voice;
    }
    QCOMPARE(commandsSeen, 1);
    QVERIFY(voice >= 9);

    // The other way: voice is taken, commands and anything else pass on.
    peer.setRemote(QHostAddress::LocalHost, qobject_cast<UdpLink*>(link.inner())->boundPort());
    QVERIFY(peer.write(command));
    QVERIFY(peer.write(QByteArray("RCMV") + QByteArray(5, '\0')));  // not whole frames
    QVERIFY(peer.write(fromVoiceLink.last().at(0).toByteArray()));  // a voice frame
    QTRY_COMPARE_WITH_TIMEOUT(commands.count(), 2, kPatience);
    QCOMPARE(commands.at(0).at(0).toByteArray(), command);
    QCOMPARE(commands.at(1).at(0).toByteArray().size(), qsizetype(9));
    QTRY_COMPARE_WITH_TIMEOUT(link.voiceDatagramsReceived(), std::uint64_t(1), kPatience);
    QVERIFY(!VoiceUdpLink::isVoiceDatagram(command));
}

// The phrase from one voice link to another over UDP, with a command
// datagram each way: the commands arrive as commands, the phrase whole. Both
// are paced by one clock the test steps, 10 ms at a time, letting each
// step's datagrams arrive on loopback before the next.
void TestVoiceLink::phraseOverUdpBesideCommands()
{
    const auto clock = std::make_shared<VirtualClock>(0);
    const auto run = [&](std::chrono::milliseconds duration) {
        for (auto t = 0ms; t < duration; t += VoiceUdpLink::kTick) {
            clock->advance(VoiceUdpLink::kTick);
            QCoreApplication::processEvents();
        }
    };
    Pcm heard;
    auto sink = std::make_shared<VoiceDecoderSink>(
        [&](std::span<const std::int16_t> pcm) { heard.insert(heard.end(), pcm.begin(), pcm.end()); });
    auto aircraftUdp = std::make_unique<UdpLink>(QHostAddress::LocalHost, 0);
    aircraftUdp->setReplyToSender(true);
    VoiceUdpLink aircraft(std::move(aircraftUdp), std::make_shared<VoiceEncoderSource>(), sink, clock);
    QSignalSpy aircraftCommands(&aircraft, &Link::datagramReceived);
    aircraft.open();
    const quint16 port = qobject_cast<UdpLink*>(aircraft.inner())->boundPort();

    auto source = std::make_shared<VoiceEncoderSource>(0ms);
    VoiceUdpLink console(std::make_unique<UdpLink>(QHostAddress::LocalHost, 0, QHostAddress::LocalHost, port), source,
                         nullptr, clock);
    QSignalSpy consoleCommands(&console, &Link::datagramReceived);
    console.open();
    const QByteArray command = rcm::test::commandFrame(5).mid(rcm::kPreambleSize);
    QVERIFY(console.write(command));
    QTRY_COMPARE_WITH_TIMEOUT(aircraftCommands.count(), 1, kPatience);
    QCOMPARE(aircraftCommands.at(0).at(0).toByteArray(), command);
    QVERIFY(aircraft.write(command));  // to whoever sent the last datagram
    QTRY_COMPARE_WITH_TIMEOUT(consoleCommands.count(), 1, kPatience);

    source->pushPcm(phrase());
    source->endTalk();
    run(std::chrono::milliseconds(20 * phraseFrames()));
    QTRY_COMPARE_WITH_TIMEOUT(sink->speechFrames(), std::uint64_t(phraseFrames()), kPatience);
    const std::uint64_t enough = sink->samplesOut() + 2 * rcm::voice::kFrameSamples;
    run(40ms);
    QTRY_VERIFY_WITH_TIMEOUT(sink->samplesOut() >= enough, kPatience);
    QCOMPARE(aircraftCommands.count(), 1);  // voice never passed for a command
    verifyPhrase(heard);
}

// The console's side, a link worker on a voice line with the phrase to say,
// against uasim --voice-out --voice-in on the other end of a null modem:
// uasim's WAV holds the phrase, as long as it went in, with its energy in the
// same bands; and the console hears uasim's phrase likewise.
void TestVoiceLink::uasimRecordsThePhraseAndSpeaksBack()
{
    PtyBridge cable;
    QVERIFY(cable.open());
    QTemporaryDir dir;
    QVERIFY(dir.isValid());
    const QString heardPath = dir.filePath(QStringLiteral("heard.wav"));
    QProcess uasim;
    uasim.setProcessChannelMode(QProcess::ForwardedErrorChannel);
    uasim.start(QStringLiteral(RCM_BIN_DIR "/uasim"),
                {QStringLiteral("--serial"), cable.path(1), QStringLiteral("--voice-out"), heardPath,
                 QStringLiteral("--voice-in"), QStringLiteral(RCM_SOURCE_DIR "/resources/voice/phrase.wav")});
    QVERIFY2(uasim.waitForStarted(), "build uasim first");
    // uasim's line is running: from here on the console's bytes all reach it.
    QTRY_VERIFY_WITH_TIMEOUT(cable.bytesFrom(1) > 0, kPatience);

    Pcm consoleHeard;
    auto sink = std::make_shared<VoiceDecoderSink>(
        [&](std::span<const std::int16_t> pcm) { consoleHeard.insert(consoleHeard.end(), pcm.begin(), pcm.end()); });
    auto source = std::make_shared<VoiceEncoderSource>(0ms);
    source->pushPcm(phrase());
    source->endTalk();
    LinkWorker worker(std::make_unique<VoiceSerialLink>(std::make_unique<SerialLink>(cable.path(0)), source, sink),
                      nullptr);
    rcm::Message command;
    command.header.set(rcm::ItemId::ID_UA_source, rcm::Value::pair(44, 133));
    worker.setCommand(command);
    QSignalSpy replies(&worker, &LinkWorker::messageReceived);
    worker.start();

    // uasim answers the commands, and says its phrase.
    QTRY_VERIFY_WITH_TIMEOUT(replies.count() >= 2, kPatience);
    QTRY_COMPARE_WITH_TIMEOUT(sink->speechFrames(), std::uint64_t(phraseFrames()), kPatience);
    QCOMPARE(sink->stats().lostFrames, std::uint64_t(0));
    verifyPhrase(consoleHeard);

    // uasim's record of what it would put on the VHF radio.
    std::string error;
    const auto heardSoFar = [&] {
        const auto wav = rcm::WavFile::read(heardPath.toStdString(), error);
        return wav ? soundingPart(wav->samples).size() / rcm::voice::kFrameSamples : 0;
    };
    QTRY_COMPARE_WITH_TIMEOUT(heardSoFar(), phraseFrames(), kPatience);
    worker.stop();
    uasim.terminate();
    QVERIFY(uasim.waitForFinished(kPatience));
    QCOMPARE(uasim.exitStatus(), QProcess::NormalExit);
    const auto heard = rcm::WavFile::read(heardPath.toStdString(), error);
    QVERIFY2(heard, error.c_str());
    QCOMPARE(heard->sampleRate, rcm::voice::kSampleRate);
    verifyPhrase(heard->samples);
}

// uasim over UDP learns where to send from the console's first command: its
// --voice-in waits for that, so the console hears the whole phrase however
// late its first command comes (here, a second after uasim was ready).
void TestVoiceLink::uasimOverUdpSpeaksFromTheFirstCommand()
{
    rcm::test::UasimProcess uasim(
        {QStringLiteral("--voice-in"), QStringLiteral(RCM_SOURCE_DIR "/resources/voice/phrase.wav")});
    QVERIFY2(uasim.start(), "build uasim first");
    QTRY_VERIFY_WITH_TIMEOUT(uasim.listening(), kPatience);
    QTest::qWait(1000);  // the console comes late: this is what is being tested, not a wait for something

    Pcm heard;
    auto sink = std::make_shared<VoiceDecoderSink>(
        [&](std::span<const std::int16_t> pcm) { heard.insert(heard.end(), pcm.begin(), pcm.end()); });
    LinkWorker worker(std::make_unique<VoiceUdpLink>(
                          std::make_unique<UdpLink>(QHostAddress::LocalHost, 0, QHostAddress::LocalHost, uasim.port()),
                          std::make_shared<VoiceEncoderSource>(), sink),
                      nullptr);
    rcm::Message command;
    command.header.set(rcm::ItemId::ID_UA_source, rcm::Value::pair(44, 133));
    worker.setCommand(command);
    worker.start();
    QTRY_COMPARE_WITH_TIMEOUT(sink->speechFrames(), std::uint64_t(phraseFrames()), kPatience);
    const std::uint64_t enough = sink->samplesOut() + 2 * rcm::voice::kFrameSamples;
    QTRY_VERIFY_WITH_TIMEOUT(sink->samplesOut() >= enough, kPatience);
    QCOMPARE(sink->stats().lostFrames, std::uint64_t(0));
    verifyPhrase(heard);
    worker.stop();
}

// uasim --voice-echo (what gcs --rehearsal starts when the console has
// voice) says back what it hears: the console hears its own phrase.
void TestVoiceLink::uasimEchoesWhatItHears()
{
    rcm::test::UasimProcess uasim({QStringLiteral("--voice-echo")});
    QVERIFY2(uasim.start(), "build uasim first");
    QTRY_VERIFY_WITH_TIMEOUT(uasim.listening(), kPatience);
    Pcm heard;
    auto sink = std::make_shared<VoiceDecoderSink>(
        [&](std::span<const std::int16_t> pcm) { heard.insert(heard.end(), pcm.begin(), pcm.end()); });
    auto source = std::make_shared<VoiceEncoderSource>(0ms);
    LinkWorker worker(std::make_unique<VoiceUdpLink>(
                          std::make_unique<UdpLink>(QHostAddress::LocalHost, 0, QHostAddress::LocalHost, uasim.port()),
                          source, sink),
                      nullptr);
    rcm::Message command;
    command.header.set(rcm::ItemId::ID_UA_source, rcm::Value::pair(44, 133));
    worker.setCommand(command);
    QSignalSpy replies(&worker, &LinkWorker::messageReceived);
    worker.start();
    QTRY_VERIFY_WITH_TIMEOUT(replies.count() >= 1, kPatience);  // uasim knows where to answer
    source->pushPcm(phrase());
    source->endTalk();
    QTRY_COMPARE_WITH_TIMEOUT(sink->speechFrames(), std::uint64_t(phraseFrames()), kPatience);
    const std::uint64_t enough = sink->samplesOut() + 2 * rcm::voice::kFrameSamples;
    QTRY_VERIFY_WITH_TIMEOUT(sink->samplesOut() >= enough, kPatience);
    // Through Codec 2 twice (tandem coding), which takes more from the high
    // bands than once: compared with the phrase coded twice here.
    const auto coded = [](const Pcm& pcm) {
        rcm::voice::VoiceEncoder encoder;
        std::vector<std::uint8_t> bytes;
        encoder.encode(pcm, bytes);
        encoder.finish(bytes);
        rcm::voice::VoiceDecoder decoder;
        Pcm out;
        decoder.decode(bytes, out);
        return out;
    };
    verifyPhrase(heard, coded(coded(phrase())));
    worker.stop();
}

QTEST_GUILESS_MAIN(TestVoiceLink)
#include "tst_voicelink.moc"
