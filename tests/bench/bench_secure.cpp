// Secure link benchmark: what AES-256-HCTR2 encryption and authentication add
// to encoding and decoding one frame. Not part of the test run; the figures
// and the command are written down in docs/performance.md.
//
//   build/bin/bench_secure
//
// The message is the largest ordinary command (the well-equipped aircraft,
// full header) with a 199-byte flight plan section, so both blocks carry
// data. Plain and secure are encoded with the same options (16 bytes of
// BLOCK 1 padding, sections of at most 199 bytes): the only difference
// measured is the cipher and its checks. Each figure is the fastest of 200
// rounds of 1,000 frames, plain and secure rounds interleaved: on a busy
// machine the fastest round is the one nothing interrupted, and neither side
// is favoured by when it ran.
//
// Below the table, the receiver's added work is taken apart: HCTR2 alone
// (two 223-byte decipherings a frame) and the structure checks alone, so
// that the share of each in the clean frame's overhead can be read off.
#include "codec/message/Airframe.h"
#include "codec/secure/Hctr2.h"
#include "codec/message/MessageDecoder.h"
#include "codec/message/MessageEncoder.h"
#include "codec/secure/SecureCodec.h"
#include "codec/voice/SecureVoice.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <numeric>
#include <random>
#include <span>
#include <string>
#include <vector>

using namespace rcm;
using Clock = std::chrono::steady_clock;

namespace {

constexpr int kFrames = 1000;
constexpr int kRounds = 200;
constexpr std::uint32_t kTime = 102030;
constexpr std::uint32_t kDate = 261112;

Message fullCommand(std::uint32_t id)
{
    Message m = restingCommand(Airframe::wellEquipped());
    m.header.set(ItemId::ID_msg, id & 0xFFFFFF);
    m.header.set(ItemId::ID_UA_source, Value::pair(44, 133));
    m.header.set(ItemId::time_UTC, kTime);
    m.header.set(ItemId::date_UTC, kDate);
    m.header.set(ItemId::ID_BLK12_format, Value::pair(1, 1));
    m.header.set(ItemId::ID_GCS_destination, Value::pair(44, 30226));
    m.header.set(ItemId::ID_GCS_backup, Value::pair(44, 41251));
    m.flightPlan.planId = 0xC0FFEE;
    m.flightPlan.sectionId = static_cast<std::uint16_t>(id);
    m.flightPlan.data.resize(secure::kMaxFlightPlanData);
    std::iota(m.flightPlan.data.begin(), m.flightPlan.data.end(), static_cast<std::uint8_t>(id));
    return m;
}

// Microseconds per frame of the fastest round.
template <typename F>
double best(std::vector<double>& rounds, F&& f)
{
    const auto t0 = Clock::now();
    f();
    rounds.push_back(std::chrono::duration<double, std::micro>(Clock::now() - t0).count() / kFrames);
    return *std::min_element(rounds.begin(), rounds.end());
}

void row(const char* what, double plain, double secure)
{
    std::printf("| %-44s | %8.2f | %8.2f | %+7.2f | %+6.1f %% |\n", what, plain, secure, secure - plain,
                100.0 * (secure - plain) / plain);
}

// The voice on a keyed link (codec/voice/SecureVoice.h): sealing and opening
// one 24-byte secure frame (two Codec 2 frames, 40 ms of speech), the
// fastest of kRounds rounds of kFrames frames, and the share of one core
// that 25 of them a second each way take.
void benchVoice()
{
    const secure::SecretKey psk = secure::generateKey();
    const secure::VoiceKeys keys = secure::deriveVoiceKeys(psk, secure::Direction::GcsToUa);
    const std::int64_t now = std::int64_t(std::chrono::duration_cast<std::chrono::microseconds>(
                                              std::chrono::system_clock::now().time_since_epoch())
                                              .count());
    voice::VoiceFrame speech;
    speech.kind = voice::FrameKind::Speech;
    std::iota(speech.payload.begin(), speech.payload.end(), std::uint8_t(1));
    std::vector<double> sealRounds, openRounds;
    double seal = 0, open = 0;
    std::uint64_t sink = 0;
    for (int r = 0; r < kRounds; ++r) {
        std::vector<std::uint8_t> stream(kFrames * voice::kSecureFrameBytes);
        voice::SecureVoiceSealer sealer(keys, [now] { return now; });
        seal = best(sealRounds, [&] {
            for (int i = 0; i < kFrames; ++i)
                sealer.seal(speech, speech,
                            std::span<std::uint8_t, voice::kSecureFrameBytes>(
                                stream.data() + std::size_t(i) * voice::kSecureFrameBytes, voice::kSecureFrameBytes));
        });
        voice::SecureVoiceOpener opener(keys, [now] { return now; });
        std::vector<std::uint8_t> plain;
        plain.reserve(kFrames * 2 * voice::kFrameBytes);
        open = best(openRounds, [&] { opener.open(stream, plain); });
        sink += plain.size() + opener.stats().accepted;
    }
    // Under attack: frames with the sync and right parity and a random rest,
    // each tried at every counter the window allows (the worst case).
    std::vector<std::uint8_t> forged(kFrames * voice::kSecureFrameBytes);
    std::mt19937 rng(1);
    for (std::size_t f = 0; f < std::size_t(kFrames); ++f) {
        const std::span<std::uint8_t> frame(forged.data() + f * voice::kSecureFrameBytes, voice::kSecureFrameBytes);
        for (auto& b : frame)
            b = static_cast<std::uint8_t>(rng());
        frame[0] = voice::kSecureSyncByte;
        voice::addParity(frame);
    }
    std::vector<double> forgedRounds;
    double refuse = 0;
    for (int r = 0; r < kRounds / 10; ++r) {
        // A clock a second on at every look: the budget of searches never
        // runs out, every forged frame is searched for whole.
        std::int64_t t = now;
        voice::SecureVoiceOpener opener(keys, [&t] { return t += 1000000; });
        std::vector<std::uint8_t> plain;
        refuse = best(forgedRounds, [&] { opener.open(forged, plain); });
        sink += opener.stats().forged;
    }
    if (sink == 1)
        std::printf(" ");
    std::printf("\nvoice on a keyed link, fastest of %d rounds of %d secure frames (40 ms of speech each):\n", kRounds,
                kFrames);
    std::printf("seal %.2f us, open %.2f us per frame; 25 frames a second each way: %.4f %% of one core\n", seal, open,
                100.0 * 25 * (seal + open) / 1e6);
    std::printf("a forged frame refused after every counter in the 30 s window was tried: %.2f us; at most %d such "
                "searches a second: %.3f %% of one core at most\n",
                refuse, voice::SecureVoiceOpener::kMaxSearchesPerSecond,
                100.0 * voice::SecureVoiceOpener::kMaxSearchesPerSecond * refuse / 1e6);
}

}  // namespace

