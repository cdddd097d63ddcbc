// Push to talk on the console: the button and the F12 key, the microphone
// or a WAV file, the level meters, and received voice on its way to the
// speaker. No sound card is needed: the rehearsal file stands in for the
// microphone, and what would be played is read from the playback FIFO.
#include "UasimProcess.h"

#include "codec/secure/SecureCodec.h"
#include "codec/voice/SecureVoice.h"
#include "codec/voice/VoiceCodec.h"
#include "codec/voice/WavFile.h"
#include "link/transport/SerialLink.h"
#include "link/transport/UdpLink.h"
#include "link/voice/VoiceEncoderSource.h"
#include "link/voice/VoiceSerialLink.h"
#include "link/voice/VoiceUdpLink.h"
#include "ui/voice/PcmFifo.h"
#include "ui/voice/PushToTalkWidget.h"
#include "ui/voice/VoiceChannel.h"

#include <QCheckBox>
#include <QMainWindow>
#include <QPushButton>
#include <QSignalSpy>
#include <QFile>
#include <QProcess>
#include <QStandardPaths>
#include <QTemporaryDir>
#include <QTest>
#include <QUdpSocket>

namespace {

constexpr int kPatience = 10000;  // ms QTRY waits for what a loaded machine may delay
const QString kPhrase = QStringLiteral(RCM_SOURCE_DIR "/resources/voice/phrase.wav");

std::size_t phraseSamples()
{
    std::string error;
    return rcm::WavFile::read(kPhrase.toStdString(), error)->samples.size();
}

// A transport that is only a replay: voice must leave it alone.
class FakeReplay : public Link {
public:
    FrameTransport transport() const override { return FrameTransport::Replay; }
    bool isStream() const override { return false; }
    bool isOpen() const override { return false; }
    QString description() const override { return QStringLiteral("replay"); }
    void open() override {}
    void close() override {}
    bool write(const QByteArray&) override { return false; }
};

struct Console {
    QMainWindow window;
    VoiceChannel* channel = new VoiceChannel(&window);
    PushToTalkWidget* widget = new PushToTalkWidget(channel);
    QCheckBox* voiceOn = widget->findChild<QCheckBox*>(QStringLiteral("voiceOn"));
    QPushButton* talk = widget->findChild<QPushButton*>(QStringLiteral("pushToTalk"));

    Console()
    {
        window.setCentralWidget(widget);
        window.show();
    }
};

}  // namespace

class TestPushToTalk : public QObject {
    Q_OBJECT

private slots:
    void voiceIsOffUntilTurnedOn();
    void buttonAndKeyTalk();
    void attachWrapsTheTransport();
    void rehearsalFileGoesOutWithItsLevel();
    void receivedVoiceIsPlayedAndMetered();
    void secureSpeechReachesUasimBitExact();
};

void TestPushToTalk::voiceIsOffUntilTurnedOn()
{
    Console c;
    QVERIFY(c.voiceOn && c.talk);
    QVERIFY(!c.channel->isEnabled());
    QVERIFY(!c.talk->isEnabled());
    c.channel->startTalking();
    QVERIFY(!c.channel->isTalking());
    // Voice off: a serial line is left as it is; a UDP link is wrapped only
    // to set aside the aircraft's voice datagrams, and sends none.
    auto serial = std::make_unique<SerialLink>(QStringLiteral("/dev/null-voice"));
    Link* plain = serial.get();
    QCOMPARE(c.channel->attach(std::move(serial)).get(), plain);
    auto udp = c.channel->attach(std::make_unique<UdpLink>(QHostAddress::LocalHost, 0));
    auto* wrapped = qobject_cast<VoiceUdpLink*>(udp.get());
    QVERIFY(wrapped);
    QSignalSpy ignored(c.channel, &VoiceChannel::voiceIgnored);
    QSignalSpy frames(udp.get(), &Link::datagramReceived);
    udp->open();
    const quint16 port = qobject_cast<UdpLink*>(wrapped->inner())->boundPort();
    QUdpSocket aircraft;
    QByteArray voice = QByteArray::fromRawData(VoiceUdpLink::kMagic, 4) + QByteArray(12, '\x55');
    for (int i = 0; i < 10; ++i)
        aircraft.writeDatagram(voice, QHostAddress::LocalHost, port);
    aircraft.writeDatagram(QByteArray(16, 'x'), QHostAddress::LocalHost, port);  // not voice: the worker's to refuse
    QTRY_COMPARE_WITH_TIMEOUT(frames.count(), 1, kPatience);
    QCOMPARE(frames.at(0).at(0).toByteArray().size(), 16);
    QTRY_COMPARE_WITH_TIMEOUT(wrapped->voiceDatagramsReceived(), std::uint64_t(10), kPatience);
    QTRY_COMPARE_WITH_TIMEOUT(ignored.count(), 1, kPatience);
    QCOMPARE(wrapped->voiceDatagramsSent(), std::uint64_t(0));
    QTest::mouseClick(c.voiceOn, Qt::LeftButton);
    QVERIFY(c.channel->isEnabled());
    QVERIFY(c.talk->isEnabled());
}

