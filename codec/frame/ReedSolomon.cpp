#include "codec/frame/ReedSolomon.h"

#include <array>
#include <cstring>

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

// The table-driven register, several times faster than libfec's
// encode_rs_ccsds (which tst_codec compares it with): a trial decoder
// encodes thousands of candidate predictions for one frame.
void encode(const std::uint8_t* data, std::uint8_t* parity)
{
    const ParityTable& tab = table();
    Register reg;
    for (std::size_t i = 0; i < kDataSize; ++i)
        reg.feed(tab, data[i]);
    const std::uint64_t regs[4] = {reg.r0, reg.r1, reg.r2, reg.r3};
    for (int w = 0; w < 4; ++w)
        for (int b = 0; b < 8; ++b)
            parity[w * 8 + b] = tab.convToDual[static_cast<std::uint8_t>(regs[w] >> (56 - 8 * b))];
}

void encodeLibfec(const std::uint8_t* data, std::uint8_t* parity)
{
    encode_rs_ccsds(const_cast<unsigned char*>(data), parity, 0);
}

bool isCodeword(const std::uint8_t* codeword)
{
    const ParityTable& tab = table();
    Register reg;
    for (std::size_t i = 0; i < kDataSize; ++i)
        reg.feed(tab, codeword[i]);
    return reg.matches(tab, codeword + kDataSize);
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
    return isCodeword(codeword) ? 0 : correct(codeword);
}

int decodeLibfec(std::uint8_t* codeword)
{
    return decode_rs_ccsds(codeword, nullptr, 0, 0);
}

}  // namespace rcm::rs