int main()
{
    std::mt19937_64 rng(1);
    std::array<std::uint8_t, secure::kKeySize> raw{};
    for (auto& b : raw)
        b = static_cast<std::uint8_t>(rng());
    const secure::SecretKey psk(raw);
    const secure::SecureCodec codec(psk, secure::Direction::GcsToUa);
    const EncodeOptions options = secure::encodeOptions();

    std::vector<Message> messages;
    for (int i = 0; i < kFrames; ++i)
        messages.push_back(fullCommand(static_cast<std::uint32_t>(i + 1)));

    // Frames to decode: plain, secure, and both with 16 byte errors per codeword.
    std::vector<DatagramBytes> plainFrames, secureFrames;
    for (const Message& m : messages) {
        Diagnostics errors;
        const EncodedBlocks p = *encodeBlocks(m, errors, options);
        plainFrames.push_back(makeDatagram(p.block1, p.block2));
        const EncodedBlocks s = *codec.encode(m, errors);
        secureFrames.push_back(makeDatagram(s.block1, s.block2));
    }
    auto corrupted = [&](std::vector<DatagramBytes> frames) {
        std::mt19937_64 r(16);
        for (auto& f : frames)
            for (std::size_t cw = 0; cw < 2; ++cw)
                for (int e = 0; e < 16; ++e)
                    f[cw * kCodewordSize + static_cast<std::size_t>(e) * 15 + r() % 15] ^= static_cast<std::uint8_t>(1 + r() % 255);
        return frames;
    };
    const std::vector<DatagramBytes> plainBad = corrupted(plainFrames), secureBad = corrupted(secureFrames);

    // The receiver's cipher on its own, with the tweaks the frames were sent with.
    const secure::SecretKey directionKey = secure::deriveDirectionKey(psk, secure::Direction::GcsToUa);
    const Hctr2 cipher(directionKey.bytes());
    std::vector<secure::Block2Tweak> block2Tweaks;
    std::vector<EncodedBlocks> plainBlocks;
    for (const Message& m : messages) {
        Diagnostics errors;
        plainBlocks.push_back(*encodeBlocks(m, errors, options));
        secure::HeaderStamp stamp;
        std::string why;
        secure::checkBlock1Structure(plainBlocks.back().block1, stamp, why);
        block2Tweaks.push_back(secure::block2Tweak(secure::Direction::GcsToUa, stamp));
    }
    const secure::Block1Tweak block1Tweak = secure::block1Tweak(secure::Direction::GcsToUa);

    std::vector<double> encPlain, encSecure, decPlain, decSecure, badPlain, badSecure, cipherOnly, hctr2Only, checksOnly;
    double ePlain = 0, eSecure = 0, dPlain = 0, dSecure = 0, bPlain = 0, bSecure = 0, cOnly = 0, hOnly = 0, kOnly = 0;
    std::size_t sink = 0;
    for (int round = 0; round < kRounds; ++round) {
        ePlain = best(encPlain, [&] {
            for (const Message& m : messages) {
                Diagnostics errors;
                const EncodedBlocks b = *encodeBlocks(m, errors, options);
                sink += makeFrame(b.block1, b.block2)[100];
            }
        });
        eSecure = best(encSecure, [&] {
            for (const Message& m : messages) {
                Diagnostics errors;
                const EncodedBlocks b = *codec.encode(m, errors);
                sink += makeFrame(b.block1, b.block2)[100];
            }
        });
        dPlain = best(decPlain, [&] {
            for (const DatagramBytes& f : plainFrames)
                sink += decodeFrame(f).message.engines.size();
        });
        // The receiver's whole path: RS, decipher, check, parse, replay and time check.
        dSecure = best(decSecure, [&] {
            secure::ReplayGuard::Options go;
            go.clock = [] { return *secure::stampSeconds(kTime, kDate); };
            secure::ReplayGuard guard(go);
            for (const DatagramBytes& f : secureFrames) {
                const secure::Opened o = secure::openFrame(codec, &guard, decodeCodewords(f));
                sink += o.accepted ? o.decoded.message.engines.size() : 1000;
            }
        });
        bPlain = best(badPlain, [&] {
            for (const DatagramBytes& f : plainBad)
                sink += decodeFrame(f).message.engines.size();
        });
        bSecure = best(badSecure, [&] {
            secure::ReplayGuard::Options go;
            go.clock = [] { return *secure::stampSeconds(kTime, kDate); };
            secure::ReplayGuard guard(go);
            for (const DatagramBytes& f : secureBad) {
                const secure::Opened o = secure::openFrame(codec, &guard, decodeCodewords(f));
                sink += o.accepted ? o.decoded.message.engines.size() : 1000;
            }
        });
        cOnly = best(cipherOnly, [&] {
            for (const DatagramBytes& f : secureFrames) {
                DecodedBlocks d;
                std::copy_n(f.begin(), kBlockSize, d.block1.begin());
                std::copy_n(f.begin() + kCodewordSize, kBlockSize, d.block2.begin());
                sink += codec.decryptBlocks(d).authentic;
            }
        });
        hOnly = best(hctr2Only, [&] {
            Block p1, p2;
            for (std::size_t i = 0; i < secureFrames.size(); ++i) {
                const DatagramBytes& f = secureFrames[i];
                cipher.decrypt(block1Tweak, std::span(f.data(), kBlockSize), p1);
                cipher.decrypt(block2Tweaks[i], std::span(f.data() + kCodewordSize, kBlockSize), p2);
                sink += p1[kBlockSize - 1] + p2[0];
            }
        });
        kOnly = best(checksOnly, [&] {
            for (const EncodedBlocks& b : plainBlocks) {
                secure::HeaderStamp stamp;
                std::string why;
                sink += secure::checkBlock1Structure(b.block1, stamp, why) + secure::checkBlock2Structure(b.block2, why);
            }
        });
    }
    if (sink % (3 * kFrames) == 1)  // keeps the work from being optimised away
        std::printf(" ");

    std::printf("AES-256-HCTR2 secure link, fastest of %d rounds of %d frames, POLYVAL %s\n\n", kRounds, kFrames,
                detail::polyvalPclmulAvailable() ? "pclmul" : "portable");
    std::printf("| %-44s | %8s | %8s | %7s | %8s |\n", "us per frame", "plain", "secure", "added", "overhead");
    std::printf("|%s|%s|%s|%s|%s|\n", std::string(46, '-').c_str(), std::string(10, '-').c_str(),
                std::string(10, '-').c_str(), std::string(9, '-').c_str(), std::string(10, '-').c_str());
    row("encode (model -> frame)", ePlain, eSecure);
    row("decode clean frame (RS + parse [+ auth])", dPlain, dSecure);
    row("decode, 16 byte errors per codeword", bPlain, bSecure);
    std::printf("\ndecipher + check alone (no RS): %.2f us per frame\n", cOnly);
    std::printf("of which HCTR2 (two 223-byte blocks deciphered): %.2f us, structure checks, which are the decode of"
                " both blocks (checkBlock1Structure + checkBlock2Structure): %.2f us\n",
                hOnly, kOnly);
    benchVoice();
    return 0;
}