void TestPushToTalk::buttonAndKeyTalk()
{
    Console c;
    c.voiceOn->setChecked(true);
    QSignalSpy talking(c.channel, &VoiceChannel::talkingChanged);
    QTest::mousePress(c.talk, Qt::LeftButton);
    QVERIFY(c.channel->isTalking());
    QTest::mouseRelease(c.talk, Qt::LeftButton);
    QVERIFY(!c.channel->isTalking());

    // F12 held anywhere in the window: here, on the check box.
    QTest::keyPress(c.voiceOn, PushToTalkWidget::kTalkKey);
    QVERIFY(c.channel->isTalking());
    QKeyEvent repeat(QEvent::KeyPress, PushToTalkWidget::kTalkKey, Qt::NoModifier, QString(), true);
    QApplication::sendEvent(c.voiceOn, &repeat);  // the key's auto-repeat changes nothing
    QVERIFY(c.channel->isTalking());
    // X's auto-repeat as Qt 6.4 passes it on: a release and a press at
    // once, neither marked auto-repeat. The talk goes on; it does not start again.
    for (int i = 0; i < 5; ++i) {
        QTest::keyRelease(c.voiceOn, PushToTalkWidget::kTalkKey);
        QTest::keyPress(c.voiceOn, PushToTalkWidget::kTalkKey);
    }
    QVERIFY(c.channel->isTalking());
    QCOMPARE(talking.count(), 3);
    QTest::keyRelease(c.voiceOn, PushToTalkWidget::kTalkKey);
    QVERIFY(c.channel->isTalking());  // the grace for a press to follow
    QTRY_VERIFY(!c.channel->isTalking());
    QCOMPARE(talking.count(), 4);
    QVERIFY(c.voiceOn->isChecked());  // F12 was not taken for anything else

    // Turning voice off stops the talk.
    QTest::keyPress(c.talk, PushToTalkWidget::kTalkKey);
    QVERIFY(c.channel->isTalking());
    c.voiceOn->setChecked(false);
    QVERIFY(!c.channel->isTalking());
}

void TestPushToTalk::attachWrapsTheTransport()
{
    VoiceChannel channel;
    channel.setEnabled(true);
    auto serial = channel.attach(std::make_unique<SerialLink>(QStringLiteral("/dev/null-voice")));
    QVERIFY(qobject_cast<VoiceSerialLink*>(serial.get()));
    QVERIFY(serial->isStream());
    auto udp = channel.attach(std::make_unique<UdpLink>(QHostAddress::LocalHost, 0));
    QVERIFY(qobject_cast<VoiceUdpLink*>(udp.get()));
    auto replay = std::make_unique<FakeReplay>();
    Link* plain = replay.get();
    QCOMPARE(channel.attach(std::move(replay)).get(), plain);
}

