// The one receive path (FrameReceiver with its predictions, TrialDecoder),
// plain and keyed, fed short streams and datagrams made from a session's
// frames and mutated as a channel or an attacker would (bit errors, slips,
// bursts, cut frames, garbage, old frames again, random datagrams), under
// ASan/UBSan. Nothing may crash; and what it promises must hold: every frame
// delivered is one that was sent, with what was sent, never one sent before
// the last delivered; what is counted adds up; memory stays bounded. Fixed
// seed, bounded work: a CTest target, not an open-ended fuzzer. An optional
// argument sets the number of rounds.
#include "tests/support/ReceiveChannel.h"

#include <cstdio>
#include <cstdlib>

using namespace rcm;
using namespace rcm::test;

namespace {

int round_ = 0;

[[noreturn]] void fail(const char* what)
{
    std::fprintf(stderr, "fuzz_receive: round %d: %s\n", round_, what);
    std::abort();
}

void check(bool ok, const char* what)
{
    if (!ok)
        fail(what);
}

void mutate(Bytes& b, std::mt19937_64& rng)
{
    if (b.empty())
        return;
    switch (rng() % 6) {
    case 0: {  // bit errors at up to 3e-2
        const double ber = static_cast<double>(1 + rng() % 300) * 1e-4;
        std::geometric_distribution<std::uint64_t> gap(ber);
        for (std::uint64_t bit = gap(rng); bit < b.size() * 8; bit += 1 + gap(rng))
            b[bit / 8] ^= static_cast<std::uint8_t>(0x80u >> (bit % 8));
        break;
    }
    case 1: {  // a slip
        const std::size_t at = rng() % b.size();
        if (rng() & 1)
            b.erase(b.begin() + static_cast<std::ptrdiff_t>(at),
                    b.begin() + static_cast<std::ptrdiff_t>(std::min(b.size(), at + 1 + rng() % 8)));
        else
            b.insert(b.begin() + static_cast<std::ptrdiff_t>(at), 1 + rng() % 8, static_cast<std::uint8_t>(rng()));
        break;
    }
    case 2: {  // a burst
        const std::size_t at = rng() % b.size();
        for (std::size_t i = at; i < std::min(b.size(), at + 1 + rng() % 60); ++i)
            b[i] = static_cast<std::uint8_t>(rng());
        break;
    }
    case 3:  // cut short
        b.resize(rng() % b.size());
        break;
    default:
        break;
    }
}

}  // namespace

int main(int argc, char** argv)
{
    const int rounds = argc > 1 ? std::atoi(argv[1]) : 100000;
    std::mt19937_64 rng(0x5EC7);
    secure::SecretKey key;
    key.mutableBytes()[0] = 0x42;
    const secure::SecureCodec codec(key, secure::Direction::GcsToUa);
    CommandSession plain;
    plain.uploadEvery = 50;
    plain.uploadStart = 10;
    CommandSession keyed = plain;
    keyed.codec = &codec;
    // The sessions' first frames and messages, made once.
    constexpr std::uint64_t kFrames = 2010;
    std::vector<FrameBytes> plainFrames, keyedFrames;
    std::vector<Message> plainMessages, keyedMessages;  // sections of 199 bytes on the keyed link
    for (std::uint64_t i = 0; i < kFrames; ++i) {
        plainFrames.push_back(plain.frameAt(i));
        keyedFrames.push_back(keyed.frameAt(i));
        plainMessages.push_back(plain.messageAt(i));
        keyedMessages.push_back(keyed.messageAt(i));
    }
    std::uint64_t frames = 0, delivered = 0, predicted = 0;
    for (round_ = 0; round_ < rounds; ++round_) {
        const bool isKeyed = rng() % 4 == 0;
        const bool datagrams = rng() % 3 == 0;
        const CommandSession& session = isKeyed ? keyed : plain;
        const std::vector<FrameBytes>& sessionFrames = isKeyed ? keyedFrames : plainFrames;
        const std::vector<Message>& messages = isKeyed ? keyedMessages : plainMessages;
        const std::uint64_t first = rng() % 2000;
        const std::uint64_t count = 1 + rng() % 4;
        std::int64_t nowMicros = session.secondsAt(first) * 1'000'000;
        FrameReceiver::Options o;
        o.mode = rng() % 2 ? FrameReceiver::Mode::Live : FrameReceiver::Mode::Recording;
        o.clock = [&] { return nowMicros; };
        if (isKeyed)
            o.keys.codecs = {&codec};
        // Predictions over fewer gaps and a small budget: every kind is still
        // tried (the search of command changes on a keyed link in part), in
        // a fraction of the time.
        o.prediction.maxGapSeconds = 4;
        o.prediction.commandChangeGap = 2;
        o.prediction.maxUnits = 1'000;
        o.prediction.unitsPerSecond = 500;
        std::uint64_t sent = first;
        std::optional<std::uint64_t> newest;
        std::uint64_t judged = 0;
        FrameReceiver receiver(o, [&](const ReceivedFrame& f) {
            ++judged;
            if (!f.delivered())
                return;
            const auto id = static_cast<std::uint32_t>(f.decoded.message.header.number(ItemId::ID_msg));
            const std::optional<std::uint64_t> i = session.indexOf(id, sent);
            check(i && *i >= first, "delivered a frame that was not sent");
            check(messages[*i] == f.decoded.message, "delivered a frame other than what was sent");
            check(!newest || *i > *newest, "delivered a frame sent before the last delivered");
            newest = *i;
            ++delivered;
            predicted += f.fromPrediction;
        });
        // The first frame clean, as a link is set up, so that later ones
        // have something to be predicted from.
        for (std::uint64_t k = 0; k < count; ++k) {
            const std::uint64_t i = first + k;
            const FrameBytes& frame = sessionFrames[i];
            Bytes bytes = datagrams ? Bytes(frame.begin() + kPreambleSize, frame.end()) : Bytes(frame.begin(), frame.end());
            if (k > 0)
                mutate(bytes, rng);
            if (rng() % 8 == 0 && i > first) {  // an old frame again, first
                const FrameBytes& old = sessionFrames[first + rng() % (i - first)];
                const Bytes again = datagrams ? Bytes(old.begin() + kPreambleSize, old.end()) : Bytes(old.begin(), old.end());
                datagrams ? receiver.receive(again) : receiver.feed(again);
            }
            if (rng() % 8 == 0) {  // garbage, or a random datagram
                Bytes junk(datagrams ? kDatagramSize : rng() % 700);
                for (std::uint8_t& b : junk)
                    b = static_cast<std::uint8_t>(rng());
                datagrams ? receiver.receive(junk) : receiver.feed(junk);
            }
            sent = i + 1;
            nowMicros = session.secondsAt(i) * 1'000'000 + 500'000;
            datagrams ? receiver.receive(bytes) : receiver.feed(bytes);
        }
        receiver.flush();
        const FrameReceiver::Stats& st = receiver.stats();
        check(st.delivered + st.refusedTotal() == judged, "delivered + refused != frames judged");
        check(st.fromPrediction <= st.delivered, "more read with predictions than delivered");
        check(receiver.senders().size() <= kMaxSenders, "senders beyond the table");
        check(st.predictionUnits <= o.prediction.maxUnits + o.prediction.unitsPerSecond * 3600, "budget overspent");
        frames += judged;
    }
    std::printf("fuzz_receive: %d rounds, %llu frames judged, %llu delivered, %llu of them with a prediction\n", rounds,
                static_cast<unsigned long long>(frames), static_cast<unsigned long long>(delivered),
                static_cast<unsigned long long>(predicted));
    return 0;
}
