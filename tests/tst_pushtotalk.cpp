// Push to talk on the console: the button and the F12 key, the microphone
// or a WAV file, the level meters, and received voice on its way to the
// speaker. No sound card is needed: the rehearsal file stands in for the
// microphone, and what would be played is read from the playback FIFO.
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

QTEST_MAIN(TestPushToTalk)
#include "tst_pushtotalk.moc"
