#include "codec/secure/Hctr2.h"

#include <openssl/crypto.h>
#include <openssl/evp.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <cstddef>
#include <cstring>
#include <functional>
#include <mutex>
#include <stdexcept>
#include <string>

#if (defined(__x86_64__) || defined(__i386__)) && (defined(__GNUC__) || defined(__clang__))
#define RCM_HCTR2_PCLMUL 1
#include <immintrin.h>
#else
#define RCM_HCTR2_PCLMUL 0
#endif

// Notation follows the HCTR2 paper (ePrint 2021/1441, section 3):
//   h = E_K(bin(0)), L = E_K(bin(1))      (bin(i): 128-bit little-endian i)
//   H_h(T, M) = POLYVAL(h, bin(2|T|+2) || pad(T) || M)          if 16 | |M|
//             = POLYVAL(h, bin(2|T|+3) || pad(T) || M || 1 || 0*) otherwise
//     (|T| in bits, pad(T) = T zero-padded to whole blocks, "1" the byte 0x01)
//   XCTR_K(S)[i] = E_K(S xor bin(i)), i = 1, 2, ...
//   Encrypt P = M || N, |M| = 16:
//     MM = M xor H(T, N); UU = E_K(MM); S = MM xor UU xor L;
//     V = N xor XCTR_K(S); U = UU xor H(T, V); C = U || V.
//
// POLYVAL (RFC 8452) works in GF(2^128) modulo x^128 + x^127 + x^126 + x^121 + 1
// with the little-endian bit order of the block (bit i of the 128-bit
// little-endian integer is the coefficient of x^i), so no bit reflection is
// needed: dot(a, b) = a * b * x^-128, S_j = dot(S_{j-1} xor X_j, h).
// Blocks are folded kPowers at a time with precomputed key powers
// hp[k] = h^(k+1) * x^(-128k), so that one chunk of m blocks costs m
// unreduced products and a single Montgomery reduction:
//   S' = dot(S xor X_1, hp[m-1]) xor dot(X_2, hp[m-2]) xor ... dot(X_m, hp[0]).

