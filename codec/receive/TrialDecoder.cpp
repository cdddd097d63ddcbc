#include "codec/receive/TrialDecoder.h"

#include "codec/frame/ReedSolomon.h"
#include "codec/message/MessageEncoder.h"
#include "codec/message/MessagePrediction.h"
#include "codec/secure/SecureCodec.h"

#include <cstring>
#include <optional>

namespace rcm {
namespace {

using Codeword = std::array<std::uint8_t, kCodewordSize>;

Codeword codewordOf(const Block& data)
{
    Codeword c;
    std::memcpy(c.data(), data.data(), kBlockSize);
    rs::encode(c.data(), c.data() + kBlockSize);
    return c;
}

std::optional<EncodedBlocks> encodeAsSent(const Message& m, bool keyed)
{
    Diagnostics errors;
    return encodeBlocks(m, errors, keyed ? secure::encodeOptions() : EncodeOptions{});
}

// `last` with ID_msg `idStep` and time_UTC `timeStep` seconds on: a sender's
// clock and its counter need not tick together.
Message advanced(const Message& last, std::uint32_t idStep, std::uint32_t timeStep)
{
    Message m = advanceMessage(last, timeStep);
    if (const Value* id = last.header.find(ItemId::ID_msg))
        m.header.set(ItemId::ID_msg, (id->number + idStep) % rcm::kMessageIdModulus);
    return m;
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
    std::size_t p = 0;
    while (p < kBlockSize && plain[p] == kPad55)
        ++p;
    while (p < kBlockSize) {
        const ItemInfo* info = findItem(plain[p]);
        if (!info || p + 1 + info->size > kBlockSize)
            break;
        if (info->owner != UnitKind::Header)
            for (std::size_t j = 1; j <= info->size; ++j)
                at.push_back(p + j);
        p += 1 + info->size;
    }
    return at;
}

// Keeps the first prediction (of several that fit) with the fewest corrections.
struct Best {
    int corrected = -1;
    Block block{};
    secure::HeaderStamp stamp;
    void offer(int c, const std::uint8_t* data, const secure::HeaderStamp& s = {})
    {
        if (c < 0 || (corrected >= 0 && c >= corrected))
            return;
        corrected = c;
        std::memcpy(block.data(), data, kBlockSize);
        stamp = s;
    }
};

// What BLOCK 1 of `d` says, as a history to predict the next frame from;
// BLOCK 2 as in `before`.
std::optional<SenderHistory> block1History(const DecodedBlocks& d, const secure::SecureCodec* codec,
                                           const SenderHistory& before)
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
    h.message.flightPlan = before.message.flightPlan;
    h.messageId = static_cast<std::uint32_t>(h.message.header.number(ItemId::ID_msg));
    return h;
}

}  // namespace

