// Decoding with what the receiver expects: FrameReceiver's Options::retry.
// When plain RS leaves a codeword beyond correction, each codeword is decoded
// again with a prediction of it (rs::decodeWithPrediction):
//   BLOCK 1  the last frame accepted from a sender advanced by n = 1, 2 ...
//            seconds (advanceMessage), encoded as its sender encodes it;
//            before anything was accepted, the byte-wise majority of the
//            last few frames received (plain link only);
//   BLOCK 2  an empty section, or the last one accepted again (the
//            aircraft repeats its acknowledgement in every status frame).
// On the plain link a prediction need not be exact: the bytes in which the
// sent frame differs from it (a changed command) are errors RS corrects. On
// a keyed link the prediction is enciphered first, and ciphertext changes
// wholly with any plaintext byte, so the prediction must be exact; there
// time_UTC is also tried one second either side of ID_msg's step, and, for
// the frames up to 10 s after the last accepted one, every single-byte change of
// a command value (about 10^5 candidates for a typical command frame, each
// enciphered, RS-encoded and compared by parity distance).
// Every result still goes through the receiver's acceptance decision.
// docs/protocol.md, "Decoding with what the receiver expects", says why a
// trial cannot turn a wrong prediction into a wrong frame.
//
// Plain C++20, no Qt. Not thread-safe: one per FrameReceiver.
#pragma once

#include "codec/frame/TrialDecode.h"
#include "codec/receive/FrameReceiver.h"

#include <cstdint>
#include <deque>
#include <optional>
#include <span>
#include <vector>

namespace rcm {

class TrialDecoder {
public:
    struct Options {
        std::uint32_t maxGapSeconds = 30;      // predictions n = 1 .. this many seconds after the last accepted
        std::uint32_t commandChangeGap = 10;   // keyed: single-byte command changes tried up to n = this
        int margin = rs::kTrialMargin;         // most bytes a trial may correct
        int majorityFrames = 5;                // plain link, nothing accepted yet: frames voted over
    };

    struct Stats {
        std::uint64_t calls = 0;
        std::uint64_t block1FromPrediction = 0;
        std::uint64_t block1FromCommandChange = 0;  // keyed: a single-byte change found
        std::uint64_t block1FromMajority = 0;
        std::uint64_t block2FromPrediction = 0;
    };

    TrialDecoder() : TrialDecoder(Options{}) {}
    explicit TrialDecoder(Options options) : m_options(options) {}

    // Candidate decodings of `received`, best first (FrameReceiver::Retry).
    std::vector<DecodedBlocks> candidates(std::span<const std::uint8_t, kDatagramSize> received,
                                          const DecodedBlocks& plain, const FrameReceiver& receiver);
    // A Retry that calls `decoder`, which must outlive the receiver.
    static FrameReceiver::Retry retryFor(TrialDecoder& decoder);

    const Stats& stats() const { return m_stats; }

private:
    Options m_options;
    Stats m_stats;
    std::deque<std::vector<std::uint8_t>> m_recent;  // last received BLOCK 1 codewords, for the majority
    // The newest BLOCK 1 read (plainly or by a trial) of a frame the receiver
    // then refused because its BLOCK 2 stayed unreadable (a flight plan
    // section): a better prediction than an older accepted frame.
    std::optional<SenderHistory> m_unaccepted;
};

}  // namespace rcm
