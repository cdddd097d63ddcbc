#include "link/rehearsal/RehearsalChannel.h"

#include "link/aircraft/FaultInjector.h"

#include <QPointer>

namespace {

// Frames a receiver may still be assembling (a stream's resynchronisation).
constexpr std::size_t kRecentFrames = 16;

}  // namespace

class RehearsalChannel::EndLink : public Link {
public:
    EndLink(RehearsalChannel& channel, End end) : m_channel(channel), m_end(end) {}
    ~EndLink() override { m_channel.m_ends[m_end] = nullptr; }

    FrameTransport transport() const override
    {
        return m_channel.m_stream ? FrameTransport::Serial : FrameTransport::Udp;
    }
    bool isStream() const override { return m_channel.m_stream; }
    bool isOpen() const override { return m_open; }
    QString description() const override { return QStringLiteral("rehearsal channel"); }
    void open() override
    {
        if (!m_open) {
            m_open = true;
            emit opened();
        }
    }
    void close() override
    {
        if (m_open) {
            m_open = false;
            emit closed();
        }
    }
    bool write(const QByteArray& bytes) override
    {
        if (!m_open)
            return false;
        m_channel.carry(m_end, bytes);
        return true;
    }
    void deliver(const QByteArray& bytes)
    {
        if (!m_open)
            return;
        if (m_channel.m_stream)
            emit bytesReceived(bytes);
        else
            emit datagramReceived(bytes);
    }

private:
    RehearsalChannel& m_channel;
    End m_end;
    bool m_open = false;
};

RehearsalChannel::RehearsalChannel(bool stream, std::uint64_t seed) : m_stream(stream), m_rng(seed) {}

RehearsalChannel::~RehearsalChannel() = default;

std::unique_ptr<Link> RehearsalChannel::takeEnd(End end)
{
    auto link = std::make_unique<EndLink>(*this, end);
    m_ends[end] = link.get();
    return link;
}

void RehearsalChannel::apply(const FaultSpec& fault, double nowSeconds)
{
    m_now = nowSeconds;
    for (End sender : {Console, Aircraft}) {
        const bool applies =
            fault.direction == FaultDirection::Both || (fault.direction == FaultDirection::Up) == (sender == Console);
        if (!applies)
            continue;
        Faults& f = m_faults[sender];
        switch (fault.kind) {
            case FaultSpec::Kind::BitErrors:
                f.ber = fault.value;
                break;
            case FaultSpec::Kind::Outage:
                f.outageUntil = nowSeconds + fault.value;
                break;
            case FaultSpec::Kind::Slip:
                f.slip = fault.value;
                break;
            case FaultSpec::Kind::Burst:
                f.burst = fault.value;
                break;
            case FaultSpec::Kind::Clear:
                f = Faults{};
                break;
            case FaultSpec::Kind::CallDrop:
                // In process there is no modem: nothing passes until the console has redialled.
                f.outageUntil = nowSeconds + Scenario::kCallDropOutage;
                break;
        }
    }
}

bool RehearsalChannel::inOutage(End sender) const
{
    return m_now < m_faults[sender].outageUntil;
}

void RehearsalChannel::carry(End sender, QByteArray bytes)
{
    Counters& counters = m_counters[sender];
    ++counters.framesSent;
    auto& recent = m_recent[sender];
    recent.push_back(bytes);
    if (recent.size() > kRecentFrames)
        recent.pop_front();
    if (inOutage(sender)) {
        ++counters.framesInOutage;
        return;
    }
    damage(m_faults[sender], bytes, counters);
    if (EndLink* receiver = m_ends[sender == Console ? Aircraft : Console])
        receiver->deliver(bytes);
}

void RehearsalChannel::damage(Faults& faults, QByteArray& bytes, Counters& counters)
{
    const QByteArray original = bytes;
    std::uniform_real_distribution<double> chance(0.0, 1.0);
    if (faults.ber > 0) {
        FaultSettings settings;
        settings.bitErrorRate = faults.ber;
        settings.seed = m_rng();
        FaultInjector injector(settings);
        injector.flipRandomBits(std::span(reinterpret_cast<std::uint8_t*>(bytes.data()), std::size_t(bytes.size())));
    }
    if (faults.burst > 0 && chance(m_rng) < faults.burst && bytes.size() >= 20) {
        const int length = std::min<int>(int(bytes.size()), std::uniform_int_distribution<int>(20, 60)(m_rng));
        const int start = std::uniform_int_distribution<int>(0, int(bytes.size()) - length)(m_rng);
        std::uniform_int_distribution<int> byte(0, 255);
        std::uniform_int_distribution<int> nonZero(1, 255);
        // A burst starts and ends with an error; between, each byte is noise.
        for (int i = start; i < start + length; ++i) {
            const bool edge = i == start || i == start + length - 1;
            bytes[i] = char(uchar(bytes[i]) ^ (edge ? nonZero(m_rng) : byte(m_rng)));
        }
    }
    if (faults.slip > 0 && chance(m_rng) < faults.slip) {
        const int count = std::uniform_int_distribution<int>(1, 3)(m_rng);
        const int at = std::uniform_int_distribution<int>(0, int(bytes.size()) - count)(m_rng);
        if (std::uniform_int_distribution<int>(0, 1)(m_rng) == 0) {
            bytes.remove(at, count);
        } else {
            QByteArray added(count, 0);
            for (char& c : added)
                c = char(std::uniform_int_distribution<int>(0, 255)(m_rng));
            bytes.insert(at, added);
        }
    }
    if (bytes != original)
        ++counters.framesDamaged;
}
