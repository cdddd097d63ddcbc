#include "codec/secure/SecureCodec.h"

#include "codec/secure/Hctr2.h"
#include "codec/message/DigitPairs.h"
#include "codec/message/HexDigits.h"
#include "codec/message/ItemTable.h"
#include "codec/message/MessageDecoder.h"

#include <openssl/core_names.h>
#include <openssl/crypto.h>
#include <openssl/kdf.h>
#include <openssl/rand.h>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace rcm::secure {
namespace {

constexpr std::uint8_t kTweakMagic[4] = {0x52, 0x43, 0x4D, 0x01};  // "RCM", version 1
constexpr std::string_view kInfoGcsToUa = "RCM-GCS v1 AES-256-HCTR2 GCS->UA";
constexpr std::string_view kInfoUaToGcs = "RCM-GCS v1 AES-256-HCTR2 UA->GCS";
constexpr std::string_view kInfoFingerprint = "RCM-GCS v1 key fingerprint";
constexpr std::size_t kKeyFileMaxBytes = 2 * kKeySize + 2;  // hex digits, "\r\n"

std::span<const std::uint8_t> bytesOf(std::string_view s)
{
    return {reinterpret_cast<const std::uint8_t*>(s.data()), s.size()};
}

void putBe24(std::uint8_t* p, std::uint32_t v)
{
    p[0] = static_cast<std::uint8_t>(v >> 16);
    p[1] = static_cast<std::uint8_t>(v >> 8);
    p[2] = static_cast<std::uint8_t>(v);
}

std::string errnoText() { return std::strerror(errno); }

std::string modeText(mode_t mode)
{
    char buf[8];
    std::snprintf(buf, sizeof buf, "%04o", static_cast<unsigned>(mode & 07777));
    return buf;
}

std::string directionSuffix(Direction d) { return d == Direction::GcsToUa ? "gcs-to-ua" : "ua-to-gcs"; }

// The state files of ReplayGuard and MessageCounter: three lines,
// "<magic> 1", "key <fingerprint>", "<field> <decimal>".
struct StateFile {
    std::string fingerprint;
    std::uint32_t value = 0;
};

// Nothing when the file does not exist; throws for one that exists but is
// not readable or not in the format.
std::optional<StateFile> readStateFile(const std::string& path, std::string_view magic, std::string_view field)
{
    std::FILE* f = std::fopen(path.c_str(), "rb");
    if (!f) {
        if (errno == ENOENT)
            return std::nullopt;
        throw std::runtime_error("cannot read the state file " + path + ": " + errnoText());
    }
    char buf[256];
    const std::size_t n = std::fread(buf, 1, sizeof buf - 1, f);
    const bool failed = std::ferror(f) || !std::feof(f);
    std::fclose(f);
    if (failed)
        throw std::runtime_error("cannot read the state file " + path + " (unreadable or too long)");
    buf[n] = '\0';

    char magicRead[32] = {}, keyWord[8] = {}, print[40] = {}, fieldRead[32] = {};
    unsigned version = 0;
    unsigned long value = 0;
    int consumed = 0;
    const int got = std::sscanf(buf, "%31s %u\n%7s %39s\n%31s %lu\n%n", magicRead, &version, keyWord, print,
                                fieldRead, &value, &consumed);
    if (got != 6 || magicRead != magic || version != 1 || std::string_view(keyWord) != "key" ||
        fieldRead != field || value >= kMessageIdModulus || static_cast<std::size_t>(consumed) != n)
        throw std::runtime_error("the state file " + path + " is not a " + std::string(magic) +
                                 " file; move it away only if you know the link's state is lost");
    return StateFile{print, static_cast<std::uint32_t>(value)};
}

bool writeStateFile(const std::string& path, std::string_view magic, const std::string& fingerprint,
                    std::string_view field, std::uint32_t value, std::string& error)
{
    const std::string text = std::string(magic) + " 1\nkey " + fingerprint + "\n" + std::string(field) + " " +
                             std::to_string(value) + "\n";
    return writeFileAtomically(path, text, error);
}

}  // namespace

std::string_view directionName(Direction d) { return d == Direction::GcsToUa ? "GCS->UA" : "UA->GCS"; }

