// The secure link: encode-then-encipher with AES-256-HCTR2, authenticated by
// the message's own redundancy, with replay protection. docs/security.md has
// the threat model and the argument; this header has the exact bytes.
//
// Why no tag. A frame is 2 x 223 data bytes and the source document allows
// only encryption "that does not increase the message size ... performed
// prior to FEC encoding". So each 223-byte block is enciphered as one wide
// block with HCTR2 (codec/secure/Hctr2.h), a tweakable strong pseudorandom
// permutation: any ciphertext (or tweak) the sender did not produce
// deciphers to bytes indistinguishable from uniformly random. A block is
// accepted only when bytes that our encoder always writes come out as written
// (Bellare and Rogaway, "Encode-then-encipher encryption", ASIACRYPT 2000).
// Those bytes are the tag.
//
// Keys. The 256-bit pre-shared key (PSK) of one aircraft is never used
// directly. Each direction has its own key:
//     K_dir = HKDF-SHA256(salt = none (RFC 5869: 32 zero bytes), IKM = PSK,
//                         info = "RCM-GCS v1 AES-256-HCTR2 GCS->UA"  or
//                                "RCM-GCS v1 AES-256-HCTR2 UA->GCS", L = 32)
// No aircraft identity is mixed in: the key file is already per aircraft, and
// an identity in the derivation would be one more thing both ends must agree
// on beforehand, whose mismatch would look exactly like forgery.
//
// Tweaks (dd = 01 for GCS->UA, 02 for UA->GCS):
//     BLOCK 1:  52 43 4D 01 dd 01                       6 bytes: "RCM", version 1, direction, block 1
//     BLOCK 2:  52 43 4D 01 dd 02 II II II TT TT TT DD DD DD
//               15 bytes: as BLOCK 1 with block 2, then BLOCK 1's ID_msg,
//               time_UTC and date_UTC value bytes exactly as they stand in
//               BLOCK 1 (big-endian uint24 each)
// So a BLOCK 2 deciphers correctly only beside the BLOCK 1 it was sent with.
//
// Checked bytes (what decides "forged"). With encryption on, the encoder
// keeps >= 16 bytes of padding in BLOCK 1 (EncodeOptions{16, 199}) and a
// flight plan section carries at most 199 bytes. A deciphered block passes
// only when:
//   BLOCK 1  bytes 0..15 are 55 (128 bits: the bound below counts these
//            only), then more 55 bytes, then a run of items with known
//            Item_IDs and no padding, BEGIN or END between them, ending
//            exactly at byte 223; the items decode with no diagnostic at all
//            (values in range, two-bit fields valid, no repeats, no orphans);
//            ID_msg, time_UTC and date_UTC are present.
//   BLOCK 2  x = byte 0 <= 199; bytes 7+x .. 221 are 55 (215 - x >= 16
//            bytes); byte 222 is 00; the section decodes with no diagnostic.
// Forgery bound per attempt. An attempt the sender never produced gives, for
// at least one block, a fresh (tweak, ciphertext) pair, so that block's
// plaintext is uniform (up to HCTR2's distinguishing advantage, ~ sigma^2 /
// 2^128 for sigma 16-byte blocks ever enciphered under the key). If it is
// BLOCK 1, it passes with probability <= 2^-128 (its first 16 bytes alone).
// If BLOCK 1 is a genuine one, BLOCK 2 is the fresh one and passes with
// sum_{x=0}^{199} 2^-8 * 2^-8(215-x) * 2^-8 = 2^-144 * 256/255 < 2^-143.9
// (x fixes byte 0, then 215-x padding bytes and End_Of_String). Hence
//     Pr[one forged frame accepted] <= 2^-128 + Adv_HCTR2.
// A genuine frame sent again is caught by ReplayGuard, not by the cipher.
//
// Plain C++20 over OpenSSL 3; no Qt.
#pragma once

#include "codec/message/Diagnostic.h"
#include "codec/frame/Frame.h"
#include "codec/message/DecodeResult.h"
#include "codec/message/MessageEncoder.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace rcm {

class Hctr2;

