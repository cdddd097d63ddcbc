// RS(255,223) as CCSDS 131.0-B defines it (dual basis), over plain byte
// buffers in libfec's style. libfec does the correcting; a table-driven check
// answers the common question "is this codeword clean?" in a fraction of the
// time libfec's full decode takes.
#pragma once

#include <cstddef>
#include <cstdint>

namespace rcm::rs {

inline constexpr std::size_t kDataSize = 223;
inline constexpr std::size_t kParitySize = 32;
inline constexpr std::size_t kCodewordSize = 255;
inline constexpr int kMaxCorrectable = 16;

// Writes the 32 parity bytes of `data` (223 bytes).
void encode(const std::uint8_t* data, std::uint8_t* parity);

// libfec's encode_rs_ccsds, for tests that compare encode against it.
void encodeLibfec(const std::uint8_t* data, std::uint8_t* parity);

// True when `codeword` (255 bytes) is a codeword: its parity matches its data.
bool isCodeword(const std::uint8_t* codeword);

// isCodeword for two codewords at once, in little more than the time of one.
void checkCodewords(const std::uint8_t* a, const std::uint8_t* b, bool* aClean, bool* bClean);

// Corrects `codeword` in place. Returns the number of bytes corrected, or -1
// when the errors are beyond correction (the codeword is then left as it was).
int decode(std::uint8_t* codeword);

// libfec's correction alone, for a codeword already known not to be clean;
// same result as decode.
int correct(std::uint8_t* codeword);

// libfec's decode_rs_ccsds alone, without the clean check; for benchmarks and
// for tests that compare against it. Any negative return means failure.
int decodeLibfec(std::uint8_t* codeword);

}  // namespace rcm::rs