// Pushing to talk with a WAV file chosen sends the file: the link's reads
// from the source are the phrase, then idle once the key is let go; the
// "out" meter moves while it goes.
void TestPushToTalk::rehearsalFileGoesOutWithItsLevel()
{
    Console c;
    c.voiceOn->setChecked(true);
    c.widget->setRehearsalFile(kPhrase);
    QCOMPARE(c.channel->rehearsalFile(), kPhrase);
    const auto source = c.channel->source();
    QTest::mousePress(c.talk, Qt::LeftButton);
    QTRY_COMPARE_WITH_TIMEOUT(source->backlogSamples(), phraseSamples(), kPatience);

    // The link's side: a second of the voice stream, decoded.
    std::vector<std::uint8_t> bytes(rcm::voice::kBytesPerSecond);
    source->readVoice(bytes);
    rcm::voice::VoiceDecoder decoder;
    std::vector<std::int16_t> pcm;
    decoder.decode(bytes, pcm);
    QCOMPARE(decoder.stats().speechFrames, std::uint64_t(rcm::voice::kFramesPerSecond));
    QTRY_VERIFY_WITH_TIMEOUT(c.widget->sentMeter() > 0, kPatience);

    QTest::mouseRelease(c.talk, Qt::LeftButton);
    QTRY_COMPARE_WITH_TIMEOUT(source->backlogSamples(), std::size_t(0), kPatience);
    source->readVoice(bytes);
    decoder.decode(bytes, pcm);
    QVERIFY(decoder.stats().idleFrames >= rcm::voice::kFramesPerSecond - 1);
    source->readVoice(bytes);
    QTRY_COMPARE_WITH_TIMEOUT(c.widget->sentMeter(), 0, kPatience);
}

// Voice arriving over the link goes to the playback FIFO, and the "in"
// meter moves.
void TestPushToTalk::receivedVoiceIsPlayedAndMetered()
{
    Console c;
    c.voiceOn->setChecked(true);
    std::unique_ptr<Link> link = c.channel->attach(std::make_unique<UdpLink>(QHostAddress::LocalHost, 0));
    link->open();
    QVERIFY(link->isOpen());
    const quint16 port = qobject_cast<UdpLink*>(qobject_cast<VoiceUdpLink*>(link.get())->inner())->boundPort();

    VoiceEncoderSource aircraft(std::chrono::milliseconds(0));
    std::string error;
    QVERIFY(aircraft.speakFile(kPhrase.toStdString(), error));
    UdpLink peer(QHostAddress::LocalHost, 0, QHostAddress::LocalHost, port);
    peer.open();
    for (int i = 0; i < 25; ++i) {
        QByteArray datagram("RCMV");
        datagram.resize(4 + qsizetype(rcm::voice::kFrameBytes));
        aircraft.readVoice({reinterpret_cast<std::uint8_t*>(datagram.data()) + 4, rcm::voice::kFrameBytes});
        QVERIFY(peer.write(datagram));
    }
    QTRY_VERIFY_WITH_TIMEOUT(c.channel->samplesReceived() >= 24 * rcm::voice::kFrameSamples, kPatience);
    QTRY_VERIFY_WITH_TIMEOUT(c.widget->receivedMeter() > 0, kPatience);
}

namespace {

// A program the test needs from Debian (scripts/install-deps installs it), run to its end.
bool runTool(const QString& tool, const QStringList& arguments, QString* said)
{
    QProcess p;
    p.setProcessChannelMode(QProcess::MergedChannels);
    p.start(tool, arguments);
    const bool ok = p.waitForFinished(60000) && p.exitStatus() == QProcess::NormalExit && p.exitCode() == 0;
    *said = tool + QLatin1Char(' ') + arguments.join(QLatin1Char(' ')) + QStringLiteral(": ") +
            QString::fromLocal8Bit(p.readAll());
    return ok;
}

std::vector<std::int16_t> rawSamples(const QString& path)
{
    QFile f(path);
    if (!f.open(QIODevice::ReadOnly))
        return {};
    const QByteArray bytes = f.readAll();
    std::vector<std::int16_t> samples(std::size_t(bytes.size()) / 2);
    std::memcpy(samples.data(), bytes.constData(), samples.size() * 2);
    return samples;
}

// Where `part` stands in `whole` on a 20 ms slot boundary; -1 if nowhere.
qsizetype slotOf(const std::vector<std::int16_t>& whole, const std::vector<std::int16_t>& part)
{
    const std::size_t slot = rcm::voice::kFrameSamples;
    for (std::size_t at = 0; at + part.size() <= whole.size(); at += slot)
        if (std::equal(part.begin(), part.end(), whole.begin() + std::ptrdiff_t(at)))
            return qsizetype(at);
    return -1;
}

}  // namespace

