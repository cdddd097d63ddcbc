// The 600-byte frame and the 510-byte datagram around the two data blocks.
#pragma once

#include "codec/frame/ReedSolomon.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

namespace rcm {

inline constexpr std::size_t kPreambleSize = 90;           // 88 x 55, 0F 0F
inline constexpr std::size_t kPreambleFill = 88;
inline constexpr std::uint8_t kPreambleFillByte = 0x55;
inline constexpr std::uint8_t kPreambleMark = 0x0F;
inline constexpr std::size_t kBlockSize = rs::kDataSize;        // 223
inline constexpr std::size_t kCodewordSize = rs::kCodewordSize; // 255
inline constexpr std::size_t kDatagramSize = 2 * kCodewordSize; // 510
inline constexpr std::size_t kFrameSize = kPreambleSize + kDatagramSize; // 600

using Block = std::array<std::uint8_t, kBlockSize>;
using FrameBytes = std::array<std::uint8_t, kFrameSize>;
using DatagramBytes = std::array<std::uint8_t, kDatagramSize>;

const std::array<std::uint8_t, kPreambleSize>& preamble();

// Encodes both blocks with RS(255,223) into the two codewords (510 bytes).
void encodeCodewords(const Block& block1, const Block& block2, std::span<std::uint8_t, kDatagramSize> out);
DatagramBytes makeDatagram(const Block& block1, const Block& block2);
FrameBytes makeFrame(const Block& block1, const Block& block2);

// Bytes Reed-Solomon corrected in each codeword of a frame, -1 where a
// codeword was beyond correction: the one type for these counts, from the
// decoder through the receive path to what the link says of each frame.
struct Corrections {
    int block1 = 0;
    int block2 = 0;
    bool ok() const { return block1 >= 0 && block2 >= 0; }
    friend bool operator==(const Corrections&, const Corrections&) = default;
};

// Both blocks after RS decoding. A block whose codeword was beyond correction
// holds the received data bytes as they were.
struct DecodedBlocks {
    Block block1{};
    Block block2{};
    Corrections corrected;
    bool ok() const { return corrected.ok(); }
};

// Decodes the two codewords (510 bytes: a datagram, or a frame after its preamble).
DecodedBlocks decodeCodewords(std::span<const std::uint8_t, kDatagramSize> codewords);

}  // namespace rcm
