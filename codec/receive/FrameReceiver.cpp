#include "codec/receive/FrameReceiver.h"

#include "codec/message/FlightPlanTransfer.h"
#include "codec/message/MessageEncoder.h"
#include "codec/secure/SecureCodec.h"

#include <algorithm>
#include <chrono>
#include <cstring>
#include <utility>

namespace rcm {
namespace {

constexpr std::uint32_t kIdMask = rcm::kMessageIdModulus - 1;

std::int64_t systemUtcMicros()
{
    using namespace std::chrono;
    return duration_cast<microseconds>(system_clock::now().time_since_epoch()).count();
}

struct Verdict {
    std::optional<Refusal> refusal;
    std::string detail;
};

Verdict refuse(Refusal r, std::string detail) { return {r, std::move(detail)}; }

Refusal refusalFor(Diagnostic::Kind kind)
{
    using Kind = Diagnostic::Kind;
    switch (kind) {
    case Kind::OutOfRange:
    case Kind::CorruptField:
    case Kind::ReservedBits:
        return Refusal::InvalidField;
    case Kind::UnknownItem:
    case Kind::Truncated:
        return Refusal::UnknownItem;
    case Kind::BadPadding:
        return Refusal::BadPadding;
    case Kind::Uncorrectable:
        return Refusal::Uncorrectable;
    case Kind::Forged:
        return Refusal::Forged;
    default:
        return Refusal::Warning;
    }
}

std::uint32_t senderKey(const Message& m)
{
    const Value* v = m.header.find(ItemId::ID_UA_source);
    return v ? static_cast<std::uint32_t>((v->number << 16) | v->second) : 0;
}

std::string codewordsDetail(const DecodedBlocks& b)
{
    return std::string("block 1 ") + (b.corrected.block1 < 0 ? "beyond correction" : "good") + ", block 2 " +
           (b.corrected.block2 < 0 ? "beyond correction" : "good");
}

// Ciphertext looks random: about one byte in 256 is 55, where a plain
// frame's padding (BLOCK 1's, or an empty BLOCK 2's 215 bytes) has dozens,
// and BLOCK 1 holds some 150 distinct byte values, where a run of one
// value (a preamble followed by constant bytes) holds one.
bool looksEnciphered(const DecodedBlocks& b)
{
    const auto count = std::count(b.block1.begin(), b.block1.end(), kPad55) +
                       std::count(b.block2.begin(), b.block2.end(), kPad55);
    bool seen[256] = {};
    int distinct = 0;
    for (std::uint8_t x : b.block1)
        distinct += !std::exchange(seen[x], true);
    return count < 8 && distinct >= 64;
}

// The exactness rules of docs/protocol.md section 8 for a plain frame whose
// codewords decoded. Fills `r` with everything read.
Verdict exactPlain(const DecodedBlocks& blocks, DecodeResult& r)
{
    std::size_t loose = 0;
    decodeBlock1(blocks.block1, r.message, r.diagnostics, &loose);
    decodeBlock2(blocks.block2, r.message.flightPlan, r.diagnostics);
    if (!r.diagnostics.empty()) {
        if (looksEnciphered(blocks))
            return refuse(Refusal::Enciphered, "the blocks look enciphered, and no key was given");
        const Diagnostic& d = r.diagnostics.front();
        return refuse(refusalFor(d.kind), d.toString());
    }
    // Padding first, then items back to back to the end of the block: what
    // the profile's encoder writes. The decoder skips 55, AA, BEGIN and END
    // anywhere, which lets a block read a few bytes off still decode.
    const auto first = std::find_if(blocks.block1.begin(), blocks.block1.end(), [](std::uint8_t b) { return b != kPad55; });
    if (first != blocks.block1.end() && (*first == kPadAA || *first == kBegin || *first == kEnd))
        return refuse(Refusal::BadPadding, "block 1 offset " + std::to_string(first - blocks.block1.begin()) +
                                               ": BEGIN, END or padding AA where items belong");
    if (loose != 0)
        return refuse(Refusal::BadPadding,
                      "block 1: " + std::to_string(loose) + " bytes between or after the items are not items");
    const Unit& h = r.message.header;
    for (ItemId id : {ItemId::ID_msg, ItemId::time_UTC, ItemId::date_UTC})
        if (!h.has(id))
            return refuse(Refusal::MissingHeaderItem, "block 1: no " + std::string(itemInfo(id).name));
    const FlightPlanSection& s = r.message.flightPlan;
    if (s.planId == 0 && !s.empty())
        return refuse(Refusal::InvalidField, "block 2: flight_plan_ID 0 with a section or data");
    Diagnostics errors;
    const std::optional<EncodedBlocks> again = encodeBlocks(r.message, errors);
    if (!again || again->block1 != blocks.block1 || again->block2 != blocks.block2)
        return refuse(Refusal::NotCanonical, "block 1: items not in the order the profile's encoder writes them");
    return {};
}

std::optional<std::int64_t> stampOf(const Message& m)
{
    return secure::stampSeconds(static_cast<std::uint32_t>(m.header.number(ItemId::time_UTC)),
                                static_cast<std::uint32_t>(m.header.number(ItemId::date_UTC)));
}

// "1 message later", "3 messages later".
std::string messagesLater(std::uint32_t step)
{
    return std::to_string(step) + (step == 1 ? " message later" : " messages later");
}

// Does a frame (ID `id`, stamp `seconds`, section `s`) follow `h`?
Verdict follows(const SenderHistory& h, std::uint32_t id, std::int64_t seconds, const FlightPlanSection& s)
{
    const std::uint32_t step = (id - h.messageId) & kIdMask;
    if (step == 0 || step >= rcm::kMessageIdModulus / 2)
        return refuse(Refusal::Replayed, "ID_msg " + std::to_string(id) + " is not ahead of the last accepted " +
                                             std::to_string(h.messageId));
    if (step > kMaxMessageIdStep)
        return refuse(Refusal::MessageIdStep, "ID_msg " + std::to_string(id) + " is " + std::to_string(step) +
                                                  " ahead of the last accepted; at most " +
                                                  std::to_string(kMaxMessageIdStep));
    const std::int64_t elapsed = seconds - h.stampSeconds;
    if (elapsed < 0 || elapsed > std::int64_t{step} + kTimeStepSlackSeconds)
        return refuse(Refusal::TimeStep,
                      "time_UTC is " + std::to_string(elapsed) + " s after the last accepted, " + messagesLater(step));
    if (s.empty() || s.sectionId >= kFirstControlSectionId)
        return {};
    // A new plan starts at section 0; a plan being sent goes on, or wraps
    // to section 0 for its next pass; lost frames may have carried some.
    const bool fits = s.sectionId < step || (s.planId == h.planId && s.sectionId <= std::uint32_t{h.section} + step);
    if (!fits)
        return refuse(Refusal::PlanSection, "flight plan " + rcm::planIdText(s.planId) + " section " +
                                                std::to_string(s.sectionId) + " does not follow " +
                                                (s.planId == h.planId ? "section " + std::to_string(h.section)
                                                                      : std::string("any plan being sent")) +
                                                " " + messagesLater(step));
    return {};
}

SenderHistory historyOf(const DecodedBlocks& blocks, const Message& m, std::int64_t seconds, const SenderHistory* before)
{
    SenderHistory h;
    h.blocks = blocks;
    h.message = m;
    h.messageId = static_cast<std::uint32_t>(m.header.number(ItemId::ID_msg));
    h.stampSeconds = seconds;
    const FlightPlanSection& s = m.flightPlan;
    if (!s.empty() && s.sectionId < kFirstControlSectionId) {
        h.planId = s.planId;
        h.section = s.sectionId;
    } else if (before) {
        h.planId = before->planId;
        h.section = before->section;
    }
    return h;
}

}  // namespace

std::string_view refusalName(Refusal r)
{
    switch (r) {
    case Refusal::Uncorrectable: return "uncorrectable";
    case Refusal::WrongSize: return "wrong size";
    case Refusal::Enciphered: return "enciphered";
    case Refusal::Forged: return "forged";
    case Refusal::Plaintext: return "plaintext";
    case Refusal::MissingHeaderItem: return "not exact: missing header item";
    case Refusal::BadPadding: return "not exact: bad padding";
    case Refusal::InvalidField: return "not exact: invalid field";
    case Refusal::UnknownItem: return "not exact: unknown item";
    case Refusal::NotCanonical: return "not exact: not canonical";
    case Refusal::Warning: return "not exact: warning";
    case Refusal::Replayed: return "replayed";
    case Refusal::MessageIdStep: return "implausible: message id step";
    case Refusal::TimeStep: return "implausible: time step";
    case Refusal::TimeWindow: return "stale time";
    case Refusal::PlanSection: return "implausible: plan section";
    }
    return "?";
}

std::uint64_t FrameReceiver::Stats::refusedTotal() const
{
    std::uint64_t n = 0;
    for (std::uint64_t r : refused)
        n += r;
    return n;
}

FrameReceiver::FrameReceiver(Options options, Handler handler)
    : m_options(std::move(options)),
      m_handler(std::move(handler)),
      m_sync([this](const SyncedFrame& s) {
          ReceivedFrame frame;
          frame.offset = s.offset;
          frame.raw = s.raw;
          frame.blocks = s.blocks;
          frame.preambleBitErrors = s.preambleBitErrors;
          judge(frame, s.raw.last<kDatagramSize>());
      },
             [this](const DecodedBlocks& blocks) { return exact(blocks); })
{
    if (!m_options.clock)
        m_options.clock = systemUtcMicros;
}

FrameReceiver::~FrameReceiver() = default;

bool FrameReceiver::exact(const DecodedBlocks& blocks) const
{
    if (!blocks.ok())
        return false;
    if (m_options.keys.codecs.empty()) {
        DecodeResult r;
        return !exactPlain(blocks, r).refusal;
    }
    return std::any_of(m_options.keys.codecs.begin(), m_options.keys.codecs.end(),
                       [&](const secure::SecureCodec* c) { return c->decryptBlocks(blocks).authentic; });
}

void FrameReceiver::feed(std::span<const std::uint8_t> bytes) { m_sync.feed(bytes); }

void FrameReceiver::flush() { m_sync.flush(); }

void FrameReceiver::reset()
{
    m_sync.reset();
    m_stats = Stats{};
    m_senders.clear();
    m_candidates.clear();
    m_last = nullptr;
}

void FrameReceiver::receive(std::span<const std::uint8_t> bytes, std::int64_t offset)
{
    ReceivedFrame frame;
    frame.offset = offset;
    frame.raw = bytes;
    if (bytes.size() != kDatagramSize && bytes.size() != kFrameSize) {
        frame.refusal = Refusal::WrongSize;
        frame.detail = std::to_string(bytes.size()) + " bytes; a datagram is 510 and a frame 600";
        ++m_stats.refused[static_cast<std::size_t>(Refusal::WrongSize)];
        if (m_handler)
            m_handler(frame);
        return;
    }
    const std::span<const std::uint8_t, kDatagramSize> codewords = bytes.last<kDatagramSize>();
    frame.blocks = decodeCodewords(codewords);
    judge(frame, codewords);
}

void FrameReceiver::judge(ReceivedFrame& frame, std::span<const std::uint8_t, kDatagramSize> codewords)
{
    const DecodedBlocks plain = frame.blocks;
    // Predictions can only mend bytes: not a frame that was read right and
    // refused for what it says (plaintext, not plausible).
    const auto mendable = [](Refusal r) { return r != Refusal::Plaintext && r < Refusal::Replayed; };
    if (!accept(frame, plain, true) && m_options.retry && mendable(*frame.refusal)) {
        for (const DecodedBlocks& candidate : m_options.retry(codewords, plain, *this)) {
            ReceivedFrame trial = frame;
            trial.refusal.reset();
            trial.detail.clear();
            trial.decoded = DecodeResult{};
            if (accept(trial, candidate, false)) {
                trial.fromPrediction = true;
                frame = std::move(trial);
                break;
            }
        }
    }
    if (frame.refusal) {
        ++m_stats.refused[static_cast<std::size_t>(*frame.refusal)];
    } else {
        ++m_stats.delivered;
        m_stats.fromPrediction += frame.fromPrediction;
    }
    if (m_handler)
        m_handler(frame);
}

bool FrameReceiver::accept(ReceivedFrame& frame, const DecodedBlocks& blocks, bool remember)
{
    frame.blocks = blocks;
    const bool keyed = !m_options.keys.codecs.empty();
    const auto no = [&](Verdict v) {
        frame.refusal = v.refusal;
        frame.detail = std::move(v.detail);
        if (keyed) {
            // Nothing read from a refused frame is passed on, authentic or not.
            frame.decoded.message = Message{};
            frame.decoded.diagnostics.clear();
        }
        return false;
    };
    if (!blocks.ok()) {
        // A keyed link's blocks are ciphertext: nothing in them can be read.
        if (!keyed)
            frame.decoded = decodeBlocks(blocks);
        frame.decoded.corrected.block1 = blocks.corrected.block1;
        frame.decoded.corrected.block2 = blocks.corrected.block2;
        return no(refuse(Refusal::Uncorrectable, codewordsDetail(blocks)));
    }

    // Exact: authentic on a keyed link (which checks more than the plain
    // rules), the plain rules otherwise.
    DecodeResult& r = frame.decoded;
    secure::HeaderStamp stamp;
    if (keyed) {
        bool plaintext = false;
        std::string why;
        for (const secure::SecureCodec* codec : m_options.keys.codecs) {
            secure::Authenticated a = codec->decryptBlocks(blocks);
            if (a.authentic) {
                r = std::move(a.decoded);
                stamp = a.stamp;
                frame.direction = codec->direction();
                break;
            }
            plaintext = plaintext || a.rejection == secure::Rejection::Plaintext;
            why = m_options.keys.codecs.size() == 1 ? a.detail : "sent in none of the directions given with this key";
        }
        if (!frame.direction) {
            r = DecodeResult{};
            r.corrected.block1 = blocks.corrected.block1;
            r.corrected.block2 = blocks.corrected.block2;
            return no(plaintext ? refuse(Refusal::Plaintext, "an unencrypted message on a keyed link")
                                : refuse(Refusal::Forged, why));
        }
    } else if (Verdict v = exactPlain(blocks, r); v.refusal) {
        return no(std::move(v));
    }
    r.corrected.block1 = blocks.corrected.block1;
    r.corrected.block2 = blocks.corrected.block2;

    // Plausible.
    const std::optional<std::int64_t> seconds = stampOf(r.message);
    if (!seconds)
        return no(refuse(Refusal::InvalidField, "time_UTC/date_UTC is not a valid time"));
    if (m_options.mode == Mode::Live) {
        const std::int64_t skew = *seconds - m_options.clock() / 1'000'000;
        if (skew > m_options.clockWindowSeconds || skew < -m_options.clockWindowSeconds)
            return no(refuse(Refusal::TimeWindow, "time_UTC/date_UTC is " + std::to_string(skew < 0 ? -skew : skew) +
                                                      " s " + (skew < 0 ? "behind" : "ahead of") +
                                                      " the receiver's clock; the window is " +
                                                      std::to_string(m_options.clockWindowSeconds) + " s"));
    }
    const std::uint32_t key = senderKey(r.message);
    const std::uint32_t id = static_cast<std::uint32_t>(r.message.header.number(ItemId::ID_msg));
    const auto known = m_senders.find(key);
    const SenderHistory* before = known == m_senders.end() ? nullptr : &known->second;
    if (before) {
        Verdict v = follows(*before, id, *seconds, r.message.flightPlan);
        if (v.refusal) {
            // A sender restarted, or was out of reach for long: a frame that
            // follows the last one refused this way confirms both.
            const auto candidate = m_candidates.find(key);
            if (candidate == m_candidates.end() ||
                follows(candidate->second, id, *seconds, r.message.flightPlan).refusal) {
                if (remember)
                    m_candidates[key] = historyOf(blocks, r.message, *seconds, nullptr);
                return no(std::move(v));
            }
            before = &candidate->second;
        }
    }
    if (m_options.keys.guard) {
        std::string detail;
        if (const std::optional<secure::Rejection> g = m_options.keys.guard->check(stamp, &detail))
            return no(refuse(*g == secure::Rejection::Replayed ? Refusal::Replayed : Refusal::TimeWindow, detail));
        m_options.keys.guard->accept(stamp, &frame.warning);
    }

    SenderHistory h = historyOf(blocks, r.message, *seconds, before);
    m_candidates.erase(key);
    m_last = &(m_senders[key] = std::move(h));
    return true;
}

}  // namespace rcm
