// A realistic session sent through bit errors into the one receive path, for
// tests/bench/bench_ber and tst_trialdecode: command frames one second apart,
// a few command changes a minute (an operator moving one control, or several
// together: throttle and pitch, a radio retuned), one flight plan upload, on
// the plain or the secure link. Either the console's commands as the
// aircraft reads them, or the aircraft's status frames as the console reads
// them, the console telling its receiver each command it sends
// (FrameReceiver::expect), the aircraft reporting it a second later, its
// landing gear 4 s later and its control surfaces slewing 40 degrees a
// second. Deterministic for a given seed.
#pragma once

#include "codec/message/FlightPlanTransfer.h"
#include "codec/message/MessageEncoder.h"
#include "codec/message/MessagePrediction.h"
#include "codec/receive/FrameReceiver.h"
#include "codec/receive/TrialDecoder.h"
#include "codec/secure/SecureCodec.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace rcm::test {

struct BerSessionResult {
    std::uint64_t frames = 0;          // sent and counted
    std::uint64_t deliveredCorrect = 0;
    std::uint64_t deliveredWrong = 0;  // delivered, but not what was sent with that ID_msg
    std::uint64_t refused = 0;         // judged and refused (may include false starts)
    std::map<std::string, std::uint64_t> refusedBy;  // refusalName -> count
    std::uint64_t fromPrediction = 0;  // of delivered
    std::uint64_t planFrames = 0;      // frames carrying a flight plan section
    std::uint64_t planDelivered = 0;
    TrialDecoder::Stats trials;
};

struct BerSessionOptions {
    double ber = 0;
    std::uint64_t frames = 1000;
    bool secure = false;
    bool predictions = true;         // false: plain RS only
    std::uint64_t cleanStart = 5;    // frames before the counted ones at BER 0 (link set up on the ground)
    double changesPerMinute = 3;
    std::uint64_t planAt = 60;       // counted frame at which the plan upload starts
    std::size_t planBytes = 1200;
    std::uint64_t seed = 1;
    int minItemsPerChange = 1;  // commands one change sets at once
    int maxItemsPerChange = 1;
    bool status = false;  // the aircraft's status frames, read by the console
};

// Probability that a codeword with byte error rate q has at most 16 errors.
inline double codewordReadable(double q)
{
    double sum = 0;
    for (int k = 0; k <= 16; ++k)
        sum += std::exp(std::lgamma(256.0) - std::lgamma(k + 1.0) - std::lgamma(256.0 - k) + k * std::log(q) +
                        (255 - k) * std::log1p(-q));
    return sum;
}

// The plain RS bound: both codewords within 16 byte errors.
inline double plainRsBound(double ber)
{
    const double q = 1 - std::pow(1 - ber, 8);
    const double p = codewordReadable(q);
    return p * p;
}

inline Message sessionStartMessage()
{
    Message m;
    m.header.set(ItemId::ID_msg, 4'000'000);
    m.header.set(ItemId::ID_UA_source, Value::station({44, 133}));
    m.header.set(ItemId::time_UTC, 235800);  // two minutes before midnight: date_UTC rolls over
    m.header.set(ItemId::date_UTC, 261231);
    m.header.set(ItemId::ID_BLK12_format, Value::pair(1, 1));
    m.header.set(ItemId::ID_GCS_destination, Value::station({44, 1}));
    for (std::uint8_t e = 1; e <= 2; ++e) {
        Unit& engine = m.addEngine(e);
        engine.set(ItemId::eng_status, 0x90);  // GCS control, no slave
        engine.set(ItemId::eng_prop_pitch, 120);
        engine.set(ItemId::eng_carb_SET, 137);
    }
    m.flaps.set(ItemId::FLAP_status, 0x90);
    for (ItemId f : {ItemId::F_aileron_LHS_set, ItemId::F_aileron_RHS_set, ItemId::F_lift_set, ItemId::F_rudder_set,
                     ItemId::F_elev_set, ItemId::F_airbrake_set})
        m.flaps.set(f, 0);
    m.settings.set(ItemId::land_wheels, 0xAA);
    m.settings.set(ItemId::lights, 0x99);
    Unit& radio = m.addRadio("VHF1");
    radio.set(ItemId::receiver_control, 0xA0);
    radio.set(ItemId::Rx_freq, 121500);
    radio.set(ItemId::Tx_freq, 121500);
    radio.set(ItemId::Tx_OP_power, 30);
    m.sense.set(ItemId::SA_zoom_FWD_cam, 10);
    Unit& camera = m.addCamera("NIK", 1);
    camera.set(ItemId::cam_mag_compass, 9000);
    camera.set(ItemId::cam_elev, -1500);
    camera.set(ItemId::cam_zoom_set, 40);
    return m;
}

