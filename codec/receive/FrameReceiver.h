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
//              (ID_UA_source): ID_msg ahead by 1 .. kMaxMessageIdStep (or
//              the outage), time_UTC not behind it and not ahead by more
//              than the frames between or the outage allow, a flight plan
//              section that continues the plan being sent and fits its
//              descriptor; live, time_UTC within the window of the receiver's
//              clock.
// Anything else is refused, counted by reason, never delivered.
//
// A frame older than the last accepted from its sender is never delivered.
// A sender that restarted (its ID_msg from 0 again) or was out of reach for
// long is recognised by what an old frame cannot have: a time stamp later
// than the last accepted frame's (live, also within the clock window), and
// then a next frame that follows it.
//
// Decoding with what the receiver expects (TrialDecoder, owned, unless
// Options::predictions is off): when plain decoding gives no exact frame,
// each candidate it returns goes through the same acceptance decision, in
// order, and the first one that passes is delivered (with fromPrediction
// set). A wrong prediction can therefore cost a frame but never deliver a
// wrong one that the decision would have refused. Its work is bounded by a
// budget (PredictionOptions), so no input can make the receiver fall behind
// the line.
//
// Memory is bounded: at most kMaxSenders senders are remembered; beyond
// that, the one with the fewest accepted frames is forgotten.
//
// Plain C++20, no Qt. Not thread-safe; the handler must not call back.
#pragma once

#include "codec/frame/StreamSync.h"
#include "codec/message/DecodeResult.h"
#include "codec/receive/Refusal.h"

#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
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

class TrialDecoder;

inline constexpr std::uint32_t kMaxMessageIdStep = 300;     // five minutes of frames at one a second
inline constexpr std::int64_t kTimeStepSlackSeconds = 2;    // sender's tick jitter and rounding to the second
inline constexpr std::int64_t kDefaultClockWindowSeconds = 30;
inline constexpr std::size_t kMaxSenders = 16;

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
    bool fromPrediction = false;            // delivered from a candidate of the predictions
    std::string warning;                    // delivered, but the replay state could not be written
    bool delivered() const { return !refusal; }
};

// The flight plan a sender is sending, as far as its frames showed it.
struct PlanProgress {
    std::uint32_t planId = 0;          // 0: none yet
    std::uint16_t section = 0;         // its last section seen
    std::uint32_t sectionMessageId = 0;  // ID_msg of the frame that carried it
    // From the plan's section 0 (its descriptor), once delivered; 0: unknown.
    std::uint16_t sectionCount = 0;
    std::uint64_t streamBytes = 0;     // descriptor + plan bytes: 10 + T
    std::uint16_t sectionSize = 0;     // data bytes of every section but the last
    std::uint32_t crc = 0;
};

// What the receiver knows of one sender: its last accepted frame.
struct SenderHistory {
    DecodedBlocks blocks;           // as delivered (enciphered on a keyed link)
    Message message;
    std::uint32_t messageId = 0;
    std::int64_t stampSeconds = 0;  // time_UTC + date_UTC as UTC seconds
    std::int64_t receivedMicros = 0;  // the receiver's clock when it was accepted
    std::uint64_t accepted = 0;     // frames accepted from this sender so far
    std::uint64_t serial = 0;       // the receiver's count of acceptances when it was accepted
    PlanProgress plan;
};