std::string_view rejectionName(Rejection r)
{
    // In the enumeration's order.
    static constexpr std::array<std::string_view, kRejectionCount> kNames{"forged", "replayed", "stale time",
                                                                          "plaintext"};
    const auto index = std::size_t(r);
    return index < kNames.size() ? kNames[index] : "?";
}

// ---------------------------------------------------------------- keys

SecretKey::SecretKey(std::span<const std::uint8_t, kKeySize> bytes)
{
    std::memcpy(m_bytes.data(), bytes.data(), kKeySize);
}

SecretKey::SecretKey(const SecretKey& other) : m_bytes(other.m_bytes) {}

SecretKey& SecretKey::operator=(const SecretKey& other)
{
    m_bytes = other.m_bytes;
    return *this;
}

SecretKey::~SecretKey() { OPENSSL_cleanse(m_bytes.data(), m_bytes.size()); }

SecretKey generateKey()
{
    SecretKey key;
    if (RAND_bytes(key.mutableBytes().data(), static_cast<int>(kKeySize)) != 1)
        throw std::runtime_error("OpenSSL RAND_bytes failed: no key generated");
    return key;
}

bool hkdfSha256(std::span<const std::uint8_t> salt, std::span<const std::uint8_t> ikm,
                std::span<const std::uint8_t> info, std::span<std::uint8_t> out)
{
    EVP_KDF* kdf = EVP_KDF_fetch(nullptr, "HKDF", nullptr);
    if (!kdf)
        return false;
    EVP_KDF_CTX* ctx = EVP_KDF_CTX_new(kdf);
    EVP_KDF_free(kdf);
    if (!ctx)
        return false;
    // OSSL_PARAM wants non-const pointers; OpenSSL only reads these.
    OSSL_PARAM params[5];
    OSSL_PARAM* p = params;
    *p++ = OSSL_PARAM_construct_utf8_string(OSSL_KDF_PARAM_DIGEST, const_cast<char*>("SHA256"), 0);
    *p++ = OSSL_PARAM_construct_octet_string(OSSL_KDF_PARAM_KEY, const_cast<std::uint8_t*>(ikm.data()), ikm.size());
    if (!salt.empty())
        *p++ = OSSL_PARAM_construct_octet_string(OSSL_KDF_PARAM_SALT, const_cast<std::uint8_t*>(salt.data()),
                                                 salt.size());
    if (!info.empty())
        *p++ = OSSL_PARAM_construct_octet_string(OSSL_KDF_PARAM_INFO, const_cast<std::uint8_t*>(info.data()),
                                                 info.size());
    *p = OSSL_PARAM_construct_end();
    const bool ok = EVP_KDF_derive(ctx, out.data(), out.size(), params) == 1;
    EVP_KDF_CTX_free(ctx);  // wipes its copy of the key
    return ok;
}

std::string_view keyInfo(Direction d) { return d == Direction::GcsToUa ? kInfoGcsToUa : kInfoUaToGcs; }

std::string voiceKeyInfo(Direction d, bool mac)
{
    return std::string("RCM-GCS v1 voice ") + (mac ? "HMAC-SHA256 " : "AES-256-CTR ") + std::string(directionName(d));
}

VoiceKeys deriveVoiceKeys(const SecretKey& psk, Direction d)
{
    VoiceKeys keys;
    keys.direction = d;
    for (const bool mac : {false, true}) {
        const std::string info = voiceKeyInfo(d, mac);
        SecretKey& key = mac ? keys.mac : keys.cipher;
        if (!hkdfSha256({}, psk.bytes(), bytesOf(info), key.mutableBytes()))
            throw std::runtime_error("OpenSSL HKDF-SHA256 failed: no voice key derived");
    }
    return keys;
}

SecretKey deriveDirectionKey(const SecretKey& psk, Direction d)
{
    SecretKey key;
    if (!hkdfSha256({}, psk.bytes(), bytesOf(keyInfo(d)), key.mutableBytes()))
        throw std::runtime_error("OpenSSL HKDF-SHA256 failed: no key derived");
    return key;
}

