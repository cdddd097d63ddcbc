#include "codec/frame/TrialDecode.h"

#include "codec/frame/ReedSolomon.h"

#include <cstring>

namespace rcm::rs {

int decodeWithPrediction(const std::uint8_t* received, const std::uint8_t* predicted, std::uint8_t* out, int margin)
{
    const int parityDiffers = parityDistance(received, predicted);
    std::memcpy(out, predicted, kDataSize);
    // The trial word is within parityDiffers of `predicted`, a codeword; at
    // <= 16 no other codeword can be as close, so the decoder would return it.
    if (parityDiffers <= kMaxCorrectable) {
        if (parityDiffers > margin)
            return -1;
        std::memcpy(out + kDataSize, predicted + kDataSize, kParitySize);
        return parityDiffers;
    }
    // The trial word's remainder is the difference of the two parities.
    std::memcpy(out + kDataSize, received + kDataSize, kParitySize);
    const int corrected = decodeWithParity(out, predicted + kDataSize, margin);
    return corrected >= 0 && corrected <= margin ? corrected : -1;
}

int parityDistance(const std::uint8_t* received, const std::uint8_t* predicted)
{
    int differs = 0;
    for (std::size_t i = kDataSize; i < kCodewordSize; ++i)
        differs += received[i] != predicted[i];
    return differs;
}

void majorityBytes(const std::uint8_t* const* codewords, int count, std::uint8_t* out)
{
    for (std::size_t i = 0; i < kCodewordSize; ++i) {
        // Boyer-Moore vote, then a count to see whether it is a strict majority.
        std::uint8_t candidate = 0;
        int votes = 0;
        for (int c = 0; c < count; ++c) {
            if (votes == 0)
                candidate = codewords[c][i];
            votes += codewords[c][i] == candidate ? 1 : -1;
        }
        int held = 0;
        for (int c = 0; c < count; ++c)
            held += codewords[c][i] == candidate;
        out[i] = 2 * held > count ? candidate : codewords[count - 1][i];
    }
}

}  // namespace rcm::rs
