#include "link/voice/VoiceUdpLink.h"

#include "codec/voice/VoiceCodec.h"
#include "link/voice/VoiceSink.h"
#include "link/voice/VoiceSource.h"

#include <cstring>

namespace {

constexpr qsizetype kMagicSize = sizeof VoiceUdpLink::kMagic;
// A stall makes no burst: at most this many frames are caught up at once.
constexpr std::uint64_t kMaxCatchUp = 5;

}  // namespace

VoiceUdpLink::VoiceUdpLink(std::unique_ptr<Link> inner, std::shared_ptr<VoiceSource> source,
                           std::shared_ptr<VoiceSink> sink, QObject* parent)
    : VoiceUdpLink(std::move(inner), std::move(source), std::move(sink), nullptr, parent)
{
}

VoiceUdpLink::VoiceUdpLink(std::unique_ptr<Link> inner, std::shared_ptr<VoiceSource> source,
                           std::shared_ptr<VoiceSink> sink, std::shared_ptr<Clock> clock, QObject* parent)
    : LinkWrapper(std::move(inner), parent),
      m_source(std::move(source)),
      m_sink(std::move(sink)),
      m_clock(clock ? std::move(clock) : std::make_shared<SystemClock>()),
      m_timer(m_clock->createTimer(this, Qt::PreciseTimer)),
      m_frameBytes(rcm::voice::kFrameBytes),
      m_framesPerSecond(int(rcm::voice::kFramesPerSecond))
{
    Q_ASSERT(!LinkWrapper::inner()->isStream());
    connect(m_timer, &ClockTimer::timeout, this, [this] {
        m_timer->start(kTick);
        pace();
    });
}

bool VoiceUdpLink::isVoiceDatagram(const QByteArray& datagram)
{
    const qsizetype frames = datagram.size() - kMagicSize;
    return frames >= qsizetype(rcm::voice::kFrameBytes) && frames % qsizetype(rcm::voice::kFrameBytes) == 0 &&
           std::memcmp(datagram.constData(), kMagic, kMagicSize) == 0;
}

void VoiceUdpLink::setFraming(std::size_t frameBytes, int framesPerSecond)
{
    m_frameBytes = frameBytes;
    m_framesPerSecond = framesPerSecond;
}

QString VoiceUdpLink::description() const
{
    return inner()->description() + QStringLiteral(", voice in datagrams of its own");
}

void VoiceUdpLink::open()
{
    inner()->open();
    // A transport may open at once, before anyone heard opened().
    if (inner()->isOpen() && !m_timer->isActive())
        start();
}

void VoiceUdpLink::close()
{
    m_timer->stop();
    inner()->close();
}

void VoiceUdpLink::innerOpened()
{
    start();
}

void VoiceUdpLink::innerClosed()
{
    m_timer->stop();
}

void VoiceUdpLink::start()
{
    if (m_timer->isActive())
        return;
    m_openedMicros = m_clock->steadyMicros();
    m_frames = 0;
    m_timer->start(kTick);
    pace();
}

void VoiceUdpLink::pace()
{
    if (!m_source || !inner()->isOpen())
        return;
    if (!inner()->canSend()) {
        // Nobody to send to yet (uasim before the console's first command):
        // the voice waits, from its first frame, for the link to be up,
        // rather than go to nobody.
        m_openedMicros = m_clock->steadyMicros();
        m_frames = 0;
        return;
    }
    // The frame whose 20 ms (40 ms on a keyed link) has begun goes now.
    const auto due = static_cast<std::uint64_t>((m_clock->steadyMicros() - m_openedMicros) *
                                                std::int64_t(m_framesPerSecond) / 1000000) +
                     1;
    if (due > m_frames + kMaxCatchUp)
        m_frames = due - kMaxCatchUp;
    QByteArray datagram(kMagicSize + qsizetype(m_frameBytes), Qt::Uninitialized);
    std::memcpy(datagram.data(), kMagic, kMagicSize);
    for (; m_frames < due; ++m_frames) {
        m_source->readVoice({reinterpret_cast<std::uint8_t*>(datagram.data()) + kMagicSize, m_frameBytes});
        // No peer yet: the frame is gone, as on a line nobody listens to.
        if (inner()->write(datagram))
            ++m_sent;
    }
}

void VoiceUdpLink::innerDatagramReceived(const QByteArray& datagram)
{
    if (!isVoiceDatagram(datagram)) {
        emit datagramReceived(datagram);
        return;
    }
    ++m_received;
    if (m_sink)
        m_sink->writeVoice({reinterpret_cast<const std::uint8_t*>(datagram.constData()) + kMagicSize,
                            std::size_t(datagram.size() - kMagicSize)});
}
