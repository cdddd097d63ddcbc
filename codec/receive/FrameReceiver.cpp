#include "codec/receive/FrameReceiver.h"

#include "codec/message/FlightPlanTransfer.h"
#include "codec/message/ItemTable.h"
#include "codec/message/MessageDecoder.h"
#include "codec/message/MessageEncoder.h"
#include "codec/message/ValueCodec.h"
#include "codec/receive/EncodedItems.h"
#include "codec/receive/TrialDecoder.h"
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

std::string codewordsDetail(const DecodedBlocks& b, bool block2Read)
{
    return std::string("block 1 ") + (b.corrected.block1 < 0 ? "beyond correction" : "good") + ", block 2 " +
           (!block2Read ? "not read" : b.corrected.block2 < 0 ? "beyond correction" : "good");
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

std::string planName(const FlightPlanSection& s)
{
    return "flight plan " + rcm::planIdText(s.planId) + " section " + std::to_string(s.sectionId);
}

// The data bytes section `id` of a plan with this descriptor carries, or
// nothing when the descriptor cannot describe a plan cut into sections.
std::optional<std::uint64_t> sectionBytes(const PlanProgress& p, std::uint16_t id)
{
    if (p.sectionCount == 1)
        return p.streamBytes;
    if (id + 1u < p.sectionCount)
        return p.sectionSize;
    return p.streamBytes - std::uint64_t{p.sectionSize} * (p.sectionCount - 1u);
}

// Does section `s`, `step` messages after the last accepted frame `h`, go on
// with what `h` showed of the plan being sent (docs/protocol.md section 3:
// sections 0 .. N-1, one per frame, in passes)?
Verdict planFits(const SenderHistory& h, std::uint32_t id, std::uint32_t step, const FlightPlanSection& s)
{
    if (s.empty() || s.sectionId >= kFirstControlSectionId)
        return {};
    const PlanProgress& p = h.plan;
    if (p.planId == 0 || s.planId != p.planId) {
        // A new plan starts at section 0; the first step - 1 frames of it may have been lost.
        if (s.sectionId < step)
            return {};
        return refuse(Refusal::PlanSection, planName(s) + " does not follow any plan being sent " + messagesLater(step));
    }
    // Counted from the frame that carried the last section: frames between
    // may have carried none.
    const std::uint32_t planStep = (id - p.sectionMessageId) & kIdMask;
    if (p.sectionCount != 0 && s.sectionId == 0) {
        // Section 0 with another descriptor starts that plan ID again.
        const std::optional<FlightPlanDescriptor> d = FlightPlanDescriptor::read(s.data);
        if (d && (d->sectionCount != p.sectionCount || d->crc != p.crc ||
                  FlightPlanDescriptor::kSize + std::uint64_t{d->totalBytes} != p.streamBytes ||
                  (p.sectionCount > 1 && s.data.size() != p.sectionSize)))
            return {};
    }
    if (p.sectionCount != 0) {
        const std::uint32_t n = p.sectionCount;
        if (s.sectionId >= n)
            return refuse(Refusal::PlanSection, planName(s) + ": the plan has " + std::to_string(n) + " sections");
        if (const std::optional<std::uint64_t> bytes = sectionBytes(p, s.sectionId); bytes && *bytes != s.data.size())
            return refuse(Refusal::PlanSection, planName(s) + " carries " + std::to_string(s.data.size()) +
                                                    " bytes; its plan's descriptor makes it " + std::to_string(*bytes));
        const std::uint32_t ahead = (s.sectionId + n - p.section) % n;
        if ((ahead >= 1 && ahead <= planStep) || (ahead == 0 && planStep >= n))
            return {};
    } else if ((s.sectionId > p.section && s.sectionId <= std::uint32_t{p.section} + planStep) || s.sectionId < planStep) {
        return {};
    }
    return refuse(Refusal::PlanSection,
                  planName(s) + " does not follow section " + std::to_string(p.section) + " " + messagesLater(planStep));
}

// Does a frame (ID `id`, stamp `seconds`, section `s`) follow `h`?
// `outage`: live, the seconds since the receiver accepted `h` (a sender that
// was cut off, a satellite phone redialling, may have sent nothing and kept
// its counter meanwhile); 0 for a recording.
Verdict follows(const SenderHistory& h, std::uint32_t id, std::int64_t seconds, const FlightPlanSection& s,
                std::int64_t outage)
{
    const std::uint32_t step = (id - h.messageId) & kIdMask;
    if (step == 0 || step >= rcm::kMessageIdModulus / 2)
        return refuse(Refusal::Replayed, "ID_msg " + std::to_string(id) + " is not ahead of the last accepted " +
                                             std::to_string(h.messageId));
    const std::int64_t maxStep = std::max<std::int64_t>(kMaxMessageIdStep, outage + kTimeStepSlackSeconds);
    if (step > maxStep)
        return refuse(Refusal::MessageIdStep, "ID_msg " + std::to_string(id) + " is " + std::to_string(step) +
                                                  " ahead of the last accepted; at most " + std::to_string(maxStep));
    const std::int64_t elapsed = seconds - h.stampSeconds;
    if (elapsed < 0 || elapsed > std::max<std::int64_t>(step, outage) + kTimeStepSlackSeconds)
        return refuse(Refusal::TimeStep, "time_UTC is " + std::to_string(elapsed) + " s after the last accepted, " +
                                             messagesLater(step) +
                                             (outage > step ? " and " + std::to_string(outage) + " s" : std::string()));
    return planFits(h, id, step, s);
}

// Section 0 carries the plan's descriptor: what every later section of the
// plan must fit. A descriptor that its own section contradicts is refused.
Verdict descriptorFits(const FlightPlanSection& s)
{
    if (s.empty() || s.sectionId != 0 || s.planId == 0)
        return {};
    const std::optional<FlightPlanDescriptor> d = FlightPlanDescriptor::read(s.data);
    const std::uint64_t stream = d ? FlightPlanDescriptor::kSize + std::uint64_t{d->totalBytes} : 0;
    const std::uint64_t size = s.data.size();
    const bool fits = d && d->sectionCount >= 1 && d->sectionCount <= kMaxFlightPlanSections &&
                      (d->sectionCount == 1 ? size == stream
                                            : (d->sectionCount - 1u) * size < stream && stream <= d->sectionCount * size);
    if (fits)
        return {};
    return refuse(Refusal::PlanSection, planName(s) + ": its descriptor does not fit a section of " +
                                            std::to_string(size) + " bytes");
}

// The frame refused, and why; false.
bool refuseFrame(ReceivedFrame& frame, Verdict v, bool keyed)
{
    frame.refusal = v.refusal;
    frame.detail = std::move(v.detail);
    if (keyed) {
        // Nothing read from a refused frame is passed on, authentic or not.
        frame.decoded.message = Message{};
        frame.decoded.diagnostics.clear();
    }
    return false;
}

// Keyed link: the blocks decrypted by the first key and direction they are
// authentic with, into frame.decoded; refused as plaintext or forged when
// none.
Verdict authentic(const std::vector<const secure::SecureCodec*>& codecs, const DecodedBlocks& blocks,
                  ReceivedFrame& frame, secure::HeaderStamp& stamp)
{
    bool plaintext = false;
    std::string why;
    for (const secure::SecureCodec* codec : codecs) {
        secure::Authenticated a = codec->decryptBlocks(blocks);
        if (a.authentic) {
            frame.decoded = std::move(a.decoded);
            stamp = a.stamp;
            frame.direction = codec->direction();
            return {};
        }
        plaintext = plaintext || a.rejection == secure::Rejection::Plaintext;
        why = codecs.size() == 1 ? a.detail : "sent in none of the directions given with this key";
    }
    frame.decoded = DecodeResult{};
    frame.decoded.corrected.block1 = blocks.corrected.block1;
    frame.decoded.corrected.block2 = blocks.corrected.block2;
    return plaintext ? refuse(Refusal::Plaintext, "an unencrypted message on a keyed link")
                     : refuse(Refusal::Forged, why);
}

// Live: the frame's stamp within the window around the receiver's clock.
Verdict inClockWindow(std::int64_t seconds, std::int64_t nowMicros, std::int64_t windowSeconds)
{
    const std::int64_t skew = seconds - nowMicros / 1'000'000;
    if (skew <= windowSeconds && skew >= -windowSeconds)
        return {};
    return refuse(Refusal::TimeWindow, "time_UTC/date_UTC is " + std::to_string(skew < 0 ? -skew : skew) + " s " +
                                           (skew < 0 ? "behind" : "ahead of") +
                                           " the receiver's clock; the window is " + std::to_string(windowSeconds) +
                                           " s");
}

// The replay guard shared with other receivers of the key: the stamp not
// seen before, and then remembered.
Verdict guardAccepts(secure::ReplayGuard& guard, const secure::HeaderStamp& stamp, std::string& warning)
{
    std::string detail;
    if (const std::optional<secure::Rejection> g = guard.check(stamp, &detail))
        return refuse(*g == secure::Rejection::Replayed ? Refusal::Replayed : Refusal::TimeWindow, detail);
    guard.accept(stamp, &warning);
    return {};
}

// The history a frame accepted after `before` leaves, written into `h`,
// which may be *before itself: assigning in place keeps the vectors'
// storage, which matters when a day's recording is read.
void fillHistory(SenderHistory& h, const DecodedBlocks& blocks, const Message& m, std::int64_t seconds,
                 std::int64_t nowMicros, const SenderHistory* before)
{
    PlanProgress plan = before ? before->plan : PlanProgress{};
    const std::uint64_t accepted = before ? before->accepted + 1 : 1;
    h.blocks = blocks;
    h.message = m;
    h.messageId = static_cast<std::uint32_t>(m.header.number(ItemId::ID_msg));
    h.stampSeconds = seconds;
    h.receivedMicros = nowMicros;
    h.accepted = accepted;
    const FlightPlanSection& s = m.flightPlan;
    if (!s.empty() && s.sectionId < kFirstControlSectionId) {
        if (s.planId != plan.planId)
            plan = PlanProgress{};
        plan.planId = s.planId;
        plan.section = s.sectionId;
        plan.sectionMessageId = h.messageId;
        if (s.sectionId == 0) {
            if (const std::optional<FlightPlanDescriptor> d = FlightPlanDescriptor::read(s.data)) {
                plan.sectionCount = d->sectionCount;
                plan.streamBytes = FlightPlanDescriptor::kSize + std::uint64_t{d->totalBytes};
                plan.sectionSize = static_cast<std::uint16_t>(s.data.size());
                plan.crc = d->crc;
            }
        }
    }
    h.plan = plan;
}

SenderHistory historyOf(const DecodedBlocks& blocks, const Message& m, std::int64_t seconds, std::int64_t nowMicros,
                        const SenderHistory* before)
{
    SenderHistory h;
    fillHistory(h, blocks, m, seconds, nowMicros, before);
    return h;
}

// Where the value bytes of one header item stand in an exact BLOCK 1.
struct ValueAt {
    std::size_t offset = 0;
    std::size_t size = 0;
};

std::optional<ValueAt> valueOf(const Block& b, ItemId want)
{
    std::optional<ValueAt> found;
    forEachEncodedItem(b, [&](const ItemInfo& info, std::size_t at) {
        if (info.id == want)
            found = ValueAt{at + 1, info.size};
        return !found;
    });
    return found;
}

std::uint32_t bigEndian(const std::uint8_t* p, std::size_t n)
{
    std::uint32_t v = 0;
    for (std::size_t i = 0; i < n; ++i)
        v = (v << 8) | p[i];
    return v;
}

}  // namespace

