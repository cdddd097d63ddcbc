#pragma once

// The console's side of the voice channel (docs/protocol.md section 7): what
// the operator says while pushing to talk goes to the aircraft beside the
// commands, and what the aircraft sends back is played. It owns the voice
// source and sink the link uses and the sound card (VoiceAudio, in a thread
// of its own); PushToTalkWidget is its face.
//
// Voice changes the serial line's format (commands and voice interleaved),
// so both ends must agree: it is off until the operator turns it on, and
// takes effect when the link next starts.

#include "link/transport/Link.h"

#include <QObject>
#include <QThread>
#include <QTimer>

#include <memory>

namespace rcm::secure {
struct SecureEndpoint;
}

class PcmFifo;
class VoiceAudio;
class VoiceDecoderSink;
class VoiceEncoderSource;

class VoiceChannel : public QObject {
    Q_OBJECT

public:
    // Received voice waiting to be played: 300 ms at most.
    static constexpr std::size_t kPlaybackCapacity = 2400;

    explicit VoiceChannel(QObject* parent = nullptr);
    ~VoiceChannel() override;

    bool isEnabled() const { return m_enabled; }
    // The transport with voice beside the commands when voice is on (a
    // replay is left as it is); starts the speaker. With voice off, a UDP
    // transport is wrapped all the same, to set aside voice datagrams that
    // come (voiceIgnored()); it sends none. Under the link's key
    // when it has one (null: the plain link), the voice is enciphered and
    // authenticated (codec/voice/SecureVoice.h).
    std::unique_ptr<Link> attach(std::unique_ptr<Link> link, const rcm::secure::SecureEndpoint* key = nullptr);
    bool isSecure() const { return m_secure; }

    // Empty: the microphone.
    QString rehearsalFile() const { return m_rehearsalFile; }
    bool isTalking() const { return m_talking; }

    // For status views and tests. Any thread.
    std::shared_ptr<VoiceEncoderSource> source() const { return m_source; }
    std::uint64_t samplesReceived() const;
    std::shared_ptr<PcmFifo> playback() const { return m_playback; }

public slots:
    void setEnabled(bool on);
    void setRehearsalFile(const QString& path);
    // Push to talk: down, and up.
    void startTalking();
    void stopTalking();

signals:
    void enabledChanged(bool on);
    void talkingChanged(bool talking);
    // Peak levels 0..1, about 20 times a second: what goes out, what comes in.
    void sentLevel(float level);
    void receivedLevel(float level);
    void errorOccurred(const QString& message);
    // Keyed link: voice frames that did not authenticate (forged) or came
    // again (replayed) were refused, never played; the totals of this link.
    void voiceRefused(quint64 forged, quint64 replayed);
    // Voice off here, and the aircraft sends voice datagrams all the same:
    // said once a link; they are set aside, not counted as frames.
    void voiceIgnored();

private:
    struct Received;

    void pollLevels();

    std::shared_ptr<VoiceEncoderSource> m_source;
    std::shared_ptr<PcmFifo> m_playback;
    std::shared_ptr<Received> m_received;  // shared with the link's thread
    std::shared_ptr<VoiceDecoderSink> m_sink;
    QThread m_audioThread;
    VoiceAudio* m_audio;  // lives in m_audioThread, deleted there
    QTimer m_levels;
    bool m_enabled = false;
    bool m_talking = false;
    bool m_secure = false;
    QString m_rehearsalFile;
};
