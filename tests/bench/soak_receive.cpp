// Soak of the receive path: a realistic command session through each kind
// of channel damage, 10^6 frames a row, and 100 MB of random bytes, received
// as the link worker receives (FrameReceiver with TrialDecoder's
// predictions; --plain: RS alone). Prints, per row, frames sent, delivered
// correct (and how many of them a prediction read), delivered WRONG, lost
// (sent and not delivered correct) and the refusals by reason. Delivered
// WRONG must be 0 in every row; the exit status is 1 otherwise.
//
// --attacks: what an attacker or a broken line does instead
// (tests/support/ReceiveAttacks.h): old frames replayed live and into a recording,
// splices of two frames' codewords on the plain and keyed link, streams cut,
// overlapped, with garbage between frames and byte slips (each frame libfec
// reads at its true place must be delivered), outages after which the sender
// goes on with its counter. Stale or repeated deliveries, wrong ones and
// frames libfec reads but the receiver lost must be 0 (splices on the plain
// link are measured: the profile ties nothing between the two codewords);
// exit status 1 otherwise.
//
//   soak_receive [--seed S] [--plain] [FRAMES_PER_ROW [ROW_NAME_PREFIX]]
//   soak_receive [--seed S] --attacks [FRAMES_PER_ROW [ROW_NAME_PREFIX]]
//
// --seed S draws every row's damage from other random numbers (S = 0, the
// default, is the tables in docs/performance.md).
#include "tests/support/ReceiveAttacks.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

using namespace rcm;
using namespace rcm::test;

namespace {

std::string refusals(const RowResult& r)
{
    std::string s;
    for (int i = 0; i < kRefusalCount; ++i) {
        if (r.refused[static_cast<std::size_t>(i)] == 0)
            continue;
        s += (s.empty() ? "" : ", ") + std::string(refusalName(static_cast<Refusal>(i))) + " " +
             std::to_string(r.refused[static_cast<std::size_t>(i)]);
    }
    return s.empty() ? "-" : s;
}

}  // namespace

int attacks(std::uint64_t frames, std::string_view only, std::uint64_t seedOffset)
{
    bool failed = false;
    std::printf("| row | frames | attacks | delivered correct | WRONG | stale or repeated | libfec reads | of those lost | refused by reason | s |\n");
    std::printf("|---|---:|---:|---:|---:|---:|---:|---:|---|---:|\n");
    std::fflush(stdout);
    const auto row = [&](const std::string& name, const std::function<AttackResult()>& run, std::uint64_t allowedWrong = 0,
                         bool reportUndetectable = false, bool holdLost = true) {
        if (!only.empty() && name.rfind(only, 0) != 0)
            return;
        const auto t0 = std::chrono::steady_clock::now();
        const AttackResult r = run();
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        // Splices on the plain link are measured, not held to 0: the profile
        // ties nothing between a frame's two codewords.
        const bool bad = (!reportUndetectable && r.row.wrong > allowedWrong) || r.row.stale != 0 ||
                         (holdLost && r.falseRefusals != 0);
        failed = failed || bad;
        std::printf("| %s | %llu | %llu | %llu | %llu%s | %llu | %llu | %llu | %s | %.0f |\n", name.c_str(),
                    static_cast<unsigned long long>(r.row.sent), static_cast<unsigned long long>(r.attacks),
                    static_cast<unsigned long long>(r.row.correct), static_cast<unsigned long long>(r.row.wrong),
                    reportUndetectable ? (" (the profile cannot tell " + std::to_string(r.undetectable) + ")").c_str() : "",
                    static_cast<unsigned long long>(r.row.stale), static_cast<unsigned long long>(r.recoverable),
                    static_cast<unsigned long long>(r.falseRefusals), refusals(r.row).c_str(), seconds);
        if (bad)
            std::printf("|   first wrong: %s; first stale: %s; first lost: %s |\n", r.row.firstWrong.c_str(),
                        r.row.firstStale.c_str(), r.firstFalseRefusal.c_str());
        std::fflush(stdout);
    };
    const CommandSession session;
    row("replay, live", [&] { return runReplay(session, frames, 0.5, seedOffset + 101, FrameReceiver::Mode::Live); });
    row("replay, recording", [&] { return runReplay(session, frames, 0.5, seedOffset + 102, FrameReceiver::Mode::Recording); });
    CommandSession plans;
    plans.uploadEvery = 40;
    plans.uploadStart = 2;
    plans.planBytes = 1500;
    row("splices, plain, plans back to back", [&] { return runSplices(plans, frames, 0.03, seedOffset + 103); }, 0, true);
    row("splices, plain, the soak's session", [&] { return runSplices(session, frames, 0.03, seedOffset + 104); }, 0, true);
    secure::SecretKey key;
    key.mutableBytes()[3] = 9;
    const secure::SecureCodec codec(key, secure::Direction::GcsToUa);
    CommandSession keyedPlans = plans;
    keyedPlans.codec = &codec;
    row("splices, keyed, plans back to back", [&] { return runSplices(keyedPlans, frames, 0.03, seedOffset + 105); });
    row("cut then intact", [&] { return runStreamDamage(session, StreamDamage::CutThenIntact, frames, seedOffset + 106); });
    row("overlap", [&] { return runStreamDamage(session, StreamDamage::Overlap, frames, seedOffset + 107); });
    row("garbage between", [&] { return runStreamDamage(session, StreamDamage::GarbageBetween, frames, seedOffset + 108); });
    row("byte slips 1-8", [&] { return runStreamDamage(session, StreamDamage::ByteSlips, frames, seedOffset + 109); });
    // Beyond the kinds a line makes (one slip a frame): lost frames are
    // measured here, not held to 0; wrong ones are.
    row("two byte slips a frame", [&] {
        return runStreamDamage(session, StreamDamage::TwoByteSlips, frames, seedOffset + 112);
    }, 0, false, false);
    row("mixed: cut, overlap, garbage, slips, none", [&] {
        return runStreamDamage(session, StreamDamage::Mixed, frames, seedOffset + 111);
    });
    row("outages 2-600 s", [&] { return runOutages(session, frames, 0.02, seedOffset + 110); });
    return failed ? 1 : 0;
}