// One change an operator makes: a new value for one single-byte command.
inline void changeOneCommand(Message& m, std::mt19937_64& rng)
{
    auto pick = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
    switch (pick(0, 4)) {
    case 0: m.engines[static_cast<std::size_t>(pick(0, 1))].set(ItemId::eng_carb_SET, pick(0, 255)); break;
    case 1: m.engines[static_cast<std::size_t>(pick(0, 1))].set(ItemId::eng_prop_pitch, pick(0, 255)); break;
    case 2: m.flaps.set(ItemId::F_elev_set, pick(-30, 30)); break;
    case 3: m.flaps.set(ItemId::F_rudder_set, pick(-30, 30)); break;
    default: m.cameras[0].set(ItemId::cam_zoom_set, pick(0, 255)); break;
    }
}

// One change of `items` different commands at once, of every size: one-byte
// settings, two-byte camera angles, four-byte radio frequencies, two-bit
// fields (lights, landing gear).
inline void changeCommands(Message& m, int items, std::mt19937_64& rng)
{
    auto pick = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
    constexpr int kKinds = 12;
    std::vector<int> kinds(kKinds);
    for (int k = 0; k < kKinds; ++k)
        kinds[static_cast<std::size_t>(k)] = k;
    std::shuffle(kinds.begin(), kinds.end(), rng);
    for (int i = 0; i < items && i < kKinds; ++i) {
        switch (kinds[static_cast<std::size_t>(i)]) {
        case 0: m.engines[static_cast<std::size_t>(pick(0, 1))].set(ItemId::eng_carb_SET, pick(0, 255)); break;
        case 1: m.engines[static_cast<std::size_t>(pick(0, 1))].set(ItemId::eng_prop_pitch, pick(0, 255)); break;
        case 2: m.flaps.set(ItemId::F_elev_set, pick(-30, 30)); break;
        case 3: m.flaps.set(ItemId::F_rudder_set, pick(-30, 30)); break;
        case 4: m.cameras[0].set(ItemId::cam_zoom_set, pick(0, 255)); break;
        case 5: m.cameras[0].set(ItemId::cam_mag_compass, pick(0, 35999)); break;
        case 6: m.cameras[0].set(ItemId::cam_elev, pick(-9000, 9000)); break;
        case 7: m.radios[0].set(ItemId::Rx_freq, 118000 + 25 * pick(0, 760)); break;
        case 8: m.radios[0].set(ItemId::Tx_freq, 118000 + 25 * pick(0, 760)); break;
        case 9: m.settings.set(ItemId::lights, (pick(0, 1) ? 0x80 : 0x40) | (pick(0, 1) ? 0x20 : 0x10) |
                                                   (pick(0, 1) ? 0x08 : 0x04) | (pick(0, 1) ? 0x02 : 0x01));
            break;
        case 10: m.settings.set(ItemId::land_wheels, m.settings.number(ItemId::land_wheels) == 0xAA ? 0x55 : 0xAA); break;
        default: m.sense.set(ItemId::SA_zoom_FWD_cam, pick(0, 255)); break;
        }
    }
}

// The aircraft of a status session: reports what was commanded a second
// before, its landing gear once it has moved (4 s) and its control surfaces
// as they slew (40 degrees a second).
class StatusModel {
public:
    explicit StatusModel(const Message& command) : m_state(command) { m_state.flightPlan = {}; }