std::string fingerprint(const SecretKey& psk)
{
    std::uint8_t out[8];
    if (!hkdfSha256({}, psk.bytes(), bytesOf(kInfoFingerprint), out))
        throw std::runtime_error("OpenSSL HKDF-SHA256 failed: no fingerprint");
    std::string hex;
    for (std::uint8_t b : out) {
        static constexpr char kDigits[] = "0123456789abcdef";
        hex += kDigits[b >> 4];
        hex += kDigits[b & 15];
    }
    return hex;
}

std::optional<SecretKey> readKeyFile(const std::string& path, std::string& error)
{
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) {
        error = "cannot open the key file " + path + ": " + errnoText();
        return std::nullopt;
    }
    // Checked on the open descriptor, so the file judged is the file read.
    struct stat st {};
    if (::fstat(fd, &st) != 0) {
        error = "cannot examine the key file " + path + ": " + errnoText();
        ::close(fd);
        return std::nullopt;
    }
    if (!S_ISREG(st.st_mode)) {
        error = "the key file " + path + " is not a regular file";
        ::close(fd);
        return std::nullopt;
    }
    if (st.st_mode & 077) {
        error = "the key file " + path + " has mode " + modeText(st.st_mode) +
                ": others than its owner may read or write it, so it is refused; run: chmod 600 " + path;
        ::close(fd);
        return std::nullopt;
    }
    std::uint8_t buf[kKeyFileMaxBytes + 1];
    std::size_t n = 0;
    while (n < sizeof buf) {
        const ssize_t r = ::read(fd, buf + n, sizeof buf - n);
        if (r < 0 && errno == EINTR)
            continue;
        if (r < 0) {
            error = "cannot read the key file " + path + ": " + errnoText();
            ::close(fd);
            OPENSSL_cleanse(buf, sizeof buf);
            return std::nullopt;
        }
        if (r == 0)
            break;
        n += static_cast<std::size_t>(r);
    }
    ::close(fd);

    // 64 hex digits, then nothing, "\n" or "\r\n". The error never quotes the content.
    std::size_t len = n;
    if (len > 0 && buf[len - 1] == '\n') {
        --len;
        if (len > 0 && buf[len - 1] == '\r')
            --len;
    }
    std::optional<SecretKey> key;
    key.emplace();
    if (!decodeHex(std::string_view(reinterpret_cast<const char*>(buf), len), key->mutableBytes()))
        key.reset();
    OPENSSL_cleanse(buf, sizeof buf);
    if (!key)
        error = "the key file " + path +
                " is not a key: it must hold exactly 64 hexadecimal digits (256 bits) and a newline";
    return key;
}

bool writeKeyFile(const std::string& path, const SecretKey& key, std::string& error)
{
    const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
    if (fd < 0) {
        error = errno == EEXIST ? "the key file " + path + " exists already; a key is never overwritten"
                                : "cannot create the key file " + path + ": " + errnoText();
        return false;
    }
    char text[2 * kKeySize + 1];
    for (std::size_t i = 0; i < kKeySize; ++i) {
        static constexpr char kDigits[] = "0123456789abcdef";
        text[2 * i] = kDigits[key.bytes()[i] >> 4];
        text[2 * i + 1] = kDigits[key.bytes()[i] & 15];
    }
    text[2 * kKeySize] = '\n';
    const bool ok = ::fchmod(fd, 0600) == 0 && ::write(fd, text, sizeof text) == static_cast<ssize_t>(sizeof text) &&
                    ::fsync(fd) == 0;
    OPENSSL_cleanse(text, sizeof text);
    if (!ok)
        error = "cannot write the key file " + path + ": " + errnoText();
    if (::close(fd) != 0 && ok) {
        error = "cannot write the key file " + path + ": " + errnoText();
        return false;
    }
    if (!ok)
        ::unlink(path.c_str());
    return ok;
}

std::string replayStatePath(const std::string& keyPath, Direction incoming)
{
    return keyPath + ".replay-" + directionSuffix(incoming);
}

std::string counterStatePath(const std::string& keyPath, Direction outgoing)
{
    return keyPath + ".sent-" + directionSuffix(outgoing);
}

// ---------------------------------------------------------------- tweaks

Block1Tweak block1Tweak(Direction d)
{
    return {kTweakMagic[0], kTweakMagic[1], kTweakMagic[2], kTweakMagic[3], static_cast<std::uint8_t>(d), 0x01};
}

