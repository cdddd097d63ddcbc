// What a keyed session publishes on a broker is sealed for the holders of
// the aircraft's key: AES-256-GCM under a key of its own, derived from the
// link's key with HKDF-SHA256 and a label no other use shares:
//
//     K_broker = HKDF-SHA256(IKM = PSK, salt = none, info = "RCM-GCS v1 broker AES-256-GCM", 32 bytes)
//
// A sealed payload is nonce (12 random bytes) || ciphertext || tag (16
// bytes); the associated data binds it to where it was published (the
// caller passes the topic). docs/security.md, "The broker".
//
// Plain C++20 over OpenSSL 3; no Qt.
#pragma once

#include "codec/secure/SecureCodec.h"

#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

namespace rcm::secure {

inline constexpr std::size_t kSealNonceSize = 12;
inline constexpr std::size_t kSealTagSize = 16;
inline constexpr std::size_t kSealOverhead = kSealNonceSize + kSealTagSize;

std::string_view brokerKeyInfo();  // "RCM-GCS v1 broker AES-256-GCM"
SecretKey deriveBrokerKey(const SecretKey& psk);

// Throws std::runtime_error when OpenSSL fails (no random bytes, no cipher).
std::vector<std::uint8_t> sealBrokerPayload(const SecretKey& key, std::span<const std::uint8_t> associated,
                                            std::span<const std::uint8_t> plain);
// Nothing when the tag does not verify (another key, another topic, a changed
// byte) or the payload is shorter than nonce and tag.
std::optional<std::vector<std::uint8_t>> openBrokerPayload(const SecretKey& key,
                                                           std::span<const std::uint8_t> associated,
                                                           std::span<const std::uint8_t> sealed);

}  // namespace rcm::secure
