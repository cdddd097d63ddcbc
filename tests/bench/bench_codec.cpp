// Codec benchmark: encode and decode rates beside libfec's own decode_rs_ccsds
// measured in the same run, synchroniser throughput, and a bit-error-rate sweep
// against the theoretical RS(255,223) bound. Not part of the test run: speed
// is measured here and written down in docs/performance.md.
//
//   build/bin/bench_codec                 all measurements
//   build/bin/bench_codec --day FILE      also write a 24-hour recording (86,400 frames)
//   build/bin/bench_codec --libfec FILE   only: decode every 600-byte frame of FILE with
//                                         libfec's decode_rs_ccsds (both codewords), and read FILE
//                                         through the receive path as `rcm decode --summary` does,
//                                         fastest of 5 each
#include "codec/message/Airframe.h"
#include "codec/message/MessageDecoder.h"
#include "codec/message/MessageEncoder.h"
#include "codec/message/TextFormat.h"
#include "codec/frame/ReedSolomon.h"
#include "codec/frame/StreamSync.h"
#include "codec/receive/FrameReceiver.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <numeric>
#include <random>
#include <string>
#include <vector>

using namespace rcm;
using Clock = std::chrono::steady_clock;

namespace {

double secondsSince(Clock::time_point t0)
{
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

// The fastest of several runs: other processes only ever add time, so the
// minimum is the figure least disturbed by them.
template <typename F>
double bestOf(int runs, F&& f)
{
    double best = 1e300;
    for (int i = 0; i < runs; ++i) {
        const auto t0 = Clock::now();
        f();
        best = std::min(best, secondsSince(t0));
    }
    return best;
}

constexpr int kRuns = 7;

// The well-equipped aircraft with a full header: the largest ordinary command.
Message fullCommand(std::uint32_t id)
{
    Message m = restingCommand(Airframe::wellEquipped());
    m.header.set(ItemId::ID_msg, id & 0xFFFFFF);
    m.header.set(ItemId::ID_UA_source, Value::pair(44, 133));
    m.header.set(ItemId::time_UTC, (id / 3600 % 24) * 10000 + (id / 60 % 60) * 100 + id % 60);
    m.header.set(ItemId::date_UTC, 261122);
    m.header.set(ItemId::ID_BLK12_format, Value::pair(1, 1));
    m.header.set(ItemId::ID_GCS_destination, Value::pair(44, 30226));
    m.header.set(ItemId::ID_GCS_backup, Value::pair(44, 41251));
    return m;
}

std::vector<std::uint8_t> frameBytes(const Message& m)
{
    Diagnostics errors;
    const auto f = encodeFrame(m, errors);
    return {f->begin(), f->end()};
}

void corruptBytes(std::mt19937_64& rng, std::uint8_t* p, int count)
{
    std::vector<int> pos(255);
    std::iota(pos.begin(), pos.end(), 0);
    std::shuffle(pos.begin(), pos.end(), rng);
    for (int i = 0; i < count; ++i)
        p[pos[i]] ^= static_cast<std::uint8_t>(1 + rng() % 255);
}

// Probability that a codeword of 255 symbols has at most 16 symbol errors.
double codewordBound(double ber)
{
    const double ps = 1.0 - std::pow(1.0 - ber, 8);
    double sum = 0;
    for (int k = 0; k <= 16; ++k) {
        const double logc = std::lgamma(256.0) - std::lgamma(k + 1.0) - std::lgamma(256.0 - k);
        sum += std::exp(logc + k * std::log(ps) + (255 - k) * std::log1p(-ps));
    }
    return sum;
}

void flipBits(std::mt19937_64& rng, std::vector<std::uint8_t>& bytes, double ber)
{
    // Geometric gaps between flipped bits: exact for independent errors, and
    // fast at low rates.
    std::geometric_distribution<std::uint64_t> gap(ber);
    const std::uint64_t bits = bytes.size() * 8;
    for (std::uint64_t b = gap(rng); b < bits; b += 1 + gap(rng))
        bytes[b / 8] ^= static_cast<std::uint8_t>(0x80u >> (b % 8));
}

}  // namespace

int main(int argc, char** argv)
{
    for (int i = 1; i + 1 < argc; ++i) {
        if (std::string(argv[i]) != "--libfec")
            continue;
        std::ifstream in(argv[i + 1], std::ios::binary);
        const std::vector<char> file((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        const std::size_t count = file.size() / kFrameSize;
        long failed = 0;
        const double s = bestOf(5, [&] {
            failed = 0;
            std::uint8_t cw[kCodewordSize];
            for (std::size_t f = 0; f < count; ++f)
                for (std::size_t c = 0; c < 2; ++c) {
                    std::memcpy(cw, file.data() + f * kFrameSize + kPreambleSize + c * kCodewordSize, kCodewordSize);
                    failed += rs::decodeLibfec(cw) < 0;
                }
        });
        // The receive path rcm decode --summary runs (FrameReceiver, a
        // recording, predictions on), on the same bytes in memory.
        std::uint64_t delivered = 0;
        const double r = bestOf(5, [&] {
            FrameReceiver::Options o;
            o.mode = FrameReceiver::Mode::Recording;
            FrameReceiver receiver(o, nullptr);
            const auto* bytes = reinterpret_cast<const std::uint8_t*>(file.data());
            for (std::size_t off = 0; off < file.size(); off += 65536)
                receiver.feed(std::span<const std::uint8_t>(bytes + off, std::min<std::size_t>(65536, file.size() - off)));
            receiver.flush();
            delivered = receiver.stats().delivered;
        });
        std::printf("libfec decode_rs_ccsds of %s: %zu frames, both codewords: %.3f s (%ld failed)\n", argv[i + 1],
                    count, s, failed);
        std::printf("the receive path (FrameReceiver, recording): %.3f s, %llu delivered = %.3f x libfec\n", r,
                    static_cast<unsigned long long>(delivered), r / s);
        return 0;
    }
    std::string dayFile;
    for (int i = 1; i + 1 < argc; ++i)
        if (std::string(argv[i]) == "--day")
            dayFile = argv[i + 1];

    std::mt19937_64 rng(1);
    const int n = 20000;

    // 1. Encoding.
    {
        std::vector<Message> messages;
        for (int i = 0; i < n; ++i)
            messages.push_back(fullCommand(static_cast<std::uint32_t>(i)));
        std::size_t sink = 0;
        const double s = bestOf(kRuns, [&] {
            for (const Message& m : messages) {
                Diagnostics errors;
                sink += (*encodeFrame(m, errors))[100];
            }
        });
        std::printf("encode (model -> 600-byte frame)       %9.0f frames/s  %7.2f us/frame  [%zu]\n", n / s,
                    1e6 * s / n, sink % 2);
    }

    // The text format, both ways, on the same message (rcm decode prints a
    // day's log through formatMessage; rcm encode reads through parseMessage).
    {
        const Message m = fullCommand(1);
        const std::string text = formatMessage(m);
        std::size_t sink = 0;
        const double format = bestOf(kRuns, [&] {
            for (int i = 0; i < n; ++i)
                sink += formatMessage(m).size();
        });
        const double parse = bestOf(kRuns, [&] {
            for (int i = 0; i < n; ++i)
                sink += parseMessage(text).errors.size();
        });
        std::printf("text format (%zu bytes)                formatMessage %6.2f us, parseMessage %6.2f us  [%zu]\n",
                    text.size(), 1e6 * format / n, 1e6 * parse / n, sink % 2);
    }

    // Frames for the decoding measurements.
    std::vector<std::vector<std::uint8_t>> frames;
    for (int i = 0; i < n; ++i)
        frames.push_back(frameBytes(fullCommand(static_cast<std::uint32_t>(i))));

    // 2. libfec alone, clean and with 16 errors per codeword.
    auto libfecTime = [&](int errors) {
        std::vector<std::vector<std::uint8_t>> cws;
        std::mt19937_64 r(errors);
        for (const auto& f : frames)
            for (int b = 0; b < 2; ++b) {
                std::vector<std::uint8_t> cw(f.begin() + 90 + 255 * b, f.begin() + 90 + 255 * (b + 1));
                corruptBytes(r, cw.data(), errors);
                cws.push_back(std::move(cw));
            }
        // Each run decodes fresh copies: libfec corrects in place.
        std::vector<std::vector<std::uint8_t>> work;
        long total = 0;
        const double s = bestOf(kRuns, [&] {
            work = cws;  // not timed in any meaningful way: a memcpy of 10 MB is ~1 ms
            total = 0;
            for (auto& cw : work)
                total += rs::decodeLibfec(cw.data());
        });
        if (total != static_cast<long>(errors) * static_cast<long>(cws.size()))
            std::printf("unexpected libfec result %ld\n", total);
        return 1e6 * s / static_cast<double>(cws.size());
    };
    const double libfecClean = libfecTime(0);
    const double libfec16 = libfecTime(16);
    std::printf("libfec decode_rs_ccsds, clean          %9.2f us/codeword (%.2f us per frame of two)\n", libfecClean,
                2 * libfecClean);
    std::printf("libfec decode_rs_ccsds, 16 errors      %9.2f us/codeword (%.2f us per frame of two)\n", libfec16,
                2 * libfec16);

    // 3. Clean frames through the whole receive path: sync + check + parse.
    {
        std::vector<std::uint8_t> stream;
        for (const auto& f : frames)
            stream.insert(stream.end(), f.begin(), f.end());
        std::size_t parsed = 0;
        const double s = bestOf(kRuns, [&] {
            StreamSync sync([&](const SyncedFrame& fr) {
                if (fr.ok())
                    parsed += decodeBlocks(fr.blocks).message.engines.size();
            });
            for (std::size_t off = 0; off < stream.size(); off += 4096)
                sync.feed(std::span<const std::uint8_t>(stream).subspan(off, std::min<std::size_t>(4096, stream.size() - off)));
            sync.flush();
        });
        const double us = 1e6 * s / n;
        std::printf("receive clean frame (sync+check+parse) %9.0f frames/s  %7.2f us/frame = %.3f x two libfec decodes  [%zu]\n",
                    n / s, us, us / (2 * libfecClean), parsed / 3 / kRuns);
    }

    // 4. Frames with 16 byte errors in each codeword.
    {
        std::vector<std::vector<std::uint8_t>> bad = frames;
        std::mt19937_64 r(16);
        for (auto& f : bad) {
            corruptBytes(r, f.data() + 90, 16);
            corruptBytes(r, f.data() + 345, 16);
        }
        long corrected = 0;
        const double s = bestOf(kRuns, [&] {
            corrected = 0;
            for (const auto& f : bad) {
                const DecodeResult d = decodeFrame(f);
                corrected += d.corrected.block1 + d.corrected.block2;
            }
        });
        const double us = 1e6 * s / n;
        std::printf("decode frame, 16 errors per codeword   %9.0f frames/s  %7.2f us/frame = %.3f x two libfec decodes  [%ld]\n",
                    n / s, us, us / (2 * libfec16), corrected / n);
    }

    // 5. Synchroniser throughput on a noisy stream: 300 random bytes between
    //    frames and a bit error rate of 1e-3.
    {
        std::vector<std::uint8_t> stream;
        for (const auto& f : frames) {
            for (int i = 0; i < 300; ++i)
                stream.push_back(static_cast<std::uint8_t>(rng()));
            stream.insert(stream.end(), f.begin(), f.end());
        }
        flipBits(rng, stream, 1e-3);
        std::size_t good = 0;
        const double s = bestOf(3, [&] {
            good = 0;
            StreamSync sync([&](const SyncedFrame& fr) { good += fr.ok(); });
            for (std::size_t off = 0; off < stream.size(); off += 4096)
                sync.feed(std::span<const std::uint8_t>(stream).subspan(off, std::min<std::size_t>(4096, stream.size() - off)));
            sync.flush();
        });
        std::printf("sync noisy stream (BER 1e-3, garbage)  %9.1f MB/s  %zu of %d frames\n",
                    static_cast<double>(stream.size()) / s / 1e6, good, n);
    }

    // 6. Bit-error-rate sweep: frames recovered with the right content against
    //    the bound (both codewords with at most 16 symbol errors).
    std::printf("\n| BER | frames | recovered | recovered %% | bound %% | difference (points) |\n|---|---|---|---|---|---|\n");
    for (double ber : {1e-4, 3e-4, 1e-3, 2e-3, 3e-3, 4e-3, 5e-3, 7e-3, 1e-2}) {
        const int count = 10000;
        std::vector<std::uint8_t> stream;
        for (int i = 0; i < count; ++i) {
            const auto& f = frames[static_cast<std::size_t>(i) % frames.size()];
            stream.insert(stream.end(), f.begin(), f.end());
        }
        flipBits(rng, stream, ber);
        std::size_t recovered = 0;
        StreamSync sync([&](const SyncedFrame& fr) {
            if (!fr.ok())
                return;
            const std::size_t index = (fr.offset + 45) / 600;
            const auto& f = frames[index % frames.size()];
            recovered += std::equal(fr.blocks.block1.begin(), fr.blocks.block1.end(), f.begin() + 90) &&
                         std::equal(fr.blocks.block2.begin(), fr.blocks.block2.end(), f.begin() + 345);
        });
        sync.feed(stream);
        sync.flush();
        const double bound = std::pow(codewordBound(ber), 2) * 100;
        const double got = 100.0 * static_cast<double>(recovered) / count;
        std::printf("| %.0e | %d | %zu | %.2f | %.2f | %+.2f |\n", ber, count, recovered, got, bound, got - bound);
    }

    if (!dayFile.empty()) {
        std::ofstream out(dayFile, std::ios::binary);
        for (std::uint32_t i = 0; i < 86400; ++i) {
            const auto f = frameBytes(fullCommand(i));
            out.write(reinterpret_cast<const char*>(f.data()), static_cast<std::streamsize>(f.size()));
        }
        std::printf("\nwrote %s: 86,400 frames\n", dayFile.c_str());
    }
    return 0;
}
