// The one receive path: bytes in, messages out, each frame either delivered
// or refused with a reason. Sync (StreamSync, for a byte stream), RS,
// decipher and authenticate when keys are given, decode, then the
// acceptance decision of docs/protocol.md section 8:
//   exact      both codewords decoded; ID_msg, time_UTC and date_UTC present;
//              BLOCK 1 is padding then items back to back, in the canonical
//              order the encoder writes; BLOCK 2 padding and End_Of_String as
//              the profile says; no diagnostic at all (on a keyed link the
//              authentication checks this and more);
//   plausible  after the last frame accepted from the same sender
//              (ID_UA_source): ID_msg ahead by 1 .. kMaxMessageIdStep,
//              time_UTC not behind it and not ahead by more than the frames
//              between allow, a flight plan section that fits the plan being
//              sent; live, time_UTC within the window of the receiver's clock.
// Anything else is refused, counted by reason, never delivered.
//
// Decoding with what the receiver expects plugs in at Options::retry: when
// plain decoding gives no exact frame, each candidate it returns goes
// through the same acceptance decision, in order, and the first one that
// passes is delivered (with fromPrediction set). A wrong prediction can
// therefore cost a frame but never deliver a wrong one that the decision
// would have refused.
//
// Plain C++20, no Qt. Not thread-safe; the handler must not call back.
#pragma once

#include "codec/frame/StreamSync.h"
#include "codec/message/MessageDecoder.h"

#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace rcm {

namespace secure {
class SecureCodec;
class ReplayGuard;
enum class Direction : std::uint8_t;
}  // namespace secure

// Why a frame was not delivered. Names (refusalName) are for logs and the
// status bar.
enum class Refusal : std::uint8_t {
    // the bytes
    Uncorrectable,      // a codeword beyond correction
    WrongSize,          // a datagram that is not 510 bytes
    Enciphered,         // no key, and the blocks look enciphered (no padding anywhere)
    Forged,             // keyed: does not authenticate in any direction given
    Plaintext,          // keyed: an unencrypted message
    // not exact
    MissingHeaderItem,  // no ID_msg, time_UTC or date_UTC
    BadPadding,         // BLOCK 1 not padding then items back to back; BLOCK 2 padding or End_Of_String
    InvalidField,       // a value out of range, a corrupt two-bit field, reserved bits set
    UnknownItem,        // an Item_ID the profile does not define, or an item cut off by the block's end
    NotCanonical,       // items not in the order the profile's encoder writes them
    Warning,            // any other diagnostic (orphan item, repeated item, unit without its key)
    // not plausible (from here on: FrameReceiver retries no prediction)
    Replayed,           // ID_msg not ahead of the last accepted from this sender
    MessageIdStep,      // ID_msg ahead by more than kMaxMessageIdStep
    TimeStep,           // time_UTC behind the last accepted, or further ahead than the ID step allows
    TimeWindow,         // live: time_UTC/date_UTC outside the window of the receiver's clock
    PlanSection,        // a flight plan section that neither continues the plan being sent nor starts one
};
inline constexpr int kRefusalCount = 16;
std::string_view refusalName(Refusal r);  // "uncorrectable", "not exact: bad padding", ...

inline constexpr std::uint32_t kMaxMessageIdStep = 300;     // five minutes of frames at one a second
inline constexpr std::int64_t kTimeStepSlackSeconds = 2;    // sender's tick jitter and rounding to the second
inline constexpr std::int64_t kDefaultClockWindowSeconds = 30;

// One frame as the receiver judged it. Spans are valid only in the handler.
struct ReceivedFrame {
    std::int64_t offset = 0;                // stream: first preamble byte (as SyncedFrame); datagram: 0
    std::span<const std::uint8_t> raw;      // as received: the frame, or the datagram
    DecodedBlocks blocks;                   // after RS (still enciphered on a keyed link)
    int preambleBitErrors = 0;              // stream only
    std::optional<Refusal> refusal;         // none: delivered
    std::string detail;                     // refused: one line saying what and where
    // Delivered: the message. Refused on the plain link: what could be read,
    // for forensic display only. Refused on a keyed link: empty.
    DecodeResult decoded;
    std::optional<secure::Direction> direction;  // keyed and delivered: the direction it authenticated in
    bool fromPrediction = false;            // delivered from a candidate of Options::retry
    std::string warning;                    // delivered, but the replay state could not be written
    bool delivered() const { return !refusal; }
};

