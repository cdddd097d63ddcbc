// A realistic command session and the damage a channel does to it, streamed
// through FrameReceiver as the link worker runs it, with TrialDecoder's
// predictions when plain decoding fails: what tests/codec/tst_receive.cpp asserts
// on (10^4 frames a row) and tests/bench/soak_receive.cpp measures (10^6
// frames a row). Receive::Plain leaves the predictions out, for comparison.
//
// The session: one command frame a second from one console, ID_msg + 1 and
// time_UTC + 1 s each, a command change every 20 s or so (engine carb,
// elevator, lights), and every 10 minutes a flight plan upload of 4 sections
// sent in 3 passes. Frame i is a pure function of i, so a delivered message
// is checked against what was sent with that ID_msg without keeping them all.
#pragma once

#include "codec/frame/Frame.h"
#include "codec/message/FlightPlanTransfer.h"
#include "codec/message/MessageEncoder.h"
#include "codec/message/MessagePrediction.h"
#include "codec/receive/FrameReceiver.h"
#include "codec/receive/TrialDecoder.h"
#include "codec/secure/SecureCodec.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cstring>
#include <optional>
#include <cstdint>
#include <functional>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace rcm::test {

using Bytes = std::vector<std::uint8_t>;

class CommandSession {
public:
    std::uint64_t uploadEvery = 600;  // frames between flight plan uploads
    std::uint64_t uploadStart = 100;  // its first frame within each uploadEvery
    std::size_t planBytes = 800;      // 4 sections of 215 with the descriptor
    int passes = 3;
    // Keyed: every frame enciphered with it (sections of 199 bytes); not owned.
    const secure::SecureCodec* codec = nullptr;

    // Starts near the ID_msg wrap and a day before midnight, so a long run crosses both.
    std::uint32_t firstId = 16'700'000;
    std::int64_t firstSeconds = 1'798'675'200 - 3600;  // 2026-12-31 23:00:00 UTC
    StationId source{44, 133};

    std::uint32_t idAt(std::uint64_t i) const { return static_cast<std::uint32_t>((firstId + i) % (1u << 24)); }
    std::int64_t secondsAt(std::uint64_t i) const { return firstSeconds + static_cast<std::int64_t>(i); }

    // The frame index that sent `id`, or nothing when none of the first `sent` did.
    std::optional<std::uint64_t> indexOf(std::uint32_t id, std::uint64_t sent) const
    {
        const std::uint64_t i = (id - firstId) & ((1u << 24) - 1);
        return i < sent ? std::optional<std::uint64_t>(i) : std::nullopt;
    }

    Message messageAt(std::uint64_t i) const
    {
        Message m;
        m.header.set(ItemId::ID_msg, idAt(i));
        m.header.set(ItemId::ID_UA_source, Value::station(source));
        setTime(m, secondsAt(i));
        m.header.set(ItemId::ID_BLK12_format, Value::pair(1, 1));
        Unit& engine = m.addEngine(1);
        engine.setFieldCode(ItemId::eng_status, 0, 0b10);  // control GCS
        engine.setFieldCode(ItemId::eng_status, 1, 0b01);  // no slave
        engine.set(ItemId::eng_prop_pitch, 128);
        engine.set(ItemId::eng_carb_SET, static_cast<std::int64_t>(mix(i / 20) % 256));
        m.flaps.setFieldCode(ItemId::FLAP_status, 0, 0b10);
        m.flaps.setFieldCode(ItemId::FLAP_status, 1, 0b01);
        m.flaps.set(ItemId::F_elev_set, static_cast<std::int64_t>(mix(i / 37 + 7) % 255) - 127);
        m.flaps.set(ItemId::F_rudder_set, 0);
        for (int f = 0; f < 4; ++f)
            m.settings.setFieldCode(ItemId::lights, f, (mix(i / 61 + 11) >> f & 1) ? 0b10 : 0b01);
        const std::uint64_t j = i % uploadEvery;
        if (j >= uploadStart) {
            const FlightPlanUploader plan = uploader(i / uploadEvery);
            const std::uint64_t k = j - uploadStart;
            if (k < static_cast<std::uint64_t>(passes) * plan.sections().size())
                m.flightPlan = plan.sections()[k % plan.sections().size()];
        }
        return m;
    }

    FrameBytes frameAt(std::uint64_t i) const
    {
        Diagnostics errors;
        std::optional<FrameBytes> f;
        if (codec) {
            if (const std::optional<EncodedBlocks> b = codec->encode(messageAt(i), errors))
                f = makeFrame(b->block1, b->block2);
        } else {
            f = encodeFrame(messageAt(i), errors);
        }
        if (!f)
            throw std::logic_error("CommandSession: frame " + std::to_string(i) + " does not encode");
        return *f;
    }

