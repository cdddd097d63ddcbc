// The flight plan tab with a long plan: how long the GUI thread is busy
// opening it, with one edit on the map, and painting the map (grid only, and
// over the offline tiles of an MBTiles file when one is given).
//
//     QT_QPA_PLATFORM=offscreen build/bin/bench_planview [ITEMS] [MBTILES]
//
// ITEMS defaults to 10000 waypoints (1,582 BLOCK 2 sections); MBTILES, e.g.
// from scripts/make-demo-mbtiles.py. Figures in docs/performance.md.

#include "Spread.h"

#include "ui/plan/FlightPlanUpload.h"
#include "ui/plan/FlightPlanWidget.h"
#include "ui/plan/PlanMapView.h"

#include <QApplication>
#include <QElapsedTimer>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QSignalSpy>
#include <QTemporaryDir>

#include <cmath>
#include <cstdio>

namespace {

QString writePlan(const QTemporaryDir& dir, int count)
{
    QJsonArray items;
    for (int i = 0; i < count; ++i) {
        // A lawnmower survey: rows 2 km long, 30 m apart.
        const int row = i / 50;
        const int along = row % 2 == 0 ? i % 50 : 49 - i % 50;
        items.append(QJsonObject{{QStringLiteral("type"), QStringLiteral("SimpleItem")},
                                 {QStringLiteral("command"), 16},
                                 {QStringLiteral("frame"), 3},
                                 {QStringLiteral("autoContinue"), true},
                                 {QStringLiteral("params"), QJsonArray{0, 0, 0, QJsonValue(), 52.19 + row * 0.00027,
                                                                       0.10 + along * 0.00060, 100}}});
    }
    const QJsonObject root{{QStringLiteral("fileType"), QStringLiteral("Plan")},
                           {QStringLiteral("version"), 1},
                           {QStringLiteral("mission"), QJsonObject{{QStringLiteral("items"), items}}}};
    const QString path = dir.filePath(QStringLiteral("long.plan"));
    QFile file(path);
    if (!file.open(QIODevice::WriteOnly))
        return {};
    file.write(QJsonDocument(root).toJson());
    return path;
}

}  // namespace

int main(int argc, char* argv[])
{
    QApplication app(argc, argv);
    const int count = argc > 1 ? std::atoi(argv[1]) : 10000;
    const QString mbtiles = argc > 2 ? QString::fromLocal8Bit(argv[2]) : QString();
    QTemporaryDir dir;
    const QString path = writePlan(dir, count);

    FlightPlanUpload upload;
    FlightPlanWidget widget(&upload);
    widget.resize(1280, 720);
    widget.show();
    QCoreApplication::processEvents();

    std::vector<std::int64_t> open;
    std::vector<std::int64_t> edit;
    std::vector<std::int64_t> grid;
    QElapsedTimer t;
    for (int run = 0; run < 5; ++run) {
        t.start();
        QString error;
        if (!widget.loadPlan(path, &error)) {
            std::fprintf(stderr, "%s\n", qPrintable(error));
            return 1;
        }
        open.push_back(t.nsecsElapsed() / 1000);
    }
    std::printf("%d waypoints: %s\n", count, qPrintable(widget.summary()));
    for (int run = 0; run < 20; ++run) {
        t.start();
        widget.moveItem(count / 2, {52.2 + run * 1e-4, 0.12});
        edit.push_back(t.nsecsElapsed() / 1000);
    }
    for (int run = 0; run < 20; ++run) {
        t.start();
        widget.map()->grab();
        grid.push_back(t.nsecsElapsed() / 1000);
    }
    rcm::bench::printSpread("open", open, 0.95, 1);
    rcm::bench::printSpread("edit", edit, 0.95, 1);
    rcm::bench::printSpread("paint", grid, 0.95, 1);

    if (!mbtiles.isEmpty()) {
        TileSettings settings;
        settings.mbtilesPath = mbtiles;
        QSignalSpy changed(widget.tiles(), &MapTiles::sourceChanged);
        widget.setTileSettings(settings);
        changed.wait(5000);
        // Ask for the visible tiles, and let them arrive.
        widget.map()->grab();
        QSignalSpy arrived(widget.tiles(), &MapTiles::tileArrived);
        while (arrived.wait(500)) {
        }
        std::vector<std::int64_t> tiles;
        for (int run = 0; run < 20; ++run) {
            t.start();
            widget.map()->grab();
            tiles.push_back(t.nsecsElapsed() / 1000);
        }
        std::printf("%s, %lld tiles arrived\n", qPrintable(widget.tiles()->description()),
                    static_cast<long long>(arrived.count()));
        rcm::bench::printSpread("tiles", tiles, 0.95, 1);
    }
    return 0;
}