Block2Tweak block2Tweak(Direction d, const HeaderStamp& stamp)
{
    Block2Tweak t{kTweakMagic[0], kTweakMagic[1], kTweakMagic[2], kTweakMagic[3], static_cast<std::uint8_t>(d), 0x02};
    putBe24(&t[6], stamp.messageId);
    putBe24(&t[9], stamp.timeUtc);
    putBe24(&t[12], stamp.dateUtc);
    return t;
}

// ---------------------------------------------------------------- checks

bool checkBlock1Structure(const Block& plain, Message& message, Diagnostics& diagnostics, HeaderStamp& stamp,
                          std::string& why)
{
    // The 128 counted bits first: almost every forgery stops here.
    if (std::any_of(plain.begin(), plain.begin() + kMinBlock1Padding, [](std::uint8_t b) { return b != kPad55; })) {
        why = "BLOCK 1 does not start with 16 padding bytes";
        return false;
    }
    // Then the structure the encoder always writes, read in the decoder's walk
    // over the items: our encoder validates every value, so any diagnostic
    // means the block was not written by a key holder; and items back to back
    // to the end of the block leave no byte unaccounted for, where a decoder
    // silently skips padding, BEGIN and END between items.
    const std::size_t before = diagnostics.size();
    std::size_t looseBytes = 0;
    decodeBlock1(plain, message, diagnostics, &looseBytes);
    if (diagnostics.size() != before) {
        why = "BLOCK 1 items do not decode cleanly";
        return false;
    }
    if (looseBytes != 0) {
        why = "BLOCK 1 has bytes between its items that are not items";
        return false;
    }
    const Unit& header = message.header;
    if (!header.has(ItemId::ID_msg) || !header.has(ItemId::time_UTC) || !header.has(ItemId::date_UTC)) {
        why = "BLOCK 1 lacks ID_msg, time_UTC or date_UTC, which the secure link requires";
        return false;
    }
    stamp.messageId = static_cast<std::uint32_t>(header.number(ItemId::ID_msg));
    stamp.timeUtc = static_cast<std::uint32_t>(header.number(ItemId::time_UTC));
    stamp.dateUtc = static_cast<std::uint32_t>(header.number(ItemId::date_UTC));
    return true;
}

bool checkBlock1Structure(const Block& plain, HeaderStamp& stamp, std::string& why)
{
    Message message;
    Diagnostics diagnostics;
    return checkBlock1Structure(plain, message, diagnostics, stamp, why);
}

bool checkBlock2Structure(const Block& plain, FlightPlanSection& section, Diagnostics& diagnostics, std::string& why)
{
    // The decoder checks the padding and End_Of_String (the counted bits) as
    // it reads; only the secure link's smaller section limit is extra.
    if (plain[0] > kMaxFlightPlanData) {
        why = "BLOCK 2 carries more than " + std::to_string(kMaxFlightPlanData) + " flight plan bytes";
        return false;
    }
    const std::size_t before = diagnostics.size();
    decodeBlock2(plain, section, diagnostics);
    if (diagnostics.size() != before) {
        why = "BLOCK 2 padding or End_Of_String is not as sent";
        return false;
    }
    return true;
}

bool checkBlock2Structure(const Block& plain, std::string& why)
{
    FlightPlanSection section;
    Diagnostics diagnostics;
    return checkBlock2Structure(plain, section, diagnostics, why);
}

bool looksLikePlaintext(const DecodedBlocks& blocks)
{
    if (blocks.corrected.block1 < 0)
        return false;
    Message m;
    Diagnostics d;
    decodeBlock1(blocks.block1, m, d);
    if (!d.empty())
        return false;
    if (blocks.corrected.block2 >= 0)
        decodeBlock2(blocks.block2, m.flightPlan, d);
    return d.empty();
}

// ---------------------------------------------------------------- cipher

SecureCodec::SecureCodec(const SecretKey& psk, Direction direction) : m_direction(direction)
{
    const SecretKey key = deriveDirectionKey(psk, direction);
    m_cipher = std::make_unique<Hctr2>(key.bytes());
}

SecureCodec::~SecureCodec() = default;