    // The status sent at `seconds` (its counter `id`), having received `command`.
    Message next(const Message& command, std::uint32_t id, std::uint32_t time, std::uint32_t date)
    {
        Message s = withCommanded(m_state, command);
        const auto gear = command.settings.number(ItemId::land_wheels);
        if (gear != m_gearCommanded) {
            m_gearCommanded = gear;
            m_gearMoving = 4;
        }
        if (m_gearMoving > 0 && --m_gearMoving > 0)
            s.settings.set(ItemId::land_wheels, m_state.settings.number(ItemId::land_wheels));
        for (ItemId f : {ItemId::F_aileron_LHS_set, ItemId::F_aileron_RHS_set, ItemId::F_lift_set, ItemId::F_rudder_set,
                         ItemId::F_elev_set, ItemId::F_airbrake_set}) {
            const std::int64_t was = m_state.flaps.number(f);
            const std::int64_t to = command.flaps.number(f);
            s.flaps.set(f, to > was ? std::min(to, was + 40) : std::max(to, was - 40));
        }
        s.header.set(ItemId::ID_msg, id);
        s.header.set(ItemId::time_UTC, time);
        s.header.set(ItemId::date_UTC, date);
        s.flightPlan = m_acknowledgement;
        m_state = s;
        return s;
    }
    void acknowledge(const FlightPlanSection& ack) { m_acknowledgement = ack; }

private:
    Message m_state;
    std::int64_t m_gearCommanded = -1;
    int m_gearMoving = 0;
    FlightPlanSection m_acknowledgement;
};

// Flips each bit with probability `ber` (gaps between flips drawn geometrically).
class BitErrorChannel {
public:
    BitErrorChannel(double ber, std::uint64_t seed) : m_rng(seed), m_ber(ber) { draw(); }
    void apply(std::vector<std::uint8_t>& bytes)
    {
        if (m_ber <= 0)
            return;
        const std::uint64_t bits = bytes.size() * 8;
        while (m_next < m_at + bits) {
            const std::uint64_t b = m_next - m_at;
            bytes[b / 8] ^= static_cast<std::uint8_t>(0x80u >> (b % 8));
            draw();
        }
        m_at += bits;
    }

private:
    void draw() { m_next += 1 + std::geometric_distribution<std::uint64_t>(m_ber)(m_rng); }
    std::mt19937_64 m_rng;
    double m_ber;
    std::uint64_t m_at = 0;
    std::uint64_t m_next = 0;
};

