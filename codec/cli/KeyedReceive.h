// The keyed side of rcm decode: a codec for each direction tried, and the
// receiver's replay guard with --replay-state.
#pragma once

#include "codec/cli/Options.h"
#include "codec/secure/SecureCodec.h"

#include <array>
#include <memory>
#include <vector>

namespace rcm::cli {

struct Keyed {
    std::vector<std::unique_ptr<rcm::secure::SecureCodec>> codecs;
    std::unique_ptr<rcm::secure::ReplayGuard> guard;
    std::array<std::uint64_t, rcm::secure::kRejectionCount> rejected{};
    bool persistWarned = false;
};

// Nothing, with the reason on standard error, when the key cannot be used.
std::unique_ptr<Keyed> loadKeyed(const Options& o);

// A keyed frame: the authenticated message and its direction, or the reason
// it was refused.
struct KeyedResult {
    bool accepted = false;
    rcm::DecodeResult decoded;
    rcm::secure::Direction direction = rcm::secure::Direction::GcsToUa;
    rcm::secure::Rejection rejection = rcm::secure::Rejection::Forged;
    std::string detail;
};

KeyedResult openKeyed(Keyed& k, const rcm::DecodedBlocks& blocks);

}  // namespace rcm::cli