bool SecureCodec::encryptBlocks(EncodedBlocks& blocks, std::string& error) const
{
    // The sender refuses what the receiver would refuse, so a mistake shows
    // here with its reason instead of as "forged" at the other end.
    HeaderStamp stamp;
    std::string why;
    if (!checkBlock1Structure(blocks.block1, stamp, why) || !checkBlock2Structure(blocks.block2, why)) {
        error = "cannot be sent on the secure link: " + why;
        return false;
    }
    encipherBlock1(blocks.block1);
    encipherBlock2(blocks.block2, stamp);
    return true;
}

void SecureCodec::encipherBlock1(Block& block) const
{
    m_cipher->encrypt(block1Tweak(m_direction), block, block);
}

void SecureCodec::encipherBlock2(Block& block, const HeaderStamp& stamp) const
{
    m_cipher->encrypt(block2Tweak(m_direction, stamp), block, block);
}

std::optional<EncodedBlocks> SecureCodec::encode(const Message& message, Diagnostics& errors) const
{
    std::string missing;
    for (ItemId id : {ItemId::ID_msg, ItemId::time_UTC, ItemId::date_UTC}) {
        if (!message.header.has(id))
            missing += (missing.empty() ? "" : ", ") + std::string(itemInfo(id).name);
    }
    std::optional<EncodedBlocks> blocks = encodeBlocks(message, errors, encodeOptions());
    if (!missing.empty()) {
        errors.push_back({Diagnostic::Kind::MissingKey, 1, -1, "header",
                          "the secure link needs ID_msg, time_UTC and date_UTC in every message; missing: " + missing});
        return std::nullopt;
    }
    if (!blocks)
        return std::nullopt;
    std::string error;
    if (!encryptBlocks(*blocks, error)) {  // not expected after the checks above
        errors.push_back({Diagnostic::Kind::DoesNotFit, 1, -1, "secure link", error});
        return std::nullopt;
    }
    return blocks;
}

Authenticated SecureCodec::decryptBlocks(const DecodedBlocks& in) const
{
    // Every return is `return a`, so the result is built in place.
    Authenticated a;
    DecodeResult& r = a.decoded;
    r.corrected.block1 = in.corrected.block1;
    r.corrected.block2 = in.corrected.block2;
    if (in.corrected.block1 < 0) {
        // BLOCK 2's tweak comes from BLOCK 1, so nothing can be checked.
        r.diagnostics.push_back({Diagnostic::Kind::Uncorrectable, 1, -1, "",
                                 "more than 16 byte errors in the codeword; frame not read"});
        a.detail = "BLOCK 1 beyond correction";
        return a;
    }
    // Nothing read from a refused frame is passed on: not its items, and not
    // the decoder's diagnostics, whose text would describe bytes of an
    // attacker's deciphered block.
    auto refuse = [&](std::string why) {
        r.message = Message{};
        r.diagnostics.clear();
        a.rejection = looksLikePlaintext(in) ? Rejection::Plaintext : Rejection::Forged;
        a.detail = a.rejection == Rejection::Plaintext
                       ? "an unencrypted message on a keyed link"
                       : std::move(why) + " after deciphering (" + std::string(directionName(m_direction)) + ")";
    };

    Block p1;
    m_cipher->decrypt(block1Tweak(m_direction), in.block1, p1);
    HeaderStamp stamp;
    std::string why;
    if (!checkBlock1Structure(p1, r.message, r.diagnostics, stamp, why)) {
        refuse(std::move(why));
        return a;
    }
    if (in.corrected.block2 >= 0) {
        Block p2;
        m_cipher->decrypt(block2Tweak(m_direction, stamp), in.block2, p2);
        if (!checkBlock2Structure(p2, r.message.flightPlan, r.diagnostics, why)) {
            refuse(std::move(why));
            return a;
        }
    } else {
        r.diagnostics.push_back({Diagnostic::Kind::Uncorrectable, 2, -1, "",
                                 "more than 16 byte errors in the codeword; block not read"});
    }
    a.authentic = true;
    a.stamp = stamp;
    return a;
}

// ---------------------------------------------------------------- replay

std::int64_t systemUtcSeconds()
{
    return std::chrono::duration_cast<std::chrono::seconds>(std::chrono::system_clock::now().time_since_epoch())
        .count();
}