namespace rcm {

namespace {

constexpr std::size_t kBlock = 16;
// POLYVAL blocks per reduction: the 13 blocks of the secure link's 207-byte
// message part make one chunk.
constexpr std::size_t kPowers = 16;
constexpr std::size_t kXctrBatch = 16;  // XCTR counter blocks per AES call

std::atomic<bool> g_forcePortable{false};

static_assert(std::endian::native == std::endian::little || std::endian::native == std::endian::big,
              "Hctr2: mixed-endian hosts are not supported");

// Used on big-endian hosts only (below).
[[maybe_unused]] constexpr std::uint64_t bswap64(std::uint64_t v)
{
    v = ((v & 0x00FF00FF00FF00FFu) << 8) | ((v >> 8) & 0x00FF00FF00FF00FFu);
    v = ((v & 0x0000FFFF0000FFFFu) << 16) | ((v >> 16) & 0x0000FFFF0000FFFFu);
    return (v << 32) | (v >> 32);
}

// HCTR2's integers (bin(i), the POLYVAL state) are little-endian. memcpy
// compiles to one unaligned load or store; the swap only exists on
// big-endian hosts.
inline std::uint64_t load64le(const std::uint8_t* p)
{
    std::uint64_t v;
    std::memcpy(&v, p, 8);
    if constexpr (std::endian::native == std::endian::big)
        v = bswap64(v);
    return v;
}

inline void store64le(std::uint8_t* p, std::uint64_t v)
{
    if constexpr (std::endian::native == std::endian::big)
        v = bswap64(v);
    std::memcpy(p, &v, 8);
}

// d = a xor b over n bytes, a word at a time. XOR is bytewise, so byte order
// does not matter here. d may equal a or b.
inline void xorBytes(std::uint8_t* d, const std::uint8_t* a, const std::uint8_t* b,
                     std::size_t n)
{
    std::size_t i = 0;
    for (; i + 8 <= n; i += 8) {
        std::uint64_t x, y;
        std::memcpy(&x, a + i, 8);
        std::memcpy(&y, b + i, 8);
        x ^= y;
        std::memcpy(d + i, &x, 8);
    }
    for (; i < n; ++i)
        d[i] = a[i] ^ b[i];
}

inline void xor16(std::uint8_t* d, const std::uint8_t* a, const std::uint8_t* b)
{
    xorBytes(d, a, b, kBlock);
}

// ---------------------------------------------------------------- POLYVAL key

// One key power: w = {lo, hi, lo ^ hi} (Karatsuba operands) and r = the same
// words bit-reversed (for the high halves in the portable multiply).
struct KeyPower {
    std::uint64_t w[3];
    std::uint64_t r[3];
};

struct PolyKey {
    KeyPower p[kPowers];
};

// ------------------------------------------------- portable, constant time

// Low 64 bits of the carry-less product x * y, from ordinary multiplications
// of operands whose bits are spread out 4 apart ("holes" absorb the carries),
// as in BearSSL's ghash_ctmul64. No branches, no secret-indexed tables.
inline std::uint64_t bmul64(std::uint64_t x, std::uint64_t y)
{
    constexpr std::uint64_t m0 = 0x1111111111111111u;
    constexpr std::uint64_t m1 = 0x2222222222222222u;
    constexpr std::uint64_t m2 = 0x4444444444444444u;
    constexpr std::uint64_t m3 = 0x8888888888888888u;
    const std::uint64_t x0 = x & m0, x1 = x & m1, x2 = x & m2, x3 = x & m3;
    const std::uint64_t y0 = y & m0, y1 = y & m1, y2 = y & m2, y3 = y & m3;
    std::uint64_t z0 = (x0 * y0) ^ (x1 * y3) ^ (x2 * y2) ^ (x3 * y1);
    std::uint64_t z1 = (x0 * y1) ^ (x1 * y0) ^ (x2 * y3) ^ (x3 * y2);
    std::uint64_t z2 = (x0 * y2) ^ (x1 * y1) ^ (x2 * y0) ^ (x3 * y3);
    std::uint64_t z3 = (x0 * y3) ^ (x1 * y2) ^ (x2 * y1) ^ (x3 * y0);
    z0 &= m0;
    z1 &= m1;
    z2 &= m2;
    z3 &= m3;
    return z0 | z1 | z2 | z3;
}

inline std::uint64_t rev64(std::uint64_t x)
{
    x = ((x >> 1) & 0x5555555555555555u) | ((x & 0x5555555555555555u) << 1);
    x = ((x >> 2) & 0x3333333333333333u) | ((x & 0x3333333333333333u) << 2);
    x = ((x >> 4) & 0x0F0F0F0F0F0F0F0Fu) | ((x & 0x0F0F0F0F0F0F0F0Fu) << 4);
    x = ((x >> 8) & 0x00FF00FF00FF00FFu) | ((x & 0x00FF00FF00FF00FFu) << 8);
    x = ((x >> 16) & 0x0000FFFF0000FFFFu) | ((x & 0x0000FFFF0000FFFFu) << 16);
    return (x >> 32) | (x << 32);
}

// Montgomery reduction of the 256-bit product v0..v3 (little-endian words):
// returns v * x^-128 mod P in {s0, s1}. Each step adds v_i * P * x^(64i),
// which clears word i because P = 1 mod x^64.
inline void reduce(std::uint64_t v0, std::uint64_t v1, std::uint64_t v2,
                   std::uint64_t v3, std::uint64_t& s0, std::uint64_t& s1)
{
    v1 ^= (v0 << 63) ^ (v0 << 62) ^ (v0 << 57);
    v2 ^= v0 ^ (v0 >> 1) ^ (v0 >> 2) ^ (v0 >> 7);
    v2 ^= (v1 << 63) ^ (v1 << 62) ^ (v1 << 57);
    v3 ^= v1 ^ (v1 >> 1) ^ (v1 >> 2) ^ (v1 >> 7);
    s0 = v2;
    s1 = v3;
}

// dot(a, b) = a * b * x^-128, straightforward (used for the key powers).
void dotPortable(const std::uint64_t a[2], const std::uint64_t b[2],
                 std::uint64_t out[2])
{
    const std::uint64_t a2 = a[0] ^ a[1], b2 = b[0] ^ b[1];
    const std::uint64_t l0 = bmul64(a[0], b[0]);
    const std::uint64_t l1 = bmul64(a[1], b[1]);
    const std::uint64_t l2 = bmul64(a2, b2);
    const std::uint64_t h0 = rev64(bmul64(rev64(a[0]), rev64(b[0]))) >> 1;
    const std::uint64_t h1 = rev64(bmul64(rev64(a[1]), rev64(b[1]))) >> 1;
    const std::uint64_t h2 = rev64(bmul64(rev64(a2), rev64(b2))) >> 1;
    const std::uint64_t m0 = l2 ^ l0 ^ l1, m1 = h2 ^ h0 ^ h1;
    reduce(l0, h0 ^ m0, l1 ^ m1, h1, out[0], out[1]);
}

void makeKey(const std::uint8_t h[16], PolyKey& k)
{
    std::uint64_t cur[2] = {load64le(h), load64le(h + 8)};
    const std::uint64_t base[2] = {cur[0], cur[1]};
    for (std::size_t i = 0; i < kPowers; ++i) {
        if (i > 0)
            dotPortable(cur, base, cur);
        KeyPower& p = k.p[i];
        p.w[0] = cur[0];
        p.w[1] = cur[1];
        p.w[2] = cur[0] ^ cur[1];
        for (int j = 0; j < 3; ++j)
            p.r[j] = rev64(p.w[j]);
    }
    OPENSSL_cleanse(cur, sizeof cur);
}

// The blocks one POLYVAL call absorbs: three runs of whole blocks, in order,
// any of them empty (the tweak's hash: its length block, its whole blocks,
// its padded last block; a message's: its whole blocks, its padded last
// block), so that nothing is copied to make them contiguous. Where a block
// comes from depends only on lengths, never on secret data.
struct Blocks {
    struct Run {
        const std::uint8_t* p = nullptr;
        std::size_t n = 0;
    };
    Run runs[3];