namespace secure {

inline constexpr std::size_t kKeySize = 32;                 // the PSK and each direction's key
inline constexpr std::size_t kMinBlock1Padding = 16;        // checked: 128 bits
inline constexpr std::size_t kMaxFlightPlanData = 199;      // leaves >= 16 checked padding bytes in BLOCK 2
inline constexpr std::int64_t kDefaultWindowSeconds = 30;

// What encodeBlocks must be given for a block the secure link can send.
inline EncodeOptions encodeOptions() { return EncodeOptions{kMinBlock1Padding, kMaxFlightPlanData}; }

enum class Direction : std::uint8_t { GcsToUa = 0x01, UaToGcs = 0x02 };
std::string_view directionName(Direction d);  // "GCS->UA", "UA->GCS"
inline Direction opposite(Direction d) { return d == Direction::GcsToUa ? Direction::UaToGcs : Direction::GcsToUa; }

// Why a keyed receiver refused a frame whose codewords decoded.
enum class Rejection : std::uint8_t {
    Forged,     // a block's checked bytes did not come out as written: not sent with this key and direction
    Replayed,   // authentic, but its ID_msg is not ahead of the last accepted one
    StaleTime,  // authentic and new, but its time_UTC/date_UTC is outside the window of the receiver's clock
    Plaintext,  // not authentic, and it parses cleanly as an unencrypted message: a downgrade
};
inline constexpr int kRejectionCount = 4;
std::string_view rejectionName(Rejection r);  // "forged", "replayed", "stale time", "plaintext"

// 32 secret bytes, wiped when destroyed. Never printed: use fingerprint().
class SecretKey {
public:
    SecretKey() = default;
    explicit SecretKey(std::span<const std::uint8_t, kKeySize> bytes);
    SecretKey(const SecretKey& other);
    SecretKey& operator=(const SecretKey& other);
    ~SecretKey();