std::optional<std::int64_t> stampSeconds(std::uint32_t timeUtc, std::uint32_t dateUtc)
{
    return utcSeconds(timeUtc, dateUtc);
}

bool messageIdAhead(std::uint32_t id, std::uint32_t last)
{
    const std::uint32_t d = (id - last) & (kMessageIdModulus - 1);
    return d >= 1 && d < kMessageIdModulus / 2;
}

ReplayGuard::ReplayGuard(Options options) : m_options(std::move(options))
{
    if (!m_options.clock)
        m_options.clock = systemUtcSeconds;
    if (m_options.stateFile.empty())
        return;
    const std::optional<StateFile> state = readStateFile(m_options.stateFile, "rcm-replay-state", "last_accepted_id");
    if (!state)
        return;
    if (state->fingerprint != m_options.keyFingerprint) {
        m_notice = "the replay state " + m_options.stateFile +
                   " was recorded under another key; starting afresh under this one";
        return;
    }
    m_last = state->value;
}

std::optional<Rejection> ReplayGuard::check(const HeaderStamp& stamp, std::string* detail) const
{
    if (m_last && !messageIdAhead(stamp.messageId, *m_last)) {
        if (detail)
            *detail = "ID_msg " + std::to_string(stamp.messageId) + " is not ahead of the last accepted " +
                      std::to_string(*m_last);
        return Rejection::Replayed;
    }
    const std::optional<std::int64_t> sent = stampSeconds(stamp.timeUtc, stamp.dateUtc);
    if (!sent) {
        if (detail)
            *detail = "time_UTC " + std::to_string(stamp.timeUtc) + " date_UTC " + std::to_string(stamp.dateUtc) +
                      " is not a valid time";
        return Rejection::StaleTime;
    }
    const std::int64_t skew = *sent - m_options.clock();
    if (skew > m_options.windowSeconds || skew < -m_options.windowSeconds) {
        if (detail)
            *detail = "time_UTC/date_UTC is " + std::to_string(skew < 0 ? -skew : skew) + " s " +
                      (skew < 0 ? "behind" : "ahead of") + " the receiver's clock; the window is " +
                      std::to_string(m_options.windowSeconds) + " s";
        return Rejection::StaleTime;
    }
    return std::nullopt;
}

bool ReplayGuard::accept(const HeaderStamp& stamp, std::string* error)
{
    m_last = stamp.messageId;
    if (m_options.stateFile.empty())
        return true;
    std::string e;
    if (writeStateFile(m_options.stateFile, "rcm-replay-state", m_options.keyFingerprint, "last_accepted_id",
                       stamp.messageId, e))
        return true;
    if (error)
        *error = e;
    return false;
}

Opened openFrame(const SecureCodec& codec, ReplayGuard* guard, const DecodedBlocks& blocks)
{
    Authenticated a = codec.decryptBlocks(blocks);
    Opened o;
    o.rejection = a.rejection;
    o.detail = std::move(a.detail);
    o.decoded = std::move(a.decoded);
    if (!a.authentic)
        return o;
    o.stamp = a.stamp;
    if (guard) {
        std::string detail;
        if (const std::optional<Rejection> r = guard->check(a.stamp, &detail)) {
            // Authentic but refused: the message is not passed on.
            o.rejection = r;
            o.detail = std::move(detail);
            o.decoded.message = Message{};
            o.decoded.diagnostics.clear();
            return o;
        }
        guard->accept(a.stamp, &o.persistError);
    }
    o.accepted = true;
    return o;
}

// ---------------------------------------------------------------- sender

MessageCounter::MessageCounter(Options options) : m_options(std::move(options))
{
    if (!m_options.clock)
        m_options.clock = systemUtcSeconds;
    if (m_options.reserve == 0)
        m_options.reserve = 1;
    std::optional<StateFile> state;
    if (!m_options.stateFile.empty())
        state = readStateFile(m_options.stateFile, "rcm-send-counter", "next_id");
    if (state && state->fingerprint == m_options.keyFingerprint)
        m_next = state->value;
    else
        m_next = static_cast<std::uint32_t>(m_options.clock() & (kMessageIdModulus - 1));
    if (m_options.stateFile.empty())
        return;
    std::string error;
    if (!persist(m_next, &error))
        throw std::runtime_error(error + "; without it a restart could reuse message IDs");
}

