// Frames delivered against bit error rate: a realistic command session
// (tests/BerSession.h) through the one receive path, plain and secure link,
// with decoding with predictions and without. Prints a table and writes CSV
// for scripts/plot-ber. Never run by CTest; figures in docs/performance.md.
//
//   bench_ber [frames per row] [csv path]      defaults: 10000, ber.csv
#include "../BerSession.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

int main(int argc, char** argv)
{
    using namespace rcm::test;
    const std::uint64_t frames = argc > 1 ? std::strtoull(argv[1], nullptr, 10) : 10000;
    const std::string csvPath = argc > 2 ? argv[2] : "ber.csv";
    std::FILE* csv = std::fopen(csvPath.c_str(), "w");
    if (!csv) {
        std::fprintf(stderr, "bench_ber: cannot write %s\n", csvPath.c_str());
        return 1;
    }
    std::fprintf(csv, "link,ber,frames,delivered_correct,delivered_wrong,refused,from_prediction,plan_frames,"
                      "plan_delivered,plain_rs_only_correct,plain_rs_bound\n");
    std::printf("%-6s %-7s %7s %9s %7s %7s %9s %9s %8s %8s %8s\n", "link", "BER", "frames", "correct", "WRONG",
                "refused", "predicted", "plan", "%correct", "%RSonly", "%bound");
    const double bers[] = {1e-3, 3e-3, 5e-3, 7e-3, 1e-2, 1.5e-2, 2e-2, 2.5e-2, 3e-2};
    for (bool secure : {false, true}) {
        for (double ber : bers) {
            const auto start = std::chrono::steady_clock::now();
            BerSessionOptions o;
            o.ber = ber;
            o.frames = frames;
            o.secure = secure;
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
