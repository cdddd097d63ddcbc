#include "codec/voice/SecureVoice.h"

#include <openssl/crypto.h>
#include <openssl/evp.h>
#include <openssl/core_names.h>
#include <openssl/params.h>

#include <algorithm>
#include <cstring>
#include <stdexcept>

namespace rcm::voice {

namespace {

constexpr std::size_t kHeaderBytes = 2;
constexpr std::size_t kPayloadBytes = kSecureFrameHalves * kCodec2Bytes;  // 16
constexpr std::size_t kTagAt = kHeaderBytes + kPayloadBytes;              // 18
constexpr std::size_t kDataBytes = kTagAt + kTagBytes;                    // 22: what the parity covers
static_assert(kDataBytes + 2 == kSecureFrameBytes);
constexpr std::uint8_t kFlagsMask = 0xC0;
constexpr std::uint8_t kCounterMask = 0x3F;
constexpr std::uint64_t kCounterModulus = 64;

using Payload = std::array<std::uint8_t, kPayloadBytes>;
using Tag = std::array<std::uint8_t, kTagBytes>;
using Keystream = std::array<std::uint8_t, 1 + kPayloadBytes>;

void putCounter(std::uint64_t counter, std::uint8_t* out)
{
    for (int i = 7; i >= 0; --i) {
        out[i] = static_cast<std::uint8_t>(counter);
        counter >>= 8;
    }
}

}  // namespace

// The two primitives under one direction's keys: the tag, and the keystream
// for a counter and tag.
class SecureVoiceCipher {
public:
    explicit SecureVoiceCipher(const secure::VoiceKeys& keys) : m_ctx(EVP_CIPHER_CTX_new())
    {
        if (!m_ctx || EVP_EncryptInit_ex(m_ctx, EVP_aes_256_ctr(), nullptr, keys.cipher.bytes().data(), nullptr) != 1)
            throw std::runtime_error("OpenSSL cannot make AES-256-CTR for the voice");
        // HMAC keyed once; each tag re-initialises it with that key (a
        // fetch and a key schedule per tag would cost four times as much).
        m_macAlgorithm = EVP_MAC_fetch(nullptr, "HMAC", nullptr);
        m_mac = m_macAlgorithm ? EVP_MAC_CTX_new(m_macAlgorithm) : nullptr;
        char digest[] = "SHA256";
        const OSSL_PARAM params[] = {OSSL_PARAM_construct_utf8_string("digest", digest, 0), OSSL_PARAM_construct_end()};
        if (!m_mac || EVP_MAC_init(m_mac, keys.mac.bytes().data(), keys.mac.bytes().size(), params) != 1)
            throw std::runtime_error("OpenSSL cannot make HMAC-SHA256 for the voice");
    }
    ~SecureVoiceCipher()
    {
        EVP_CIPHER_CTX_free(m_ctx);  // wipes the key schedule
        EVP_MAC_CTX_free(m_mac);     // and the HMAC key
        EVP_MAC_free(m_macAlgorithm);
    }

    // `header1` is byte 1 with its flags in the clear.
    Tag tag(std::uint64_t counter, std::uint8_t header0, std::uint8_t header1, const Payload& payload)
    {
        std::array<std::uint8_t, 8 + kHeaderBytes + kPayloadBytes> message;
        putCounter(counter, message.data());
        message[8] = header0;
        message[9] = header1;
        std::memcpy(message.data() + 10, payload.data(), kPayloadBytes);
        std::array<std::uint8_t, EVP_MAX_MD_SIZE> mac;
        std::size_t length = 0;
        if (EVP_MAC_init(m_mac, nullptr, 0, nullptr) != 1 || EVP_MAC_update(m_mac, message.data(), message.size()) != 1 ||
            EVP_MAC_final(m_mac, mac.data(), &length, mac.size()) != 1 || length < kTagBytes)
            throw std::runtime_error("OpenSSL HMAC-SHA256 failed");
        Tag t;
        std::memcpy(t.data(), mac.data(), kTagBytes);
        OPENSSL_cleanse(mac.data(), mac.size());
        return t;
    }

