// Decoding with what the receiver expects: FrameReceiver's predictions.
// When plain RS leaves a codeword beyond correction, each codeword is decoded
// again with a prediction of it (rs::decodeWithPrediction):
//   BLOCK 1  the last frame accepted from a sender advanced by n = 1, 2 ...
//            seconds (advanceMessage), encoded as its sender encodes it;
//            the same with this end's own last command applied
//            (withCommanded: the console's command, which the aircraft's
//            next status reports); on the plain link, either with the bytes
//            that recent frames agree on (the sender repeats a changed
//            command in every frame, so after a change of several items two
//            frames already carry the new bytes); before anything was
//            accepted, the byte-wise majority of the last few frames
//            received (plain link only);
//   BLOCK 2  an empty section, the last one accepted again (the aircraft
//            repeats its acknowledgement in every status frame), the
//            acknowledgement of a plan this end sent (its descriptor), the
//            sections of the plan being sent delivered in an earlier pass
//            (passes 2 and 3 repeat pass 1), and on the plain link the copies
//            of one section from several passes combined byte by byte.
// On the plain link a prediction need not be exact: the bytes in which the
// sent frame differs from it (a changed command) are errors RS corrects. On
// a keyed link the prediction is enciphered first, and ciphertext changes
// wholly with any plaintext byte, so the prediction must be exact; there
// time_UTC is also tried one second either side of ID_msg's step, the own
// command applied to all units, to all but one and to one alone, and, as a
// last resort, every single-byte change of a command value (about 10^5
// candidates, each enciphered, RS-encoded and compared by parity distance).
// Every result still goes through the receiver's acceptance decision.
// docs/protocol.md section 9 says why a trial cannot turn a wrong
// prediction into a wrong frame.
//
// Bounded cost: predictions are made from the few senders accepted last
// (PredictionOptions::maxSenders), each sender's predicted codewords are
// made once per accepted frame and kept, and all the work is paid from a
// budget (PredictionOptions) that refills with the receiver's clock, or
// with the input in a recording.
//
// Plain C++20, no Qt. Not thread-safe: one per FrameReceiver.
#pragma once

#include "codec/frame/TrialDecode.h"
#include "codec/receive/FrameReceiver.h"
#include "codec/secure/SecureCodec.h"

#include <array>
#include <cstdint>
#include <deque>
#include <memory>
#include <optional>
#include <span>
#include <vector>

namespace rcm {

class TrialDecoder {
public:
    struct Stats {
        std::uint64_t calls = 0;
        std::uint64_t block1FromPrediction = 0;     // the last accepted frame advanced
        std::uint64_t block1FromExpected = 0;       // ... with this end's own command applied
        std::uint64_t block1FromCopies = 0;         // ... with the bytes recent frames agree on
        std::uint64_t block1FromChangedCommands = 0;  // plain: ... with the command bytes that differ erased
        std::uint64_t block1FromCommandChange = 0;  // keyed: a single-byte change found
        std::uint64_t block1FromMajority = 0;
        std::uint64_t block2FromPrediction = 0;     // empty, or the last section again
        std::uint64_t block2FromPlan = 0;           // a section delivered in an earlier pass
        std::uint64_t block2FromCopies = 0;         // copies of a section from several passes combined
        std::uint64_t cut = 0;                      // calls the budget cut short
    };

    struct Candidates {
        std::vector<DecodedBlocks> blocks;  // best first
        std::uint64_t units = 0;            // work spent
        bool cut = false;                   // the budget ran out before every prediction was tried
    };

    // `keyed`: the receiver deciphers (its predictions must then be exact).
    explicit TrialDecoder(PredictionOptions options = {}, bool keyed = false);
    ~TrialDecoder();
    TrialDecoder(const TrialDecoder&) = delete;
    TrialDecoder& operator=(const TrialDecoder&) = delete;

    // Candidate decodings of `received`, best first. `block2Read`: false when
    // codeword 2 was not decoded yet (a datagram whose codeword 1 failed).
    // `nowMicros`: the receiver's clock, live; 0 in a recording.
    Candidates candidates(std::span<const std::uint8_t, kDatagramSize> received, const DecodedBlocks& plain,
                          bool block2Read, const FrameReceiver& receiver, std::int64_t nowMicros);
    // Every frame the receiver judged, after the decision: what later
    // predictions learn from. `accepted`: its sender's history when delivered.
    void observe(std::span<const std::uint8_t, kDatagramSize> received, const ReceivedFrame& frame,
                 const SenderHistory* accepted);
    // This end's own last frame (FrameReceiver::expect).
    void expect(const Message& sent);

