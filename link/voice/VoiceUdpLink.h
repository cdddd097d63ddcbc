#pragma once

// Voice beside the commands over UDP (docs/protocol.md section 7): a
// datagram transport, normally a UdpLink, wrapped so that voice travels in
// datagrams of its own to the same peer and port as the commands.
//
//   voice datagram: "RCMV" (52 43 4D 56), then one or more whole 12-byte
//   voice frames (codec/voice/VoiceCodec.h); this link sends one frame per
//   datagram, 50 a second, idle frames included, so the far decoder keeps
//   step and counts lost datagrams by the frames' sequence.
//
// A command datagram is 510 bytes, which 4 + 12k never is, and the magic
// must match too. Datagrams of neither kind go on as datagramReceived(),
// where the worker counts them as of the wrong size.
//
// Voice is paced by a steady clock (the host's monotonic one unless a test
// passes its own), a frame every 20 ms, as the voice phase of the serial line
// would carry it.

#include "link/clock/Clock.h"
#include "link/transport/LinkWrapper.h"

#include <chrono>
#include <cstdint>
#include <memory>

class VoiceSink;
class VoiceSource;

class VoiceUdpLink : public LinkWrapper {
    Q_OBJECT

public:
    static constexpr char kMagic[4] = {'R', 'C', 'M', 'V'};
    static constexpr std::chrono::milliseconds kTick{10};

    // `inner` a datagram transport, moved in and made a child. A null source
    // sends no voice; a null sink drops what is received.
    VoiceUdpLink(std::unique_ptr<Link> inner, std::shared_ptr<VoiceSource> source, std::shared_ptr<VoiceSink> sink,
                 QObject* parent = nullptr);
    // Paced by `clock`; the system clock when null.
    VoiceUdpLink(std::unique_ptr<Link> inner, std::shared_ptr<VoiceSource> source, std::shared_ptr<VoiceSink> sink,
                 std::shared_ptr<Clock> clock, QObject* parent = nullptr);

    // True for a datagram of the voice format above.
    static bool isVoiceDatagram(const QByteArray& datagram);

    // The frames sent, one a datagram: 12 bytes 50 times a second (plain
    // voice) or, on a keyed link, 24 bytes 25 times (codec/voice/SecureVoice.h).
    void setFraming(std::size_t frameBytes, int framesPerSecond);

    QString description() const override;

    // The link's thread.
    std::uint64_t voiceDatagramsSent() const { return m_sent; }
    std::uint64_t voiceDatagramsReceived() const { return m_received; }

public slots:
    void open() override;
    void close() override;

private:
    void innerOpened() override;
    void innerClosed() override;
    void innerDatagramReceived(const QByteArray& datagram) override;
    void start();
    void pace();

    std::shared_ptr<VoiceSource> m_source;
    std::shared_ptr<VoiceSink> m_sink;
    std::shared_ptr<Clock> m_clock;
    ClockTimer* m_timer;              // a child
    std::int64_t m_openedMicros = 0;  // m_clock's steady time when the link opened
    std::uint64_t m_frames = 0;  // voice frames taken from the source since the link opened
    std::size_t m_frameBytes;
    int m_framesPerSecond;
    std::uint64_t m_sent = 0;
    std::uint64_t m_received = 0;
};