    static std::uint64_t mix(std::uint64_t x)
    {
        x += 0x9E3779B97F4A7C15ull;
        x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
        x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
        return x ^ (x >> 31);
    }

private:
    static void setTime(Message& m, std::int64_t seconds)
    {
        using namespace std::chrono;
        const sys_seconds t{std::chrono::seconds{seconds}};
        const sys_days day = floor<days>(t);
        const year_month_day ymd{day};
        const hh_mm_ss hms{t - day};
        m.header.set(ItemId::time_UTC, hms.hours().count() * 10000 + hms.minutes().count() * 100 + hms.seconds().count());
        m.header.set(ItemId::date_UTC, (int(ymd.year()) % 100) * 10000 + int(unsigned(ymd.month())) * 100 +
                                           int(unsigned(ymd.day())));
    }

    FlightPlanUploader uploader(std::uint64_t n) const
    {
        std::vector<std::uint8_t> plan(planBytes);
        for (std::size_t b = 0; b < plan.size(); ++b)
            plan[b] = static_cast<std::uint8_t>(mix(n * planBytes + b));
        return FlightPlanUploader(static_cast<std::uint32_t>(n + 1), plan,
                                  codec ? secure::kMaxFlightPlanData : FlightPlanSection::kMaxData, passes);
    }
};

// What the channel does to each frame.
struct Channel {
    enum class Kind {
        Clean,
        Slip,              // 1-3 bytes lost or inserted at a random place in the frame
        OverwriteBurst,    // 20-60 bytes overwritten with random bytes
        InsertBurst,       // 20-60 random bytes inserted
        BitErrors,         // each bit flipped with probability ber
        ConstantFollower,  // after each frame: a preamble and 510 bytes of 00, 55, AA, 0F or FF in turn
        RandomFollower,    // after each frame: a preamble and 510 random bytes
        ByteErrors16,      // exactly 16 random byte errors in each codeword at random places
    };
    Channel(Kind k, double bitErrorRate, std::string rowName) : kind(k), ber(bitErrorRate), name(std::move(rowName)) {}

    Kind kind = Kind::Clean;
    double ber = 0;
    std::string name;

    // Appends frame `f`, damaged, to `out`.
    void transmit(const FrameBytes& f, Bytes& out, std::mt19937_64& rng) const
    {
        const auto uniform = [&](std::size_t lo, std::size_t hi) {
            return std::uniform_int_distribution<std::size_t>(lo, hi)(rng);
        };
        const std::size_t start = out.size();
        out.insert(out.end(), f.begin(), f.end());
        switch (kind) {
        case Kind::Clean:
            break;
        case Kind::Slip: {
            const std::size_t n = uniform(1, 3);
            const std::size_t at = start + uniform(0, kFrameSize - n);
            if (rng() & 1) {
                out.erase(out.begin() + static_cast<std::ptrdiff_t>(at), out.begin() + static_cast<std::ptrdiff_t>(at + n));
            } else {
                Bytes extra(n);
                for (auto& b : extra)
                    b = static_cast<std::uint8_t>(rng());
                out.insert(out.begin() + static_cast<std::ptrdiff_t>(at), extra.begin(), extra.end());
            }
            break;
        }
        case Kind::OverwriteBurst: {
            const std::size_t n = uniform(20, 60);
            const std::size_t at = start + uniform(0, kFrameSize - n);
            for (std::size_t k = 0; k < n; ++k)
                out[at + k] = static_cast<std::uint8_t>(rng());
            break;
        }
        case Kind::InsertBurst: {
            Bytes extra(uniform(20, 60));
            for (auto& b : extra)
                b = static_cast<std::uint8_t>(rng());
            out.insert(out.begin() + static_cast<std::ptrdiff_t>(start + uniform(0, kFrameSize)), extra.begin(),
                       extra.end());
            break;
        }
        case Kind::BitErrors: {
            std::geometric_distribution<std::uint64_t> gap(ber);
            const std::uint64_t bits = (out.size() - start) * 8;
            for (std::uint64_t bit = gap(rng); bit < bits; bit += 1 + gap(rng))
                out[start + bit / 8] ^= static_cast<std::uint8_t>(0x80u >> (bit % 8));
            break;
        }
        case Kind::ConstantFollower:
        case Kind::RandomFollower: {
            static constexpr std::uint8_t kConstants[] = {0x00, 0x55, 0xAA, 0x0F, 0xFF};
            const std::uint8_t c = kConstants[m_followers++ % 5];
            out.insert(out.end(), preamble().begin(), preamble().end());
            for (std::size_t k = 0; k < kDatagramSize; ++k)
                out.push_back(kind == Kind::RandomFollower ? static_cast<std::uint8_t>(rng()) : c);
            break;
        }
        case Kind::ByteErrors16:
            for (std::size_t cw = 0; cw < 2; ++cw)
                corruptBytes(&out[start + kPreambleSize + cw * kCodewordSize], rng);
            break;
        }
    }

