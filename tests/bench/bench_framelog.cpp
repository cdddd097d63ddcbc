// Times the frame log at the size of a 24-hour session: 172,800 serial
// frames of 600 bytes (one a second each way). The console has to open and
// index such a file in well under a second.
//
//   bench_framelog [directory]    (default: a temporary directory)

#include "link/framelog/FrameLog.h"
#include "link/framelog/FrameLogReader.h"

#include <QDir>
#include <QElapsedTimer>
#include <QFile>
#include <QFileInfo>
#include <QRandomGenerator>
#include <QTemporaryDir>

#include <algorithm>
#include <cstdio>
#include <vector>

#ifdef Q_OS_LINUX
#include <fcntl.h>
#include <unistd.h>
#endif

namespace {

constexpr int kFrames = 172800;
constexpr int kRuns = 5;

// Evicts the file from the page cache so the first open pays for the disk
// reads, as it would for yesterday's log.
bool dropFromPageCache(const QString& path)
{
#ifdef Q_OS_LINUX
    QFile f(path);
    if (!f.open(QIODevice::ReadOnly))
        return false;
    ::fdatasync(f.handle());
    return ::posix_fadvise(f.handle(), 0, 0, POSIX_FADV_DONTNEED) == 0;
#else
    Q_UNUSED(path);
    return false;
#endif
}

double openAndIndexMs(const QString& path, int* count)
{
    QElapsedTimer timer;
    timer.start();
    FrameLogReader reader;
    if (!reader.open(path)) {
        std::fprintf(stderr, "%s\n", qPrintable(reader.errorString()));
        return -1;
    }
    *count = reader.count();
    return timer.nsecsElapsed() / 1e6;
}

}  // namespace

int main(int argc, char** argv)
{
    QTemporaryDir tmp;
    const QString dir = argc > 1 ? QString::fromLocal8Bit(argv[1]) : tmp.path();
    const QString path = QDir(dir).filePath(QStringLiteral("bench-framelog.pcapng"));
    QFile::remove(path);

    FrameRecord r;
    r.bytes.resize(600);
    QRandomGenerator rng(1);
    for (char& c : r.bytes)
        c = char(rng.bounded(256));
    r.transport = FrameTransport::Serial;

    QElapsedTimer timer;
    timer.start();
    {
        FrameLog log;
        QString error;
        if (!log.open(path, &error)) {
            std::fprintf(stderr, "%s\n", qPrintable(error));
            return 1;
        }
        const qint64 t0 = 1795305600000000;  // 2026-11-22T00:00:00Z
        for (int i = 0; i < kFrames; ++i) {
            r.utcMicros = t0 + qint64(i / 2) * 1000000 + (i % 2) * 250000;
            r.direction = i % 2 ? FrameDirection::Received : FrameDirection::Sent;
            r.status = i % 2 ? FrameStatus::Corrected : FrameStatus::NotChecked;
            r.correctedSymbols = i % 2 ? QList<int>{i % 9, 0} : QList<int>{};
            r.bytes[0] = char(i);
            if (!log.append(r)) {
                std::fprintf(stderr, "%s\n", qPrintable(log.errorString()));
                return 1;
            }
        }
    }
    const double writeMs = timer.nsecsElapsed() / 1e6;
    std::printf("wrote %d frames, %.1f MB, in %.0f ms (%.1f us/frame)\n", kFrames, QFileInfo(path).size() / 1e6,
                writeMs, writeMs * 1000 / kFrames);

    int count = 0;
    if (dropFromPageCache(path)) {
        std::printf("open+index, cold page cache: %.1f ms\n", openAndIndexMs(path, &count));
    }
    std::vector<double> warm;
    for (int run = 0; run < kRuns; ++run)
        warm.push_back(openAndIndexMs(path, &count));
    std::sort(warm.begin(), warm.end());
    std::printf("open+index, warm page cache: median %.1f ms, best %.1f ms (%d runs), %d records\n", warm[kRuns / 2],
                warm.front(), kRuns, count);

    FrameLogReader reader;
    reader.open(path);
    timer.restart();
    QRandomGenerator pick(2);
    qint64 bytes = 0;
    for (int i = 0; i < 200000; ++i)
        bytes += reader.recordAt(pick.bounded(reader.count())).bytes.size();
    std::printf("200000 random recordAt: %.1f ms\n", timer.nsecsElapsed() / 1e6);
    return count == kFrames && bytes == 200000LL * 600 ? 0 : 1;
}