std::vector<DecodedBlocks> TrialDecoder::candidates(std::span<const std::uint8_t, kDatagramSize> received,
                                                    const DecodedBlocks& plain, const FrameReceiver& receiver)
{
    ++m_stats.calls;
    const std::uint8_t* r1 = received.data();
    const std::uint8_t* r2 = received.data() + kCodewordSize;
    const std::vector<const secure::SecureCodec*>& codecs = receiver.options().keys.codecs;
    const bool keyed = !codecs.empty();
    const int margin = m_options.margin;

    // BLOCK 2 from `d`'s BLOCK 1 (plaintext `m1` when known) and sender `h`.
    auto block2 = [&](DecodedBlocks& d, const Message& like, const secure::SecureCodec* codec,
                      const secure::HeaderStamp& stamp) {
        if (d.corrected.block2 >= 0)
            return true;
        FlightPlanSection sections[2] = {FlightPlanSection{}, like.flightPlan};
        for (const FlightPlanSection& s : sections) {
            Message m = like;
            m.flightPlan = s;
            std::optional<EncodedBlocks> enc = encodeAsSent(m, keyed);
            if (!enc)
                continue;
            if (codec)
                codec->encipherBlock2(enc->block2, stamp);
            const Codeword p = codewordOf(enc->block2);
            Codeword out;
            const int c = rs::decodeWithPrediction(r2, p.data(), out.data(), margin);
            if (c >= 0) {
                std::memcpy(d.block2.data(), out.data(), kBlockSize);
                d.corrected.block2 = c;
                ++m_stats.block2FromPrediction;
                return true;
            }
            if (s.empty() && like.flightPlan.empty())
                break;
        }
        return false;
    };

    std::vector<DecodedBlocks> out;
    std::vector<const SenderHistory*> histories;
    if (receiver.lastAccepted())
        histories.push_back(receiver.lastAccepted());
    for (const auto& [key, h] : receiver.senders())
        if (&h != receiver.lastAccepted())
            histories.push_back(&h);

    if (histories.empty()) {
        // Nothing accepted yet: on the plain link, consecutive frames repeat
        // most bytes, so a vote over the last few is a prediction.
        if (keyed || m_options.majorityFrames < 3)
            return out;
        m_recent.emplace_back(r1, r1 + kCodewordSize);
        while (m_recent.size() > static_cast<std::size_t>(m_options.majorityFrames))
            m_recent.pop_front();
        if (m_recent.size() < 3)
            return out;
        DecodedBlocks d = plain;
        if (d.corrected.block1 < 0) {
            std::vector<const std::uint8_t*> votes;
            for (const auto& cw : m_recent)
                votes.push_back(cw.data());
            Codeword vote;
            rs::majorityBytes(votes.data(), static_cast<int>(votes.size()), vote.data());
            Block data;
            std::memcpy(data.data(), vote.data(), kBlockSize);
            const Codeword p = codewordOf(data);
            Codeword decoded;
            d.corrected.block1 = rs::decodeWithPrediction(r1, p.data(), decoded.data(), margin);
            if (d.corrected.block1 < 0)
                return out;
            std::memcpy(d.block1.data(), decoded.data(), kBlockSize);
            ++m_stats.block1FromMajority;
        }
        Message m1;
        Diagnostics ignored;
        decodeBlock1(d.block1, m1, ignored);
        if (block2(d, m1, nullptr, {}))
            out.push_back(d);
        return out;
    }
    m_recent.clear();
    if (m_unaccepted) {
        const SenderHistory* last = histories.front();
        const std::uint32_t ahead = (m_unaccepted->messageId - last->messageId) & (rcm::kMessageIdModulus - 1);
        if (ahead >= 1 && ahead <= m_options.maxGapSeconds)
            histories.insert(histories.begin(), &*m_unaccepted);
        else
            m_unaccepted.reset();
    }
    std::optional<SenderHistory> readBlock1;  // this frame's BLOCK 1, if its BLOCK 2 stays unreadable

    std::vector<const secure::SecureCodec*> tryCodecs = codecs;
    if (!keyed)
        tryCodecs.push_back(nullptr);
    for (const SenderHistory* h : histories) {
        for (const secure::SecureCodec* codec : tryCodecs) {
            DecodedBlocks d = plain;
            secure::HeaderStamp stamp;
            if (d.corrected.block1 >= 0 && codec) {
                const secure::Authenticated a = codec->decryptBlocks(d);
                if (!a.authentic)
                    continue;
                stamp = a.stamp;
            }
            if (d.corrected.block1 < 0) {
                Best best;
                for (std::uint32_t n = 1; n <= m_options.maxGapSeconds && best.corrected < 0; ++n) {
                    if (!codec) {
                        std::optional<EncodedBlocks> enc = encodeAsSent(advanceMessage(h->message, n), false);
                        if (!enc)
                            continue;
                        const Codeword p = codewordOf(enc->block1);
                        Codeword decoded;
                        best.offer(rs::decodeWithPrediction(r1, p.data(), decoded.data(), margin), decoded.data());
                        continue;
                    }
                    for (std::uint32_t t : {n, n - 1, n + 1}) {
                        const Message m = advanced(h->message, n, t);
                        std::optional<EncodedBlocks> enc = encodeAsSent(m, true);
                        if (!enc)
                            continue;
                        codec->encipherBlock1(enc->block1);
                        const Codeword p = codewordOf(enc->block1);
                        const int distance = rs::parityDistance(r1, p.data());
                        best.offer(distance <= margin ? distance : -1, p.data(), stampOf(m));
                    }
                }
                if (best.corrected >= 0) {
                    ++m_stats.block1FromPrediction;
                } else if (codec) {
                    for (std::uint32_t n = 1; n <= m_options.commandChangeGap && best.corrected < 0; ++n) {
                        const Message m = advanced(h->message, n, n);
                        std::optional<EncodedBlocks> enc = encodeAsSent(m, true);
                        if (!enc)
                            continue;
                        for (std::size_t at : commandValueBytes(enc->block1)) {
                            for (int v = 0; v < 256; ++v) {
                                if (v == enc->block1[at])
                                    continue;
                                Block b = enc->block1;
                                b[at] = static_cast<std::uint8_t>(v);
                                codec->encipherBlock1(b);
                                const Codeword p = codewordOf(b);
                                const int distance = rs::parityDistance(r1, p.data());
                                best.offer(distance <= margin ? distance : -1, p.data(), stampOf(m));
                            }
                        }
                    }
                    m_stats.block1FromCommandChange += best.corrected >= 0;
                }
                if (best.corrected < 0)
                    continue;
                d.block1 = best.block;
                d.corrected.block1 = best.corrected;
                stamp = best.stamp;
            }
            if (block2(d, h->message, codec, stamp)) {
                out.push_back(d);
            } else if (!readBlock1) {
                readBlock1 = block1History(d, codec, *h);
            }
        }
    }
    if (readBlock1)
        m_unaccepted = std::move(readBlock1);
    return out;
}

FrameReceiver::Retry TrialDecoder::retryFor(TrialDecoder& decoder)
{
    return [&decoder](std::span<const std::uint8_t, kDatagramSize> received, const DecodedBlocks& plain,
                      const FrameReceiver& receiver) { return decoder.candidates(received, plain, receiver); };
}

}  // namespace rcm
