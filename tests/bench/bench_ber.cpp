// Frames delivered against bit error rate: a realistic session
// (tests/support/BerSession.h) through the one receive path, plain and secure link,
// with decoding with predictions and without. Prints a table and writes CSV
// for scripts/plot-ber. Never run by CTest; figures in docs/performance.md.
//
//   bench_ber [--items MIN-MAX] [--status] [--link plain|secure] [--ber R,R,...] [--seed N] [frames per row] [csv path]
//
// defaults: one single-byte command per change, the console's commands as
// the aircraft reads them, both links, BER 1e-3 .. 3e-2, 10000 frames,
// ber.csv. --items 1-4: each change sets 1 to 4 commands at once, of every
// size. --status: the aircraft's status frames as the console reads them,
// the console's own commands its prediction. --seed N: another session and
// other bit errors (default 1), to see how much a figure owes to one draw.
#include "tests/support/BerSession.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

int main(int argc, char** argv)
{
    using namespace rcm::test;
    int minItems = 1, maxItems = 1;
    bool status = false;
    std::uint64_t seed = 1;
    std::vector<bool> links = {false, true};
    std::vector<double> bers = {1e-3, 3e-3, 5e-3, 7e-3, 1e-2, 1.5e-2, 2e-2, 2.5e-2, 3e-2};
    std::vector<std::string> rest;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--items" && i + 1 < argc) {
            if (std::sscanf(argv[++i], "%d-%d", &minItems, &maxItems) != 2 || minItems < 1 || maxItems < minItems) {
                std::fprintf(stderr, "bench_ber: --items MIN-MAX, e.g. 1-4\n");
                return 2;
            }
        } else if (a == "--seed" && i + 1 < argc) {
            seed = std::strtoull(argv[++i], nullptr, 10);
        } else if (a == "--help" || a == "-h") {
            std::printf("bench_ber [--items MIN-MAX] [--status] [--link plain|secure] [--ber R,R,...] [--seed N] "
                        "[frames per row] [csv path]\n");
            return 0;
        } else if (a == "--status") {
            status = true;
        } else if (a == "--link" && i + 1 < argc) {
            const std::string l = argv[++i];
            links = {l == "secure"};
        } else if (a == "--ber" && i + 1 < argc) {
            bers.clear();
            for (char* t = std::strtok(argv[++i], ","); t; t = std::strtok(nullptr, ","))
                bers.push_back(std::strtod(t, nullptr));
        } else {
            rest.push_back(a);
        }
    }
    const std::uint64_t frames = !rest.empty() ? std::strtoull(rest[0].c_str(), nullptr, 10) : 10000;
    const std::string csvPath = rest.size() > 1 ? rest[1] : "ber.csv";
    std::FILE* csv = std::fopen(csvPath.c_str(), "w");
    if (!csv) {
        std::fprintf(stderr, "bench_ber: cannot write %s\n", csvPath.c_str());
        return 1;
    }
    std::fprintf(csv, "link,ber,frames,delivered_correct,delivered_wrong,refused,from_prediction,plan_frames,"
                      "plan_delivered,plain_rs_only_correct,plain_rs_bound\n");
    std::printf("%s, %d-%d commands per change, seed %llu\n",
                status ? "status frames read by the console" : "commands read by the aircraft", minItems, maxItems,
                static_cast<unsigned long long>(seed));
    std::printf("%-6s %-7s %7s %9s %7s %7s %9s %9s %8s %8s %8s\n", "link", "BER", "frames", "correct", "WRONG",
                "refused", "predicted", "plan", "%correct", "%RSonly", "%bound");
    for (bool secure : links) {
        for (double ber : bers) {
            const auto start = std::chrono::steady_clock::now();
            BerSessionOptions o;
            o.ber = ber;
            o.frames = frames;
            o.secure = secure;
            o.minItemsPerChange = minItems;
            o.maxItemsPerChange = maxItems;
            o.status = status;
            o.seed = seed;
            const BerSessionResult r = runBerSession(o);
            o.predictions = false;
            const BerSessionResult plainOnly = runBerSession(o);
            const double seconds =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            const double bound = plainRsBound(ber);
            const char* link = secure ? "secure" : "plain";
            std::printf("%-6s %-7.1e %7llu %9llu %7llu %7llu %9llu %4llu/%-4llu %8.2f %8.2f %8.2f  (%.0f s)\n", link,
                        ber, static_cast<unsigned long long>(r.frames),
                        static_cast<unsigned long long>(r.deliveredCorrect),
                        static_cast<unsigned long long>(r.deliveredWrong + plainOnly.deliveredWrong),
                        static_cast<unsigned long long>(r.refused), static_cast<unsigned long long>(r.fromPrediction),
                        static_cast<unsigned long long>(r.planDelivered),
                        static_cast<unsigned long long>(r.planFrames), 100.0 * r.deliveredCorrect / r.frames,
                        100.0 * plainOnly.deliveredCorrect / plainOnly.frames, 100 * bound, seconds);
            std::fflush(stdout);
            std::fprintf(csv, "%s,%g,%llu,%llu,%llu,%llu,%llu,%llu,%llu,%llu,%.6f\n", link, ber,
                         static_cast<unsigned long long>(r.frames),
                         static_cast<unsigned long long>(r.deliveredCorrect),
                         static_cast<unsigned long long>(r.deliveredWrong + plainOnly.deliveredWrong),
                         static_cast<unsigned long long>(r.refused), static_cast<unsigned long long>(r.fromPrediction),
                         static_cast<unsigned long long>(r.planFrames), static_cast<unsigned long long>(r.planDelivered),
                         static_cast<unsigned long long>(plainOnly.deliveredCorrect), bound);
        }
    }
    std::fclose(csv);
    return 0;
}
