#include "ui/voice/VoiceChannel.h"

#include "codec/secure/SecureCodec.h"
#include "link/voice/VoiceDecoderSink.h"
#include "link/voice/VoiceEncoderSource.h"
#include "link/voice/VoiceUdpLink.h"
#include "link/voice/WithVoice.h"
#include "ui/voice/PcmFifo.h"
#include "ui/voice/VoiceAudio.h"

#include <QPointer>

#include <algorithm>
#include <functional>
#include <utility>
#include <atomic>
#include <cstdlib>

// What the link's thread tells the GUI about the voice received.
struct VoiceChannel::Received {
    std::atomic<std::uint64_t> samples{0};
    std::atomic<float> level{0};
};

VoiceChannel::VoiceChannel(QObject* parent)
    : QObject(parent),
      m_source(std::make_shared<VoiceEncoderSource>()),
      m_playback(std::make_shared<PcmFifo>(kPlaybackCapacity)),
      m_received(std::make_shared<Received>()),
      m_audio(new VoiceAudio(m_source, m_playback)),
      m_levels(this)
{
    // The sink outlives nothing it refers to: the FIFO and the counters are shared.
    m_sink = std::make_shared<VoiceDecoderSink>(
        [playback = m_playback, received = m_received](std::span<const std::int16_t> pcm) {
            playback->push(pcm);
            int peak = 0;
            for (const std::int16_t s : pcm)
                peak = std::max(peak, std::abs(int(s)));
            received->samples += pcm.size();
            received->level = float(peak) / 32768.0f;
        });
    m_audioThread.setObjectName(QStringLiteral("audio"));
    m_audio->moveToThread(&m_audioThread);
    connect(&m_audioThread, &QThread::finished, m_audio, &QObject::deleteLater);
    connect(m_audio, &VoiceAudio::errorOccurred, this, &VoiceChannel::errorOccurred);
    m_audioThread.start();
    m_levels.setInterval(50);
    connect(&m_levels, &QTimer::timeout, this, &VoiceChannel::pollLevels);
}

VoiceChannel::~VoiceChannel()
{
    // VoiceAudio's destructor, in its thread, stops the card.
    m_audioThread.quit();
    m_audioThread.wait();
}

std::uint64_t VoiceChannel::samplesReceived() const
{
    return m_received->samples.load();
}

namespace {

// Voice that comes while voice is off here: set aside, said once.
class IgnoredVoice : public VoiceSink {
public:
    explicit IgnoredVoice(std::function<void()> first) : m_first(std::move(first)) {}
    void writeVoice(std::span<const std::uint8_t>) override
    {
        if (const std::function<void()> first = std::exchange(m_first, nullptr))
            first();
    }

private:
    std::function<void()> m_first;
};

}  // namespace

std::unique_ptr<Link> VoiceChannel::attach(std::unique_ptr<Link> link, const rcm::secure::SecureEndpoint* key)
{
    if (!link || link->transport() == FrameTransport::Replay)
        return link;
    if (!m_enabled) {
        if (link->isStream())
            return link;  // a serial line's format is the far end's to agree on: voice is off there too
        // The aircraft may speak in datagrams of their own all the same: they
        // are voice, set aside and said once, not fifty frames a second of
        // the wrong size in the frame log. Nothing is sent.
        auto ignored = std::make_shared<IgnoredVoice>([self = QPointer<VoiceChannel>(this)] {
            QMetaObject::invokeMethod(
                self, [self] { emit self->voiceIgnored(); }, Qt::QueuedConnection);
        });
        return std::make_unique<VoiceUdpLink>(std::move(link), nullptr, ignored);
    }
    m_playback->clear();
    QMetaObject::invokeMethod(m_audio, &VoiceAudio::startPlayback, Qt::QueuedConnection);
    m_levels.start();
    VoiceSecurity security;
    m_secure = key && key->voiceSend && key->voiceReceive;
    if (m_secure) {
        security.send = key->voiceSend;
        security.receive = key->voiceReceive;
        // From the link's thread, queued to this one.
        security.refused = [self = QPointer<VoiceChannel>(this)](std::uint64_t forged, std::uint64_t replayed) {
            QMetaObject::invokeMethod(
                self, [self, forged, replayed] { emit self->voiceRefused(forged, replayed); }, Qt::QueuedConnection);
        };
    }
    return withVoice(std::move(link), m_source, m_sink, security);
}

void VoiceChannel::setEnabled(bool on)
{
    if (on == m_enabled)
        return;
    m_enabled = on;
    if (!on) {
        stopTalking();
        QMetaObject::invokeMethod(m_audio, &VoiceAudio::stopPlayback, Qt::QueuedConnection);
        m_levels.stop();
        emit sentLevel(0);
        emit receivedLevel(0);
    }
    emit enabledChanged(on);
}

void VoiceChannel::setRehearsalFile(const QString& path)
{
    m_rehearsalFile = path;
}

void VoiceChannel::startTalking()
{
    if (m_talking || !m_enabled)
        return;
    m_talking = true;
    if (m_rehearsalFile.isEmpty())
        QMetaObject::invokeMethod(m_audio, &VoiceAudio::startCapture, Qt::QueuedConnection);
    else
        QMetaObject::invokeMethod(
            m_audio, [audio = m_audio, path = m_rehearsalFile] { audio->speakFile(path); }, Qt::QueuedConnection);
    m_levels.start();
    emit talkingChanged(true);
}

void VoiceChannel::stopTalking()
{
    if (!m_talking)
        return;
    m_talking = false;
    if (m_rehearsalFile.isEmpty()) {
        QMetaObject::invokeMethod(m_audio, &VoiceAudio::stopCapture, Qt::QueuedConnection);
    } else {
        // Letting go of the key cuts the recording short, as it would a
        // speaker; queued behind speakFile(), which may not have run yet.
        QMetaObject::invokeMethod(
            m_audio,
            [source = m_source] {
                source->clear();
                source->endTalk();
            },
            Qt::QueuedConnection);
    }
    emit talkingChanged(false);
}

void VoiceChannel::pollLevels()
{
    emit sentLevel(m_source->sentLevel());
    emit receivedLevel(m_received->level.exchange(0));
}