    std::size_t count() const { return runs[0].n + runs[1].n + runs[2].n; }
};

// Both implementations walk the runs the same way: chunks of at most kPowers
// blocks, counted from the first block across run boundaries; within a chunk
// of m blocks the i-th takes key power m-1-i, the chunk's first block has the
// state folded in, and each chunk ends with one reduction. The inner loops
// run over contiguous blocks, so they carry no per-block bookkeeping.

void polyvalPortable(std::uint64_t st[2], const PolyKey& k, const Blocks& in)
{
    std::uint64_t s0 = st[0], s1 = st[1];
    std::size_t left = in.count(); // blocks not yet absorbed
    std::size_t chunk = 0;         // blocks left in the current chunk
    // Karatsuba: l/r = low halves / bit-reversed high halves of lo*lo, hi*hi
    // and (lo^hi)*(lo^hi), summed over the chunk (the carry-less product is
    // bilinear, so the reversal of the high halves can wait until the end of
    // the chunk).
    std::uint64_t l0 = 0, l1 = 0, l2 = 0, r0 = 0, r1 = 0, r2 = 0;
    for (const Blocks::Run& run : in.runs) {
        const std::uint8_t* p = run.p;
        for (std::size_t n = run.n; n > 0;) {
            if (chunk == 0) {
                chunk = std::min(left, kPowers);
                l0 = l1 = l2 = r0 = r1 = r2 = 0;
            }
            const std::size_t take = std::min(n, chunk);
            for (std::size_t i = 0; i < take; ++i, p += kBlock) {
                const std::uint64_t a0 = load64le(p) ^ s0, a1 = load64le(p + 8) ^ s1;
                s0 = s1 = 0; // only the chunk's first block carries the state
                const KeyPower& hp = k.p[chunk - 1 - i];
                const std::uint64_t ra0 = rev64(a0), ra1 = rev64(a1);
                l0 ^= bmul64(a0, hp.w[0]);
                l1 ^= bmul64(a1, hp.w[1]);
                l2 ^= bmul64(a0 ^ a1, hp.w[2]);
                r0 ^= bmul64(ra0, hp.r[0]);
                r1 ^= bmul64(ra1, hp.r[1]);
                r2 ^= bmul64(ra0 ^ ra1, hp.r[2]);
            }
            n -= take;
            left -= take;
            chunk -= take;
            if (chunk == 0) {
                const std::uint64_t h0 = rev64(r0) >> 1, h1 = rev64(r1) >> 1,
                                    h2 = rev64(r2) >> 1;
                const std::uint64_t m0 = l2 ^ l0 ^ l1, m1 = h2 ^ h0 ^ h1;
                reduce(l0, h0 ^ m0, l1 ^ m1, h1, s0, s1);
            }
        }
    }
    st[0] = s0;
    st[1] = s1;
}

// ------------------------------------------------------------- PCLMULQDQ

#if RCM_HCTR2_PCLMUL
// x86 is little-endian, so st[] and the key words load straight into lanes.
__attribute__((target("pclmul,sse4.1")))
void polyvalPclmul(std::uint64_t st[2], const PolyKey& k, const Blocks& in)
{
    // x^57 + x^62 + x^63: the low part of P above x^0, shifted down by 64.
    const __m128i poly = _mm_set_epi64x(0, static_cast<long long>(0xC200000000000000u));
    const __m128i zero = _mm_setzero_si128();
    __m128i s = _mm_loadu_si128(reinterpret_cast<const __m128i*>(st));
    std::size_t left = in.count();
    std::size_t chunk = 0;
    // Karatsuba, as in the portable code: three products per block, the
    // middle term corrected once per chunk.
    __m128i lo = zero, mid = zero, hi = zero;
    for (const Blocks::Run& run : in.runs) {
        const std::uint8_t* p = run.p;
        for (std::size_t n = run.n; n > 0;) {
            if (chunk == 0) {
                chunk = std::min(left, kPowers);
                lo = mid = hi = zero;
            }
            const std::size_t take = std::min(n, chunk);
            for (std::size_t i = 0; i < take; ++i, p += kBlock) {
                const __m128i x = _mm_xor_si128(
                    _mm_loadu_si128(reinterpret_cast<const __m128i*>(p)), s);
                s = zero;
                const std::uint64_t* w = k.p[chunk - 1 - i].w;
                const __m128i hk = _mm_loadu_si128(reinterpret_cast<const __m128i*>(w));
                const __m128i hm = _mm_loadl_epi64(reinterpret_cast<const __m128i*>(w + 2));
                const __m128i xm = _mm_xor_si128(x, _mm_shuffle_epi32(x, 0x4E));
                lo = _mm_xor_si128(lo, _mm_clmulepi64_si128(x, hk, 0x00));
                hi = _mm_xor_si128(hi, _mm_clmulepi64_si128(x, hk, 0x11));
                mid = _mm_xor_si128(mid, _mm_clmulepi64_si128(xm, hm, 0x00));
            }
            n -= take;
            left -= take;
            chunk -= take;
            if (chunk == 0) {
                mid = _mm_xor_si128(mid, _mm_xor_si128(lo, hi));
                lo = _mm_xor_si128(lo, _mm_slli_si128(mid, 8));
                hi = _mm_xor_si128(hi, _mm_srli_si128(mid, 8));
                // Montgomery reduction, the same two steps as reduce() above.
                __m128i t = _mm_clmulepi64_si128(lo, poly, 0x00);
                lo = _mm_xor_si128(_mm_shuffle_epi32(lo, 0x4E), t);
                t = _mm_clmulepi64_si128(lo, poly, 0x00);
                lo = _mm_xor_si128(_mm_shuffle_epi32(lo, 0x4E), t);
                s = _mm_xor_si128(hi, lo);
            }
        }
    }
    _mm_storeu_si128(reinterpret_cast<__m128i*>(st), s);
}

bool cpuHasPclmul() noexcept
{
    static const bool has = [] {
        __builtin_cpu_init();
        return __builtin_cpu_supports("pclmul") && __builtin_cpu_supports("sse4.1");
    }();
    return has;
}
#else
bool cpuHasPclmul() noexcept { return false; }
#endif

using PolyvalFn = void (*)(std::uint64_t*, const PolyKey&, const Blocks&);

PolyvalFn pickPolyval(bool pclmul)
{
#if RCM_HCTR2_PCLMUL
    if (pclmul)
        return &polyvalPclmul;
#else
    (void)pclmul;
#endif
    return &polyvalPortable;
}

// ------------------------------------------------------------------ OpenSSL

struct CtxFree {
    void operator()(EVP_CIPHER_CTX* c) const noexcept { EVP_CIPHER_CTX_free(c); }
};
using CtxPtr = std::unique_ptr<EVP_CIPHER_CTX, CtxFree>;

struct CipherFree {
    void operator()(EVP_CIPHER* c) const noexcept { EVP_CIPHER_free(c); }
};

[[noreturn]] void throwOpenSsl(const char* what)
{
    throw std::runtime_error(std::string("Hctr2: OpenSSL ") + what + " failed");
}

void checkArgs(std::span<const std::uint8_t> in, std::span<std::uint8_t> out,
               const char* op)
{
    if (in.size() < kBlock)
        throw std::invalid_argument(std::string("Hctr2::") + op
            + ": message must be at least 16 bytes, got " + std::to_string(in.size()));
    if (out.size() != in.size())
        throw std::invalid_argument(std::string("Hctr2::") + op
            + ": output size " + std::to_string(out.size())
            + " differs from input size " + std::to_string(in.size()));
    const std::less<const std::uint8_t*> lt;
    const std::uint8_t* i0 = in.data();
    const std::uint8_t* o0 = out.data();
    if (i0 != o0 && lt(i0, o0 + out.size()) && lt(o0, i0 + in.size()))
        throw std::invalid_argument(std::string("Hctr2::") + op
            + ": input and output overlap without being the same buffer");
}

} // namespace

// ====================================================================== Hctr2

// What one call derives from the message and the key: kept together on the
// stack so that a single wipe covers it, also when OpenSSL throws midway.
// Left uninitialised: every byte is written before it is read.
struct Scratch {
    std::uint8_t a[kBlock], b[kBlock], s[kBlock];
    std::uint8_t pad[kBlock];                // a partial last block, padded
    std::uint8_t ks[kXctrBatch * kBlock];    // XCTR keystream
    std::uint64_t st[2];                     // POLYVAL state
    std::uint64_t tweakState[2];

