#include "codec/frame/TrialDecode.h"

#include "codec/frame/ReedSolomon.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <vector>

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

namespace {

// The copies' byte values at one place, the likeliest first: by count, ties
// to the later copy.
struct PlaceValues {
    std::array<std::uint8_t, 2> value{};  // the two likeliest
    int distinct = 0;
    bool strictMajority = false;
};

PlaceValues valuesAt(const std::uint8_t* const* copies, int count, std::size_t i)
{
    std::array<int, 256> seen{};
    std::array<int, 256> last{};
    std::uint8_t order[16];
    int distinct = 0;
    for (int c = 0; c < count; ++c) {
        const std::uint8_t v = copies[c][i];
        if (seen[v]++ == 0 && distinct < 16)
            order[distinct++] = v;
        last[v] = c;
    }
    std::sort(order, order + distinct, [&](std::uint8_t a, std::uint8_t b) {
        return seen[a] != seen[b] ? seen[a] > seen[b] : last[a] > last[b];
    });
    PlaceValues p;
    p.distinct = distinct;
    p.value[0] = order[0];
    p.value[1] = distinct > 1 ? order[1] : order[0];
    p.strictMajority = 2 * seen[order[0]] > count;
    return p;
}

int distance(const std::uint8_t* a, const std::uint8_t* b)
{
    int d = 0;
    for (std::size_t i = 0; i < kCodewordSize; ++i)
        d += a[i] != b[i];
    return d;
}

// The checks of a decoded word against the copies (TrialDecode.h).
bool fitsCopies(const std::uint8_t* const* copies, int count, const std::uint8_t* word, int& noCopy)
{
    noCopy = 0;
    for (std::size_t i = 0; i < kCodewordSize; ++i) {
        bool inCopy = false;
        for (int c = 0; c < count && !inCopy; ++c)
            inCopy = copies[c][i] == word[i];
        if (!inCopy && ++noCopy > kMaxNoCopyBytes)
            return false;
    }
    int nearestOther = static_cast<int>(kCodewordSize);
    for (int c = 0; c + 1 < count; ++c)
        nearestOther = std::min(nearestOther, distance(copies[c], word));
    return distance(copies[count - 1], word) <= nearestOther + kCopiesLastSlack;
}

}  // namespace

CopiesDecode decodeFromCopies(const std::uint8_t* const* copies, int count, std::uint8_t* out, int maxDecodes)
{
    CopiesDecode result;
    if (count < 2)
        return result;
    std::uint8_t base[kCodewordSize];
    std::vector<int> unsure;  // places without a strict majority
    std::vector<std::array<std::uint8_t, 2>> alternatives;
    for (std::size_t i = 0; i < kCodewordSize; ++i) {
        const PlaceValues p = valuesAt(copies, count, i);
        base[i] = p.value[0];
        if (!p.strictMajority) {
            unsure.push_back(static_cast<int>(i));
            alternatives.push_back(p.value);
        }
    }
    const int places = static_cast<int>(unsure.size());
    const int guessed = places <= kMaxCorrectable * 2 ? 0 : places - kCopiesErased;
    if (guessed > kMaxCopiesGuessed)
        return result;  // too far apart to be copies of one codeword
    const int erased = places - guessed;
    const std::uint32_t choices = std::uint32_t{1} << guessed;
    std::uint8_t word[kCodewordSize];
    for (std::uint32_t choice = 0; choice < choices; ++choice) {
        if (result.decodes == maxDecodes)
            return result;
        std::memcpy(word, base, kCodewordSize);
        for (int g = 0; g < guessed; ++g)
            word[unsure[static_cast<std::size_t>(erased + g)]] =
                alternatives[static_cast<std::size_t>(erased + g)][(choice >> g) & 1];
        ++result.decodes;
        if (decodeWithErasures(word, unsure.data(), erased) < 0)
            continue;
        if (fitsCopies(copies, count, word, result.noCopy)) {
            std::memcpy(out, word, kCodewordSize);
            result.found = true;
            return result;
        }
    }
    return result;
}

}  // namespace rcm::rs