    std::span<const std::uint8_t, kKeySize> bytes() const { return m_bytes; }
    std::span<std::uint8_t, kKeySize> mutableBytes() { return m_bytes; }

private:
    std::array<std::uint8_t, kKeySize> m_bytes{};
};

// 32 bytes from OpenSSL's CSPRNG; throws std::runtime_error if it fails.
SecretKey generateKey();

// HKDF-SHA256 (RFC 5869) through OpenSSL's EVP_KDF "HKDF". An empty salt is
// RFC 5869's default (HashLen zero bytes). False when OpenSSL fails.
bool hkdfSha256(std::span<const std::uint8_t> salt, std::span<const std::uint8_t> ikm,
                std::span<const std::uint8_t> info, std::span<std::uint8_t> out);

// The info strings above, and the key of one direction.
std::string_view keyInfo(Direction d);
SecretKey deriveDirectionKey(const SecretKey& psk, Direction d);

// The voice channel's keys of one direction (docs/security.md section 8):
//     K_cipher = HKDF-SHA256(IKM = PSK, info = "RCM-GCS v1 voice AES-256-CTR GCS->UA" | "... UA->GCS", 32 bytes)
//     K_mac    = HKDF-SHA256(IKM = PSK, info = "RCM-GCS v1 voice HMAC-SHA256 GCS->UA" | "... UA->GCS", 32 bytes)
// Each domain (frames, voice, cipher, MAC, direction) has its own info, so no
// key serves two purposes.
struct VoiceKeys {
    Direction direction = Direction::GcsToUa;
    SecretKey cipher;
    SecretKey mac;
};
std::string voiceKeyInfo(Direction d, bool mac);
VoiceKeys deriveVoiceKeys(const SecretKey& psk, Direction d);

// 16 hex digits naming a key without revealing it, for logs and for checking
// that both ends hold the same key: the first 8 bytes of
// HKDF-SHA256(IKM = PSK, info = "RCM-GCS v1 key fingerprint").
std::string fingerprint(const SecretKey& psk);

// ---------------------------------------------------------------- key file
//
// Format: exactly 64 hexadecimal digits (either case), optionally followed by
// one "\n" or "\r\n"; nothing else. Made by `rcm keygen FILE`, or by
// `(umask 077; openssl rand -hex 32 > FILE)`.
// The file must be a regular file with no permission for group or others
// (mode 0600 or 0400): a key others can read is no secret, and one others
// can write is not ours. Errors name the file and, for the mode, the fix;
// they never contain key bytes.

std::optional<SecretKey> readKeyFile(const std::string& path, std::string& error);
// Creates `path` with mode 0600; refuses to overwrite an existing file.
bool writeKeyFile(const std::string& path, const SecretKey& key, std::string& error);

// Where the replay state of frames arriving in `incoming` lives: beside the
// key, "<key path>.replay-gcs-to-ua" or "<key path>.replay-ua-to-gcs". One
// file per direction, so a console and a simulator sharing a key file on one
// machine do not share state.
std::string replayStatePath(const std::string& keyPath, Direction incoming);
// Where the sender of `outgoing` keeps its ID_msg counter: "<key path>.sent-gcs-to-ua" ...
std::string counterStatePath(const std::string& keyPath, Direction outgoing);

// ---------------------------------------------------------------- tweaks

// ID_msg, time_UTC and date_UTC of one message: what binds BLOCK 2 to BLOCK 1
// and what the replay check reads.
struct HeaderStamp {
    std::uint32_t messageId = 0;  // 0 .. 2^24-1
    std::uint32_t timeUtc = 0;    // hhmmss as a number
    std::uint32_t dateUtc = 0;    // yymmdd as a number
    friend bool operator==(const HeaderStamp&, const HeaderStamp&) = default;
};

using Block1Tweak = std::array<std::uint8_t, 6>;
using Block2Tweak = std::array<std::uint8_t, 15>;
Block1Tweak block1Tweak(Direction d);
Block2Tweak block2Tweak(Direction d, const HeaderStamp& stamp);

// ---------------------------------------------------------------- checks

// The redundancy check of a deciphered (or about to be enciphered) BLOCK 1:
// 16 leading padding bytes, then items back to back to the end of the block
// that decode with no diagnostic, ID_msg, time_UTC and date_UTC among them.
// It decodes into `message` (appending to `diagnostics`): the receiver's one
// walk over the items is also the check. Fills `stamp` when it passes; `why`
// says what failed.
bool checkBlock1Structure(const Block& plain, Message& message, Diagnostics& diagnostics, HeaderStamp& stamp,
                          std::string& why);
bool checkBlock1Structure(const Block& plain, HeaderStamp& stamp, std::string& why);
// BLOCK 2: x <= 199, padding, End_Of_String; decodes into `section`.
bool checkBlock2Structure(const Block& plain, FlightPlanSection& section, Diagnostics& diagnostics, std::string& why);
bool checkBlock2Structure(const Block& plain, std::string& why);

// True when `blocks` parse as an unencrypted message with no diagnostic: on a
// keyed link, such a frame is a downgrade attempt (or a sender without a key).
bool looksLikePlaintext(const DecodedBlocks& blocks);

// ---------------------------------------------------------------- cipher

// What decryptBlocks found.
struct Authenticated {
    // Both codewords decoded and BLOCK 1 passed; BLOCK 2 too unless its
    // codeword was beyond correction (then the message has no flight plan
    // section and decoded.diagnostics says so, as decodeBlocks would).
    bool authentic = false;
    // Set when the codewords decoded (BLOCK 1's at least) and it is not
    // authentic: Forged or Plaintext. Neither set: BLOCK 1's codeword was
    // beyond correction, nothing could be checked.
    std::optional<Rejection> rejection;
    DecodeResult decoded;  // authentic: the message; otherwise only its corrections
    HeaderStamp stamp;     // authentic: BLOCK 1's ID_msg, time_UTC, date_UTC
    std::string detail;    // one line for logs; never key or plaintext bytes of a refused frame
};

// One direction of one aircraft's link: the sender enciphers with it, the
// receiver deciphers. Holds the derived key (the PSK is not kept). Safe to
// share between threads (Hctr2 serialises its calls).
class SecureCodec {
public:
    SecureCodec(const SecretKey& psk, Direction direction);
    ~SecureCodec();
    SecureCodec(const SecureCodec&) = delete;
    SecureCodec& operator=(const SecureCodec&) = delete;