    Scratch() = default;
    Scratch(const Scratch&) = delete;
    Scratch& operator=(const Scratch&) = delete;
    ~Scratch() { OPENSSL_cleanse(this, sizeof *this); }
};

struct Hctr2::Impl {
    PolyKey key{};
    std::uint8_t l[kBlock] = {}; // L = E_K(bin(1))
    PolyvalFn polyval = nullptr;
    CtxPtr enc;
    CtxPtr dec;
    std::mutex mutex;

    ~Impl()
    {
        OPENSSL_cleanse(&key, sizeof key);
        OPENSSL_cleanse(l, sizeof l);
        // EVP_CIPHER_CTX_free (via CtxPtr) wipes the AES key schedules.
    }

    // AES-ECB over whole blocks; in and out may be the same buffer. The
    // contexts are keyed once in the constructor, so this is only the update.
    void ecb(EVP_CIPHER_CTX* ctx, bool encrypt, const std::uint8_t* in,
             std::uint8_t* out, std::size_t len)
    {
        int outl = 0;
        const int ok = encrypt
            ? EVP_EncryptUpdate(ctx, out, &outl, in, static_cast<int>(len))
            : EVP_DecryptUpdate(ctx, out, &outl, in, static_cast<int>(len));
        if (ok != 1 || outl != static_cast<int>(len))
            throwOpenSsl(encrypt ? "AES encrypt" : "AES decrypt");
    }

