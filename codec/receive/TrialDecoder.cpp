#include "codec/receive/TrialDecoder.h"

#include "codec/frame/ReedSolomon.h"
#include "codec/message/FlightPlanTransfer.h"
#include "codec/message/ItemTable.h"
#include "codec/message/MessageDecoder.h"
#include "codec/message/MessageEncoder.h"
#include "codec/message/MessagePrediction.h"
#include "codec/receive/EncodedItems.h"

#include <algorithm>
#include <bit>
#include <cstring>
#include <optional>

namespace rcm {
namespace {

constexpr std::uint32_t kIdMask = rcm::kMessageIdModulus - 1;

// What the budget charges, in units of about a microsecond of one core of
// the reference machine (docs/performance.md).
constexpr std::uint64_t kTrialUnits = 3;      // rs::decodeWithPrediction
constexpr std::uint64_t kDecodeUnits = 8;     // rs::decode of a word beyond correction
constexpr std::uint64_t kErasureDecodeUnits = 20;  // rs::decodeWithErasures: 2-3 decodes beyond correction
constexpr std::uint64_t kEncodeUnits = 5;     // encodeBlocks
constexpr std::uint64_t kCodewordUnits = 1;   // rs::encode
constexpr std::uint64_t kEncipherUnits = 2;   // one block through HCTR2
constexpr std::uint64_t kCompareUnits = 1;    // a parity distance, a pass over the recent copies

constexpr std::size_t kRecentFrames = 4;       // plain link: frames whose agreeing bytes are taken
constexpr std::size_t kMaxSections = 128;      // plan sections kept for later passes
constexpr std::size_t kMaxBlock2Copies = 64;   // codewords 2 kept to combine
constexpr std::size_t kMaxCombined = 8;        // copies of one section combined at most
constexpr std::size_t kSimilarBytes = 96;      // of 223: two copies of one section agree in far more
constexpr int kMaxExpectedVariants = 6;
// Plain link, a change of several commands on its first frame: at most this
// many command bytes erased, and 2e + f within kErasureTrialReach (a wrong
// codeword no likelier than within a trial's 12 corrections: docs/protocol.md
// section 9).
constexpr std::size_t kMaxErasedCommandBytes = 16;
constexpr int kErasureTrialReach = 20;
constexpr std::size_t kMaxAcknowledgements = 4; // plans this end sent, whose acknowledgement may come        // keyed: changes of one command left out or taken alone

using Codeword = std::array<std::uint8_t, kCodewordSize>;

Codeword codewordOf(const Block& data)
{
    Codeword c;
    std::memcpy(c.data(), data.data(), kBlockSize);
    rs::encode(c.data(), c.data() + kBlockSize);
    return c;
}

Codeword copyOf(const std::uint8_t* bytes)
{
    Codeword c;
    std::memcpy(c.data(), bytes, kCodewordSize);
    return c;
}

std::optional<EncodedBlocks> encodeAsSent(const Message& m, bool keyed)
{
    Diagnostics errors;
    return encodeBlocks(m, errors, keyed ? secure::encodeOptions() : EncodeOptions{});
}

// BLOCK 2 (plaintext) carrying `section`, as a sender encodes it.
std::optional<Block> block2Of(const FlightPlanSection& section, bool keyed)
{
    Message m;
    m.flightPlan = section;
    const std::optional<EncodedBlocks> enc = encodeAsSent(m, keyed);
    return enc ? std::optional<Block>(enc->block2) : std::nullopt;
}

// Where ID_msg, time_UTC and date_UTC's value bytes stand in an encoded BLOCK 1.
struct HeaderPlaces {
    std::size_t id = 0, time = 0, date = 0;
    bool found = false;
};

HeaderPlaces headerPlacesOf(const Block& b)
{
    HeaderPlaces h;
    int seen = 0;
    forEachEncodedItem(b, [&](const ItemInfo& info, std::size_t at) {
        if (info.id == ItemId::ID_msg)
            h.id = at + 1, ++seen;
        else if (info.id == ItemId::time_UTC)
            h.time = at + 1, ++seen;
        else if (info.id == ItemId::date_UTC)
            h.date = at + 1, ++seen;
        return true;
    });
    h.found = seen == 3;
    return h;
}

void put24(Block& b, std::size_t at, std::uint32_t v)
{
    b[at] = static_cast<std::uint8_t>(v >> 16);
    b[at + 1] = static_cast<std::uint8_t>(v >> 8);
    b[at + 2] = static_cast<std::uint8_t>(v);
}

// `base` (whose header says `stamp`) as its sender sends it n seconds on with
// its clock t seconds on: a sender's clock and its counter need not tick together.
std::optional<std::pair<Block, secure::HeaderStamp>> advanced(const Block& base, const HeaderPlaces& at,
                                                              const secure::HeaderStamp& stamp, std::uint32_t n,
                                                              std::uint32_t t)
{
    secure::HeaderStamp s = stamp;
    s.messageId = (stamp.messageId + n) & kIdMask;
    if (!advanceTimeAndDate(s.timeUtc, s.dateUtc, t))
        return std::nullopt;
    Block b = base;
    put24(b, at.id, s.messageId);
    put24(b, at.time, s.timeUtc);
    put24(b, at.date, s.dateUtc);
    return std::make_pair(b, s);
}

secure::HeaderStamp stampOf(const Message& m)
{
    return {static_cast<std::uint32_t>(m.header.number(ItemId::ID_msg)),
            static_cast<std::uint32_t>(m.header.number(ItemId::time_UTC)),
            static_cast<std::uint32_t>(m.header.number(ItemId::date_UTC))};
}

// Offsets in an encoded BLOCK 1 of the value bytes of every item outside the
// header: what an operator's command changes.
std::vector<std::size_t> commandValueBytes(const Block& plain)
{
    std::vector<std::size_t> at;
    forEachEncodedItem(plain, [&](const ItemInfo& info, std::size_t p) {
        if (info.owner != UnitKind::Header)
            for (std::size_t j = 1; j <= info.size; ++j)
                at.push_back(p + j);
        return true;
    });
    return at;
}

// Gaps 1 .. max, the likeliest first.
std::vector<std::uint32_t> gapOrder(std::uint32_t max, std::uint32_t estimate)
{
    estimate = std::clamp<std::uint32_t>(estimate, 1, std::max<std::uint32_t>(max, 1));
    std::vector<std::uint32_t> order;
    order.reserve(max);
    for (std::uint32_t d = 0; order.size() < max; ++d) {
        if (estimate + d <= max)
            order.push_back(estimate + d);
        if (d != 0 && estimate > d)
            order.push_back(estimate - d);
    }
    return order;
}

// What BLOCK 1 of `d` says, as a history to predict the next frame from;
// BLOCK 2 as in `before`.
std::optional<SenderHistory> block1History(const DecodedBlocks& d, const secure::SecureCodec* codec,
                                           const SenderHistory& before, std::int64_t nowMicros)
{
    SenderHistory h = before;
    Diagnostics diagnostics;
    if (codec) {
        DecodedBlocks only = d;
        only.corrected.block2 = -1;
        secure::Authenticated a = codec->decryptBlocks(only);
        if (!a.authentic)
            return std::nullopt;
        h.message = std::move(a.decoded.message);
    } else {
        h.message = Message{};
        decodeBlock1(d.block1, h.message, diagnostics);
        if (!diagnostics.empty())
            return std::nullopt;
    }
    h.blocks.block1 = d.block1;
    h.message.flightPlan = before.message.flightPlan;
    h.messageId = static_cast<std::uint32_t>(h.message.header.number(ItemId::ID_msg));
    if (nowMicros != 0)
        h.receivedMicros = nowMicros;
    return h;
}

}  // namespace

// The work of one call, paid from the budget.
struct TrialDecoder::Work {
    std::uint64_t& units;
    std::uint64_t spent = 0;
    bool cut = false;
    bool take(std::uint64_t n)
    {
        if (cut || units < n) {
            cut = true;
            return false;
        }
        units -= n;
        spent += n;
        return true;
    }
};

struct TrialDecoder::Found {
    Block block{};  // BLOCK 1 as sent (enciphered on a keyed link)
    int corrected = -1;
    secure::HeaderStamp stamp;
};

TrialDecoder::TrialDecoder(PredictionOptions options, bool keyed)
    : m_options(options), m_keyed(keyed), m_units(options.maxUnits)
{
    // Never reallocated: predictionsFor() hands out references into it.
    m_predictions.reserve(2 * m_options.maxSenders + 2);
}

TrialDecoder::~TrialDecoder() = default;

void TrialDecoder::expect(const Message& sent)
{
    // A plan this end sends: the far end's acknowledgement of it echoes its
    // descriptor, which section 0 carries.
    const FlightPlanSection& s = sent.flightPlan;
    if (s.planId != 0 && s.sectionId == 0) {
        if (const std::optional<FlightPlanDescriptor> d = FlightPlanDescriptor::read(s.data)) {
            const FlightPlanSection ack = FlightPlanAcknowledgement{s.planId, *d, {}}.toSection();
            if (std::find(m_acknowledgements.begin(), m_acknowledgements.end(), ack) == m_acknowledgements.end()) {
                m_acknowledgements.push_front(ack);
                if (m_acknowledgements.size() > kMaxAcknowledgements)
                    m_acknowledgements.pop_back();
            }
        }
    }
    if (m_expected && *m_expected == withCommanded(*m_expected, sent))
        return;  // nothing this end commands has changed
    m_expected = sent;
    ++m_expectedVersion;
}

void TrialDecoder::refill(const FrameReceiver& receiver, std::int64_t nowMicros)
{
    std::uint64_t add = 0;
    if (receiver.options().mode == FrameReceiver::Mode::Live) {
        if (m_refilledMicros == 0 || nowMicros < m_refilledMicros) {
            m_refilledMicros = nowMicros;
        } else {
            const std::int64_t ms = (nowMicros - m_refilledMicros) / 1000;
            add = static_cast<std::uint64_t>(std::min<std::int64_t>(ms, 3'600'000)) * m_options.unitsPerSecond / 1000;
            m_refilledMicros += ms * 1000;
        }
    } else {
        const std::uint64_t frames = receiver.framesOfInput();
        add = std::min<std::uint64_t>(frames - m_refilledFrames, 3600) * m_options.unitsPerSecond;
        m_refilledFrames = frames;
    }
    m_units = std::min(m_options.maxUnits, m_units + add);
}

TrialDecoder::SenderPredictions& TrialDecoder::predictionsFor(const SenderHistory& h, const secure::SecureCodec* codec,
                                                              bool keyed, Work& work)
{
    for (SenderPredictions& p : m_predictions)
        if (p.serial == h.serial && p.codec == codec) {
            p.used = ++m_tick;
            return p;
        }
    SenderPredictions* slot = nullptr;
    if (m_predictions.size() < 2 * m_options.maxSenders + 2) {
        slot = &m_predictions.emplace_back();
    } else {
        slot = &*std::min_element(m_predictions.begin(), m_predictions.end(),
                                  [](const SenderPredictions& a, const SenderPredictions& b) { return a.used < b.used; });
        *slot = SenderPredictions{};
    }
    slot->serial = h.serial;
    slot->codec = codec;
    slot->used = ++m_tick;

    // The sender's frame as sent: on the plain link the block delivered; on
    // a keyed link the plaintext, encoded again.
    Block base = h.blocks.block1;
    if (keyed) {
        if (!work.take(kEncodeUnits))
            return *slot;
        const std::optional<EncodedBlocks> enc = encodeAsSent(h.message, true);
        if (!enc)
            return *slot;
        base = enc->block1;
    }
    const HeaderPlaces at = headerPlacesOf(base);
    if (!at.found)
        return *slot;
    const secure::HeaderStamp stamp = stampOf(h.message);
    for (std::uint32_t n = 1; n <= m_options.maxGapSeconds; ++n) {
        const std::uint32_t times[3] = {n, n - 1, n + 1};
        for (std::uint32_t t : std::span(times, keyed ? 3 : 1)) {
            auto next = advanced(base, at, stamp, n, t);
            if (!next || !work.take(kCodewordUnits + (codec ? kEncipherUnits : 0)))
                continue;
            if (codec)
                codec->encipherBlock1(next->first);
            slot->advanced.push_back({codewordOf(next->first), next->second, n});
        }
    }
    return *slot;
}

void TrialDecoder::makeExpected(SenderPredictions& p, const SenderHistory& h, bool keyed, Work& work)
{
    if (!m_expected || p.expectedVersion == m_expectedVersion)
        return;
    p.expectedVersion = m_expectedVersion;
    p.expected.clear();
    const int changes = commandedChanges(h.message, *m_expected);
    if (changes == 0)
        return;
    // All the command's changes; on a keyed link, where the prediction must
    // be exact, also all but one (a part still moving) and one alone.
    const std::uint64_t all = ~std::uint64_t{0};
    std::vector<std::uint64_t> masks = {all};
    if (keyed && changes > 1) {
        for (int i = 0; i < changes && i < kMaxExpectedVariants; ++i) {
            const std::uint64_t bit = std::uint64_t{1} << i;
            masks.push_back(all & ~bit);
            masks.push_back(bit);
        }
    }
    const secure::HeaderStamp stamp = stampOf(h.message);
    for (std::uint64_t mask : masks) {
        if (!work.take(kEncodeUnits))
            return;
        const std::optional<EncodedBlocks> enc = encodeAsSent(withCommanded(h.message, *m_expected, mask), keyed);
        if (!enc)
            continue;
        const HeaderPlaces at = headerPlacesOf(enc->block1);
        if (!at.found)
            continue;
        for (std::uint32_t n = 1; n <= m_options.maxGapSeconds; ++n) {
            const std::uint32_t times[3] = {n, n - 1, n + 1};
            for (std::uint32_t t : std::span(times, keyed ? 3 : 1)) {
                auto next = advanced(enc->block1, at, stamp, n, t);
                if (!next || !work.take(kCodewordUnits + (p.codec ? kEncipherUnits : 0)))
                    continue;
                if (p.codec)
                    p.codec->encipherBlock1(next->first);
                p.expected.push_back({codewordOf(next->first), next->second, n});
            }
        }
    }
}

std::optional<TrialDecoder::Found> TrialDecoder::findBlock1(const SenderHistory& h, const secure::SecureCodec* codec,
                                                            bool keyed, const std::uint8_t* r1,
                                                            std::uint32_t gapEstimate, Work& work)
{
    SenderPredictions& p = predictionsFor(h, codec, keyed, work);
    const std::vector<std::uint32_t> order = gapOrder(m_options.maxGapSeconds, gapEstimate);

    if (std::optional<Found> f = tryPredictions(p.advanced, order, keyed, r1, work)) {
        ++m_stats.block1FromPrediction;
        return f;
    }
    makeExpected(p, h, keyed, work);
    if (std::optional<Found> f = tryPredictions(p.expected, order, keyed, r1, work)) {
        ++m_stats.block1FromExpected;
        return f;
    }
    if (!keyed && !m_recent.empty() && work.take(kCompareUnits))
        if (std::optional<Found> f = fromAgreedBytes(p, order, r1, work)) {
            ++m_stats.block1FromCopies;
            return f;
        }
    if (!keyed)
        if (std::optional<Found> f = fromChangedCommands(p, order, r1, work)) {
            ++m_stats.block1FromChangedCommands;
            return f;
        }
    if (codec && &h == m_lastHistory)
        if (std::optional<Found> f = searchCommandChange(h, codec, r1, gapEstimate, work)) {
            ++m_stats.block1FromCommandChange;
            return f;
        }
    return std::nullopt;
}

// Tries every prediction of `list` gap by gap, the likeliest first; of those
// of one gap that fit (keyed: the time variants), the one needing fewest
// corrections.
std::optional<TrialDecoder::Found> TrialDecoder::tryPredictions(const std::vector<Predicted>& list,
                                                                const std::vector<std::uint32_t>& order, bool keyed,
                                                                const std::uint8_t* r1, Work& work) const
{
    const int margin = m_options.margin;
    for (std::uint32_t n : order) {
        Found best;
        for (const Predicted& pred : list) {
            if (pred.n != n)
                continue;
            if (keyed) {
                if (!work.take(kCompareUnits))
                    return std::nullopt;
                const int distance = rs::parityDistance(r1, pred.codeword.data());
                if (distance <= margin && (best.corrected < 0 || distance < best.corrected)) {
                    std::memcpy(best.block.data(), pred.codeword.data(), kBlockSize);
                    best.corrected = distance;
                    best.stamp = pred.stamp;
                }
                continue;
            }
            if (!work.take(kTrialUnits))
                return std::nullopt;
            Codeword out;
            const int c = rs::decodeWithPrediction(r1, pred.codeword.data(), out.data(), margin);
            if (c >= 0) {
                std::memcpy(best.block.data(), out.data(), kBlockSize);
                best.corrected = c;
                return best;
            }
        }
        if (best.corrected >= 0)
            return best;
    }
    return std::nullopt;
}

// The bytes the frames received last agree on: the most recent pair of them
// (this frame first) that holds the same value at a place; -1 where none
// does. A changed command is in every frame after the change, so two of them
// carry it, where the channel's errors rarely agree.
std::optional<std::array<int, kBlockSize>> TrialDecoder::agreedBytes(const std::uint8_t* r1) const
{
    std::array<const std::uint8_t*, kRecentFrames + 1> copies{};
    std::size_t count = 0;
    copies[count++] = r1;
    for (const Codeword& frame : m_recent)
        copies[count++] = frame.data();
    std::array<int, kBlockSize> agreed;
    agreed.fill(-1);
    bool any = false;
    for (std::size_t i = 0; i < kBlockSize; ++i) {
        for (std::size_t b = 1; b < count && agreed[i] < 0; ++b)
            for (std::size_t a = 0; a < b; ++a)
                if (copies[a][i] == copies[b][i]) {
                    agreed[i] = copies[a][i];
                    break;
                }
        any = any || agreed[i] >= 0;
    }
    if (!any)
        return std::nullopt;
    return agreed;
}

// Plain link: the predictions with the bytes the last frames agree on put in.
std::optional<TrialDecoder::Found> TrialDecoder::fromAgreedBytes(const SenderPredictions& p,
                                                                 const std::vector<std::uint32_t>& order,
                                                                 const std::uint8_t* r1, Work& work) const
{
    const std::optional<std::array<int, kBlockSize>> agreed = agreedBytes(r1);
    if (!agreed)
        return std::nullopt;
    for (const std::vector<Predicted>* list : {&p.advanced, &p.expected}) {
        for (std::uint32_t n : order) {
            for (const Predicted& pred : *list) {
                if (pred.n != n)
                    continue;
                Codeword hybrid = pred.codeword;
                bool differs = false;
                for (std::size_t i = 0; i < kBlockSize; ++i)
                    if ((*agreed)[i] >= 0 && hybrid[i] != (*agreed)[i]) {
                        hybrid[i] = static_cast<std::uint8_t>((*agreed)[i]);
                        differs = true;
                    }
                if (!differs)
                    continue;
                if (!work.take(kCodewordUnits + kTrialUnits))
                    return std::nullopt;
                rs::encode(hybrid.data(), hybrid.data() + kBlockSize);
                Codeword out;
                const int c = rs::decodeWithPrediction(r1, hybrid.data(), out.data(), m_options.margin);
                if (c >= 0) {
                    Found f;
                    std::memcpy(f.block.data(), out.data(), kBlockSize);
                    f.corrected = c;
                    return f;
                }
            }
        }
    }
    return std::nullopt;
}

// Plain link: the two likeliest predictions (with this end's command
// first) with the command value bytes in which this frame differs from them
// erased: a change of several commands costs one syndrome a byte instead of
// two, so its first frame is read through as many channel errors as the
// frames after it. When that fails, once more with only the bytes that
// differ in two bits or more erased: a changed value rarely differs from
// the last in one bit alone, a byte the channel hit mostly does, and each
// such byte left to the prediction costs nothing when the prediction was
// right (and two syndromes, as any error, when it was not).
std::optional<TrialDecoder::Found> TrialDecoder::fromChangedCommands(const SenderPredictions& p,
                                                                     const std::vector<std::uint32_t>& order,
                                                                     const std::uint8_t* r1, Work& work) const
{
    for (const std::vector<Predicted>* list : {&p.expected, &p.advanced}) {
        for (std::size_t k = 0; k < order.size() && k < 2; ++k) {
            for (const Predicted& pred : *list) {
                if (pred.n != order[k])
                    continue;
                if (!work.take(kCompareUnits))
                    return std::nullopt;
                Block data;
                std::memcpy(data.data(), pred.codeword.data(), kBlockSize);
                std::vector<int> erased, changed;
                for (std::size_t at : commandValueBytes(data))
                    if (r1[at] != data[at]) {
                        erased.push_back(static_cast<int>(at));
                        if (std::popcount(static_cast<unsigned>(r1[at] ^ data[at])) > 1)
                            changed.push_back(static_cast<int>(at));
                    }
                for (const std::vector<int>* places : {&erased, &changed}) {
                    if (places == &changed && changed.size() == erased.size())
                        break;
                    if (places->empty() || places->size() > kMaxErasedCommandBytes)
                        continue;
                    if (!work.take(kErasureDecodeUnits))
                        return std::nullopt;
                    if (std::optional<Found> found = decodeErased(pred, r1, *places))
                        return found;
                }
            }
        }
    }
    return std::nullopt;
}

// pred's data with r1's parity, the `erased` places erased, libfec's
// errors-and-erasures decoder: kept within 2e + f <= kErasureTrialReach.
std::optional<TrialDecoder::Found> TrialDecoder::decodeErased(const Predicted& pred, const std::uint8_t* r1,
                                                              const std::vector<int>& erased)
{
    Codeword word = pred.codeword;
    std::memcpy(word.data() + kBlockSize, r1 + kBlockSize, rs::kParitySize);
    const Codeword trial = word;
    const int f = static_cast<int>(erased.size());
    if (rs::decodeWithErasures(word.data(), erased.data(), f) < 0)
        return std::nullopt;
    int errors = 0;  // corrected outside the erased places
    for (std::size_t i = 0; i < kCodewordSize; ++i)
        errors += word[i] != trial[i] && std::find(erased.begin(), erased.end(), static_cast<int>(i)) == erased.end();
    if (2 * errors + f > kErasureTrialReach)
        return std::nullopt;
    Found found;
    std::memcpy(found.block.data(), word.data(), kBlockSize);
    found.corrected = errors + f;
    found.stamp = pred.stamp;
    return found;
}

std::optional<TrialDecoder::Found> TrialDecoder::searchCommandChange(const SenderHistory& h,
                                                                     const secure::SecureCodec* codec,
                                                                     const std::uint8_t* r1, std::uint32_t gapEstimate,
                                                                     Work& work)
{
    // The costliest prediction by far: it may spend the budget down to a
    // quarter only, and starts only above half, so the cheap predictions of
    // the frames that follow are always paid for.
    const std::uint64_t floor = m_options.maxUnits / 4;
    if (m_units < m_options.maxUnits / 2 || !work.take(kEncodeUnits))
        return std::nullopt;
    const std::optional<EncodedBlocks> enc = encodeAsSent(h.message, true);
    if (!enc)
        return std::nullopt;
    const HeaderPlaces at = headerPlacesOf(enc->block1);
    if (!at.found)
        return std::nullopt;
    const std::vector<std::size_t> places = commandValueBytes(enc->block1);
    const secure::HeaderStamp stamp = stampOf(h.message);
    for (std::uint32_t n : gapOrder(m_options.commandChangeGap, gapEstimate)) {
        auto next = advanced(enc->block1, at, stamp, n, n);
        if (!next)
            continue;
        Found best;
        for (std::size_t place : places) {
            for (int v = 0; v < 256; ++v) {
                if (v == next->first[place])
                    continue;
                if (m_units < floor + kEncipherUnits + kCodewordUnits || !work.take(kEncipherUnits + kCodewordUnits)) {
                    work.cut = true;
                    return std::nullopt;
                }
                Block b = next->first;
                b[place] = static_cast<std::uint8_t>(v);
                codec->encipherBlock1(b);
                const Codeword p = codewordOf(b);
                const int distance = rs::parityDistance(r1, p.data());
                if (distance <= m_options.margin && (best.corrected < 0 || distance < best.corrected)) {
                    best.block = b;
                    best.corrected = distance;
                    best.stamp = next->second;
                }
            }
        }
        if (best.corrected >= 0)
            return best;
    }
    return std::nullopt;
}

bool TrialDecoder::findBlock2(const SenderHistory& h, const secure::SecureCodec* codec, bool keyed,
                              const secure::HeaderStamp& stamp, const std::uint8_t* r2, DecodedBlocks& d, Work& work)
{
    const int margin = m_options.margin;
    const auto fits = [&](const Block& plain) {
        Block b = plain;
        if (codec) {
            if (!work.take(kEncipherUnits))
                return false;
            codec->encipherBlock2(b, stamp);
        }
        if (!work.take(kCodewordUnits + (keyed ? kCompareUnits : kTrialUnits)))
            return false;
        const Codeword p = codewordOf(b);
        if (keyed) {
            const int distance = rs::parityDistance(r2, p.data());
            if (distance > margin)
                return false;
            d.block2 = b;
            d.corrected.block2 = distance;
            return true;
        }
        Codeword out;
        const int c = rs::decodeWithPrediction(r2, p.data(), out.data(), margin);
        if (c < 0)
            return false;
        std::memcpy(d.block2.data(), out.data(), kBlockSize);
        d.corrected.block2 = c;
        return true;
    };

    // An empty section, or the last one again (the acknowledgement an
    // aircraft repeats).
    static const std::optional<Block> emptyPlain = block2Of({}, false);
    if (emptyPlain && fits(*emptyPlain)) {
        ++m_stats.block2FromPrediction;
        return true;
    }
    const FlightPlanSection& last = h.message.flightPlan;
    if (!last.empty()) {
        if (!work.take(kEncodeUnits))
            return false;
        if (const std::optional<Block> b = block2Of(last, keyed); b && fits(*b)) {
            ++m_stats.block2FromPrediction;
            return true;
        }
    }

    // The acknowledgement of a plan this end sent.
    for (const FlightPlanSection& ack : m_acknowledgements) {
        if (ack == last || !work.take(kEncodeUnits))
            continue;
        if (const std::optional<Block> b = block2Of(ack, keyed); b && fits(*b)) {
            ++m_stats.block2FromPrediction;
            return true;
        }
    }

    // The plan being sent, from an earlier pass: its next sections first.
    for (const Section* s : heldSectionsAhead(h.plan))
        if (fits(s->plain)) {
            ++m_stats.block2FromPlan;
            return true;
        }
    return !keyed && block2FromCopies(r2, d, work);
}

// The sections held of the plan being sent, the one after the last received first.
std::vector<const TrialDecoder::Section*> TrialDecoder::heldSectionsAhead(const PlanProgress& plan) const
{
    std::vector<const Section*> held;
    if (plan.planId == 0)
        return held;
    for (const Section& s : m_sections)
        if (s.planId == plan.planId)
            held.push_back(&s);
    const std::uint32_t cycle = plan.sectionCount ? plan.sectionCount : 0x10000u;
    const auto ahead = [&](const Section* s) { return (s->sectionId + 2 * cycle - plan.section - 1) % cycle; };
    std::sort(held.begin(), held.end(), [&](const Section* a, const Section* b) { return ahead(a) < ahead(b); });
    return held;
}

// Plain link: the copies of this section from earlier passes (or repeats),
// combined with this one (rs::decodeFromCopies): codewords 2 of frames whose
// BLOCK 2 nothing read, kept from the last kMaxBlock2Copies frames, similar
// to this one. The result must then also fit this frame's parity bytes
// (a trial with it as the prediction). Every decode is paid from the budget.
bool TrialDecoder::block2FromCopies(const std::uint8_t* r2, DecodedBlocks& d, Work& work)
{
    if (m_block2Copies.empty() || !work.take(kCompareUnits * 8))
        return false;
    std::vector<const std::uint8_t*> copies;
    for (const Codeword& c : m_block2Copies) {
        std::size_t same = 0;
        for (std::size_t i = 0; i < kBlockSize; ++i)
            same += c[i] == r2[i];
        if (same >= kSimilarBytes)
            copies.push_back(c.data());
        if (copies.size() + 1 == kMaxCombined)
            break;
    }
    if (copies.empty())
        return false;
    std::reverse(copies.begin(), copies.end());
    copies.push_back(r2);  // the frame being read last
    const int affordable = static_cast<int>(std::min<std::uint64_t>(work.units / kErasureDecodeUnits, 1u << 12));
    Codeword combined;
    const rs::CopiesDecode c =
        rs::decodeFromCopies(copies.data(), static_cast<int>(copies.size()), combined.data(), affordable);
    work.take(static_cast<std::uint64_t>(c.decodes) * kErasureDecodeUnits);
    if (!c.found && c.decodes == affordable)
        work.cut = true;  // the budget ended the choices
    if (!c.found || !work.take(kTrialUnits))
        return false;
    Codeword out;
    const int corrected = rs::decodeWithPrediction(r2, combined.data(), out.data(), m_options.margin);
    if (corrected < 0)
        return false;
    std::memcpy(d.block2.data(), out.data(), kBlockSize);
    d.corrected.block2 = corrected;
    ++m_stats.block2FromCopies;
    return true;
}

bool TrialDecoder::majority(const std::uint8_t* r1, const DecodedBlocks& plain, DecodedBlocks& d, Work& work)
{
    d = plain;
    m_majority.push_front(copyOf(r1));
    while (m_majority.size() > static_cast<std::size_t>(m_options.majorityFrames))
        m_majority.pop_back();
    if (m_majority.size() < 3)
        return false;
    if (d.corrected.block1 < 0) {
        if (!work.take(kCodewordUnits + kTrialUnits))
            return false;
        // Oldest first, this frame last: where no value holds a majority, its byte.
        std::vector<const std::uint8_t*> votes;
        for (auto it = m_majority.rbegin(); it != m_majority.rend(); ++it)
            votes.push_back(it->data());
        Codeword vote;
        rs::majorityBytes(votes.data(), static_cast<int>(votes.size()), vote.data());
        Block data;
        std::memcpy(data.data(), vote.data(), kBlockSize);
        const Codeword p = codewordOf(data);
        Codeword decoded;
        d.corrected.block1 = rs::decodeWithPrediction(r1, p.data(), decoded.data(), m_options.margin);
        if (d.corrected.block1 < 0)
            return false;
        std::memcpy(d.block1.data(), decoded.data(), kBlockSize);
        ++m_stats.block1FromMajority;
    }
    return d.corrected.block2 >= 0;
}

// The senders to predict from: the last accepted first.
std::vector<const SenderHistory*> TrialDecoder::sendersToPredict(const FrameReceiver& receiver) const
{
    std::vector<const SenderHistory*> histories;
    for (const auto& [key, h] : receiver.senders())
        histories.push_back(&h);
    std::sort(histories.begin(), histories.end(),
              [](const SenderHistory* a, const SenderHistory* b) { return a->serial > b->serial; });
    if (histories.size() > m_options.maxSenders)
        histories.resize(m_options.maxSenders);
    return histories;
}

// How many seconds on from `h` this frame likely is: by the clock when live,
// by the frames received since the last delivery otherwise.
std::uint32_t TrialDecoder::likelyGap(const FrameReceiver& receiver, const SenderHistory& h,
                                      std::int64_t nowMicros) const
{
    if (receiver.options().mode != FrameReceiver::Mode::Live)
        return static_cast<std::uint32_t>(std::min<std::uint64_t>(m_framesSinceDelivery + 1, m_options.maxGapSeconds));
    const std::int64_t sinceMicros = nowMicros - h.receivedMicros;
    return static_cast<std::uint32_t>(
        std::clamp<std::int64_t>((sinceMicros + 500'000) / 1'000'000, 1, m_options.maxGapSeconds));
}

// BLOCK 1 as `codec` reads it (nullptr: the plain link): the decoded one if
// it is authentic, else one a prediction from `h` finds.
std::optional<DecodedBlocks> TrialDecoder::readBlock1(const SenderHistory& h, const secure::SecureCodec* codec,
                                                      bool keyed, const DecodedBlocks& start, const std::uint8_t* r1,
                                                      std::uint32_t gapEstimate, secure::HeaderStamp& stamp, Work& work)
{
    DecodedBlocks d = start;
    if (d.corrected.block1 >= 0 && codec) {
        DecodedBlocks only = d;
        only.corrected.block2 = -1;
        if (!work.take(kEncipherUnits))
            return std::nullopt;
        const secure::Authenticated a = codec->decryptBlocks(only);
        if (!a.authentic)
            return std::nullopt;
        stamp = a.stamp;
    }
    if (d.corrected.block1 < 0) {
        const std::optional<Found> f = findBlock1(h, codec, keyed, r1, gapEstimate, work);
        if (!f)
            return std::nullopt;
        d.block1 = f->block;
        d.corrected.block1 = f->corrected;
        stamp = f->stamp;
    }
    return d;
}

TrialDecoder::Candidates TrialDecoder::candidates(std::span<const std::uint8_t, kDatagramSize> received,
                                                  const DecodedBlocks& plain, bool block2Read,
                                                  const FrameReceiver& receiver, std::int64_t nowMicros)
{
    Candidates out;
    refill(receiver, nowMicros);
    Work work{m_units};
    ++m_stats.calls;
    const std::uint8_t* r1 = received.data();
    const std::uint8_t* r2 = received.data() + kCodewordSize;
    const std::vector<const secure::SecureCodec*>& codecs = receiver.options().keys.codecs;
    const bool keyed = !codecs.empty();
    DecodedBlocks start = plain;
    const auto finished = [&] {
        out.units = work.spent;
        out.cut = work.cut;
        m_stats.cut += work.cut;
        return out;
    };

    // Codeword 2 not decoded yet: it is needed once BLOCK 1 is read.
    bool block2Tried = block2Read;
    const auto readBlock2 = [&](DecodedBlocks& d) {
        if (block2Tried || !work.take(kDecodeUnits))
            return;
        block2Tried = true;
        Codeword c = copyOf(r2);
        start.corrected.block2 = rs::decode(c.data());
        if (start.corrected.block2 >= 0)
            std::memcpy(start.block2.data(), c.data(), kBlockSize);
        d.block2 = start.block2;
        d.corrected.block2 = start.corrected.block2;
    };

    std::vector<const SenderHistory*> histories = sendersToPredict(receiver);
    m_lastHistory = histories.empty() ? nullptr : histories.front();
    if (histories.empty()) {
        // Nothing accepted yet: on the plain link, consecutive frames repeat
        // most bytes, so a vote over the last few is a prediction.
        if (!keyed && m_options.majorityFrames >= 3) {
            DecodedBlocks d;
            if (majority(r1, start, d, work)) {
                out.blocks.push_back(d);
            } else if (d.corrected.block1 >= 0) {
                readBlock2(d);
                static const SenderHistory none;
                if (d.corrected.block2 >= 0 || findBlock2(none, nullptr, false, {}, r2, d, work))
                    out.blocks.push_back(d);
            }
        }
        return finished();
    }
    m_majority.clear();
    if (m_unaccepted) {
        const std::uint32_t ahead = (m_unaccepted->messageId - histories.front()->messageId) & kIdMask;
        if (ahead >= 1 && ahead <= m_options.maxGapSeconds)
            histories.insert(histories.begin(), &*m_unaccepted);
        else
            m_unaccepted.reset();
    }
    std::optional<SenderHistory> unaccepted;  // this frame's BLOCK 1, if its BLOCK 2 stays unreadable

    std::vector<const secure::SecureCodec*> tryCodecs = codecs;
    if (!keyed)
        tryCodecs.push_back(nullptr);
    for (const SenderHistory* h : histories) {
        const std::uint32_t gap = likelyGap(receiver, *h, nowMicros);
        for (const secure::SecureCodec* codec : tryCodecs) {
            if (work.cut)
                break;
            secure::HeaderStamp stamp;
            std::optional<DecodedBlocks> d = readBlock1(*h, codec, keyed, start, r1, gap, stamp, work);
            if (!d)
                continue;
            if (d->corrected.block2 < 0)
                readBlock2(*d);
            if (d->corrected.block2 >= 0 || findBlock2(*h, codec, keyed, stamp, r2, *d, work)) {
                out.blocks.push_back(*d);
            } else if (!unaccepted) {
                unaccepted = block1History(*d, codec, *h, nowMicros);
            }
        }
        if (work.cut)
            break;
    }
    if (unaccepted) {
        unaccepted->serial = (std::uint64_t{1} << 63) | ++m_tick;
        m_unaccepted = std::move(unaccepted);
    }
    return finished();
}

void TrialDecoder::observe(std::span<const std::uint8_t, kDatagramSize> received, const ReceivedFrame& frame,
                           const SenderHistory* accepted)
{
    const std::uint8_t* r1 = received.data();
    const std::uint8_t* r2 = received.data() + kCodewordSize;
    const bool delivered = frame.delivered();
    m_framesSinceDelivery = delivered ? 0 : m_framesSinceDelivery + 1;
    if (!m_keyed && frame.refusal != Refusal::WrongSize) {
        // Codeword 1 as decoded where it was (as received when that needed
        // no correction), else as received.
        const int corrected = frame.blocks.corrected.block1;
        if (m_recent.size() == kRecentFrames)
            m_recent.pop_back();
        m_recent.push_front(corrected > 0 ? codewordOf(frame.blocks.block1) : copyOf(r1));
        if (!delivered && frame.blocks.corrected.block2 < 0) {
            m_block2Copies.push_front(copyOf(r2));
            if (m_block2Copies.size() > kMaxBlock2Copies)
                m_block2Copies.pop_back();
        }
    }
    if (!delivered || !accepted)
        return;
    const FlightPlanSection& s = frame.decoded.message.flightPlan;
    if (s.empty() || s.sectionId >= kFirstControlSectionId)
        return;
    Section kept;
    kept.planId = s.planId;
    kept.sectionId = s.sectionId;
    if (m_keyed) {
        const std::optional<Block> b = block2Of(s, true);
        if (!b)
            return;
        kept.plain = *b;
    } else {
        kept.plain = frame.blocks.block2;
    }
    std::erase_if(m_sections,
                  [&](const Section& x) { return x.planId == kept.planId && x.sectionId == kept.sectionId; });
    m_sections.push_back(kept);
    if (m_sections.size() > kMaxSections)
        m_sections.pop_front();
}

}  // namespace rcm