// A frame sent a second after another differs from it in ID_msg and
// time_UTC (and at midnight date_UTC) alone, as long as no command changed:
// such a frame is exact exactly when the last one was and its new header
// values are valid, and reads as the last one with those three values.
// Keeping the last exact plain frame saves decoding, encoding and comparing
// every frame of a long recording again.
struct FrameReceiver::Exactness {
    DecodedBlocks blocks;
    Message message;
    std::array<ValueAt, 3> values;  // ID_msg, time_UTC, date_UTC, in block order
    bool held = false;

    void keep(const DecodedBlocks& b, const Message& m)
    {
        held = false;
        const ItemId ids[3] = {ItemId::ID_msg, ItemId::time_UTC, ItemId::date_UTC};
        for (int i = 0; i < 3; ++i) {
            const std::optional<ValueAt> v = valueOf(b.block1, ids[i]);
            if (!v)
                return;
            values[static_cast<std::size_t>(i)] = *v;
        }
        blocks = b;
        message = m;
        held = true;
    }

    // True when `b` differs from the kept frame only in the three values,
    // and they are valid: then it is exact, and read() reads it.
    bool matches(const DecodedBlocks& b) const { return values3(b).has_value(); }

    // The message `b` holds when matches(b); false, `out` untouched, otherwise.
    bool read(const DecodedBlocks& b, Message& out) const
    {
        const std::optional<std::array<std::uint32_t, 3>> v = values3(b);
        if (!v)
            return false;
        out = message;
        out.header.set(ItemId::ID_msg, (*v)[0]);
        out.header.set(ItemId::time_UTC, (*v)[1]);
        out.header.set(ItemId::date_UTC, (*v)[2]);
        return true;
    }

private:
    std::optional<std::array<std::uint32_t, 3>> values3(const DecodedBlocks& b) const
    {
        if (!held || std::memcmp(b.block2.data(), blocks.block2.data(), kBlockSize) != 0)
            return std::nullopt;
        std::array<ValueAt, 3> sorted = values;
        std::sort(sorted.begin(), sorted.end(), [](const ValueAt& x, const ValueAt& y) { return x.offset < y.offset; });
        std::size_t from = 0;
        for (const ValueAt& v : sorted) {
            if (std::memcmp(b.block1.data() + from, blocks.block1.data() + from, v.offset - from) != 0)
                return std::nullopt;
            from = v.offset + v.size;
        }
        if (std::memcmp(b.block1.data() + from, blocks.block1.data() + from, kBlockSize - from) != 0)
            return std::nullopt;
        const std::uint32_t id = bigEndian(b.block1.data() + values[0].offset, values[0].size);
        const std::uint32_t time = bigEndian(b.block1.data() + values[1].offset, values[1].size);
        const std::uint32_t date = bigEndian(b.block1.data() + values[2].offset, values[2].size);
        if (!checkValue(itemInfo(ItemId::time_UTC), Value::of(time)).empty() ||
            !checkValue(itemInfo(ItemId::date_UTC), Value::of(date)).empty())
            return std::nullopt;
        return std::array<std::uint32_t, 3>{id, time, date};
    }
};

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
          ReceivedFrame& frame = freshFrame();
          frame.offset = s.offset;
          frame.raw = s.raw;
          frame.blocks = s.blocks;
          frame.preambleBitErrors = s.preambleBitErrors;
          judge(frame, s.raw.last<kDatagramSize>());
      },
             [this](const DecodedBlocks& blocks) { return exact(blocks); }),
      m_exactCache(std::make_unique<Exactness>())
{
    if (!m_options.clock)
        m_options.clock = systemUtcMicros;
    if (m_options.predictions)
        m_trial = std::make_unique<TrialDecoder>(m_options.prediction, !m_options.keys.codecs.empty());
}