// How much work decoding with predictions may take (TrialDecoder).
struct PredictionOptions {
    std::uint32_t maxGapSeconds = 30;     // predictions n = 1 .. this many seconds after the last accepted
    std::uint32_t commandChangeGap = 10;  // keyed: single-byte command changes tried up to n = this
    int margin = 12;                      // most bytes a trial may correct (rs::kTrialMargin)
    int majorityFrames = 5;               // plain link, nothing accepted yet: frames voted over
    std::size_t maxSenders = 3;           // senders predicted from, most recently accepted first
    // The budget, in work units of about a microsecond of one core of the
    // reference machine (a trial costs 3, a candidate encipherment 3, a
    // decode beyond correction 8). It refills by unitsPerSecond per second
    // of the receiver's clock (live), or per frame's worth of input (600
    // bytes, or a datagram) in a recording, up to maxUnits: enough for one
    // search of single-byte command changes on a keyed link. A frame whose
    // predictions find the budget spent is refused as uncorrectable.
    std::uint64_t unitsPerSecond = 20'000;
    std::uint64_t maxUnits = 600'000;
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
        // Decoding with what the receiver expects (docs/protocol.md section
        // 9); false: Reed-Solomon alone.
        bool predictions = true;
        PredictionOptions prediction;
    };

    struct Stats {
        std::uint64_t delivered = 0;
        std::uint64_t fromPrediction = 0;  // of delivered
        std::array<std::uint64_t, kRefusalCount> refused{};
        std::uint64_t predictionUnits = 0;    // work spent on predictions
        std::uint64_t predictionsCut = 0;     // frames whose predictions the budget cut short
        std::uint64_t sendersForgotten = 0;   // senders dropped to keep the table bounded
        std::uint64_t refusedTotal() const;
    };

    FrameReceiver(Options options, Handler handler);
    ~FrameReceiver();
    FrameReceiver(const FrameReceiver&) = delete;
    FrameReceiver& operator=(const FrameReceiver&) = delete;

    // A byte stream (serial line, a recording of one): frames found by their preamble.
    void feed(std::span<const std::uint8_t> bytes);
    void flush();  // end of stream: see StreamSync::flush
    // One datagram (510 bytes, else refused as WrongSize), or one frame
    // already delimited (600 bytes, as a frame log row holds it).
    void receive(std::span<const std::uint8_t> bytes, std::int64_t offset = 0);

    // What this end just sent: the console's command, which the aircraft's
    // next status frames should report. A prediction of what arrives next
    // (docs/protocol.md section 9), never a condition on it.
    void expect(const Message& sent);

    const Stats& stats() const { return m_stats; }
    const StreamSync::Stats& syncStats() const { return m_sync.stats(); }
    // The last accepted frame of each sender (keyed by ID_UA_source; a frame
    // without one is sender {0, 0}), and the most recent of them all.
    const std::map<std::uint32_t, SenderHistory>& senders() const { return m_senders; }
    const SenderHistory* lastAccepted() const { return m_last; }
    const Options& options() const { return m_options; }
    // The predictor, when Options::predictions is on.
    const TrialDecoder* predictions() const { return m_trial.get(); }
    // Forgets senders and statistics (not the keys' replay state).
    void reset();
    // The exactness rules alone (authentication on a keyed link): what
    // StreamSync asks to choose between readings of one frame.
    bool exact(const DecodedBlocks& blocks) const;
    // Frames' worth of input so far (600 bytes of stream or one datagram
    // each): what the budget of a recording refills with.
    std::uint64_t framesOfInput() const;

private:
    struct Exactness;
    ReceivedFrame& freshFrame();
    void judge(ReceivedFrame& frame, std::span<const std::uint8_t, kDatagramSize> codewords);
    bool accept(ReceivedFrame& frame, const DecodedBlocks& blocks, bool remember);
    SenderHistory& keepHistory(std::uint32_t key, SenderHistory h);

    Options m_options;
    Handler m_handler;
    StreamSync m_sync;
    Stats m_stats;
    std::unique_ptr<TrialDecoder> m_trial;
    std::map<std::uint32_t, SenderHistory> m_senders;
    // Per sender: an exact frame refused as implausible but later than the
    // last accepted, which the next one may confirm (a sender restarted, or
    // a long outage).
    std::map<std::uint32_t, SenderHistory> m_candidates;
    const SenderHistory* m_last = nullptr;
    std::uint64_t m_serial = 0;
    // The latest stamp of a sender forgotten: a sender seen again must not
    // come back with frames older than it (its replayed frames).
    std::optional<std::int64_t> m_forgottenStamp;
    std::uint64_t m_datagrams = 0;
    bool m_block2Read = true;  // false while judging a datagram whose codeword 2 was not decoded
    // The last plain frame found exact, to judge the next one that differs
    // from it only in the header's counter and clock without decoding again.
    std::unique_ptr<Exactness> m_exactCache;
    ReceivedFrame m_frame;  // the frame being judged (freshFrame)
};

}  // namespace rcm
