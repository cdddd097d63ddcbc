#pragma once

// Reads map tiles in a thread of its own, for MapTiles: from an MBTiles file
// or a tile server, decoding them there into images ready to paint. Every
// call and every signal carries the generation of MapTiles' settings it
// belongs to, so that what was asked of an earlier source is told apart.
//
// It keeps the tiles asked for in a stack: the newest, what the view shows
// now, is read first, and the oldest are let go when too many wait.

#include "link/maptiles/MapTiles.h"

#include <QImage>
#include <QList>
#include <QObject>
#include <QRectF>
#include <QSet>
#include <QString>

#include <memory>

class MbTilesFile;
class TileServer;

// What the loader found when it opened a source.
struct TileSourceInfo {
    MapTiles::Source source = MapTiles::Source::None;
    QString description = QStringLiteral("no map tiles");
    QString attribution;
    int minZoom = 0;
    int maxZoom = 19;
    QRectF bounds;
};
Q_DECLARE_METATYPE(TileSourceInfo)

class TileLoader : public QObject {
    Q_OBJECT

public:
    // At most this many tile server requests at a time, as browsers do per
    // server: enough to fill a screen soon, few enough to share a slow link.
    static constexpr int kMaxInFlight = 6;
    // Tiles waiting beyond this many (the view has moved on) are let go,
    // the oldest first.
    static constexpr int kMaxWaiting = 256;
    // Online tiles cover zoom 0 to this, as most tile servers do.
    static constexpr int kOnlineMaxZoom = 19;

    explicit TileLoader(QObject* parent = nullptr);
    ~TileLoader() override;  // closes the source, in the loader thread

    static void registerMetaTypes();

    // Both are called in the loader thread (queued by MapTiles).
    // Closes the source and opens the one the settings say; opened() tells
    // which, failed() first why not.
    void open(quint64 generation, const TileSettings& settings);
    // One of tileLoaded(), tileMissing() or tileDropped() follows for the id.
    void load(quint64 generation, const TileId& id);

signals:
    void opened(quint64 generation, const TileSourceInfo& info);
    void tileLoaded(quint64 generation, const TileId& id, const QImage& image);
    // The source has no such tile: asking again would get the same.
    void tileMissing(quint64 generation, const TileId& id);
    // Not loaded this time (let go while waiting, the network down): it may be asked for again.
    void tileDropped(quint64 generation, const TileId& id);
    // Once per cause for each source opened.
    void failed(quint64 generation, const QString& text);

private:
    void close();
    void report(const QString& text);
    void scheduleNext();
    void loadNext();
    void loadFromFile(const TileId& id);
    void decoded(const TileId& id, const QByteArray& data, const QString& where);

    quint64 m_generation = 0;
    std::unique_ptr<MbTilesFile> m_file;
    TileServer* m_server = nullptr;  // child
    QList<TileId> m_waiting;         // newest last
    bool m_nextScheduled = false;
    QSet<QString> m_reported;
};