FrameReceiver::~FrameReceiver() = default;

// One frame object, used again for every frame: its message's storage is
// kept, so a frame read like the last costs no allocation. Every field but
// the message is reset here; every path sets the message before it is read.
ReceivedFrame& FrameReceiver::freshFrame()
{
    ReceivedFrame& f = m_frame;
    f.offset = 0;
    f.raw = {};
    f.blocks = DecodedBlocks{};
    f.preambleBitErrors = 0;
    f.refusal.reset();
    f.detail.clear();
    f.decoded.diagnostics.clear();
    f.decoded.corrected = Corrections{};
    f.direction.reset();
    f.fromPrediction = false;
    f.warning.clear();
    return f;
}

bool FrameReceiver::exact(const DecodedBlocks& blocks) const
{
    if (!blocks.ok())
        return false;
    if (m_options.keys.codecs.empty()) {
        if (m_exactCache->matches(blocks))
            return true;
        DecodeResult r;
        if (exactPlain(blocks, r).refusal)
            return false;
        m_exactCache->keep(blocks, r.message);
        return true;
    }
    return std::any_of(m_options.keys.codecs.begin(), m_options.keys.codecs.end(),
                       [&](const secure::SecureCodec* c) { return c->decryptBlocks(blocks).authentic; });
}