inline BerSessionResult runBerSession(const BerSessionOptions& o)
{
    std::mt19937_64 rng(o.seed);
    BitErrorChannel channel(o.ber, o.seed * 7919 + 1);
    const std::int64_t startSeconds = *secure::stampSeconds(235800, 261231);
    std::int64_t nowMicros = startSeconds * 1'000'000;

    std::unique_ptr<secure::SecureEndpoint> console, aircraft;
    if (o.secure) {
        secure::SecretKey psk;
        std::mt19937_64 keyRng(o.seed ^ 0x5EC);
        for (std::uint8_t& b : psk.mutableBytes())
            b = static_cast<std::uint8_t>(keyRng());
        secure::SecureEndpoint::Options eo;
        eo.persistState = false;
        eo.clock = [&nowMicros] { return nowMicros / 1'000'000; };
        std::string error;
        console = secure::SecureEndpoint::fromKey(psk, secure::Direction::GcsToUa, "", error, eo);
        aircraft = secure::SecureEndpoint::fromKey(psk, secure::Direction::UaToGcs, "", error, eo);
        if (!console || !aircraft)
            throw std::runtime_error("secure endpoint: " + error);
    }
    // Commands: the aircraft reads them. Status: the console does.
    secure::SecureEndpoint* sender = o.status ? aircraft.get() : console.get();
    secure::SecureEndpoint* reader = o.status ? console.get() : aircraft.get();

    FrameReceiver::Options ro;
    ro.clock = [&nowMicros] { return nowMicros; };
    if (o.secure) {
        ro.keys.codecs = {reader->receiver.get()};
        ro.keys.guard = reader->guard.get();
    }
    ro.predictions = o.predictions;

    BerSessionResult result;
    std::map<std::uint32_t, Message> sent;  // by ID_msg, counted frames only
    std::map<std::uint32_t, bool> planFrame;
    FrameReceiver receiver(ro, [&](const ReceivedFrame& f) {
        if (!f.delivered()) {
            ++result.refused;
            ++result.refusedBy[std::string(refusalName(*f.refusal))];
            return;
        }
        const auto id = static_cast<std::uint32_t>(f.decoded.message.header.number(ItemId::ID_msg));
        const auto it = sent.find(id);
        if (it == sent.end())
            return;  // a clean start frame
        if (it->second == f.decoded.message) {
            ++result.deliveredCorrect;
            result.planDelivered += planFrame[id];
        } else {
            ++result.deliveredWrong;
        }
        result.fromPrediction += f.fromPrediction;
    });

    Message m = sessionStartMessage();
    StatusModel statusModel(m);
    std::vector<std::uint8_t> plan(o.planBytes);
    for (std::uint8_t& b : plan)
        b = static_cast<std::uint8_t>(rng());
    std::unique_ptr<FlightPlanUploader> uploader;
    std::uint64_t planSections = 0;
    const double changeChance = o.changesPerMinute / 60.0;
    const std::uint64_t total = o.cleanStart + o.frames;
    for (std::uint64_t i = 0; i < total; ++i) {
        if (i > 0) {
            m = advanceMessage(m, 1);
            if (std::uniform_real_distribution<double>(0, 1)(rng) < changeChance) {
                if (o.maxItemsPerChange <= 1)
                    changeOneCommand(m, rng);
                else
                    changeCommands(m, std::uniform_int_distribution<int>(o.minItemsPerChange, o.maxItemsPerChange)(rng),
                                   rng);
            }
        }
        const bool counted = i >= o.cleanStart;
        if (counted && i - o.cleanStart == o.planAt)
            uploader = std::make_unique<FlightPlanUploader>(7, plan, o.secure ? secure::kMaxFlightPlanData
                                                                             : FlightPlanSection::kMaxData);
        m.flightPlan = {};
        if (uploader)
            if (std::optional<FlightPlanSection> s = uploader->next()) {
                m.flightPlan = *s;
                ++planSections;
            }
        Message out = m;
        if (o.status) {
            // The status sent this second reports the command of the last
            // one; the plan is acknowledged once every section went out once.
            if (uploader && planSections == uploader->sections().size() + 1)
                statusModel.acknowledge(FlightPlanAcknowledgement{7, uploader->descriptor(), {}}.toSection());
            out = statusModel.next(m, static_cast<std::uint32_t>(2'000'000 + i),
                                   static_cast<std::uint32_t>(m.header.number(ItemId::time_UTC)),
                                   static_cast<std::uint32_t>(m.header.number(ItemId::date_UTC)));
        }
        Diagnostics errors;
        std::optional<EncodedBlocks> blocks = o.secure ? sender->sender->encode(out, errors) : encodeBlocks(out, errors);
        if (!blocks)
            throw std::runtime_error("session message does not encode: " + (errors.empty() ? std::string() : errors.front().toString()));
        const FrameBytes frame = makeFrame(blocks->block1, blocks->block2);
        std::vector<std::uint8_t> bytes(frame.begin(), frame.end());
        if (counted) {
            const auto id = static_cast<std::uint32_t>(out.header.number(ItemId::ID_msg));
            sent[id] = out;
            planFrame[id] = !out.flightPlan.empty() && out.flightPlan.sectionId < kFirstControlSectionId;
            result.planFrames += planFrame[id];
            channel.apply(bytes);
            ++result.frames;
        }
        nowMicros = (startSeconds + static_cast<std::int64_t>(i)) * 1'000'000 + 500'000;
        receiver.feed(bytes);
        if (o.status)
            receiver.expect(m);  // the console's command of this second, sent
    }
    receiver.flush();
    if (receiver.predictions())
        result.trials = receiver.predictions()->stats();
    return result;
}

}  // namespace rcm::test