    // st = state after bin(2|T| + 2 + partial) || pad(T), in one POLYVAL call
    // so that short tweaks cost a single reduction.
    void hashTweak(std::span<const std::uint8_t> tweak, bool partial,
                   std::uint64_t st[2], Scratch& sc) const
    {
        std::uint8_t lenBlock[kBlock] = {};
        const std::uint64_t bits = static_cast<std::uint64_t>(tweak.size()) * 8u;
        store64le(lenBlock, 2u * bits + 2u + (partial ? 1u : 0u));
        const std::size_t full = tweak.size() / kBlock, rem = tweak.size() % kBlock;
        Blocks in{{{lenBlock, 1}, {tweak.data(), full}, {sc.pad, 0}}};
        if (rem) {
            std::memset(sc.pad, 0, kBlock);
            std::memcpy(sc.pad, tweak.data() + full * kBlock, rem);
            in.runs[2].n = 1;
        }
        st[0] = st[1] = 0;
        polyval(st, key, in);
    }

    // out = block xor H(T, msg), H continued from the tweak state.
    void hashMessage(const std::uint64_t tweakState[2], const std::uint8_t* msg,
                     std::size_t len, const std::uint8_t* block, std::uint8_t* out,
                     Scratch& sc) const
    {
        sc.st[0] = tweakState[0];
        sc.st[1] = tweakState[1];
        const std::size_t full = len / kBlock, rem = len % kBlock;
        Blocks in{{{msg, full}, {sc.pad, 0}, {}}};
        if (rem) {
            std::memset(sc.pad, 0, kBlock);
            std::memcpy(sc.pad, msg + full * kBlock, rem);
            sc.pad[rem] = 0x01;
            in.runs[1].n = 1;
        }
        polyval(sc.st, key, in);
        store64le(out, load64le(block) ^ sc.st[0]);
        store64le(out + 8, load64le(block + 8) ^ sc.st[1]);
    }

