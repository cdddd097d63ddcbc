#include "codec/secure/BrokerSeal.h"

#include <openssl/evp.h>
#include <openssl/rand.h>

#include <climits>
#include <stdexcept>

namespace rcm::secure {
namespace {

constexpr std::string_view kInfoBroker = "RCM-GCS v1 broker AES-256-GCM";

struct CipherContext {
    EVP_CIPHER_CTX* ctx = EVP_CIPHER_CTX_new();
    ~CipherContext() { EVP_CIPHER_CTX_free(ctx); }
};

bool fitsInt(std::size_t n)
{
    return n <= static_cast<std::size_t>(INT_MAX);
}

// What sealing and opening share: AES-256-GCM keyed with the key and the
// nonce, the associated data taken in, then in (inSize bytes) run through to
// out; *length is what was written. Sealing and opening differ only after.
bool runGcm(const CipherContext& c, bool sealing, const SecretKey& key, const std::uint8_t* nonce,
            std::span<const std::uint8_t> associated, const std::uint8_t* in, std::size_t inSize, std::uint8_t* out,
            int* length)
{
    return c.ctx &&
           EVP_CipherInit_ex(c.ctx, EVP_aes_256_gcm(), nullptr, key.bytes().data(), nonce, sealing ? 1 : 0) == 1 &&
           EVP_CipherUpdate(c.ctx, nullptr, length, associated.data(), int(associated.size())) == 1 &&
           EVP_CipherUpdate(c.ctx, out, length, in, int(inSize)) == 1;
}

}  // namespace

std::string_view brokerKeyInfo()
{
    return kInfoBroker;
}

SecretKey deriveBrokerKey(const SecretKey& psk)
{
    SecretKey key;
    const auto info = std::span(reinterpret_cast<const std::uint8_t*>(kInfoBroker.data()), kInfoBroker.size());
    if (!hkdfSha256({}, psk.bytes(), info, key.mutableBytes()))
        throw std::runtime_error("OpenSSL HKDF-SHA256 failed: no broker key derived");
    return key;
}

std::vector<std::uint8_t> sealBrokerPayload(const SecretKey& key, std::span<const std::uint8_t> associated,
                                            std::span<const std::uint8_t> plain)
{
    if (!fitsInt(plain.size()) || !fitsInt(associated.size()))
        throw std::runtime_error("a broker payload over 2 GiB cannot be sealed");
    std::vector<std::uint8_t> out(kSealNonceSize + plain.size() + kSealTagSize);
    if (RAND_bytes(out.data(), int(kSealNonceSize)) != 1)
        throw std::runtime_error("OpenSSL gave no random bytes for a nonce");
    CipherContext c;
    int length = 0;
    int tail = 0;
    const bool ok = runGcm(c, true, key, out.data(), associated, plain.data(), plain.size(),
                           out.data() + kSealNonceSize, &length) &&
                    EVP_EncryptFinal_ex(c.ctx, out.data() + kSealNonceSize + length, &tail) == 1 &&
                    EVP_CIPHER_CTX_ctrl(c.ctx, EVP_CTRL_GCM_GET_TAG, int(kSealTagSize),
                                        out.data() + kSealNonceSize + plain.size()) == 1;
    if (!ok)
        throw std::runtime_error("OpenSSL AES-256-GCM sealing failed");
    return out;
}

std::optional<std::vector<std::uint8_t>> openBrokerPayload(const SecretKey& key,
                                                           std::span<const std::uint8_t> associated,
                                                           std::span<const std::uint8_t> sealed)
{
    if (sealed.size() < kSealOverhead || !fitsInt(sealed.size()) || !fitsInt(associated.size()))
        return std::nullopt;
    const std::size_t plainSize = sealed.size() - kSealOverhead;
    std::vector<std::uint8_t> plain(plainSize);
    // GCM wants a writable tag buffer.
    std::uint8_t tag[kSealTagSize];
    std::copy(sealed.end() - kSealTagSize, sealed.end(), tag);
    CipherContext c;
    int length = 0;
    int tail = 0;
    const bool ok = runGcm(c, false, key, sealed.data(), associated, sealed.data() + kSealNonceSize, plainSize,
                           plain.data(), &length) &&
                    EVP_CIPHER_CTX_ctrl(c.ctx, EVP_CTRL_GCM_SET_TAG, int(kSealTagSize), tag) == 1 &&
                    EVP_DecryptFinal_ex(c.ctx, plain.data() + length, &tail) == 1;
    if (!ok)
        return std::nullopt;
    return plain;
}

}  // namespace rcm::secure
