#include "codec/voice/VoiceCodec.h"

#include <codec2/codec2.h>

#include <algorithm>
#include <cassert>
#include <cstring>

namespace rcm::voice {
namespace {

constexpr std::size_t kDataBytes = 10;  // sync, kind and sequence, payload: what RS protects
constexpr std::size_t kParityBytes = kFrameBytes - kDataBytes;
static_assert(kParityBytes == 2);
constexpr std::uint8_t kKindMask = 0xC0;
constexpr std::uint8_t kSequenceMask = 0x3F;
static_assert(kSequenceMask + 1 == kSequenceModulus);

// GF(256) with the field polynomial x^8+x^4+x^3+x^2+1 (0x11D), primitive
// element x: the field of most byte-wide Reed-Solomon codes.
struct Field {
    std::array<std::uint8_t, 512> exp{};
    std::array<int, 256> log{};
    constexpr Field()
    {
        int x = 1;
        for (int i = 0; i < 255; ++i) {
            exp[static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(x);
            log[static_cast<std::size_t>(x)] = i;
            x <<= 1;
            if (x & 0x100)
                x ^= 0x11D;
        }
        for (std::size_t i = 255; i < exp.size(); ++i)
            exp[i] = exp[i - 255];
    }
    constexpr std::uint8_t mul(std::uint8_t a, std::uint8_t b) const
    {
        return a == 0 || b == 0 ? 0 : exp[static_cast<std::size_t>(log[a] + log[b])];
    }
};
constexpr Field kField;

// Generator (x + a)(x + a^2) = x^2 + g1 x + g0, a the primitive element.
constexpr std::uint8_t kG1 = kField.exp[1] ^ kField.exp[2];
constexpr std::uint8_t kG0 = kField.exp[3];

}  // namespace

// The last two bytes: the remainder of data(x) x^2 modulo the generator,
// byte 0 the highest power.
void addParity(std::span<std::uint8_t> frame)
{
    const std::size_t data = frame.size() - 2;
    std::uint8_t r1 = 0;
    std::uint8_t r0 = 0;
    for (std::size_t i = 0; i < data; ++i) {
        const std::uint8_t feedback = frame[i] ^ r1;
        r1 = r0 ^ kField.mul(feedback, kG1);
        r0 = kField.mul(feedback, kG0);
    }
    frame[data] = r1;
    frame[data + 1] = r0;
}

int correctOneByte(std::span<std::uint8_t> cw)
{
    std::uint8_t s1 = 0;  // cw(a)
    std::uint8_t s2 = 0;  // cw(a^2)
    for (const std::uint8_t c : cw) {
        s1 = kField.mul(s1, kField.exp[1]) ^ c;
        s2 = kField.mul(s2, kField.exp[2]) ^ c;
    }
    if (s1 == 0 && s2 == 0)
        return 0;
    if (s1 == 0 || s2 == 0)
        return -1;
    // One error e at power i: s1 = e a^i, s2 = e a^2i, so a^i = s2 / s1.
    const int i = (kField.log[s2] - kField.log[s1] + 255) % 255;
    if (i >= static_cast<int>(cw.size()))
        return -1;
    const std::uint8_t e = kField.exp[static_cast<std::size_t>((kField.log[s1] - i + 255) % 255)];
    cw[cw.size() - 1 - static_cast<std::size_t>(i)] ^= e;
    return 1;
}

namespace {

CODEC2* createCodec2()
{
    CODEC2* c = codec2_create(CODEC2_MODE_3200);
    assert(c && codec2_samples_per_frame(c) == static_cast<int>(kFrameSamples) &&
           codec2_bytes_per_frame(c) == static_cast<int>(kCodec2Bytes));
    return c;
}

}  // namespace

bool parseFrame(std::span<const std::uint8_t, kFrameBytes> bytes, VoiceFrame& frame)
{
    std::array<std::uint8_t, kFrameBytes> cw;
    std::memcpy(cw.data(), bytes.data(), kFrameBytes);
    const int corrected = correctOneByte(cw);
    if (corrected < 0 || cw[0] != kSyncByte)
        return false;
    const auto kind = static_cast<std::uint8_t>(cw[1] & kKindMask);
    if (kind != static_cast<std::uint8_t>(FrameKind::Speech) && kind != static_cast<std::uint8_t>(FrameKind::Idle))
        return false;
    frame.kind = static_cast<FrameKind>(kind);
    frame.sequence = cw[1] & kSequenceMask;
    std::memcpy(frame.payload.data(), cw.data() + 2, kCodec2Bytes);
    frame.corrected = corrected;
    return true;
}

VoiceEncoder::VoiceEncoder() : m_codec2(createCodec2(), codec2_destroy) {}

VoiceEncoder::~VoiceEncoder() = default;

void buildFrame(FrameKind kind, std::uint8_t sequence, std::span<const std::uint8_t, kCodec2Bytes> payload,
                FrameSpan out)
{
    out[0] = kSyncByte;
    out[1] = static_cast<std::uint8_t>(kind) | (sequence & kSequenceMask);
    std::memcpy(out.data() + 2, payload.data(), kCodec2Bytes);
    addParity(out);
}

void VoiceEncoder::frame(FrameKind kind, const std::uint8_t* payload, FrameSpan out)
{
    buildFrame(kind, m_sequence, std::span<const std::uint8_t, kCodec2Bytes>(payload, kCodec2Bytes), out);
    m_sequence = (m_sequence + 1) & kSequenceMask;
}

void VoiceEncoder::speechFrame(PcmFrame pcm, FrameSpan out)
{
    std::array<short, kFrameSamples> speech;
    std::copy(pcm.begin(), pcm.end(), speech.begin());
    std::array<unsigned char, kCodec2Bytes> bits;
    codec2_encode(m_codec2.get(), bits.data(), speech.data());
    frame(FrameKind::Speech, bits.data(), out);
}

void VoiceEncoder::idleFrame(FrameSpan out)
{
    const std::array<std::uint8_t, kCodec2Bytes> zeros{};
    frame(FrameKind::Idle, zeros.data(), out);
}

void VoiceEncoder::encode(std::span<const std::int16_t> pcm, std::vector<std::uint8_t>& out)
{
    while (!pcm.empty()) {
        const std::size_t n = std::min(pcm.size(), kFrameSamples - m_pending);
        std::copy_n(pcm.begin(), n, m_buffer.begin() + static_cast<std::ptrdiff_t>(m_pending));
        m_pending += n;
        pcm = pcm.subspan(n);
        if (m_pending == kFrameSamples) {
            out.resize(out.size() + kFrameBytes);
            speechFrame(m_buffer, FrameSpan(out.data() + out.size() - kFrameBytes, kFrameBytes));
            m_pending = 0;
        }
    }
}

void VoiceEncoder::finish(std::vector<std::uint8_t>& out)
{
    if (m_pending == 0)
        return;
    std::fill(m_buffer.begin() + static_cast<std::ptrdiff_t>(m_pending), m_buffer.end(), std::int16_t{0});
    out.resize(out.size() + kFrameBytes);
    speechFrame(m_buffer, FrameSpan(out.data() + out.size() - kFrameBytes, kFrameBytes));
    m_pending = 0;
}

VoiceDecoder::VoiceDecoder() : m_codec2(createCodec2(), codec2_destroy) {}

VoiceDecoder::~VoiceDecoder() = default;

void VoiceDecoder::reset()
{
    m_codec2.reset(createCodec2());
    m_stream = FrameStream(kFrameBytes, kMaxMisses);
    m_hasLast = false;
    m_lastSequence = 0;
    m_stats = Stats{};
}

void VoiceDecoder::decode(std::span<const std::uint8_t> bytes, std::vector<std::int16_t>& pcm)
{
    m_stats.bytesIn += bytes.size();
    m_stream.feed(bytes, [&] { process(pcm); });
}

bool VoiceDecoder::frameAt(std::uint64_t offset, VoiceFrame& frame) const
{
    return parseFrame(std::span<const std::uint8_t, kFrameBytes>(m_stream.at(offset), kFrameBytes), frame);
}

// Frames missing between the last frame taken and one at `offset` with
// `sequence`: the count the sequence gives (modulo 64) nearest to what the
// bytes in between would hold.
std::uint64_t VoiceDecoder::framesLostBefore(std::uint64_t offset, std::uint8_t sequence) const
{
    if (!m_hasLast)
        return 0;
    const std::int64_t byBytes = static_cast<std::int64_t>((offset - m_stream.lastEnd + kFrameBytes / 2) / kFrameBytes);
    const std::int64_t bySequence = (sequence - m_lastSequence - 1 + 2 * kSequenceModulus) % kSequenceModulus;
    const std::int64_t turns = (byBytes - bySequence + kSequenceModulus / 2) / kSequenceModulus;
    return static_cast<std::uint64_t>(std::max<std::int64_t>(0, bySequence + turns * kSequenceModulus));
}

void VoiceDecoder::take(std::uint64_t offset, const VoiceFrame& frame, std::uint64_t lost,
                        std::vector<std::int16_t>& pcm)
{
    m_stats.bytesSkipped += offset - (m_hasLast ? m_stream.lastEnd : 0);
    m_stats.lostFrames += lost;
    pcm.resize(pcm.size() + lost * kFrameSamples, 0);
    const std::size_t at = pcm.size();
    pcm.resize(at + kFrameSamples, 0);
    if (frame.kind == FrameKind::Speech) {
        std::array<short, kFrameSamples> speech;
        codec2_decode(m_codec2.get(), speech.data(), frame.payload.data());
        std::copy(speech.begin(), speech.end(), pcm.begin() + static_cast<std::ptrdiff_t>(at));
        ++m_stats.speechFrames;
    } else {
        ++m_stats.idleFrames;
    }
    if (frame.corrected > 0)
        ++m_stats.correctedFrames;
    m_hasLast = true;
    m_lastSequence = frame.sequence;
    m_stream.took(offset);
}

void VoiceDecoder::process(std::vector<std::int16_t>& pcm)
{
    VoiceFrame frame;
    const auto inStep = [&](std::uint64_t offset) {
        if (frameAt(offset, frame))
            take(offset, frame, framesLostBefore(offset, frame.sequence), pcm);
        else if (m_stream.missed())
            ++m_stats.resyncs;
    };
    const auto hunt = [&](std::uint64_t end) {
        for (; m_stream.scan + kFrameBytes <= end; ++m_stream.scan) {
            if (*m_stream.at(m_stream.scan) != kSyncByte || !frameAt(m_stream.scan, frame))
                continue;
            const std::uint64_t lost = framesLostBefore(m_stream.scan, frame.sequence);
            const std::uint64_t byBytes =
                m_hasLast ? (m_stream.scan - m_stream.lastEnd + kFrameBytes / 2) / kFrameBytes : 0;
            // The sequence agrees with the bytes in between: a 1 in 2^12
            // chance for a false frame (sync, RS, kind), less 3 in 64.
            if (m_hasLast && lost + 1 >= byBytes && lost <= byBytes + 1) {
                take(m_stream.scan, frame, lost, pcm);
                return true;
            }
            // Otherwise the next frame must follow, in sequence.
            if (m_stream.scan + 2 * kFrameBytes > end)
                return false;  // wait for it
            VoiceFrame next;
            if (*m_stream.at(m_stream.scan + kFrameBytes) == kSyncByte && frameAt(m_stream.scan + kFrameBytes, next) &&
                next.sequence == ((frame.sequence + 1) & kSequenceMask)) {
                take(m_stream.scan, frame, lost, pcm);
                return true;
            }
        }
        return false;
    };
    m_stream.search(inStep, hunt);
}

}  // namespace rcm::voice
