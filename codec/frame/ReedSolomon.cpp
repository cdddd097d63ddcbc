#include "codec/frame/ReedSolomon.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <vector>

// fec.h has no extern "C" guard and puts names like UNKNOWN and parity in the
// global namespace: include it here and nowhere else.
extern "C" {
#include <fec.h>
}

namespace rcm::rs {
namespace {

// A byte-at-a-time LFSR over the conventional basis. T[f] is the parity
// register after feeding one byte with feedback f into an all-zero register;
// libfec's own encoder produces it, so the check cannot drift from libfec's code.
// The 32-byte register is held big-endian in four 64-bit words: word 0's top
// byte is parity byte 0.
struct ParityTable {
    std::array<std::array<std::uint64_t, 4>, 256> t{};
    std::array<std::uint8_t, 256> dualToConv{};
    std::array<std::uint8_t, 256> convToDual{};
    ParityTable()
    {
        for (int f = 0; f < 256; ++f) {
            unsigned char data = static_cast<unsigned char>(f);
            unsigned char parity[kParitySize];
            encode_rs_8(&data, parity, static_cast<int>(kDataSize) - 1);
            for (int w = 0; w < 4; ++w) {
                std::uint64_t word = 0;
                for (int b = 0; b < 8; ++b)
                    word = (word << 8) | parity[w * 8 + b];
                t[f][w] = word;
            }
            dualToConv[f] = Tal1tab[f];
            convToDual[f] = Taltab[f];
        }
    }
};

const ParityTable& table()
{
    static const ParityTable instance;
    return instance;
}

}  // namespace

namespace {

// The parity register after the data bytes, conventional basis, big-endian
// words. Feeding byte i needs the register after byte i-1: a chain of
// dependent loads. Two codewords go through together so that their two chains
// overlap in the processor.
struct Register {
    std::uint64_t r0 = 0, r1 = 0, r2 = 0, r3 = 0;
    void feed(const ParityTable& tab, std::uint8_t dualByte)
    {
        const unsigned fb = tab.dualToConv[dualByte] ^ static_cast<unsigned>(r0 >> 56);
        const auto& row = tab.t[fb];
        r0 = ((r0 << 8) | (r1 >> 56)) ^ row[0];
        r1 = ((r1 << 8) | (r2 >> 56)) ^ row[1];
        r2 = ((r2 << 8) | (r3 >> 56)) ^ row[2];
        r3 = (r3 << 8) ^ row[3];
    }
    // The register after the data bytes of `word` (dual basis).
    static Register after(const ParityTable& tab, const std::uint8_t* word)
    {
        Register reg;
        for (std::size_t i = 0; i < kDataSize; ++i)
            reg.feed(tab, word[i]);
        return reg;
    }
    // Parity byte k (0 .. 31) in the conventional basis, coefficient of x^(31-k).
    std::uint8_t parityByte(std::size_t k) const
    {
        const std::uint64_t regs[4] = {r0, r1, r2, r3};
        return static_cast<std::uint8_t>(regs[k / 8] >> (56 - 8 * (k % 8)));
    }
    // Compare in the conventional basis: convert the received parity.
    bool matches(const ParityTable& tab, const std::uint8_t* parity) const
    {
        const std::uint64_t regs[4] = {r0, r1, r2, r3};
        for (int w = 0; w < 4; ++w) {
            std::uint64_t word = 0;
            for (int b = 0; b < 8; ++b)
                word = (word << 8) | tab.dualToConv[parity[w * 8 + b]];
            if (word != regs[w])
                return false;
        }
        return true;
    }
};

}  // namespace

namespace {

// GF(2^8) of the CCSDS code in the conventional basis: field polynomial
// x^8+x^7+x^2+x+1, alpha = x; roots of the generator alpha^(11 (112 + i)),
// i = 0 .. 31. Log/antilog tables as libfec keeps them (kA0: log of 0).
constexpr int kA0 = 255;
constexpr int kFirstRoot = 112;
constexpr int kPrimitive = 11;
constexpr int kInversePrimitive = 116;  // 11 * 116 = 1 modulo 255
constexpr int kRoots = static_cast<int>(kParitySize);

struct Field {
    std::array<std::uint8_t, 256> alphaTo{};
    std::array<std::uint8_t, 256> indexOf{};
    // times[i][v]: v times the generator's root i; the syndromes' Horner steps.
    std::array<std::array<std::uint8_t, 256>, kParitySize> times{};
    Field()
    {
        unsigned x = 1;
        for (int i = 0; i < 255; ++i) {
            alphaTo[static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(x);
            indexOf[x] = static_cast<std::uint8_t>(i);
            x <<= 1;
            if (x & 0x100)
                x ^= 0x187;
        }
        alphaTo[255] = 0;
        indexOf[0] = kA0;
        for (int i = 0; i < static_cast<int>(kParitySize); ++i) {
            const int rootLog = ((kFirstRoot + i) * kPrimitive) % 255;
            for (int v = 1; v < 256; ++v)
                times[static_cast<std::size_t>(i)][static_cast<std::size_t>(v)] =
                    alphaTo[static_cast<std::size_t>((indexOf[static_cast<std::size_t>(v)] + rootLog) % 255)];
        }
    }
};

const Field& field()
{
    static const Field instance;
    return instance;
}

// x modulo 255 for x >= 0, as libfec computes it: no division.
inline int modnn(int x)
{
    while (x >= 255) {
        x -= 255;
        x = (x >> 8) + (x & 255);
    }
    return x;
}

// The syndromes (log form): the remainder's values at the generator's roots;
// false when all are 0.
bool syndromes(const Field& gf, const std::uint8_t* remainder, int* s)
{
    bool nonzero = false;
    for (int i = 0; i < kRoots; ++i) {
        const auto& times = gf.times[static_cast<std::size_t>(i)];
        unsigned v = 0;
        for (int k = 0; k < kRoots; ++k)
            v = times[v] ^ remainder[k];
        nonzero = nonzero || v != 0;
        s[i] = gf.indexOf[v];
    }
    return nonzero;
}

// Berlekamp-Massey: the error locator polynomial from the syndromes.
// `lambda` holds the locator of the `erasures` erased places already (1
// without erasures); as libfec's decode_rs with erasures, the iteration then
// starts after them.
void errorLocator(const Field& gf, const int* s, std::uint8_t* lambda, int erasures = 0)
{
    const auto& alphaTo = gf.alphaTo;
    const auto& indexOf = gf.indexOf;
    int b[kRoots + 1];
    int t[kRoots + 1];
    for (int i = 0; i <= kRoots; ++i)
        b[i] = indexOf[lambda[i]];
    int el = erasures;
    for (int r = erasures + 1; r <= kRoots; ++r) {
        unsigned discr = 0;
        for (int i = 0; i < r; ++i)
            if (lambda[i] != 0 && s[r - i - 1] != kA0)
                discr ^= alphaTo[static_cast<std::size_t>(modnn(indexOf[lambda[i]] + s[r - i - 1]))];
        const int discrLog = indexOf[discr];
        if (discrLog == kA0) {
            std::memmove(&b[1], b, kRoots * sizeof b[0]);
            b[0] = kA0;
            continue;
        }
        t[0] = lambda[0];
        for (int i = 0; i < kRoots; ++i)
            t[i + 1] = b[i] != kA0 ? lambda[i + 1] ^ alphaTo[static_cast<std::size_t>(modnn(discrLog + b[i]))]
                                   : lambda[i + 1];
        if (2 * el <= r + erasures - 1) {
            el = r + erasures - el;
            for (int i = 0; i <= kRoots; ++i)
                b[i] = lambda[i] == 0 ? kA0 : modnn(indexOf[lambda[i]] - discrLog + 255);
        } else {
            std::memmove(&b[1], b, kRoots * sizeof b[0]);
            b[0] = kA0;
        }
        for (int i = 0; i <= kRoots; ++i)
            lambda[i] = static_cast<std::uint8_t>(t[i]);
    }
}

// The locator in log form; returns its degree.
int toLogForm(const Field& gf, const std::uint8_t* lambda, int* lambdaLog)
{
    int degree = 0;
    for (int i = 0; i <= kRoots; ++i) {
        lambdaLog[i] = gf.indexOf[lambda[i]];
        if (lambdaLog[i] != kA0)
            degree = i;
    }
    return degree;
}

// Chien search: the roots of the error locator (`root`) and the error
// positions they stand for (`loc`); returns how many were found.
int chienSearch(const Field& gf, const int* lambdaLog, int degLambda, int* root, int* loc)
{
    int reg[kRoots + 1];
    std::memcpy(&reg[1], &lambdaLog[1], kRoots * sizeof reg[0]);
    int count = 0;
    for (int i = 1, k = kInversePrimitive - 1; i <= 255; ++i, k = modnn(k + kInversePrimitive)) {
        unsigned q = 1;
        for (int j = degLambda; j > 0; --j) {
            if (reg[j] != kA0) {
                const int next = reg[j] + j;
                reg[j] = next >= 255 ? next - 255 : next;
                q ^= gf.alphaTo[static_cast<std::size_t>(reg[j])];
            }
        }
        if (q != 0)
            continue;
        root[count] = i;
        loc[count] = k;
        if (++count == degLambda)
            break;
    }
    return count;
}

// Forney: the error values at the `count` positions found, applied to `word`
// (dual basis).
void correctErrors(const Field& gf, const int* s, const int* lambdaLog, int degLambda, const int* root, const int* loc,
                   int count, std::uint8_t* word)
{
    const auto& alphaTo = gf.alphaTo;
    const auto& indexOf = gf.indexOf;
    const int degOmega = degLambda - 1;
    int omega[kRoots + 1];
    for (int i = 0; i <= degOmega; ++i) {
        unsigned tmp = 0;
        for (int j = i; j >= 0; --j)
            if (s[i - j] != kA0 && lambdaLog[j] != kA0)
                tmp ^= alphaTo[static_cast<std::size_t>(modnn(s[i - j] + lambdaLog[j]))];
        omega[i] = indexOf[tmp];
    }
    const ParityTable& tab = table();
    for (int j = count - 1; j >= 0; --j) {
        unsigned num1 = 0;
        for (int i = degOmega; i >= 0; --i)
            if (omega[i] != kA0)
                num1 ^= alphaTo[static_cast<std::size_t>(modnn(omega[i] + i * root[j]))];
        const unsigned num2 = alphaTo[static_cast<std::size_t>(modnn(root[j] * (kFirstRoot - 1) + 255))];
        unsigned den = 0;
        for (int i = std::min(degLambda, kRoots - 1) & ~1; i >= 0; i -= 2)
            if (lambdaLog[i + 1] != kA0)
                den ^= alphaTo[static_cast<std::size_t>(modnn(lambdaLog[i + 1] + i * root[j]))];
        if (num1 != 0) {
            const unsigned error =
                alphaTo[static_cast<std::size_t>(modnn(indexOf[num1] + indexOf[num2] + 255 - indexOf[den]))];
            std::uint8_t& byte = word[loc[j]];
            byte = tab.convToDual[static_cast<std::uint8_t>(tab.dualToConv[byte] ^ error)];
        }
    }
}

// The erasure locator of the places `at` (codeword indices): the product of
// (1 + X alpha^(11 (254 - place))), libfec's initial lambda.
void erasureLocator(const Field& gf, const int* at, int count, std::uint8_t* lambda)
{
    lambda[1] = gf.alphaTo[static_cast<std::size_t>(modnn(kPrimitive * (254 - at[0])))];
    for (int i = 1; i < count; ++i) {
        const int u = modnn(kPrimitive * (254 - at[i]));
        for (int j = i + 1; j > 0; --j) {
            const int t = gf.indexOf[lambda[j - 1]];
            if (t != kA0)
                lambda[j] ^= gf.alphaTo[static_cast<std::size_t>(modnn(u + t))];
        }
    }
}

// libfec's decode_rs (decode_rs.h; with eras_pos when `count` places are
// erased) from the remainder of the word modulo the generator instead of
// from the word itself: the syndromes are the remainder's values at the
// generator's roots, 32 coefficients instead of 255. `remainder[k]` is the
// coefficient of x^(31-k), conventional basis; `word` is corrected in place,
// dual basis. The same steps as libfec's (Berlekamp-Massey, Chien search,
// Forney), so the same result; `maxErrors` (errors at unknown places) stops
// before the Chien search when the error locator already says more.
int correctWithErasures(std::uint8_t* word, const std::uint8_t* remainder, const int* erasures, int count,
                        int maxErrors)
{
    const Field& gf = field();
    int s[kRoots];
    if (!syndromes(gf, remainder, s))
        return 0;
    std::uint8_t lambda[kRoots + 1] = {1};
    if (count > 0)
        erasureLocator(gf, erasures, count, lambda);
    errorLocator(gf, s, lambda, count);
    int lambdaLog[kRoots + 1];
    const int degLambda = toLogForm(gf, lambda, lambdaLog);
    if (degLambda - count > maxErrors)
        return -1;
    int root[kRoots];
    int loc[kRoots];
    const int found = chienSearch(gf, lambdaLog, degLambda, root, loc);
    if (degLambda != found)
        return -1;
    // Beyond reach, the locator can lose an erased place among its roots:
    // then the word found is not within the erasures and e errors.
    for (int i = 0; i < count; ++i)
        if (std::find(loc, loc + found, erasures[i]) == loc + found)
            return -1;
    correctErrors(gf, s, lambdaLog, degLambda, root, loc, found, word);
    return found;
}

// Errors only.
int correctFromRemainder(std::uint8_t* word, const std::uint8_t* remainder, int maxErrors)
{
    return correctWithErasures(word, remainder, nullptr, 0, maxErrors);
}

// correctFromRemainder on a copy: `word` is left as received when it fails.
int correctUnlessFailed(std::uint8_t* word, const std::uint8_t* remainder, int maxErrors)
{
    std::uint8_t copy[kCodewordSize];
    std::memcpy(copy, word, kCodewordSize);
    const int corrected = correctFromRemainder(copy, remainder, maxErrors);
    if (corrected > 0)
        std::memcpy(word, copy, kCodewordSize);
    return corrected;
}

// The remainder of a word (dual basis) modulo the generator, conventional
// basis, coefficient of x^31 first; false when it is 0 (a codeword).
bool remainderOf(const std::uint8_t* word, std::uint8_t* remainder)
{
    const ParityTable& tab = table();
    const Register reg = Register::after(tab, word);
    std::uint8_t any = 0;
    for (std::size_t k = 0; k < kParitySize; ++k) {
        remainder[k] = reg.parityByte(k) ^ tab.dualToConv[word[kDataSize + k]];
        any |= remainder[k];
    }
    return any != 0;
}

}  // namespace

// The table-driven register, several times faster than libfec's
// encode_rs_ccsds (which tst_codec compares it with): a trial decoder
// encodes thousands of candidate predictions for one frame.
void encode(const std::uint8_t* data, std::uint8_t* parity)
{
    const ParityTable& tab = table();
    const Register reg = Register::after(tab, data);
    for (std::size_t k = 0; k < kParitySize; ++k)
        parity[k] = tab.convToDual[reg.parityByte(k)];
}

void encodeLibfec(const std::uint8_t* data, std::uint8_t* parity)
{
    encode_rs_ccsds(const_cast<unsigned char*>(data), parity, 0);
}

bool isCodeword(const std::uint8_t* codeword)
{
    const ParityTable& tab = table();
    return Register::after(tab, codeword).matches(tab, codeword + kDataSize);
}

void checkCodewords(const std::uint8_t* a, const std::uint8_t* b, bool* aClean, bool* bClean)
{
    const ParityTable& tab = table();
    Register ra, rb;
    for (std::size_t i = 0; i < kDataSize; ++i) {
        ra.feed(tab, a[i]);
        rb.feed(tab, b[i]);
    }
    *aClean = ra.matches(tab, a + kDataSize);
    *bClean = rb.matches(tab, b + kDataSize);
}

int correct(std::uint8_t* codeword)
{
    unsigned char copy[kCodewordSize];
    std::memcpy(copy, codeword, kCodewordSize);
    const int corrected = decode_rs_ccsds(copy, nullptr, 0, 0);
    if (corrected < 0)
        return -1;
    std::memcpy(codeword, copy, kCodewordSize);
    return corrected;
}

int decode(std::uint8_t* codeword)
{
    return decodeWithin(codeword, kRoots);
}

int decodeWithin(std::uint8_t* codeword, int maxErrors)
{
    std::uint8_t remainder[kParitySize];
    if (!remainderOf(codeword, remainder))
        return 0;
    return correctUnlessFailed(codeword, remainder, maxErrors);
}

int decodeWithParity(std::uint8_t* word, const std::uint8_t* codewordParity, int maxErrors)
{
    const ParityTable& tab = table();
    std::uint8_t remainder[kParitySize];
    std::uint8_t any = 0;
    for (std::size_t k = 0; k < kParitySize; ++k) {
        remainder[k] = tab.dualToConv[word[kDataSize + k]] ^ tab.dualToConv[codewordParity[k]];
        any |= remainder[k];
    }
    if (!any)
        return 0;
    return correctUnlessFailed(word, remainder, maxErrors);
}

int decodeWithErasures(std::uint8_t* codeword, const int* erasures, int count)
{
    if (count < 0 || count > kRoots)
        return -1;
    std::uint8_t remainder[kParitySize];
    if (!remainderOf(codeword, remainder))
        return 0;
    std::uint8_t copy[kCodewordSize];
    std::memcpy(copy, codeword, kCodewordSize);
    // Beyond 2 e + f <= 32 the locator cannot be right, so at most
    // (32 - f) / 2 errors beside the erasures; beyond reach it may still split
    // into roots whose values do not make a codeword: the result is checked.
    if (correctWithErasures(copy, remainder, erasures, count, (kRoots - count) / 2) < 0 || !isCodeword(copy))
        return -1;
    // Bytes changed: an erased place may have been right (libfec counts so too).
    int changed = 0;
    for (std::size_t i = 0; i < kCodewordSize; ++i)
        changed += copy[i] != codeword[i];
    std::memcpy(codeword, copy, kCodewordSize);
    return changed;
}

int decodeLibfec(std::uint8_t* codeword)
{
    return decode_rs_ccsds(codeword, nullptr, 0, 0);
}

int decodeLibfecWithErasures(std::uint8_t* codeword, const int* erasures, int count)
{
    std::vector<int> places(erasures, erasures + count);  // libfec writes its roots' places into it
    places.resize(kParitySize);
    return decode_rs_ccsds(codeword, places.data(), count, 0);
}

}  // namespace rcm::rs