    Keystream keystream(std::uint64_t counter, const Tag& tag)
    {
        std::array<std::uint8_t, 16> iv{};
        putCounter(counter, iv.data());
        std::memcpy(iv.data() + 8, tag.data(), kTagBytes);
        const Keystream zeros{};
        Keystream ks;
        int n = 0;
        if (EVP_EncryptInit_ex(m_ctx, nullptr, nullptr, nullptr, iv.data()) != 1 ||
            EVP_EncryptUpdate(m_ctx, ks.data(), &n, zeros.data(), int(zeros.size())) != 1 || n != int(ks.size()))
            throw std::runtime_error("OpenSSL AES-256-CTR failed");
        return ks;
    }

private:
    EVP_CIPHER_CTX* m_ctx;
    EVP_MAC* m_macAlgorithm = nullptr;
    EVP_MAC_CTX* m_mac = nullptr;
};

std::uint64_t counterAt(std::int64_t utcMicros)
{
    return static_cast<std::uint64_t>(std::max<std::int64_t>(0, utcMicros) / kCounterMicros);
}

// ---------------------------------------------------------------- sender

SecureVoiceSealer::SecureVoiceSealer(const secure::VoiceKeys& keys, UtcMicros clock)
    : m_cipher(std::make_unique<SecureVoiceCipher>(keys)), m_clock(std::move(clock))
{
}

SecureVoiceSealer::~SecureVoiceSealer() = default;

void SecureVoiceSealer::seal(const VoiceFrame& first, const VoiceFrame& second,
                             std::span<std::uint8_t, kSecureFrameBytes> out)
{
    SecureVoiceFrame frame;
    frame.speech = {first.kind == FrameKind::Speech, second.kind == FrameKind::Speech};
    if (frame.speech[0])
        frame.payload[0] = first.payload;
    if (frame.speech[1])
        frame.payload[1] = second.payload;
    seal(frame, out);
}

void SecureVoiceSealer::seal(const SecureVoiceFrame& frame, std::span<std::uint8_t, kSecureFrameBytes> out)
{
    // From the clock at the start, then one a frame; caught up with the
    // clock should the stream have fallen far behind it (a long stall), so
    // that the receiver's window keeps it.
    const std::uint64_t now = counterAt(m_clock());
    if (m_next == 0 || m_next + 10 * kSecureFramesPerSecond < now)
        m_next = now;
    const std::uint64_t counter = m_next++;
    const auto flags = static_cast<std::uint8_t>((frame.speech[0] ? 0x80 : 0) | (frame.speech[1] ? 0x40 : 0));
    const auto header1 = static_cast<std::uint8_t>(flags | (counter & kCounterMask));
    Payload payload{};
    for (std::size_t h = 0; h < kSecureFrameHalves; ++h)
        if (frame.speech[h])
            std::memcpy(payload.data() + h * kCodec2Bytes, frame.payload[h].data(), kCodec2Bytes);
    const Tag tag = m_cipher->tag(counter, kSecureSyncByte, header1, payload);
    const Keystream ks = m_cipher->keystream(counter, tag);
    out[0] = kSecureSyncByte;
    out[1] = static_cast<std::uint8_t>(header1 ^ (ks[0] & kFlagsMask));
    for (std::size_t i = 0; i < kPayloadBytes; ++i)
        out[kHeaderBytes + i] = payload[i] ^ ks[1 + i];
    std::memcpy(out.data() + kTagAt, tag.data(), kTagBytes);
    addParity(out);
}

// ---------------------------------------------------------------- receiver

SecureVoiceOpener::SecureVoiceOpener(const secure::VoiceKeys& keys, UtcMicros clock, std::int64_t windowSeconds)
    : m_cipher(std::make_unique<SecureVoiceCipher>(keys)),
      m_clock(std::move(clock)),
      m_window(static_cast<std::uint64_t>(std::max<std::int64_t>(1, windowSeconds)) * 1000000 / kCounterMicros)
{
}

SecureVoiceOpener::~SecureVoiceOpener() = default;

SecureVoiceOpener::Verdict SecureVoiceOpener::tryFrame(std::uint64_t offset, SecureVoiceFrame& frame)
{
    std::array<std::uint8_t, kSecureFrameBytes> cw;
    std::memcpy(cw.data(), m_stream.at(offset), kSecureFrameBytes);
    const int corrected = correctOneByte(cw);
    if (corrected < 0 || cw[0] != kSecureSyncByte)
        return Verdict::NotAFrame;
    const std::uint64_t low = cw[1] & kCounterMask;
    Tag tag;
    std::memcpy(tag.data(), cw.data() + kTagAt, kTagBytes);
    const auto authentic = [&](std::uint64_t counter) {
        const Keystream ks = m_cipher->keystream(counter, tag);
        const auto header1 = static_cast<std::uint8_t>((cw[1] ^ (ks[0] & kFlagsMask)));
        Payload payload;
        for (std::size_t i = 0; i < kPayloadBytes; ++i)
            payload[i] = cw[kHeaderBytes + i] ^ ks[1 + i];
        const Tag expected = m_cipher->tag(counter, cw[0], header1, payload);
        if (CRYPTO_memcmp(expected.data(), tag.data(), kTagBytes) != 0)
            return false;
        frame.counter = counter;
        frame.speech = {(header1 & 0x80) != 0, (header1 & 0x40) != 0};
        for (std::size_t h = 0; h < kSecureFrameHalves; ++h)
            std::memcpy(frame.payload[h].data(), payload.data() + h * kCodec2Bytes, kCodec2Bytes);
        return true;
    };

    // The counters this frame may have: those with its low 6 bits, within
    // the window of this clock, ahead of the last accepted; the next one
    // after the last first, as a stream in step has it.
    const std::uint64_t now = counterAt(m_clock());
    const std::uint64_t earliest = now > m_window ? now - m_window : 0;
    const std::uint64_t latest = now + m_window;
    const auto withLow = [&](std::uint64_t from) {  // the first counter >= from with the low bits
        return from + ((low - (from % kCounterModulus) + kCounterModulus) % kCounterModulus);
    };
    std::uint64_t first = withLow(m_hasLast ? std::max(earliest, m_lastCounter + 1) : earliest);
    if (m_hasLast && withLow(m_lastCounter + 1) >= earliest && withLow(m_lastCounter + 1) <= latest &&
        authentic(withLow(m_lastCounter + 1))) {
        if (corrected > 0)
            ++m_stats.correctedFrames;
        return Verdict::Accepted;
    }
    // Every counter of the window costs a tag: at most so many such
    // searches a second, so that a flood of forgeries cannot make the
    // receiver fall behind (it refuses them unchecked instead).
    const std::int64_t second = m_clock() / 1000000;
    if (second != m_searchSecond) {
        m_searchSecond = second;
        m_searches = 0;
    }
    if (m_searches >= kMaxSearchesPerSecond) {
        if (corrected > 0)
            return Verdict::Garbled;
        ++m_stats.unchecked;
        return Verdict::Forged;
    }
    ++m_searches;
    for (std::uint64_t c = first; c <= latest; c += kCounterModulus) {
        if (m_hasLast && c == withLow(m_lastCounter + 1))
            continue;  // tried
        if (authentic(c)) {
            if (corrected > 0)
                ++m_stats.correctedFrames;
            return Verdict::Accepted;
        }
    }
    // Sent before, and accepted then: the one counter behind the last with these bits.
    if (m_hasLast) {
        const std::uint64_t back = m_lastCounter - ((m_lastCounter - low) % kCounterModulus);
        if (back <= m_lastCounter && authentic(back))
            return Verdict::Replayed;
    }
    return corrected == 0 ? Verdict::Forged : Verdict::Garbled;
}

void SecureVoiceOpener::take(std::uint64_t offset, const SecureVoiceFrame& frame, std::vector<std::uint8_t>& plain)
{
    if (m_hasLast)
        m_stats.lostFrames += frame.counter - m_lastCounter - 1;
    ++m_stats.accepted;
    // Each half a plain frame whose sequence follows the counter, so that the
    // decoder places it, and counts what was lost, as the counter says.
    for (std::size_t h = 0; h < kSecureFrameHalves; ++h) {
        const auto sequence = static_cast<std::uint8_t>((frame.counter * kSecureFrameHalves + h) % kSequenceModulus);
        plain.resize(plain.size() + kFrameBytes);
        buildFrame(frame.speech[h] ? FrameKind::Speech : FrameKind::Idle, sequence,
                   frame.speech[h] ? std::span<const std::uint8_t, kCodec2Bytes>(frame.payload[h])
                                   : std::span<const std::uint8_t, kCodec2Bytes>(std::array<std::uint8_t, 8>{}),
                   FrameSpan(plain.data() + plain.size() - kFrameBytes, kFrameBytes));
    }
    m_hasLast = true;
    m_lastCounter = frame.counter;
    m_stream.took(offset);
}

void SecureVoiceOpener::open(std::span<const std::uint8_t> bytes, std::vector<std::uint8_t>& plain)
{
    m_stats.bytesIn += bytes.size();
    m_stream.feed(bytes, [&] { process(plain); });
}

void SecureVoiceOpener::process(std::vector<std::uint8_t>& plain)
{
    SecureVoiceFrame frame;
    const auto inStep = [&](std::uint64_t offset) {
        switch (tryFrame(offset, frame)) {
            case Verdict::Accepted:
                take(offset, frame, plain);
                return;
            case Verdict::Replayed:
                // A frame put into the stream: skipped whole, never played.
                ++m_stats.replayed;
                m_stream.passed();
                return;
            case Verdict::Forged:
                ++m_stats.forged;
                m_stream.passed();
                return;
            case Verdict::Garbled:
                ++m_stats.garbled;
                break;
            case Verdict::NotAFrame:
                break;
        }
        if (m_stream.missed())
            ++m_stats.resyncs;
    };
    const auto hunt = [&](std::uint64_t end) {
        for (; m_stream.scan + kSecureFrameBytes <= end; ++m_stream.scan) {
            if (*m_stream.at(m_stream.scan) != kSecureSyncByte)
                continue;
            const Verdict verdict = tryFrame(m_stream.scan, frame);
            if (verdict == Verdict::Accepted) {
                take(m_stream.scan, frame, plain);
                return true;
            }
            if (verdict == Verdict::Replayed)
                ++m_stats.replayed;
            else if (verdict == Verdict::Forged)
                ++m_stats.forged;
        }
        return false;
    };
    m_stream.search(inStep, hunt);
}

}  // namespace rcm::voice