    Direction direction() const { return m_direction; }

    // Enciphers blocks from encodeBlocks(message, errors, secure::encodeOptions()),
    // in place. Refuses (false, blocks unchanged, `error` says why) blocks the
    // receiver would reject: too little padding, no ID_msg/time_UTC/date_UTC,
    // a flight plan section over 199 bytes.
    bool encryptBlocks(EncodedBlocks& blocks, std::string& error) const;

    // encodeBlocks with the secure options, then encryptBlocks. Nothing, with
    // the reasons in `errors`, when either refuses.
    std::optional<EncodedBlocks> encode(const Message& message, Diagnostics& errors) const;

    // Deciphers RS-decoded blocks and checks their redundancy; no replay check
    // (see openFrame).
    Authenticated decryptBlocks(const DecodedBlocks& blocks) const;

    // One plaintext block enciphered as encryptBlocks would, without its
    // checks: a receiver enciphers its predictions of what its sender sent
    // (codec/receive/TrialDecoder.h) to compare them with what arrived.
    void encipherBlock1(Block& block) const;
    void encipherBlock2(Block& block, const HeaderStamp& stamp) const;

private:
    Direction m_direction;
    std::unique_ptr<Hctr2> m_cipher;
};

// ---------------------------------------------------------------- replay

// UTC seconds since 1970-01-01; tests inject their own.
using UtcClock = std::function<std::int64_t()>;
std::int64_t systemUtcSeconds();

// time_UTC hhmmss + date_UTC yymmdd (20yy) as UTC seconds since 1970, or
// nothing when they are not a valid time and date.
std::optional<std::int64_t> stampSeconds(std::uint32_t timeUtc, std::uint32_t dateUtc);

// True when `id` is ahead of `last` by 1 .. 2^23 - 1 modulo 2^24: the counter
// may wrap, and half the space is "ahead".
bool messageIdAhead(std::uint32_t id, std::uint32_t last);

// The receiver's memory of what it accepted. A message passes when its ID_msg
// is ahead of the last accepted one (any ID when none was accepted yet) and
// its time and date are within `windowSeconds` of the receiver's clock. The
// last accepted ID is updated only by accept(), which the caller calls only
// for an authenticated message that passed check(); with a state file it is
// written there at once (temporary file, fsync, rename), so it survives a
// restart. Not thread-safe.
//
// State file, text, mode 0600:
//     rcm-replay-state 1
//     key <fingerprint of the PSK>
//     last_accepted_id <decimal>
// A state file recorded under another key fingerprint is ignored (the new
// key starts afresh; notice() says so). One that cannot be read or parsed is
// an error: the constructor throws std::runtime_error naming the file, rather
// than silently forgetting what it accepted.
class ReplayGuard {
public:
    struct Options {
        std::int64_t windowSeconds = kDefaultWindowSeconds;
        std::string stateFile;       // empty: memory only
        std::string keyFingerprint;  // recorded in and checked against the state file
        UtcClock clock;              // empty: systemUtcSeconds
    };

    explicit ReplayGuard(Options options);
    ReplayGuard() : ReplayGuard(Options{}) {}

    // Nothing when the stamp may be accepted; else Replayed or StaleTime,
    // with a one-line reason in `detail` when given.
    std::optional<Rejection> check(const HeaderStamp& stamp, std::string* detail = nullptr) const;
    // Records an accepted message. False when the state file could not be
    // written (`error` says why); the guard keeps the new state in memory.
    bool accept(const HeaderStamp& stamp, std::string* error = nullptr);