    // Exactly 16 bytes of a codeword changed, at distinct random places, each to another value.
    static void corruptBytes(std::uint8_t* codeword, std::mt19937_64& rng, int mustInclude = -1)
    {
        std::vector<std::size_t> places(kCodewordSize);
        for (std::size_t k = 0; k < places.size(); ++k)
            places[k] = k;
        std::shuffle(places.begin(), places.end(), rng);
        places.resize(rs::kMaxCorrectable);
        if (mustInclude >= 0 && std::find(places.begin(), places.end(), std::size_t(mustInclude)) == places.end())
            places[0] = static_cast<std::size_t>(mustInclude);
        for (std::size_t p : places)
            codeword[p] ^= static_cast<std::uint8_t>(1 + rng() % 255);
    }

private:
    mutable std::uint64_t m_followers = 0;
};

// How the receiver decodes: as the link worker does, or RS alone.
enum class Receive { WithPredictions, Plain };

struct RowResult {
    std::uint64_t sent = 0;
    std::uint64_t correct = 0;
    std::uint64_t fromPrediction = 0;  // of the delivered, read with a prediction
    std::uint64_t wrong = 0;
    std::uint64_t stale = 0;  // delivered again, or after a newer frame
    std::uint64_t lost = 0;  // sent and not delivered
    std::array<std::uint64_t, kRefusalCount> refused{};
    std::string firstWrong;  // what the first wrong frame was, for the report
    std::string firstStale;
};

// Streams `frames` frames of `session` through `channel` into a live
// FrameReceiver whose clock is the sender's (half a second after each frame
// is sent), fed in pieces of one frame.
inline RowResult runRow(const CommandSession& session, const Channel& channel, std::uint64_t frames, std::uint64_t seed,
                        Receive how = Receive::WithPredictions)
{
    RowResult row;
    std::int64_t nowMicros = 0;
    std::uint64_t sent = 0;
    FrameReceiver::Options options;
    options.clock = [&] { return nowMicros; };
    options.predictions = how == Receive::WithPredictions;
    FrameReceiver receiver(options, [&](const ReceivedFrame& f) {
        if (!f.delivered())
            return;
        const std::uint32_t id = static_cast<std::uint32_t>(f.decoded.message.header.number(ItemId::ID_msg));
        const std::optional<std::uint64_t> i = session.indexOf(id, sent);
        if (i && session.messageAt(*i) == f.decoded.message) {
            ++row.correct;
            return;
        }
        if (++row.wrong == 1)
            row.firstWrong = "ID_msg " + std::to_string(id) + " at stream offset " + std::to_string(f.offset);
    });
    std::mt19937_64 rng(seed);
    Bytes bytes;
    for (std::uint64_t i = 0; i < frames; ++i) {
        bytes.clear();
        channel.transmit(session.frameAt(i), bytes, rng);
        sent = i + 1;
        nowMicros = session.secondsAt(i) * 1'000'000 + 500'000;
        receiver.feed(bytes);
    }
    receiver.flush();
    row.sent = frames;
    row.lost = frames - row.correct;
    row.refused = receiver.stats().refused;
    row.fromPrediction = receiver.stats().fromPrediction;
    return row;
}

// `megabytes` of random bytes: anything delivered is wrong.
inline RowResult runRandomBytes(std::uint64_t megabytes, std::uint64_t seed, Receive how = Receive::WithPredictions)
{
    RowResult row;
    FrameReceiver::Options options;
    options.mode = FrameReceiver::Mode::Recording;
    options.predictions = how == Receive::WithPredictions;
    FrameReceiver receiver(options, [&](const ReceivedFrame& f) {
        if (f.delivered() && ++row.wrong == 1)
            row.firstWrong = "at stream offset " + std::to_string(f.offset);
    });
    std::mt19937_64 rng(seed);
    Bytes bytes(1 << 20);
    for (std::uint64_t m = 0; m < megabytes; ++m) {
        for (std::size_t k = 0; k < bytes.size(); k += 8) {
            const std::uint64_t r = rng();
            std::memcpy(&bytes[k], &r, 8);
        }
        receiver.feed(bytes);
    }
    receiver.flush();
    row.refused = receiver.stats().refused;
    return row;
}

}  // namespace rcm::test