void FrameReceiver::feed(std::span<const std::uint8_t> bytes) { m_sync.feed(bytes); }

void FrameReceiver::flush() { m_sync.flush(); }

void FrameReceiver::expect(const Message& sent)
{
    if (m_trial)
        m_trial->expect(sent);
}

std::uint64_t FrameReceiver::framesOfInput() const { return m_sync.stats().bytesIn / kFrameSize + m_datagrams; }

void FrameReceiver::reset()
{
    m_sync.reset();
    m_stats = Stats{};
    m_senders.clear();
    m_candidates.clear();
    m_last = nullptr;
    m_serial = 0;
    m_forgottenStamp.reset();
    m_datagrams = 0;
    *m_exactCache = Exactness{};
    if (m_trial)
        m_trial = std::make_unique<TrialDecoder>(m_options.prediction, !m_options.keys.codecs.empty());
}

void FrameReceiver::receive(std::span<const std::uint8_t> bytes, std::int64_t offset)
{
    ++m_datagrams;
    ReceivedFrame& frame = freshFrame();
    frame.offset = offset;
    frame.raw = bytes;
    if (bytes.size() != kDatagramSize && bytes.size() != kFrameSize) {
        frame.refusal = Refusal::WrongSize;
        frame.decoded.message = Message{};
        frame.detail = std::to_string(bytes.size()) + " bytes; a datagram is 510 and a frame 600";
        ++m_stats.refused[static_cast<std::size_t>(Refusal::WrongSize)];
        if (m_handler)
            m_handler(frame);
        return;
    }
    const std::span<const std::uint8_t, kDatagramSize> codewords = bytes.last<kDatagramSize>();
    // Codeword 2 is decoded only once codeword 1 is read (plainly, or by a
    // prediction): a frame whose BLOCK 1 cannot be read is refused whatever
    // BLOCK 2 holds, and a flood of random datagrams costs one decode each.
    std::uint8_t cw[kCodewordSize];
    std::memcpy(cw, codewords.data(), kCodewordSize);
    frame.blocks.corrected.block1 = rs::decode(cw);
    std::memcpy(frame.blocks.block1.data(), frame.blocks.corrected.block1 >= 0 ? cw : codewords.data(), kBlockSize);
    std::memcpy(frame.blocks.block2.data(), codewords.data() + kCodewordSize, kBlockSize);
    frame.blocks.corrected.block2 = -1;
    m_block2Read = frame.blocks.corrected.block1 >= 0;
    if (m_block2Read) {
        std::memcpy(cw, codewords.data() + kCodewordSize, kCodewordSize);
        frame.blocks.corrected.block2 = rs::decode(cw);
        if (frame.blocks.corrected.block2 >= 0)
            std::memcpy(frame.blocks.block2.data(), cw, kBlockSize);
    }
    judge(frame, codewords);
    m_block2Read = true;
}

