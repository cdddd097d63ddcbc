// Reed-Solomon decoding helped by a prediction of the codeword: the
// receiver's guess of what was sent (the last accepted frame advanced by a
// second, known padding ...). docs/protocol.md, "Decoding with what the
// receiver expects", has the argument for the margin.
//
// A trial replaces all 223 received data bytes by the predicted ones, keeps
// the 32 received parity bytes, and decodes. Where the sent data differs from
// the prediction in k bytes (a changed command, the time), those are k errors
// that RS corrects back to the sent values, together with the channel's
// errors in the parity: the channel's errors in the data bytes are gone. The
// result is accepted only when the decoder corrected at most kTrialMargin
// bytes, well inside its reach of 16: a wrong codeword must then lie within
// 12 bytes of the trial word while every other codeword is at least 33 bytes
// from the sent one.
#pragma once

#include <cstdint>

namespace rcm::rs {

inline constexpr int kTrialMargin = 12;

// Decodes `received` (255 bytes as received) with `predicted` (a codeword,
// 255 bytes) into `out` (255 bytes). Returns the bytes corrected, or -1 when
// the trial word is beyond correction or needed more than `margin`
// corrections (then `out` is unspecified).
int decodeWithPrediction(const std::uint8_t* received, const std::uint8_t* predicted, std::uint8_t* out,
                         int margin = kTrialMargin);

// Parity bytes (of 32) in which `received` differs from `predicted`. When
// the prediction's data bytes are all right this is what the trial corrects,
// so a caller with many candidate codewords compares them by it first, and
// decodeWithPrediction gives `predicted` back whenever this is <= margin.
int parityDistance(const std::uint8_t* received, const std::uint8_t* predicted);

// Byte-wise majority of `count` received codewords (255 bytes each) into
// `out`; where no byte value holds a strict majority, the last codeword's
// byte. For frames that repeat most of their bytes (the same message a second
// later), a few noisy copies together say more than one.
void majorityBytes(const std::uint8_t* const* codewords, int count, std::uint8_t* out);

// Decoding from several received copies of one codeword (the same flight
// plan section in two passes), when no copy is within RS's reach alone.
// Where the copies agree the byte is very likely right; where they do not
// (no value with a strict majority), the sent byte is very likely one of
// theirs. Those places are erased (at most 32) and the rest decoded; with
// more than 32 such places, the values of kCopiesGuessed + (places - 32) of
// them are tried from the copies, each choice decoded with the other 30
// erased (one error left to correct). A result is taken only when it is a
// codeword that
//   - takes every byte from some copy but at most kMaxNoCopyBytes;
//   - is the codeword of the last copy (the frame being read): no further
//     from it than kCopiesLastSlack bytes more than from the nearest other
//     copy (another section's codeword lies near that section's copy, and
//     at least 33 bytes from this one's sent word).
inline constexpr int kMaxNoCopyBytes = 4;
inline constexpr int kCopiesErased = 30;      // erased while guessing: one error left to correct
inline constexpr int kMaxCopiesGuessed = 10;  // places tried from the copies: at most 2^10 decodes
inline constexpr int kCopiesLastSlack = 16;

struct CopiesDecode {
    int decodes = 0;   // RS decodes spent (each about one decode beyond correction)
    bool found = false;
    int noCopy = 0;    // bytes of the result in no copy
};

// `copies`: `count` (>= 2) received words of 255 bytes, the one being read
// last. Writes the codeword into `out` when found; spends at most
// `maxDecodes` decodes.
CopiesDecode decodeFromCopies(const std::uint8_t* const* copies, int count, std::uint8_t* out, int maxDecodes);

}  // namespace rcm::rs
