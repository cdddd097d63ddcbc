// A ground station's signing key for what it publishes on a broker:
// Ed25519 (RFC 8032) through OpenSSL's EVP interface. docs/security.md,
// "The broker", says what is signed and why.
//
// The key file holds the 32-byte Ed25519 private key (the seed) as 64 hex
// digits and a newline, in exactly the format and with exactly the checks of
// an aircraft's key file (SecureCodec.h: readKeyFile, mode 0600, never
// overwritten): a station key readable by others is refused as a link key
// is. The public key, 32 bytes, is what others trust: written as 64 hex
// digits after the station's name in a trust file ("GB_30226 3d40...").
//
// Plain C++20 over OpenSSL 3; no Qt.
#pragma once

#include "codec/secure/SecureCodec.h"

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace rcm::secure {

inline constexpr std::size_t kStationPublicKeySize = 32;
inline constexpr std::size_t kStationSignatureSize = 64;
using StationPublicKey = std::array<std::uint8_t, kStationPublicKeySize>;
using StationSignature = std::array<std::uint8_t, kStationSignatureSize>;

class StationSigningKey {
public:
    // A new key from OpenSSL's CSPRNG; throws std::runtime_error if it fails.
    static StationSigningKey generate();
    // From the seed; throws std::runtime_error if OpenSSL refuses it.
    explicit StationSigningKey(const SecretKey& seed);
    // Reads a key file as readKeyFile does (mode 0600, 64 hex digits).
    static std::optional<StationSigningKey> fromFile(const std::string& path, std::string& error);

    StationSigningKey(StationSigningKey&&) noexcept;
    StationSigningKey& operator=(StationSigningKey&&) noexcept;
    ~StationSigningKey();

    const StationPublicKey& publicKey() const { return m_public; }
    // Safe from several threads at once: each call has its own context.
    StationSignature sign(std::span<const std::uint8_t> message) const;
    // Writes the seed as writeKeyFile does (mode 0600, never over a file).
    bool writeFile(const std::string& path, std::string& error) const;

private:
    struct Pkey;
    std::unique_ptr<Pkey> m_key;
    SecretKey m_seed;
    StationPublicKey m_public{};
};

// Ed25519 verification of `signature` over `message` under `key`.
bool verifyStationSignature(const StationPublicKey& key, std::span<const std::uint8_t> message,
                            std::span<const std::uint8_t> signature);

// The same for one key, many messages: OpenSSL's key made once. Safe from
// several threads at once.
class StationVerifier {
public:
    // Throws std::runtime_error if OpenSSL refuses the key.
    explicit StationVerifier(const StationPublicKey& key);
    ~StationVerifier();
    StationVerifier(const StationVerifier&) = delete;
    StationVerifier& operator=(const StationVerifier&) = delete;

    const StationPublicKey& publicKey() const { return m_public; }
    bool verify(std::span<const std::uint8_t> message, std::span<const std::uint8_t> signature) const;

private:
    struct Pkey;
    std::unique_ptr<Pkey> m_key;
    StationPublicKey m_public;
};

// 64 lowercase hex digits, and back (either case; nothing for anything else).
std::string hexOf(std::span<const std::uint8_t> bytes);
std::optional<StationPublicKey> parseStationPublicKey(std::string_view hex);

}  // namespace rcm::secure
