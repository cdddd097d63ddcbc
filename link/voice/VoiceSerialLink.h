#pragma once

// The satellite modem's 9,600 bps shared by commands and voice (PROFILE.md
// section 4, docs/protocol.md section 7): a stream transport, normally a
// SerialLink, wrapped so that every byte pair on the line is one control
// byte and one voice byte, C V C V ..., 1,200 bytes a second with no gap.
//
// Sending. The worker's frame (600 bytes, once a second) is the control
// phase; the voice phase comes from a VoiceSource. The line is paced here, by
// a steady clock (Options::clock, the host's monotonic one unless a test
// passes its own): every tick (10 ms) the bytes due since the line
// started are written, `lead` bytes ahead, so the modem's buffer never runs
// dry between ticks. A frame is sent whole, and the next one, if it was
// written before this one ended, follows at once, so frames stand exactly
// 1,200 bytes apart. With no frame to send the control phase carries fill
// and voice goes on. The first frame after fill is held `frameHold`, so that
// the worker's next tick, a second later, has that much slack.
//
// Receiving. rcm::VoiceDemultiplexer finds the control phase by the
// preamble: its bytes go on as bytesReceived() for the worker's
// synchroniser, the other phase to the VoiceSink.
//
// Flow control: a modem whose buffer is full drops CTS and the port stops
// taking bytes (SerialLink's bytesToWrite() grows). The pacing then writes
// nothing while the port holds more than `lead` bytes: the line stalls
// instead of queueing seconds of voice and commands behind the modem.
//
// The port's bit rate is not the line's: at 8N1 a byte takes 10 bits, so a
// modem whose data rate is 9,600 bps wants its serial port at 19,200 baud or
// more, with the modem buffering. The pacing here is what holds the line to
// 1,200 bytes a second. A modem whose clock differs from the host's by
// 100 ppm drifts 0.12 bytes a second against it: its buffer holds `lead`
// bytes, so that is minutes before it runs dry or grows by a frame.

#include "codec/voice/VoiceMux.h"
#include "link/clock/Clock.h"
#include "link/transport/LinkWrapper.h"

#include <chrono>
#include <cstdint>
#include <memory>

class VoiceSink;
class VoiceSource;

class VoiceSerialLink : public LinkWrapper {
    Q_OBJECT

public:
    struct Options {
        int bytesPerSecond = int(rcm::kMuxedFrameSize);  // the line: a frame and its voice each second
        std::chrono::milliseconds tick{10};
        int lead = 24;  // bytes written ahead of the line: 20 ms
        std::chrono::milliseconds frameHold{200};
        // The line's time and ticks; null: the system clock.
        std::shared_ptr<Clock> clock;
    };

    // `inner` a stream transport, moved in and made a child. A null source
    // sends idle voice; a null sink drops what is received.
    VoiceSerialLink(std::unique_ptr<Link> inner, std::shared_ptr<VoiceSource> source, std::shared_ptr<VoiceSink> sink,
                    Options options, QObject* parent = nullptr);
    VoiceSerialLink(std::unique_ptr<Link> inner, std::shared_ptr<VoiceSource> source, std::shared_ptr<VoiceSink> sink);
    ~VoiceSerialLink() override;

    QString description() const override;

    // The link's thread.
    const rcm::VoiceMultiplexer& multiplexer() const { return *m_mux; }
    const rcm::VoiceDemultiplexer& demultiplexer() const { return *m_demux; }
    // Line bytes written since the port last opened. The link's thread.
    std::uint64_t lineBytesWritten() const { return m_written; }
    // Ticks whose bytes were held back because the port had not taken the
    // last ones (the modem's CTS was down). The link's thread.
    std::uint64_t flowControlHolds() const { return m_flowControlHolds; }

public slots:
    void close() override;
    // One 600-byte frame, to go out at the next frame boundary of the line.
    // False when closed or for anything else than 600 bytes.
    bool write(const QByteArray& bytes) override;

private:
    void innerOpened() override;
    void innerClosed() override;
    void innerBytesReceived(const QByteArray& bytes) override;
    void pace();
    std::int64_t nanosSinceOpened() const;

    std::shared_ptr<VoiceSource> m_source;
    std::shared_ptr<VoiceSink> m_sink;
    Options m_options;
    std::unique_ptr<rcm::VoiceMultiplexer> m_mux;
    std::unique_ptr<rcm::VoiceDemultiplexer> m_demux;
    std::shared_ptr<Clock> m_clock;
    ClockTimer* m_timer;              // a child
    std::int64_t m_openedMicros = 0;  // m_clock's steady time when the port opened
    std::uint64_t m_written = 0;   // line bytes written since then
    std::uint64_t m_skipped = 0;   // line bytes never written: the event loop stalled, or flow control held them
    std::uint64_t m_flowControlHolds = 0;
    std::int64_t m_holdUntil = 0;  // ns since the port opened: the first frame after fill waits until then
};
