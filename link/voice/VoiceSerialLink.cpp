#include "link/voice/VoiceSerialLink.h"

#include "codec/voice/VoiceCodec.h"
#include "codec/voice/VoiceMux.h"
#include "link/voice/VoiceSink.h"
#include "link/voice/VoiceSource.h"

#include <algorithm>
#include <vector>

namespace {

// When the event loop stalled, the line went idle anyway; making up for it
// with a burst would only queue bytes in the modem, as latency. At most this
// many ticks' bytes go out at once beyond the lead.
constexpr int kMaxTicksOfCatchUp = 4;

// A voice source when none was given: idle frames for ever.
class IdleVoice : public VoiceSource {
public:
    void readVoice(std::span<std::uint8_t> out) override
    {
        while (!out.empty()) {
            if (m_position == m_frame.size()) {
                m_encoder.idleFrame(m_frame);
                m_position = 0;
            }
            const std::size_t n = std::min(out.size(), m_frame.size() - m_position);
            std::copy_n(m_frame.begin() + static_cast<std::ptrdiff_t>(m_position), n, out.begin());
            m_position += n;
            out = out.subspan(n);
        }
    }

private:
    rcm::voice::VoiceEncoder m_encoder;
    std::array<std::uint8_t, rcm::voice::kFrameBytes> m_frame{};
    std::size_t m_position = rcm::voice::kFrameBytes;
};

}  // namespace

VoiceSerialLink::VoiceSerialLink(std::unique_ptr<Link> inner, std::shared_ptr<VoiceSource> source,
                                 std::shared_ptr<VoiceSink> sink, Options options, QObject* parent)
    : LinkWrapper(std::move(inner), parent),
      m_source(source ? std::move(source) : std::make_shared<IdleVoice>()),
      m_sink(std::move(sink)),
      m_options(options),
      m_mux(std::make_unique<rcm::VoiceMultiplexer>()),
      m_demux(std::make_unique<rcm::VoiceDemultiplexer>(
          [this](std::span<const std::uint8_t> control) {
              emit bytesReceived(QByteArray(reinterpret_cast<const char*>(control.data()), qsizetype(control.size())));
          },
          [this](std::span<const std::uint8_t> voice) {
              if (m_sink)
                  m_sink->writeVoice(voice);
          })),
      m_clock(m_options.clock ? m_options.clock : std::make_shared<SystemClock>()),
      m_timer(m_clock->createTimer(this, Qt::PreciseTimer))
{
    Q_ASSERT(LinkWrapper::inner()->isStream());
    connect(m_timer, &ClockTimer::timeout, this, [this] {
        m_timer->start(m_options.tick);
        pace();
    });
}

VoiceSerialLink::VoiceSerialLink(std::unique_ptr<Link> inner, std::shared_ptr<VoiceSource> source,
                                 std::shared_ptr<VoiceSink> sink)
    : VoiceSerialLink(std::move(inner), std::move(source), std::move(sink), Options{})
{
}

VoiceSerialLink::~VoiceSerialLink() = default;

QString VoiceSerialLink::description() const
{
    return inner()->description() + QStringLiteral(", voice multiplexed at %1 bit/s").arg(m_options.bytesPerSecond * 8);
}

void VoiceSerialLink::close()
{
    m_timer->stop();
    inner()->close();
}

bool VoiceSerialLink::write(const QByteArray& bytes)
{
    if (!isOpen() || std::size_t(bytes.size()) != rcm::kFrameSize)
        return false;
    const bool afterFill = !m_mux->sendingFrame() && m_mux->queuedFrames() == 0;
    m_mux->queueFrame(std::span<const std::uint8_t, rcm::kFrameSize>(
        reinterpret_cast<const std::uint8_t*>(bytes.constData()), rcm::kFrameSize));
    if (afterFill)
        m_holdUntil = nanosSinceOpened() + std::chrono::nanoseconds(m_options.frameHold).count();
    return true;
}

void VoiceSerialLink::innerOpened()
{
    // A new line: what was half sent or half received is gone.
    m_mux = std::make_unique<rcm::VoiceMultiplexer>();
    m_demux->reset();
    m_openedMicros = m_clock->steadyMicros();
    m_written = 0;
    m_skipped = 0;
    m_flowControlHolds = 0;
    m_holdUntil = 0;
    m_timer->start(m_options.tick);
    pace();
}

void VoiceSerialLink::innerClosed()
{
    m_timer->stop();
}

void VoiceSerialLink::pace()
{
    if (!inner()->isOpen())
        return;
    const std::int64_t now = nanosSinceOpened();
    const auto lineTime = static_cast<std::uint64_t>(now / 1000 * m_options.bytesPerSecond / 1000000);
    std::uint64_t due = (static_cast<std::uint64_t>(m_options.lead) + lineTime - m_skipped) & ~std::uint64_t(1);
    const auto tickBytes = static_cast<std::uint64_t>(m_options.bytesPerSecond * m_options.tick.count() / 1000);
    const std::uint64_t most = m_written + static_cast<std::uint64_t>(m_options.lead) + kMaxTicksOfCatchUp * tickBytes;
    if (due > most) {
        m_skipped += due - most;
        due = most;
    }
    if (due <= m_written)
        return;
    if (inner()->bytesToWrite() > m_options.lead) {
        // The modem's flow control holds the line (CTS down): what is due
        // now would only queue behind it. The line stalls, as when the event
        // loop does, and goes on where it stopped once the modem takes bytes.
        m_skipped += due - m_written;
        ++m_flowControlHolds;
        return;
    }
    const std::size_t pairs = static_cast<std::size_t>(due - m_written) / 2;
    std::vector<std::uint8_t> voice(pairs);
    m_source->readVoice(voice);
    QByteArray line(qsizetype(2 * pairs), Qt::Uninitialized);
    m_mux->setHoldFill(now < m_holdUntil);
    m_mux->multiplex(voice, std::span(reinterpret_cast<std::uint8_t*>(line.data()), 2 * pairs));
    inner()->write(line);
    m_written += 2 * pairs;
}

std::int64_t VoiceSerialLink::nanosSinceOpened() const
{
    return (m_clock->steadyMicros() - m_openedMicros) * 1000;
}

void VoiceSerialLink::innerBytesReceived(const QByteArray& bytes)
{
    m_demux->feed({reinterpret_cast<const std::uint8_t*>(bytes.constData()), std::size_t(bytes.size())});
}
