#include "codec/secure/StationSigningKey.h"

#include "codec/message/HexDigits.h"

#include <openssl/evp.h>

#include <stdexcept>
#include <utility>

namespace rcm::secure {

struct StationSigningKey::Pkey {
    EVP_PKEY* pkey = nullptr;
    ~Pkey() { EVP_PKEY_free(pkey); }
};

StationSigningKey::StationSigningKey(const SecretKey& seed) : m_key(std::make_unique<Pkey>()), m_seed(seed)
{
    m_key->pkey = EVP_PKEY_new_raw_private_key(EVP_PKEY_ED25519, nullptr, m_seed.bytes().data(), m_seed.bytes().size());
    std::size_t length = m_public.size();
    if (!m_key->pkey || EVP_PKEY_get_raw_public_key(m_key->pkey, m_public.data(), &length) != 1 ||
        length != m_public.size())
        throw std::runtime_error("OpenSSL refused an Ed25519 key");
}

StationSigningKey StationSigningKey::generate()
{
    return StationSigningKey(generateKey());
}

std::optional<StationSigningKey> StationSigningKey::fromFile(const std::string& path, std::string& error)
{
    const std::optional<SecretKey> seed = readKeyFile(path, error);
    if (!seed)
        return std::nullopt;
    try {
        return StationSigningKey(*seed);
    } catch (const std::exception& e) {
        error = "the key file " + path + ": " + e.what();
        return std::nullopt;
    }
}

StationSigningKey::StationSigningKey(StationSigningKey&&) noexcept = default;
StationSigningKey& StationSigningKey::operator=(StationSigningKey&&) noexcept = default;
StationSigningKey::~StationSigningKey() = default;

StationSignature StationSigningKey::sign(std::span<const std::uint8_t> message) const
{
    StationSignature signature{};
    EVP_MD_CTX* ctx = EVP_MD_CTX_new();
    std::size_t length = signature.size();
    // Ed25519 signs the message itself (no digest named): one-shot only.
    const bool ok = ctx && EVP_DigestSignInit(ctx, nullptr, nullptr, nullptr, m_key->pkey) == 1 &&
                    EVP_DigestSign(ctx, signature.data(), &length, message.data(), message.size()) == 1 &&
                    length == signature.size();
    EVP_MD_CTX_free(ctx);
    if (!ok)
        throw std::runtime_error("OpenSSL Ed25519 signing failed");
    return signature;
}

bool StationSigningKey::writeFile(const std::string& path, std::string& error) const
{
    return writeKeyFile(path, m_seed, error);
}

namespace {

bool verifyWith(EVP_PKEY* pkey, std::span<const std::uint8_t> message, std::span<const std::uint8_t> signature)
{
    if (!pkey || signature.size() != kStationSignatureSize)
        return false;
    EVP_MD_CTX* ctx = EVP_MD_CTX_new();
    const bool ok = ctx && EVP_DigestVerifyInit(ctx, nullptr, nullptr, nullptr, pkey) == 1 &&
                    EVP_DigestVerify(ctx, signature.data(), signature.size(), message.data(), message.size()) == 1;
    EVP_MD_CTX_free(ctx);
    return ok;
}

}  // namespace

bool verifyStationSignature(const StationPublicKey& key, std::span<const std::uint8_t> message,
                            std::span<const std::uint8_t> signature)
{
    const std::unique_ptr<EVP_PKEY, void (*)(EVP_PKEY*)> pkey(
        EVP_PKEY_new_raw_public_key(EVP_PKEY_ED25519, nullptr, key.data(), key.size()), &EVP_PKEY_free);
    return verifyWith(pkey.get(), message, signature);
}

struct StationVerifier::Pkey {
    EVP_PKEY* pkey = nullptr;
    ~Pkey() { EVP_PKEY_free(pkey); }
};

StationVerifier::StationVerifier(const StationPublicKey& key) : m_key(std::make_unique<Pkey>()), m_public(key)
{
    m_key->pkey = EVP_PKEY_new_raw_public_key(EVP_PKEY_ED25519, nullptr, key.data(), key.size());
    if (!m_key->pkey)
        throw std::runtime_error("OpenSSL refused an Ed25519 public key");
}

StationVerifier::~StationVerifier() = default;

bool StationVerifier::verify(std::span<const std::uint8_t> message, std::span<const std::uint8_t> signature) const
{
    return verifyWith(m_key->pkey, message, signature);
}

std::string hexOf(std::span<const std::uint8_t> bytes)
{
    static constexpr char kDigits[] = "0123456789abcdef";
    std::string hex;
    hex.reserve(bytes.size() * 2);
    for (std::uint8_t b : bytes) {
        hex += kDigits[b >> 4];
        hex += kDigits[b & 15];
    }
    return hex;
}

std::optional<StationPublicKey> parseStationPublicKey(std::string_view hex)
{
    StationPublicKey key{};
    if (!decodeHex(hex, key))
        return std::nullopt;
    return key;
}

}  // namespace rcm::secure