// Real speech through the console's push-to-talk to the simulated aircraft
// on a keyed link: espeak-ng speaks, sox makes it 8 kHz, the console says the
// file with push to talk (the voice pane's WAV file), sealed under the key,
// and uasim --voice-out writes what its radio would transmit. That is
// exactly, sample for sample, what Codec 2's own c2enc and c2dec make of the
// same input, time-aligned on a 20 ms slot, with silence around it. Then a
// recorded (authentic) frame sent again and a forged one: uasim refuses and
// counts both, and plays neither.
void TestPushToTalk::secureSpeechReachesUasimBitExact()
{
    for (const char* tool : {"espeak-ng", "sox", "c2enc", "c2dec"})
        QVERIFY2(!QStandardPaths::findExecutable(QLatin1String(tool)).isEmpty(),
                 qPrintable(QStringLiteral("%1 is missing: scripts/install-deps installs it").arg(tool)));
    QTemporaryDir dir;
    QVERIFY(dir.isValid());
    const QString spoken = dir.filePath(QStringLiteral("spoken.wav"));
    const QString input = dir.filePath(QStringLiteral("input.wav"));
    QString said;
    QVERIFY2(runTool(QStringLiteral("espeak-ng"),
                     {QStringLiteral("-v"), QStringLiteral("en-gb"), QStringLiteral("-s"), QStringLiteral("160"),
                      QStringLiteral("-w"), spoken, QStringLiteral("Golf one three three, secure voice check.")},
                     &said),
             qPrintable(said));
    QVERIFY2(runTool(QStringLiteral("sox"),
                     {spoken, QStringLiteral("-r"), QStringLiteral("8000"), QStringLiteral("-c"), QStringLiteral("1"),
                      QStringLiteral("-b"), QStringLiteral("16"), QStringLiteral("-e"), QStringLiteral("signed-integer"),
                      input},
                     &said),
             qPrintable(said));
    std::string error;
    const auto speech = rcm::WavFile::read(input.toStdString(), error);
    QVERIFY2(speech && speech->sampleRate == rcm::voice::kSampleRate, error.c_str());

    // Codec 2's own programs, on the same samples padded to whole frames as the console pads them.
    std::vector<std::int16_t> padded = speech->samples;
    padded.resize((padded.size() + rcm::voice::kFrameSamples - 1) / rcm::voice::kFrameSamples *
                      rcm::voice::kFrameSamples,
                  0);
    const std::size_t frames = padded.size() / rcm::voice::kFrameSamples;
    {
        QFile raw(dir.filePath(QStringLiteral("input.raw")));
        QVERIFY(raw.open(QIODevice::WriteOnly));
        raw.write(reinterpret_cast<const char*>(padded.data()), qint64(padded.size() * 2));
    }
    QVERIFY2(runTool(QStringLiteral("c2enc"),
                     {QStringLiteral("3200"), dir.filePath(QStringLiteral("input.raw")), dir.filePath(QStringLiteral("input.c2"))},
                     &said),
             qPrintable(said));
    QVERIFY2(runTool(QStringLiteral("c2dec"),
                     {QStringLiteral("3200"), dir.filePath(QStringLiteral("input.c2")), dir.filePath(QStringLiteral("reference.raw"))},
                     &said),
             qPrintable(said));
    const std::vector<std::int16_t> reference = rawSamples(dir.filePath(QStringLiteral("reference.raw")));
    QCOMPARE(reference.size(), padded.size());

    const QString keyPath = dir.filePath(QStringLiteral("aircraft.key"));
    QVERIFY2(rcm::secure::writeKeyFile(keyPath.toStdString(), rcm::secure::generateKey(), error), error.c_str());
    const QString heardPath = dir.filePath(QStringLiteral("heard.wav"));
    rcm::test::UasimProcess uasim({QStringLiteral("--key"), keyPath, QStringLiteral("--voice-out"), heardPath});
    QVERIFY2(uasim.start(), "build uasim first");
    QTRY_VERIFY_WITH_TIMEOUT(uasim.listening(), kPatience);

    rcm::secure::SecureEndpoint::Options endpointOptions;
    endpointOptions.persistState = false;
    const auto key =
        rcm::secure::SecureEndpoint::open(keyPath.toStdString(), rcm::secure::Direction::GcsToUa, error, endpointOptions);
    QVERIFY2(key, error.c_str());
    Console c;
    c.voiceOn->setChecked(true);
    c.widget->setRehearsalFile(input);
    auto link = c.channel->attach(
        std::make_unique<UdpLink>(QHostAddress::LocalHost, 0, QHostAddress::LocalHost, uasim.port()), key.get());
    QVERIFY(c.channel->isSecure());
    link->open();
    QTest::mousePress(c.talk, Qt::LeftButton);  // held: the whole file goes
    QTRY_COMPARE_WITH_TIMEOUT(c.channel->source()->speechFramesSent(), std::uint64_t(frames), 4 * kPatience);
    const auto heard = [&] {
        const auto wav = rcm::WavFile::read(heardPath.toStdString(), error);
        return wav ? wav->samples : std::vector<std::int16_t>{};
    };
    QTRY_VERIFY_WITH_TIMEOUT(slotOf(heard(), reference) >= 0, kPatience);
    QTest::mouseRelease(c.talk, Qt::LeftButton);

    // What an attacker on the path can do: send a recorded frame again
    // (here one sealed under the key at a counter already past) and a forged one.
    QUdpSocket attacker;
    const QByteArray magic = QByteArray::fromRawData(VoiceUdpLink::kMagic, 4);
    rcm::voice::SecureVoiceSealer recorder(*key->voiceSend,
                                           [] { return QDateTime::currentMSecsSinceEpoch() * 1000 - 2000000; });
    std::array<std::uint8_t, rcm::voice::kSecureFrameBytes> old;
    rcm::voice::VoiceFrame loud;
    loud.kind = rcm::voice::FrameKind::Speech;
    loud.payload.fill(0x5A);
    recorder.seal(loud, loud, old);
    attacker.writeDatagram(magic + QByteArray(reinterpret_cast<const char*>(old.data()), int(old.size())),
                           QHostAddress::LocalHost, uasim.port());
    std::array<std::uint8_t, rcm::voice::kSecureFrameBytes> forged = old;
    forged[5] ^= 0x01;
    rcm::voice::addParity(forged);
    attacker.writeDatagram(magic + QByteArray(reinterpret_cast<const char*>(forged.data()), int(forged.size())),
                           QHostAddress::LocalHost, uasim.port());
    QTRY_VERIFY_WITH_TIMEOUT(uasim.said("voice refused, never played: 1 forged, 1 replayed"), kPatience);
    link->close();
    QVERIFY(uasim.stop(kPatience));

    const std::vector<std::int16_t> all = heard();
    const qsizetype at = slotOf(all, reference);
    QVERIFY2(at >= 0, "the speech is not in uasim's WAV, bit-exact on a slot");
    QVERIFY(std::all_of(all.begin(), all.begin() + at, [](std::int16_t s) { return s == 0; }));
    QVERIFY(std::all_of(all.begin() + at + qsizetype(reference.size()), all.end(), [](std::int16_t s) { return s == 0; }));
}

QTEST_MAIN(TestPushToTalk)
#include "tst_pushtotalk.moc"