    const Stats& stats() const { return m_stats; }
    std::uint64_t budget() const { return m_units; }

private:
    using Codeword = std::array<std::uint8_t, kCodewordSize>;
    struct Predicted {
        Codeword codeword;  // enciphered on a keyed link
        secure::HeaderStamp stamp;
        std::uint32_t n = 0;
    };
    // What one sender's last accepted frame predicts, made once.
    struct SenderPredictions {
        std::uint64_t serial = 0;  // the history's
        const secure::SecureCodec* codec = nullptr;
        std::vector<Predicted> advanced;
        std::uint64_t expectedVersion = 0;  // 0: not made yet
        std::vector<Predicted> expected;
        std::uint64_t used = 0;
    };
    struct Work;
    struct Found;
    struct Section;

    void refill(const FrameReceiver& receiver, std::int64_t nowMicros);
    SenderPredictions& predictionsFor(const SenderHistory& h, const secure::SecureCodec* codec, bool keyed, Work& work);
    void makeExpected(SenderPredictions& p, const SenderHistory& h, bool keyed, Work& work);
    std::vector<const SenderHistory*> sendersToPredict(const FrameReceiver& receiver) const;
    std::uint32_t likelyGap(const FrameReceiver& receiver, const SenderHistory& h, std::int64_t nowMicros) const;
    std::optional<DecodedBlocks> readBlock1(const SenderHistory& h, const secure::SecureCodec* codec, bool keyed,
                                            const DecodedBlocks& start, const std::uint8_t* r1,
                                            std::uint32_t gapEstimate, secure::HeaderStamp& stamp, Work& work);
    std::optional<Found> findBlock1(const SenderHistory& h, const secure::SecureCodec* codec, bool keyed,
                                    const std::uint8_t* r1, std::uint32_t gapEstimate, Work& work);
    std::optional<Found> tryPredictions(const std::vector<Predicted>& list, const std::vector<std::uint32_t>& order,
                                        bool keyed, const std::uint8_t* r1, Work& work) const;
    std::optional<std::array<int, kBlockSize>> agreedBytes(const std::uint8_t* r1) const;
    std::optional<Found> fromAgreedBytes(const SenderPredictions& p, const std::vector<std::uint32_t>& order,
                                         const std::uint8_t* r1, Work& work) const;
    bool findBlock2(const SenderHistory& h, const secure::SecureCodec* codec, bool keyed,
                    const secure::HeaderStamp& stamp, const std::uint8_t* r2, DecodedBlocks& d, Work& work);
    std::vector<const Section*> heldSectionsAhead(const PlanProgress& plan) const;
    bool block2FromCopies(const std::uint8_t* r2, DecodedBlocks& d, Work& work);
    std::optional<Found> fromChangedCommands(const SenderPredictions& p, const std::vector<std::uint32_t>& order,
                                             const std::uint8_t* r1, Work& work) const;
    static std::optional<Found> decodeErased(const Predicted& pred, const std::uint8_t* r1,
                                             const std::vector<int>& erased);
    std::optional<Found> searchCommandChange(const SenderHistory& h, const secure::SecureCodec* codec,
                                             const std::uint8_t* r1, std::uint32_t gapEstimate, Work& work);
    bool majority(const std::uint8_t* r1, const DecodedBlocks& plain, DecodedBlocks& d, Work& work);

    PredictionOptions m_options;
    bool m_keyed;
    Stats m_stats;
    std::uint64_t m_units;
    std::int64_t m_refilledMicros = 0;
    std::uint64_t m_refilledFrames = 0;
    std::uint64_t m_tick = 0;
    std::vector<SenderPredictions> m_predictions;
    std::optional<Message> m_expected;
    std::uint64_t m_expectedVersion = 0;
    std::deque<FlightPlanSection> m_acknowledgements;  // of the plans this end sent, the latest first
    // Plain link: the last frames' codewords 1 (as decoded when they were,
    // else as received), most recent first, for the bytes they agree on.
    std::deque<Codeword> m_recent;
    std::uint64_t m_framesSinceDelivery = 0;
    // Nothing accepted yet, plain link: the last BLOCK 1 codewords received, for the majority.
    std::deque<Codeword> m_majority;
    // Plan sections delivered (plaintext BLOCK 2, keyed by plan and section
    // ID), oldest first; and on the plain link the codewords 2 of frames
    // whose BLOCK 2 no prediction read, most recent first.
    struct Section {
        std::uint32_t planId = 0;
        std::uint16_t sectionId = 0;
        Block plain{};
    };
    std::deque<Section> m_sections;
    std::deque<Codeword> m_block2Copies;
    // The newest BLOCK 1 read (plainly or by a trial) of a frame the receiver
    // then refused because its BLOCK 2 stayed unreadable (a flight plan
    // section): a better prediction than an older accepted frame.
    std::optional<SenderHistory> m_unaccepted;
    const SenderHistory* m_lastHistory = nullptr;  // the receiver's last accepted, during a call
};

}  // namespace rcm
