// RS(255,223) as CCSDS 131.0-B defines it (dual basis), over plain byte
// buffers in libfec's style. A table-driven register answers the common
// question "is this codeword clean?" in a fraction of the time libfec's full
// decode takes, and gives the word's remainder modulo the generator, from
// which the decoder takes its syndromes: 32 coefficients to evaluate instead
// of 255. The decoding steps are libfec's (Berlekamp-Massey, Chien search,
// Forney), so the results are libfec's, byte for byte: tst_trialdecode
// compares them on random words with 0 to 40 errors.
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
// The same result as libfec's decode_rs_ccsds.
int decode(std::uint8_t* codeword);

// decode, giving up (-1, the codeword left as it was) as soon as the error
// locator shows more than `maxErrors` errors: a wrong guess is refused
// before the costly search for the errors' places.
int decodeWithin(std::uint8_t* codeword, int maxErrors);

// `word` (255 bytes): a codeword's 223 data bytes followed by other parity
// bytes; `codewordParity` (32 bytes): that codeword's own parity. Its
// remainder is the difference of the two parities, so no pass over the data
// is needed. Corrects `word` in place as decodeWithin does.
int decodeWithParity(std::uint8_t* word, const std::uint8_t* codewordParity, int maxErrors);

// Corrects `codeword` in place given `count` (<= 32) places known to be
// unreliable (`erasures`, indices 0..254, distinct): errors e elsewhere and
// erasures f are corrected while 2e + f <= 32. Returns the bytes changed (an
// erased place may have been right), or -1 beyond correction (the codeword
// then left as it was). libfec's decode_rs with eras_pos, from the remainder.
int decodeWithErasures(std::uint8_t* codeword, const int* erasures, int count);

// libfec's correction alone, for a codeword already known not to be clean;
// same result as decode, for tests and benchmarks that compare with libfec.
int correct(std::uint8_t* codeword);

// libfec's decode_rs_ccsds alone, without the clean check; for benchmarks and
// for tests that compare against it. Any negative return means failure.
int decodeLibfec(std::uint8_t* codeword);
// ... with `count` erasures (libfec's eras_pos).
int decodeLibfecWithErasures(std::uint8_t* codeword, const int* erasures, int count);

}  // namespace rcm::rs
