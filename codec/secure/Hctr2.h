#pragma once

// AES-HCTR2: a length-preserving, tweakable wide-block cipher.
//
// Crowley, Huckleberry, Biggers, "Length-preserving encryption with HCTR2",
// IACR ePrint 2021/1441. A message of any length >= 16 bytes is enciphered as
// one wide block: changing any bit of the plaintext or of the tweak changes
// the whole ciphertext, and the ciphertext is exactly as long as the
// plaintext. HCTR2 does not authenticate; bind context into the tweak.
//
// Plain C++20 over OpenSSL 3 (AES through EVP, ECB without padding); no Qt.

#include <cstdint>
#include <memory>
#include <span>

namespace rcm {

class Hctr2 {
public:
    // key: 16 or 32 bytes (AES-128 or AES-256); throws std::invalid_argument
    // otherwise, std::runtime_error if OpenSSL cannot set up AES.
    explicit Hctr2(std::span<const std::uint8_t> key);
    ~Hctr2();
    Hctr2(const Hctr2&) = delete;
    Hctr2& operator=(const Hctr2&) = delete;

    // Message length >= 16 bytes and out.size() == in.size(), otherwise
    // std::invalid_argument. `in` and `out` may be the same buffer (in-place)
    // or disjoint; a partial overlap throws. The tweak may be any length.
    // No allocation. Safe to call from several threads: calls on one object
    // are serialised by an internal mutex (OpenSSL cipher contexts are not
    // shareable between threads). The lock stays although each link calls
    // from its own worker thread: objects are reached through shared
    // pointers, and uncontended the lock costs about 4 ns of a 160 ns call
    // (223 bytes, PCLMULQDQ), measured with tests/bench/bench_hctr2.
    void encrypt(std::span<const std::uint8_t> tweak,
                 std::span<const std::uint8_t> in,
                 std::span<std::uint8_t> out) const;
    void decrypt(std::span<const std::uint8_t> tweak,
                 std::span<const std::uint8_t> in,
                 std::span<std::uint8_t> out) const;

private:
    struct Impl;
    std::unique_ptr<Impl> d_;
};

namespace detail {

// POLYVAL (RFC 8452), exposed for the tests. Two implementations are built:
// a constant-time portable one (carry-less multiply by masked integer
// multiplications, after BearSSL's ghash_ctmul64) and, on x86 CPUs that have
// it, one using PCLMULQDQ (chosen at run time).
enum class PolyvalImpl { Portable, Pclmul };

// True when this build and this CPU can run the PCLMULQDQ implementation.
bool polyvalPclmulAvailable() noexcept;

// POLYVAL(h, X_1 .. X_n) from a zero state. `blocks` must be a whole number
// of 16-byte blocks; throws std::invalid_argument otherwise, or if `impl` is
// Pclmul and polyvalPclmulAvailable() is false.
void polyval(PolyvalImpl impl, std::span<const std::uint8_t, 16> h,
             std::span<const std::uint8_t> blocks,
             std::span<std::uint8_t, 16> out);

// Test hook: while set, Hctr2 objects constructed afterwards use the portable
// POLYVAL even where PCLMULQDQ is available. Not for production use.
void setForcePortablePolyval(bool force) noexcept;

} // namespace detail

} // namespace rcm