    // out = in xor XCTR_K(s); in and out may be the same buffer. bin(i) only
    // touches the low 8 bytes of S for any i a message can reach.
    void xctr(const std::uint8_t s[kBlock], const std::uint8_t* in,
              std::uint8_t* out, std::size_t len, Scratch& sc)
    {
        const std::uint64_t s0 = load64le(s);
        std::uint64_t ctr = 1;
        std::size_t off = 0;
        while (off < len) {
            const std::size_t nb = std::min(kXctrBatch, (len - off + kBlock - 1) / kBlock);
            for (std::size_t b = 0; b < nb; ++b, ++ctr) {
                store64le(sc.ks + b * kBlock, s0 ^ ctr);
                std::memcpy(sc.ks + b * kBlock + 8, s + 8, 8);
            }
            ecb(enc.get(), true, sc.ks, sc.ks, nb * kBlock);
            const std::size_t n = std::min(len - off, nb * kBlock);
            xorBytes(out + off, in + off, sc.ks, n);
            off += n;
        }
    }

    // The two halves of HCTR2 are the same shape; `forward` selects E or D.
    //   forward:  first = M,  rest = N;  MM = M ^ H(N), UU = E(MM), ...
    //   backward: first = U,  rest = V;  UU = U ^ H(V), MM = D(UU), ...
    // In-place works: in's first block is read (first hash) before out's
    // first block is written (last step), and XCTR reads each byte of the
    // rest before writing it.
    // op names the public call in the errors thrown; the lock keeps calls
    // from different threads off the shared contexts.
    void run(bool forward, const char* op, std::span<const std::uint8_t> tweak,
             std::span<const std::uint8_t> in, std::span<std::uint8_t> out)
    {
        checkArgs(in, out, op);
        const std::lock_guard<std::mutex> lock(mutex);
        Scratch sc;
        const std::size_t restLen = in.size() - kBlock;
        hashTweak(tweak, restLen % kBlock != 0, sc.tweakState, sc);
        // a = first ^ H(T, rest_in); b = E(a) or D(a)
        hashMessage(sc.tweakState, in.data() + kBlock, restLen, in.data(), sc.a, sc);
        ecb(forward ? enc.get() : dec.get(), forward, sc.a, sc.b, kBlock);
        // S = MM ^ UU ^ L (symmetric in a and b)
        xor16(sc.s, sc.a, sc.b);
        xor16(sc.s, sc.s, l);
        xctr(sc.s, in.data() + kBlock, out.data() + kBlock, restLen, sc);
        // first_out = b ^ H(T, rest_out)
        hashMessage(sc.tweakState, out.data() + kBlock, restLen, sc.b, out.data(), sc);
    }
};


Hctr2::Hctr2(std::span<const std::uint8_t> key)
{
    if (key.size() != 16 && key.size() != 32)
        throw std::invalid_argument("Hctr2: key must be 16 or 32 bytes (AES-128 or AES-256), got "
                                    + std::to_string(key.size()));
    auto d = std::make_unique<Impl>();

    std::unique_ptr<EVP_CIPHER, CipherFree> cipher(
        EVP_CIPHER_fetch(nullptr, key.size() == 16 ? "AES-128-ECB" : "AES-256-ECB", nullptr));
    if (!cipher)
        throwOpenSsl("EVP_CIPHER_fetch");
    d->enc.reset(EVP_CIPHER_CTX_new());
    d->dec.reset(EVP_CIPHER_CTX_new());
    if (!d->enc || !d->dec)
        throwOpenSsl("EVP_CIPHER_CTX_new");
    if (EVP_EncryptInit_ex2(d->enc.get(), cipher.get(), key.data(), nullptr, nullptr) != 1
        || EVP_CIPHER_CTX_set_padding(d->enc.get(), 0) != 1)
        throwOpenSsl("AES encrypt init");
    if (EVP_DecryptInit_ex2(d->dec.get(), cipher.get(), key.data(), nullptr, nullptr) != 1
        || EVP_CIPHER_CTX_set_padding(d->dec.get(), 0) != 1)
        throwOpenSsl("AES decrypt init");

    // h = E_K(bin(0)), L = E_K(bin(1)), encrypted together.
    std::uint8_t hl[2 * kBlock] = {};
    hl[kBlock] = 0x01;
    d->ecb(d->enc.get(), true, hl, hl, sizeof hl);
    makeKey(hl, d->key);
    std::memcpy(d->l, hl + kBlock, kBlock);
    OPENSSL_cleanse(hl, sizeof hl);

    d->polyval = pickPolyval(cpuHasPclmul() && !g_forcePortable.load());
    d_ = std::move(d);
}

Hctr2::~Hctr2() = default;

void Hctr2::encrypt(std::span<const std::uint8_t> tweak,
                    std::span<const std::uint8_t> in,
                    std::span<std::uint8_t> out) const
{
    d_->run(true, "encrypt", tweak, in, out);
}

void Hctr2::decrypt(std::span<const std::uint8_t> tweak,
                    std::span<const std::uint8_t> in,
                    std::span<std::uint8_t> out) const
{
    d_->run(false, "decrypt", tweak, in, out);
}

// ===================================================================== detail

namespace detail {

bool polyvalPclmulAvailable() noexcept { return cpuHasPclmul(); }

void polyval(PolyvalImpl impl, std::span<const std::uint8_t, 16> h,
             std::span<const std::uint8_t> blocks,
             std::span<std::uint8_t, 16> out)
{
    if (blocks.size() % kBlock != 0)
        throw std::invalid_argument("polyval: input must be whole 16-byte blocks");
    if (impl == PolyvalImpl::Pclmul && !cpuHasPclmul())
        throw std::invalid_argument("polyval: PCLMULQDQ is not available");
    PolyKey key;
    makeKey(h.data(), key);
    std::uint64_t st[2] = {0, 0};
    const std::size_t n = blocks.size() / kBlock;
    if (n)
        pickPolyval(impl == PolyvalImpl::Pclmul)(st, key, Blocks{{{blocks.data(), n}, {}, {}}});
    store64le(out.data(), st[0]);
    store64le(out.data() + 8, st[1]);
    OPENSSL_cleanse(&key, sizeof key);
}

void setForcePortablePolyval(bool force) noexcept { g_forcePortable.store(force); }

} // namespace detail

} // namespace rcm