    std::optional<std::uint32_t> lastAccepted() const { return m_last; }
    const Options& options() const { return m_options; }
    const std::string& notice() const { return m_notice; }

private:
    Options m_options;
    std::optional<std::uint32_t> m_last;
    std::string m_notice;
};

// The whole receive path after RS decoding: authenticate, then (with a
// guard) check replay and time, and on success record the message in the
// guard. `guard` may be null: no replay or time check (forensic decoding).
struct Opened {
    bool accepted = false;
    std::optional<Rejection> rejection;  // why not accepted; neither: BLOCK 1 beyond correction
    DecodeResult decoded;                // accepted: the message
    HeaderStamp stamp;                   // accepted, Replayed, StaleTime: the authenticated stamp
    std::string detail;                  // one line for logs
    std::string persistError;            // accepted, but the guard's state file could not be written
};
Opened openFrame(const SecureCodec& codec, ReplayGuard* guard, const DecodedBlocks& blocks);

// ---------------------------------------------------------------- sender

// The sender's ID_msg across restarts, so that the receiver (whose last
// accepted ID survives restarts too) never sees a new message as replayed.
// IDs are handed out in reservations: the state file holds an ID not yet
// handed out, written before any ID up to it is used, so a crash skips at
// most `reserve` IDs and never reuses one. With no state file yet (or one
// recorded under another key) the first ID is the UTC clock in seconds
// modulo 2^24: ahead of any earlier session that sent at most one frame a
// second, for 97 days after it.
//
// State file, text, mode 0600:
//     rcm-send-counter 1
//     key <fingerprint of the PSK>
//     next_id <decimal>
// The constructor throws std::runtime_error for a state file that exists
// but cannot be read or parsed.
class MessageCounter {
public:
    struct Options {
        std::string stateFile;  // empty: memory only
        std::string keyFingerprint;
        std::uint32_t reserve = 3600;  // IDs per write: an hour at one frame a second
        UtcClock clock;                // empty: systemUtcSeconds
    };

    explicit MessageCounter(Options options);

    std::uint32_t peek() const { return m_next; }
    // The ID for the next message. When the state file cannot be written the
    // ID is still handed out and `error` says why (a restart might then reuse
    // IDs, which the receiver rejects as replayed: availability, not secrecy).
    std::uint32_t next(std::string* error = nullptr);

private:
    bool persist(std::uint32_t value, std::string* error);

    Options m_options;
    std::uint32_t m_next = 0;
    std::uint32_t m_reservedUntil = 0;  // IDs before this (mod 2^24) may be handed out
};

// ---------------------------------------------------------------- one end

// One end of a keyed link, built from the aircraft's key file: the codec for
// the direction it sends in, the codec and replay guard for the direction it
// receives, and its send counter, with their state files beside the key file
// (replayStatePath, counterStatePath). What a LinkWorker needs. The key
// itself is not kept: only the derived keys, inside the codecs.
struct SecureEndpoint {
    struct Options {
        std::int64_t windowSeconds = kDefaultWindowSeconds;
        bool persistState = true;  // false: replay state and counter in memory only (tests)
        UtcClock clock;            // empty: systemUtcSeconds
    };

    // Nothing, with the reason in `error` (never key bytes), when the key file
    // is refused or a state file cannot be read or written.
    static std::unique_ptr<SecureEndpoint> open(const std::string& keyPath, Direction sends, std::string& error,
                                                const Options& options);
    static std::unique_ptr<SecureEndpoint> open(const std::string& keyPath, Direction sends, std::string& error)
    {
        return open(keyPath, sends, error, Options{});
    }
    // The same from a key in memory; state files only when `keyPath` is not empty.
    static std::unique_ptr<SecureEndpoint> fromKey(const SecretKey& psk, Direction sends, const std::string& keyPath,
                                                   std::string& error, const Options& options);

    Direction sends = Direction::GcsToUa;
    std::string fingerprint;  // of the key, for logs and the status bar
    std::string notice;       // e.g. a state file from another key was set aside
    std::unique_ptr<SecureCodec> sender;
    std::unique_ptr<SecureCodec> receiver;
    std::unique_ptr<ReplayGuard> guard;
    std::unique_ptr<MessageCounter> counter;
    // The voice channel's keys: for the voice this end sends, and for what it receives.
    std::shared_ptr<const VoiceKeys> voiceSend;
    std::shared_ptr<const VoiceKeys> voiceReceive;
};

// Writes `content` to `path` atomically: temporary file in the same
// directory (mode 0600), fsync, rename over `path`, fsync of the directory.
bool writeFileAtomically(const std::string& path, std::string_view content, std::string& error);

}  // namespace secure
}  // namespace rcm