// What the receiver knows of one sender: its last accepted frame.
struct SenderHistory {
    DecodedBlocks blocks;           // as delivered (enciphered on a keyed link)
    Message message;
    std::uint32_t messageId = 0;
    std::int64_t stampSeconds = 0;  // time_UTC + date_UTC as UTC seconds
    std::uint32_t planId = 0;       // the plan being sent (0: none yet)
    std::uint16_t section = 0;      // its last section seen
};

class FrameReceiver {
public:
    enum class Mode {
        Live,       // time_UTC must also be within the window of the receiver's clock
        Recording,  // a recording decoded later: continuity between its own frames only
    };
    using Handler = std::function<void(const ReceivedFrame&)>;
    // UTC microseconds since 1970; empty: the system clock.
    using Clock = std::function<std::int64_t()>;
    // Decoding with what the receiver expects: given the received codewords
    // and what plain RS made of them, candidate decodings, best first.
    using Retry = std::function<std::vector<DecodedBlocks>(std::span<const std::uint8_t, kDatagramSize> received,
                                                           const DecodedBlocks& plain, const FrameReceiver& receiver)>;

    struct Keys {
        // The directions a frame may have been sent in (one on a link; both
        // for `rcm decode --key` without --direction). Not owned.
        std::vector<const secure::SecureCodec*> codecs;
        // The persistent replay state of a link's receiving direction; null
        // for none. Not owned.
        secure::ReplayGuard* guard = nullptr;
    };

    struct Options {
        Mode mode = Mode::Live;
        Clock clock;
        std::int64_t clockWindowSeconds = kDefaultClockWindowSeconds;
        Keys keys;  // no codecs: the plain link
        Retry retry;
    };

    struct Stats {
        std::uint64_t delivered = 0;
        std::uint64_t fromPrediction = 0;  // of delivered
        std::array<std::uint64_t, kRefusalCount> refused{};
        std::uint64_t refusedTotal() const;
    };

    FrameReceiver(Options options, Handler handler);
    ~FrameReceiver();

    // A byte stream (serial line, a recording of one): frames found by their preamble.
    void feed(std::span<const std::uint8_t> bytes);
    void flush();  // end of stream: see StreamSync::flush
    // One datagram (510 bytes, else refused as WrongSize), or one frame
    // already delimited (600 bytes, as a frame log row holds it).
    void receive(std::span<const std::uint8_t> bytes, std::int64_t offset = 0);

    const Stats& stats() const { return m_stats; }
    const StreamSync::Stats& syncStats() const { return m_sync.stats(); }
    // The last accepted frame of each sender (keyed by ID_UA_source; a frame
    // without one is sender {0, 0}), and the most recent of them all.
    const std::map<std::uint32_t, SenderHistory>& senders() const { return m_senders; }
    const SenderHistory* lastAccepted() const { return m_last; }
    const Options& options() const { return m_options; }
    // Forgets senders and statistics (not the keys' replay state).
    void reset();
    // The exactness rules alone (authentication on a keyed link): what
    // StreamSync asks to choose between readings of one frame.
    bool exact(const DecodedBlocks& blocks) const;

private:
    void judge(ReceivedFrame& frame, std::span<const std::uint8_t, kDatagramSize> codewords);
    bool accept(ReceivedFrame& frame, const DecodedBlocks& blocks, bool remember);

    Options m_options;
    Handler m_handler;
    StreamSync m_sync;
    Stats m_stats;
    std::map<std::uint32_t, SenderHistory> m_senders;
    // Per sender: an exact frame refused as implausible, which the next one
    // may confirm (a sender restarted, or a long outage).
    std::map<std::uint32_t, SenderHistory> m_candidates;
    const SenderHistory* m_last = nullptr;
};

}  // namespace rcm
