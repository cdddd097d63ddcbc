// What tests/codec/tst_receive.cpp asserts on (10^4 frames a row) and
// tests/bench/soak_receive.cpp measures (10^6 frames a row) beyond channel
// noise: old frames replayed into a live stream or a recording, splices of
// two frames' codewords, streams cut and overlapped and slipped, judged
// against what libfec reads at each frame's true place, and outages after
// which a sender resumes with its counter where it was.
//
// Every row streams a CommandSession (tests/support/ReceiveChannel.h) through one
// FrameReceiver as the link worker runs it (live, its clock the sender's,
// with predictions), or as `rcm decode` reads a recording.
#pragma once

#include "tests/support/ReceiveChannel.h"

#include "codec/frame/ReedSolomon.h"

#include <deque>
#include <map>
#include <set>

namespace rcm::test {

// Deliveries against what was sent, by frame index.
class DeliveryLedger {
public:
    explicit DeliveryLedger(const CommandSession& session) : m_session(session) {}

    // `sent`: frames sent so far. Returns false for a wrong frame.
    void deliver(const ReceivedFrame& f, std::uint64_t sent, RowResult& row)
    {
        const std::uint32_t id = static_cast<std::uint32_t>(f.decoded.message.header.number(ItemId::ID_msg));
        const std::optional<std::uint64_t> i = m_session.indexOf(id, sent);
        if (!i || !(m_session.messageAt(*i) == f.decoded.message)) {
            if (++row.wrong == 1)
                row.firstWrong = "ID_msg " + std::to_string(id) + " at stream offset " + std::to_string(f.offset);
            return;
        }
        if (m_delivered.size() <= *i)
            m_delivered.resize(*i + 1, false);
        if (m_delivered[*i] || (m_newest && *i < *m_newest)) {
            // Delivered again, or after a newer one: an old command acted on.
            if (++row.stale == 1)
                row.firstStale = "frame " + std::to_string(*i) + " at stream offset " + std::to_string(f.offset);
            return;
        }
        m_delivered[*i] = true;
        m_newest = std::max(m_newest.value_or(*i), *i);
        ++row.correct;
    }
    bool delivered(std::uint64_t i) const { return i < m_delivered.size() && m_delivered[i]; }

private:
    const CommandSession& m_session;
    std::vector<bool> m_delivered;
    std::optional<std::uint64_t> m_newest;
};

struct AttackResult {
    RowResult row;
    std::uint64_t attacks = 0;       // replayed frames, splices, outages ...
    // Splices the plain profile cannot tell from a frame: its BLOCK 2 and
    // the other frame's differ, and the other's is empty or starts a plan.
    std::uint64_t undetectable = 0;
    std::uint64_t recoverable = 0;   // sync rows: frames libfec reads at their true place
    std::uint64_t falseRefusals = 0; // ... that were not delivered
    std::string firstFalseRefusal;
};

// Old frames of the session replayed into it: after each frame, with
// probability `rate`, one to five consecutive frames sent before (from the
// last 30 s half the time, the last hour otherwise). Live: the receiver's
// clock is the sender's; recording: no clock at all.
inline AttackResult runReplay(const CommandSession& session, std::uint64_t frames, double rate, std::uint64_t seed,
                              FrameReceiver::Mode mode)
{
    AttackResult result;
    RowResult& row = result.row;
    DeliveryLedger ledger(session);
    std::int64_t nowMicros = 0;
    std::uint64_t sent = 0;
    FrameReceiver::Options options;
    options.mode = mode;
    options.clock = [&] { return nowMicros; };
    FrameReceiver receiver(options, [&](const ReceivedFrame& f) {
        if (f.delivered())
            ledger.deliver(f, sent, row);
    });
    std::mt19937_64 rng(seed);
    std::bernoulli_distribution replay(rate);
    for (std::uint64_t i = 0; i < frames; ++i) {
        sent = i + 1;
        nowMicros = session.secondsAt(i) * 1'000'000 + 500'000;
        receiver.feed(session.frameAt(i));
        if (i < 2 || !replay(rng))
            continue;
        const std::uint64_t back = 1 + (rng() & 1 ? rng() % std::min<std::uint64_t>(i, 30) : rng() % std::min<std::uint64_t>(i, 3600));
        const std::uint64_t burst = 1 + rng() % 5;
        for (std::uint64_t k = 0; k < burst && k < back; ++k) {
            receiver.feed(session.frameAt(i - back + k));
            ++result.attacks;
        }
    }
    receiver.flush();
    row.sent = frames;
    row.lost = frames - row.correct;
    row.refused = receiver.stats().refused;
    return result;
}

// Splices: with probability `rate` a frame's codeword 2 is replaced by that
// of the frame k = 1 .. 3 later, and the stream goes on after that frame (a
// frame-sized deletion on the codeword boundary). A splice is wrong when
// delivered with a BLOCK 2 other than its own.
inline AttackResult runSplices(const CommandSession& session, std::uint64_t frames, double rate, std::uint64_t seed)
{
    AttackResult result;
    RowResult& row = result.row;
    DeliveryLedger ledger(session);
    std::int64_t nowMicros = 0;
    std::uint64_t sent = 0;
    FrameReceiver::Options options;
    options.clock = [&] { return nowMicros; };
    if (session.codec)
        options.keys.codecs = {session.codec};
    FrameReceiver receiver(options, [&](const ReceivedFrame& f) {
        if (f.delivered())
            ledger.deliver(f, sent, row);
    });
    std::mt19937_64 rng(seed);
    std::bernoulli_distribution splice(rate);
    for (std::uint64_t i = 0; i < frames; ++i) {
        FrameBytes f = session.frameAt(i);
        if (i > 0 && i + 3 < frames && splice(rng)) {
            const std::uint64_t k = 1 + rng() % 3;
            const FrameBytes later = session.frameAt(i + k);
            const FlightPlanSection own = session.messageAt(i).flightPlan;
            const FlightPlanSection other = session.messageAt(i + k).flightPlan;
            result.undetectable += !(own == other) && (other.empty() || (other.sectionId == 0 && other.planId != own.planId));
            std::copy(later.begin() + kPreambleSize + kCodewordSize, later.end(),
                      f.begin() + kPreambleSize + kCodewordSize);
            ++result.attacks;
            sent = i + k + 1;
            nowMicros = session.secondsAt(i + k) * 1'000'000 + 500'000;
            receiver.feed(f);
            i += k;
            continue;
        }
        sent = i + 1;
        nowMicros = session.secondsAt(i) * 1'000'000 + 500'000;
        receiver.feed(f);
    }
    receiver.flush();
    row.sent = frames;
    row.lost = frames - row.correct;
    row.refused = receiver.stats().refused;
    return result;
}

enum class StreamDamage {
    CutThenIntact,   // every other frame cut short anywhere, the next one whole
    Overlap,         // each frame's last 1 .. 90 bytes overwritten by the next frame's start
    GarbageBetween,  // 1 .. 1200 bytes between frames: random, runs of 55, preamble pieces
    ByteSlips,       // 1 .. 8 bytes lost or inserted at a random place in every frame
    Mixed,           // each frame one of the above, or none, at random
    TwoByteSlips,    // two such slips in every frame
};

// A stream damaged as `damage` says; every frame libfec reads at its true
// place (both codewords decode to what was sent) must be delivered.
inline AttackResult runStreamDamage(const CommandSession& session, StreamDamage damage, std::uint64_t frames,
                                    std::uint64_t seed)
{
    AttackResult result;
    RowResult& row = result.row;
    DeliveryLedger ledger(session);
    std::int64_t nowMicros = 0;
    std::uint64_t sent = 0;
    FrameReceiver::Options options;
    options.clock = [&] { return nowMicros; };
    FrameReceiver receiver(options, [&](const ReceivedFrame& f) {
        if (f.delivered())
            ledger.deliver(f, sent, row);
    });
    std::mt19937_64 rng(seed);
    const auto uniform = [&](std::uint64_t lo, std::uint64_t hi) {
        return std::uniform_int_distribution<std::uint64_t>(lo, hi)(rng);
    };

    // The stream's bytes still needed to judge a frame with libfec.
    Bytes window;
    std::uint64_t windowBase = 0;
    struct Pending {
        std::uint64_t index;
        std::uint64_t codewords;  // stream offset of codeword 1
    };
    std::deque<Pending> pending;
    std::vector<std::uint64_t> recoverable;
    const auto judge = [&](bool final) {
        while (!pending.empty()) {
            const Pending p = pending.front();
            const std::uint64_t end = windowBase + window.size();
            if (p.codewords + kDatagramSize > end) {
                if (!final)
                    break;
                pending.pop_front();
                continue;
            }
            const FrameBytes sentFrame = session.frameAt(p.index);
            bool readable = true;
            for (std::size_t cw = 0; cw < 2 && readable; ++cw) {
                std::uint8_t c[kCodewordSize];
                std::memcpy(c, &window[p.codewords - windowBase + cw * kCodewordSize], kCodewordSize);
                readable = rs::decodeLibfec(c) >= 0 &&
                           std::equal(c, c + kBlockSize, sentFrame.begin() + kPreambleSize + cw * kCodewordSize);
            }
            if (readable)
                recoverable.push_back(p.index);
            pending.pop_front();
        }
        const std::uint64_t end = windowBase + window.size();
        const std::uint64_t keep = pending.empty() ? end : std::min(end, pending.front().codewords);
        if (keep > windowBase + 65536) {
            const std::uint64_t drop = keep - windowBase;
            window.erase(window.begin(), window.begin() + static_cast<std::ptrdiff_t>(drop));
            windowBase += drop;
        }
    };

    Bytes chunk;
    for (std::uint64_t i = 0; i < frames; ++i) {
        const FrameBytes f = session.frameAt(i);
        chunk.assign(f.begin(), f.end());
        std::uint64_t codewordsAt = kPreambleSize;  // within chunk
        StreamDamage kind = damage;
        if (damage == StreamDamage::Mixed) {
            kind = static_cast<StreamDamage>(rng() % 5);  // Mixed itself: none
            if (kind == StreamDamage::CutThenIntact)
                chunk.resize(uniform(1, kFrameSize - 1));
        }
        switch (kind) {
        case StreamDamage::Mixed:
            break;
        case StreamDamage::CutThenIntact:
            if (damage == StreamDamage::CutThenIntact && i % 2 == 0)
                chunk.resize(uniform(1, kFrameSize - 1));
            break;
        case StreamDamage::Overlap:
            chunk.resize(kFrameSize - uniform(1, 90));
            break;
        case StreamDamage::GarbageBetween: {
            const std::size_t n = uniform(1, 1200);
            const std::uint64_t kind = rng() % 4;
            for (std::size_t k = 0; k < n; ++k) {
                std::uint8_t b = static_cast<std::uint8_t>(rng());
                if (kind == 1)
                    b = kPad55;
                else if (kind == 2)
                    b = k % 90 < 88 ? kPad55 : kPreambleMark;  // preamble pieces
                chunk.push_back(b);
            }
            break;
        }
        case StreamDamage::ByteSlips:
        case StreamDamage::TwoByteSlips:
            for (int k = kind == StreamDamage::TwoByteSlips ? 2 : 1; k > 0; --k) {
                const std::size_t n = uniform(1, 8);
                const std::size_t at = uniform(0, chunk.size() - n);
                if (rng() & 1) {
                    chunk.erase(chunk.begin() + static_cast<std::ptrdiff_t>(at),
                                chunk.begin() + static_cast<std::ptrdiff_t>(at + n));
                    if (at < codewordsAt)
                        codewordsAt -= std::min<std::uint64_t>(n, codewordsAt - at);
                } else {
                    Bytes extra(n);
                    for (auto& b : extra)
                        b = static_cast<std::uint8_t>(rng());
                    chunk.insert(chunk.begin() + static_cast<std::ptrdiff_t>(at), extra.begin(), extra.end());
                    if (at <= codewordsAt)
                        codewordsAt += n;
                }
            }
            break;
        }
        const std::uint64_t start = windowBase + window.size();
        pending.push_back({i, start + codewordsAt});
        window.insert(window.end(), chunk.begin(), chunk.end());
        sent = i + 1;
        nowMicros = session.secondsAt(i) * 1'000'000 + 500'000;
        receiver.feed(chunk);
        judge(false);
    }
    receiver.flush();
    judge(true);
    for (std::uint64_t i : recoverable) {
        ++result.recoverable;
        if (!ledger.delivered(i) && ++result.falseRefusals == 1)
            result.firstFalseRefusal = "frame " + std::to_string(i);
    }
    row.sent = frames;
    row.lost = frames - row.correct;
    row.refused = receiver.stats().refused;
    return result;
}

// Outages: with probability `rate` after a frame the sender falls silent for
// 2 .. 600 s and sends nothing, its counter where it was (a satellite phone
// redialling); the receiver's clock runs on. The first frame after each
// outage must be delivered.
inline AttackResult runOutages(const CommandSession& session, std::uint64_t frames, double rate, std::uint64_t seed)
{
    AttackResult result;
    RowResult& row = result.row;
    std::int64_t nowMicros = 0;
    std::uint64_t delivered = 0;
    std::uint64_t firstAfter = 0, firstAfterDelivered = 0;
    FrameReceiver::Options options;
    options.clock = [&] { return nowMicros; };
    struct Expected {
        std::uint32_t id;
        Message message;
        bool firstAfterOutage;
    };
    std::deque<Expected> expected;  // the last few frames sent
    FrameReceiver receiver(options, [&](const ReceivedFrame& f) {
        if (!f.delivered())
            return;
        const auto id = static_cast<std::uint32_t>(f.decoded.message.header.number(ItemId::ID_msg));
        const auto it = std::find_if(expected.begin(), expected.end(), [&](const Expected& e) { return e.id == id; });
        if (it != expected.end() && f.decoded.message == it->message) {
            ++delivered;
            firstAfterDelivered += it->firstAfterOutage;
        } else if (++row.wrong == 1) {
            row.firstWrong = "at stream offset " + std::to_string(f.offset);
        }
    });
    std::mt19937_64 rng(seed);
    std::bernoulli_distribution outage(rate);
    std::int64_t silence = 0;  // seconds the sender's clock is ahead of its counter
    for (std::uint64_t i = 0; i < frames; ++i) {
        bool first = false;
        if (i > 0 && outage(rng)) {
            silence += static_cast<std::int64_t>(2 + rng() % 599);
            first = true;
            ++firstAfter;
            ++result.attacks;
        }
        // Frame i of the session, sent `silence` seconds late.
        Message m = session.messageAt(i);
        m.flightPlan = {};
        const std::int64_t t = session.secondsAt(i) + silence;
        m = advanceMessage(m, static_cast<std::uint32_t>(silence));
        m.header.set(ItemId::ID_msg, session.idAt(i));
        expected.push_back({session.idAt(i), m, first});
        if (expected.size() > 8)
            expected.pop_front();
        Diagnostics errors;
        const std::optional<FrameBytes> f = encodeFrame(m, errors);
        nowMicros = t * 1'000'000 + 500'000;
        receiver.feed(*f);
    }
    receiver.flush();
    row.sent = frames;
    row.correct = delivered;
    row.lost = frames - delivered;
    row.refused = receiver.stats().refused;
    result.recoverable = firstAfter;
    result.falseRefusals = firstAfter - firstAfterDelivered;
    return result;
}

}  // namespace rcm::test