bool MessageCounter::persist(std::uint32_t from, std::string* error)
{
    const std::uint32_t until = (from + m_options.reserve) & (kMessageIdModulus - 1);
    std::string e;
    if (!writeStateFile(m_options.stateFile, "rcm-send-counter", m_options.keyFingerprint, "next_id", until, e)) {
        if (error)
            *error = e;
        return false;
    }
    m_reservedUntil = until;
    return true;
}

std::uint32_t MessageCounter::next(std::string* error)
{
    const std::uint32_t id = m_next;
    if (!m_options.stateFile.empty() && id == m_reservedUntil)
        persist(id, error);  // on failure the next call tries again
    m_next = (id + 1) & (kMessageIdModulus - 1);
    return id;
}

// ---------------------------------------------------------------- one end

std::unique_ptr<SecureEndpoint> SecureEndpoint::open(const std::string& keyPath, Direction sends, std::string& error,
                                                     const Options& options)
{
    const std::optional<SecretKey> psk = readKeyFile(keyPath, error);
    if (!psk)
        return nullptr;
    return fromKey(*psk, sends, options.persistState ? keyPath : std::string(), error, options);
}

std::unique_ptr<SecureEndpoint> SecureEndpoint::fromKey(const SecretKey& psk, Direction sends,
                                                        const std::string& keyPath, std::string& error,
                                                        const Options& options)
{
    auto e = std::make_unique<SecureEndpoint>();
    try {
        e->sends = sends;
        e->fingerprint = secure::fingerprint(psk);
        e->sender = std::make_unique<SecureCodec>(psk, sends);
        e->receiver = std::make_unique<SecureCodec>(psk, opposite(sends));
        e->voiceSend = std::make_shared<const VoiceKeys>(deriveVoiceKeys(psk, sends));
        e->voiceReceive = std::make_shared<const VoiceKeys>(deriveVoiceKeys(psk, opposite(sends)));
        ReplayGuard::Options g;
        g.windowSeconds = options.windowSeconds;
        g.keyFingerprint = e->fingerprint;
        g.clock = options.clock;
        MessageCounter::Options c;
        c.keyFingerprint = e->fingerprint;
        c.clock = options.clock;
        if (!keyPath.empty()) {
            g.stateFile = replayStatePath(keyPath, opposite(sends));
            c.stateFile = counterStatePath(keyPath, sends);
        }
        e->guard = std::make_unique<ReplayGuard>(g);
        e->counter = std::make_unique<MessageCounter>(c);
        e->notice = e->guard->notice();
    } catch (const std::exception& x) {
        error = x.what();
        return nullptr;
    }
    return e;
}

bool writeFileAtomically(const std::string& path, std::string_view content, std::string& error)
{
    const std::size_t slash = path.rfind('/');
    const std::string dir = slash == std::string::npos ? "." : slash == 0 ? "/" : path.substr(0, slash);
    std::string temp = path + ".XXXXXX";
    const int fd = ::mkstemp(temp.data());  // mode 0600
    if (fd < 0) {
        error = "cannot create a temporary file beside " + path + ": " + errnoText();
        return false;
    }
    bool ok = true;
    std::size_t done = 0;
    while (ok && done < content.size()) {
        const ssize_t w = ::write(fd, content.data() + done, content.size() - done);
        if (w < 0 && errno == EINTR)
            continue;
        ok = w > 0;
        if (ok)
            done += static_cast<std::size_t>(w);
    }
    ok = ok && ::fsync(fd) == 0;
    if (!ok)
        error = "cannot write " + temp + ": " + errnoText();
    if (::close(fd) != 0 && ok) {
        error = "cannot write " + temp + ": " + errnoText();
        ok = false;
    }
    if (ok && ::rename(temp.c_str(), path.c_str()) != 0) {
        error = "cannot rename " + temp + " to " + path + ": " + errnoText();
        ok = false;
    }
    if (!ok) {
        ::unlink(temp.c_str());
        return false;
    }
    // The rename itself is durable only once the directory is synced.
    if (const int dfd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC); dfd >= 0) {
        ::fsync(dfd);
        ::close(dfd);
    }
    return true;
}

}  // namespace rcm::secure
