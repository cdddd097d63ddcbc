#include "codec/frame/Frame.h"

#include <algorithm>
#include <cstring>

namespace rcm {

const std::array<std::uint8_t, kPreambleSize>& preamble()
{
    static const auto bytes = [] {
        std::array<std::uint8_t, kPreambleSize> p{};
        std::fill_n(p.begin(), kPreambleFill, kPreambleFillByte);
        p[kPreambleFill] = kPreambleMark;
        p[kPreambleFill + 1] = kPreambleMark;
        return p;
    }();
    return bytes;
}

void encodeCodewords(const Block& block1, const Block& block2, std::span<std::uint8_t, kDatagramSize> out)
{
    std::uint8_t* cw1 = out.data();
    std::uint8_t* cw2 = out.data() + kCodewordSize;
    std::memcpy(cw1, block1.data(), kBlockSize);
    rs::encode(cw1, cw1 + kBlockSize);
    std::memcpy(cw2, block2.data(), kBlockSize);
    rs::encode(cw2, cw2 + kBlockSize);
}

DatagramBytes makeDatagram(const Block& block1, const Block& block2)
{
    DatagramBytes d;
    encodeCodewords(block1, block2, d);
    return d;
}

FrameBytes makeFrame(const Block& block1, const Block& block2)
{
    FrameBytes f;
    std::copy(preamble().begin(), preamble().end(), f.begin());
    encodeCodewords(block1, block2, std::span<std::uint8_t, kDatagramSize>(f.data() + kPreambleSize, kDatagramSize));
    return f;
}

DecodedBlocks decodeCodewords(std::span<const std::uint8_t, kDatagramSize> codewords)
{
    DecodedBlocks out;
    const std::uint8_t* cw1 = codewords.data();
    const std::uint8_t* cw2 = codewords.data() + kCodewordSize;
    bool clean[2];
    rs::checkCodewords(cw1, cw2, &clean[0], &clean[1]);
    std::uint8_t work[kCodewordSize];
    for (int b = 0; b < 2; ++b) {
        const std::uint8_t* cw = b == 0 ? cw1 : cw2;
        Block& block = b == 0 ? out.block1 : out.block2;
        int& corrected = b == 0 ? out.corrected.block1 : out.corrected.block2;
        if (clean[b]) {
            std::memcpy(block.data(), cw, kBlockSize);
            corrected = 0;
            continue;
        }
        // A failure leaves the codeword, and so the block, as received.
        std::memcpy(work, cw, kCodewordSize);
        corrected = rs::correct(work);
        std::memcpy(block.data(), work, kBlockSize);
    }
    return out;
}

}  // namespace rcm
