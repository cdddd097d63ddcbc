// Measures what the voice link adds to the voice's latency: the floor is
// "no more than 100 ms beyond the codec's own frame time". A VoiceSerialLink
// at its real rate (1,200 bytes a second, a command frame each second) sends
// over a pseudo-terminal to a far end in this thread, which demultiplexes
// and decodes as uasim does. A microphone is played by a timer: every 490 ms
// (so that bursts fall at every phase of the voice frames) one 20 ms frame of
// tone is pushed whole, then the talk ends.
//
//   in:  the burst's last sample pushed, i.e. the frame complete: the 20 ms
//        the codec needs to gather it is the codec's frame time, not counted
//   out: the far decoder hands the frame's 160 samples on
//
// Two figures per burst:
//   pty:   out - in as measured. The link writes 24 bytes (20 ms) ahead of
//          the line, which a pty delivers at once.
//   line:  as a 9,600 bps modem would deliver: byte n of the line cannot
//          arrive before the line's first byte plus n / 1,200 s, so "out" is
//          at least that for the last byte the decoder needed.
//
//   bench_voice [bursts]      (default 40, about 20 s)

#include "tests/support/CommandFrame.h"
#include "Spread.h"
#include "codec/message/MessageEncoder.h"
#include "codec/voice/VoiceCodec.h"
#include "codec/voice/VoiceMux.h"
#include "link/transport/SerialLink.h"
#include "link/voice/VoiceEncoderSource.h"
#include "link/voice/VoiceSerialLink.h"

#include <QCoreApplication>
#include <QElapsedTimer>
#include <QSocketNotifier>
#include <QTimer>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <deque>
#include <fcntl.h>
#include <numbers>
#include <pty.h>
#include <unistd.h>
#include <vector>

namespace {

constexpr int kBytesPerSecond = 1200;
constexpr int kBurstIntervalMs = 490;

}  // namespace

int main(int argc, char** argv)
{
    QCoreApplication app(argc, argv);
    const int bursts = argc > 1 ? std::max(1, std::atoi(argv[1])) : 40;

    int master = -1;
    int slave = -1;
    char name[256] = {};
    if (::openpty(&master, &slave, name, nullptr, nullptr) != 0) {
        std::perror("openpty");
        return 1;
    }
    ::fcntl(master, F_SETFL, ::fcntl(master, F_GETFL) | O_NONBLOCK);

    QElapsedTimer clock;
    clock.start();
    const auto now = [&] { return clock.nsecsElapsed() / 1000; };  // microseconds

    // The console: a voice line with a microphone that speaks in bursts.
    auto microphone = std::make_shared<VoiceEncoderSource>();
    VoiceSerialLink link(std::make_unique<SerialLink>(QString::fromLocal8Bit(name)), microphone, nullptr);
    link.open();
    if (!link.isOpen()) {
        std::fprintf(stderr, "cannot open %s\n", name);
        return 1;
    }
    std::uint32_t nextId = 0;
    QTimer commands;
    commands.setTimerType(Qt::PreciseTimer);
    QObject::connect(&commands, &QTimer::timeout, [&] { link.write(rcm::test::commandFrame(nextId++)); });
    commands.start(1000);
    link.write(rcm::test::commandFrame(nextId++));

    std::vector<std::int16_t> tone(rcm::voice::kFrameSamples);
    for (std::size_t i = 0; i < tone.size(); ++i)
        tone[i] = std::int16_t(8000 * std::sin(2 * std::numbers::pi * 700 * double(i) / rcm::voice::kSampleRate));
    std::deque<std::int64_t> pushed;  // bursts in flight, oldest first
    int sent = 0;
    QTimer talk;
    talk.setTimerType(Qt::PreciseTimer);
    QObject::connect(&talk, &QTimer::timeout, [&] {
        if (sent == bursts) {
            talk.stop();
            return;
        }
        microphone->pushPcm(tone);
        microphone->endTalk();
        pushed.push_back(now());
        ++sent;
    });

    // The far end: what uasim does with the line.
    std::vector<std::int64_t> overPty;
    std::vector<std::int64_t> onLine;
    std::int64_t lineStart = -1;  // when the line's first byte arrived
    std::uint64_t lineBytes = 0;
    rcm::voice::VoiceDecoder decoder;
    std::vector<std::int16_t> pcm;
    rcm::VoiceDemultiplexer demux([](std::span<const std::uint8_t>) {},
                                  [&](std::span<const std::uint8_t> voice) { decoder.decode(voice, pcm); });
    QSocketNotifier readable(master, QSocketNotifier::Read);
    QObject::connect(&readable, &QSocketNotifier::activated, [&] {
        char buffer[4096];
        for (ssize_t n; (n = ::read(master, buffer, sizeof buffer)) > 0;) {
            const std::int64_t arrived = now();
            if (lineStart < 0)
                lineStart = arrived;
            // Byte by byte, so that a frame's completion is known to the byte.
            for (ssize_t i = 0; i < n; ++i) {
                ++lineBytes;
                const std::uint64_t speechBefore = decoder.stats().speechFrames;
                pcm.clear();
                demux.feed({reinterpret_cast<const std::uint8_t*>(buffer) + i, 1});
                if (decoder.stats().speechFrames == speechBefore || pushed.empty())
                    continue;
                const std::int64_t in = pushed.front();
                pushed.pop_front();
                overPty.push_back(arrived - in);
                const std::int64_t lineArrival =
                    std::max(arrived, lineStart + std::int64_t(lineBytes * 1000000 / kBytesPerSecond));
                onLine.push_back(lineArrival - in);
            }
        }
        if (std::int64_t(overPty.size()) == bursts)
            QCoreApplication::quit();
    });

    // Started once the line runs, off any frame boundary.
    QTimer::singleShot(333, [&] { talk.start(kBurstIntervalMs); });
    QTimer::singleShot((bursts + 4) * kBurstIntervalMs + 3000, [] { QCoreApplication::quit(); });
    app.exec();

    std::printf(
        "voice latency added by the link: frame complete -> frame decoded (the codec's 20 ms frame time "
        "excluded), %d bursts of 20 ms\n",
        bursts);
    rcm::bench::printSpread("pty", overPty, 0.95, 1);
    rcm::bench::printSpread("line", onLine, 0.95, 1);
    if (std::int64_t(overPty.size()) != bursts)
        std::printf("only %zu of %d bursts were heard\n", overPty.size(), bursts);
    std::printf("codec: Codec 2 3200, 20 ms frames; link: %d bytes/s, 10 ms ticks, 24 bytes ahead\n", kBytesPerSecond);
    link.close();
    ::close(master);
    ::close(slave);
    return std::int64_t(overPty.size()) == bursts ? 0 : 1;
}