int main(int argc, char** argv)
{
    std::uint64_t seedOffset = 0;
    if (argc > 2 && std::string_view(argv[1]) == "--seed") {
        seedOffset = std::strtoull(argv[2], nullptr, 10) * 1000;
        argc -= 2;
        argv += 2;
    }
    if (argc > 1 && std::string_view(argv[1]) == "--attacks")
        return attacks(argc > 2 ? std::strtoull(argv[2], nullptr, 10) : 1'000'000, argc > 3 ? argv[3] : "",
                       seedOffset);
    Receive how = Receive::WithPredictions;
    if (argc > 1 && std::string_view(argv[1]) == "--plain") {
        how = Receive::Plain;
        --argc;
        ++argv;
    }
    const std::uint64_t frames = argc > 1 ? std::strtoull(argv[1], nullptr, 10) : 1'000'000;
    const std::string_view only = argc > 2 ? argv[2] : "";
    using K = Channel::Kind;
    const std::vector<Channel> rows = {
        {K::Clean, 0, "clean"},
        {K::Slip, 0, "slip 1-3 bytes"},
        {K::OverwriteBurst, 0, "overwrite burst 20-60"},
        {K::InsertBurst, 0, "insertion burst 20-60"},
        {K::BitErrors, 1e-3, "BER 1e-3"},
        {K::BitErrors, 3e-3, "BER 3e-3"},
        {K::BitErrors, 1e-2, "BER 1e-2"},
        {K::BitErrors, 2e-2, "BER 2e-2"},
        {K::BitErrors, 3e-2, "BER 3e-2"},
        {K::ByteErrors16, 0, "16 byte errors/codeword"},
        {K::ConstantFollower, 0, "preamble + constant"},
        {K::RandomFollower, 0, "preamble + random"},
    };
    const CommandSession session;
    bool anyWrong = false;
    std::printf("| channel (each frame) | sent | delivered correct | of which predicted | delivered WRONG | lost | refused by reason | s |\n");
    std::printf("|---|---:|---:|---:|---:|---:|---|---:|\n");
    std::fflush(stdout);
    std::uint64_t seed = seedOffset + 1;
    const auto print = [&](const std::string& name, const RowResult& r, double seconds) {
        anyWrong = anyWrong || r.wrong != 0;
        std::printf("| %s | %llu | %llu | %llu | %llu | %llu | %s | %.0f |\n", name.c_str(),
                    static_cast<unsigned long long>(r.sent), static_cast<unsigned long long>(r.correct),
                    static_cast<unsigned long long>(r.fromPrediction),
                    static_cast<unsigned long long>(r.wrong), static_cast<unsigned long long>(r.lost),
                    refusals(r).c_str(), seconds);
        if (r.wrong)
            std::printf("|   first wrong: %s |\n", r.firstWrong.c_str());
        std::fflush(stdout);
    };
    for (const Channel& c : rows) {
        ++seed;
        if (!only.empty() && c.name.rfind(only, 0) != 0)
            continue;
        const auto t0 = std::chrono::steady_clock::now();
        const RowResult r = runRow(session, c, frames, seed, how);
        print(c.name, r, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    }
    if (only.empty() || std::string_view("100 MB random bytes").rfind(only, 0) == 0) {
        const auto t0 = std::chrono::steady_clock::now();
        print("100 MB random bytes", runRandomBytes(100, seed + 1, how),
              std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    }
    return anyWrong ? 1 : 0;
}
