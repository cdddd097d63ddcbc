// Voice on a keyed link (docs/protocol.md section 7, docs/security.md section
// 8): enciphered, authenticated and replay-protected within the voice
// channel's 600 bytes a second. Two 20 ms Codec 2 3200 frames go in one
// secure frame of 24 bytes per 40 ms:
//
//   byte 0      sync E8
//   byte 1      bits 7-6: speech flags of the first and second 20 ms (1: speech,
//               0: idle), enciphered; bits 5-0: the frame counter modulo 64
//   bytes 2-17  the two Codec 2 frames (8 zero bytes for an idle half), enciphered
//   bytes 18-21 tag: the first 4 bytes of HMAC-SHA256(K_mac, C || byte 0 ||
//               byte 1 with its flags in the clear || bytes 2-17 in the clear),
//               C the frame counter as 8 bytes big-endian
//   bytes 22-23 Reed-Solomon parity over bytes 0-21 (VoiceCodec.h's code:
//               corrects one wrong byte)
//
// The counter C counts 40 ms since 1970-01-01 UTC: the sender starts it from
// its clock and adds one a frame, so it never repeats while the clock does
// not go back, and the receiver knows it from its own clock (within the
// window, 30 s as for the frames) and the 6 bits sent. It is implicit: the
// tag is over the whole of it.
//
// Encryption is SIV-like: the keystream is AES-256-CTR under K_cipher with
// the IV C || tag || 00000000, so a counter that did repeat (a clock set back
// past a restart) still gives another keystream for other speech. The tag is
// computed over the plaintext first, and checked after deciphering.
//
// A receiver accepts a frame only if its tag is right for a counter ahead of
// the last one accepted and within the window of its clock: a forged frame
// passes with probability 2^-32 per counter tried, a recorded one never
// (replayed). Neither is played; both are counted.
//
// Plain C++20 over OpenSSL 3; no Qt. Neither class is thread-safe.
#pragma once

#include "codec/secure/SecureCodec.h"
#include "codec/voice/VoiceCodec.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <vector>

namespace rcm::voice {

inline constexpr std::size_t kSecureFrameBytes = 24;
inline constexpr std::size_t kSecureFrameHalves = 2;  // 20 ms frames in one secure frame
inline constexpr std::size_t kSecureFramesPerSecond = 25;
inline constexpr std::uint8_t kSecureSyncByte = 0xE8;
inline constexpr std::size_t kTagBytes = 4;
inline constexpr std::int64_t kCounterMicros = 40000;  // one count of C
static_assert(kSecureFrameBytes * kSecureFramesPerSecond == kBytesPerSecond);

// UTC microseconds since 1970; tests pass their own.
using UtcMicros = std::function<std::int64_t()>;

// The counter of the 40 ms that holds `utcMicros`.
std::uint64_t counterAt(std::int64_t utcMicros);

// What a secure frame carries, once opened.
struct SecureVoiceFrame {
    std::uint64_t counter = 0;
    std::array<bool, kSecureFrameHalves> speech{};
    std::array<std::array<std::uint8_t, kCodec2Bytes>, kSecureFrameHalves> payload{};
};

class SecureVoiceCipher;

// The sender's side: two plain frames (speech or idle) in, one secure frame out.
class SecureVoiceSealer {
public:
    // Throws std::runtime_error when OpenSSL cannot make the cipher.
    SecureVoiceSealer(const secure::VoiceKeys& keys, UtcMicros clock);
    ~SecureVoiceSealer();
    SecureVoiceSealer(const SecureVoiceSealer&) = delete;
    SecureVoiceSealer& operator=(const SecureVoiceSealer&) = delete;

    void seal(const VoiceFrame& first, const VoiceFrame& second, std::span<std::uint8_t, kSecureFrameBytes> out);
    void seal(const SecureVoiceFrame& frame, std::span<std::uint8_t, kSecureFrameBytes> out);
    // The counter the next frame gets (0 before the first).
    std::uint64_t nextCounter() const { return m_next; }

private:
    std::unique_ptr<SecureVoiceCipher> m_cipher;
    UtcMicros m_clock;
    std::uint64_t m_next = 0;
};

// The receiver's side: the secure voice stream as it arrives (bytes in pieces
// of any size, with the line's errors and losses) in, plain voice frames
// (VoiceCodec.h) out for a VoiceDecoder, two for each frame accepted, their
// sequence numbers following the counter so that the decoder counts the
// frames lost between them.
class SecureVoiceOpener {
public:
    struct Stats : FrameStreamStats {
        std::uint64_t accepted = 0;
        std::uint64_t forged = 0;    // sync and parity right, no tag right: refused
        std::uint64_t replayed = 0;  // authentic, but not after the last accepted: refused
        std::uint64_t garbled = 0;   // parity corrected a byte and no tag was right: errors, most likely
        std::uint64_t unchecked = 0;  // of the forged: refused without the window's search, over its budget
    };

    // Two frame slots in a row that fail put the opener out of step.
    static constexpr int kMaxMisses = 2;
    // A frame that is not the next in step is tried at every counter of the
    // window (about 24 tags): at most this many such frames a second.
    static constexpr int kMaxSearchesPerSecond = 50;

    SecureVoiceOpener(const secure::VoiceKeys& keys, UtcMicros clock,
                      std::int64_t windowSeconds = secure::kDefaultWindowSeconds);
    ~SecureVoiceOpener();
    SecureVoiceOpener(const SecureVoiceOpener&) = delete;
    SecureVoiceOpener& operator=(const SecureVoiceOpener&) = delete;

    // Plain 12-byte frames appended to `plain`.
    void open(std::span<const std::uint8_t> bytes, std::vector<std::uint8_t>& plain);
    const Stats& stats() const { return m_stats; }
    bool inStep() const { return m_stream.tracking; }
    // The last counter accepted; 0 before any.
    std::uint64_t lastCounter() const { return m_hasLast ? m_lastCounter : 0; }

private:
    enum class Verdict { NotAFrame, Accepted, Replayed, Forged, Garbled };
    Verdict tryFrame(std::uint64_t offset, SecureVoiceFrame& frame);
    void take(std::uint64_t offset, const SecureVoiceFrame& frame, std::vector<std::uint8_t>& plain);
    void process(std::vector<std::uint8_t>& plain);

    std::unique_ptr<SecureVoiceCipher> m_cipher;
    UtcMicros m_clock;
    std::uint64_t m_window;  // counts either side of the clock's
    FrameStream m_stream{kSecureFrameBytes, kMaxMisses};
    bool m_hasLast = false;
    std::uint64_t m_lastCounter = 0;
    std::int64_t m_searchSecond = 0;
    int m_searches = 0;  // window searches in m_searchSecond
    Stats m_stats;
};

}  // namespace rcm::voice