void FrameReceiver::judge(ReceivedFrame& frame, std::span<const std::uint8_t, kDatagramSize> codewords)
{
    const DecodedBlocks plain = frame.blocks;
    // Predictions can only mend bytes: not a frame that was read right and
    // refused for what it says (plaintext, not plausible).
    const auto mendable = [](Refusal r) { return r != Refusal::Plaintext && r < Refusal::Replayed; };
    if (!accept(frame, plain, true) && m_trial && mendable(*frame.refusal)) {
        const std::int64_t now = m_options.mode == Mode::Live ? m_options.clock() : 0;
        const TrialDecoder::Candidates tried = m_trial->candidates(codewords, plain, m_block2Read, *this, now);
        m_stats.predictionUnits += tried.units;
        m_stats.predictionsCut += tried.cut;
        for (const DecodedBlocks& candidate : tried.blocks) {
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
    if (m_trial)
        m_trial->observe(codewords, frame, frame.delivered() ? m_last : nullptr);
    if (m_handler)
        m_handler(frame);
}

SenderHistory& FrameReceiver::keepHistory(std::uint32_t key, SenderHistory h)
{
    h.serial = ++m_serial;
    auto [it, inserted] = m_senders.insert_or_assign(key, std::move(h));
    if (m_senders.size() > kMaxSenders) {
        // The sender with the fewest frames accepted goes (the longest
        // unheard of those): a flood of one-frame senders replaces its own
        // kind, not the aircraft heard every second.
        auto victim = m_senders.end();
        for (auto s = m_senders.begin(); s != m_senders.end(); ++s) {
            if (s == it)
                continue;
            if (victim == m_senders.end() || s->second.accepted < victim->second.accepted ||
                (s->second.accepted == victim->second.accepted && s->second.serial < victim->second.serial))
                victim = s;
        }
        m_forgottenStamp = std::max(m_forgottenStamp.value_or(victim->second.stampSeconds), victim->second.stampSeconds);
        m_candidates.erase(victim->first);
        m_senders.erase(victim);
        ++m_stats.sendersForgotten;
    }
    return it->second;
}

bool FrameReceiver::accept(ReceivedFrame& frame, const DecodedBlocks& blocks, bool remember)
{
    frame.blocks = blocks;
    const bool keyed = !m_options.keys.codecs.empty();
    const auto no = [&](Verdict v) { return refuseFrame(frame, std::move(v), keyed); };
    if (!blocks.ok()) {
        // A keyed link's blocks are ciphertext: nothing in them can be read.
        if (!keyed)
            frame.decoded = decodeBlocks(blocks);
        frame.decoded.corrected.block1 = blocks.corrected.block1;
        frame.decoded.corrected.block2 = blocks.corrected.block2;
        return no(refuse(Refusal::Uncorrectable, codewordsDetail(blocks, m_block2Read || blocks.corrected.block1 >= 0)));
    }

    // Exact: authentic on a keyed link (which checks more than the plain
    // rules), the plain rules otherwise.
    DecodeResult& r = frame.decoded;
    secure::HeaderStamp stamp;
    if (keyed) {
        if (Verdict v = authentic(m_options.keys.codecs, blocks, frame, stamp); v.refusal)
            return no(std::move(v));
    } else if (!m_exactCache->read(blocks, r.message)) {
        r = DecodeResult{};
        if (Verdict v = exactPlain(blocks, r); v.refusal)
            return no(std::move(v));
        m_exactCache->keep(blocks, r.message);
    }
    r.corrected.block1 = blocks.corrected.block1;
    r.corrected.block2 = blocks.corrected.block2;

    // Plausible.
    const std::optional<std::int64_t> seconds = stampOf(r.message);
    if (!seconds)
        return no(refuse(Refusal::InvalidField, "time_UTC/date_UTC is not a valid time"));
    const bool live = m_options.mode == Mode::Live;
    const std::int64_t nowMicros = live ? m_options.clock() : 0;
    if (live)
        if (Verdict v = inClockWindow(*seconds, nowMicros, m_options.clockWindowSeconds); v.refusal)
            return no(std::move(v));
    if (Verdict v = descriptorFits(r.message.flightPlan); v.refusal)
        return no(std::move(v));
    const std::uint32_t key = senderKey(r.message);
    const std::uint32_t id = static_cast<std::uint32_t>(r.message.header.number(ItemId::ID_msg));
    const auto known = m_senders.find(key);
    const SenderHistory* before = known == m_senders.end() ? nullptr : &known->second;
    const auto outage = [&](const SenderHistory& h) -> std::int64_t {
        return live ? std::max<std::int64_t>(0, (nowMicros - h.receivedMicros + 999'999) / 1'000'000) : 0;
    };
    if (before) {
        Verdict v = follows(*before, id, *seconds, r.message.flightPlan, outage(*before));
        if (v.refusal) {
            // A sender restarted, or was out of reach for long: recognised by
            // a stamp later than the last accepted one, which no frame sent
            // before it can have, and confirmed by a next frame that follows.
            // A plan section out of place is no sign of either.
            const bool restart = *v.refusal == Refusal::Replayed || *v.refusal == Refusal::MessageIdStep ||
                                 *v.refusal == Refusal::TimeStep;
            if (!restart || *seconds <= before->stampSeconds)
                return no(std::move(v));
            const auto candidate = m_candidates.find(key);
            if (candidate == m_candidates.end() ||
                follows(candidate->second, id, *seconds, r.message.flightPlan, outage(candidate->second)).refusal) {
                if (remember)
                    m_candidates[key] = historyOf(blocks, r.message, *seconds, nowMicros, nullptr);
                return no(std::move(v));
            }
            before = &candidate->second;
        }
    } else if (m_forgottenStamp && *seconds < *m_forgottenStamp - m_options.clockWindowSeconds) {
        // A sender not (or no longer) known, older than one forgotten: it
        // may be that sender's frames again.
        return no(refuse(Refusal::Replayed, "time_UTC/date_UTC is older than the frames of senders no longer followed"));
    }
    if (m_options.keys.guard)
        if (Verdict v = guardAccepts(*m_options.keys.guard, stamp, frame.warning); v.refusal)
            return no(std::move(v));

    if (known != m_senders.end() && before == &known->second) {
        // The common case: the sender's next frame, written over its last.
        fillHistory(known->second, blocks, r.message, *seconds, nowMicros, before);
        known->second.serial = ++m_serial;
        m_candidates.erase(key);
        m_last = &known->second;
        return true;
    }
    SenderHistory h = historyOf(blocks, r.message, *seconds, nowMicros, before);  // `before` may be a candidate
    m_candidates.erase(key);
    m_last = &keepHistory(key, std::move(h));
    return true;
}

}  // namespace rcm
