#pragma once

// Map tiles for the plan view, offline first: from an MBTiles file (SQLite,
// what field crews carry), else from a tile server's URL template with a
// disk cache, else none (the view then draws a grid). The files and the
// network are read in a thread of their own (TileLoader); this GUI-side
// handle keeps the tiles that arrived in memory and never waits.
//
// Tiles are numbered as on the web ("slippy map", XYZ): zoom z, column x
// from 180 degrees west, row y from the north. MBTiles numbers rows from the
// south (TMS); the loader converts.

#include <QHash>
#include <QImage>
#include <QObject>
#include <QRectF>
#include <QString>

#include <memory>

class QSettings;

struct TileId {
    int z = 0;
    int x = 0;
    int y = 0;
    friend bool operator==(const TileId&, const TileId&) = default;
};
size_t qHash(const TileId& id, size_t seed = 0);
Q_DECLARE_METATYPE(TileId)

struct TileSettings {
    QString mbtilesPath;   // offline tiles; used first when set
    QString urlTemplate;   // "https://tile.example/{z}/{x}/{y}.png"; online tiles when set
    QString attribution;   // shown on the map for online tiles (MBTiles carry their own)
    QString cacheDir;      // QNetworkDiskCache directory for online tiles
    qint64 cacheBytes = qint64(512) << 20;
    friend bool operator==(const TileSettings&, const TileSettings&) = default;

    // What the operator chose, kept between runs under "map/" (the cache's
    // place and size are the program's, not kept).
    static TileSettings load(const QSettings& settings);
    void save(QSettings& settings) const;
};
Q_DECLARE_METATYPE(TileSettings)

class MapTiles : public QObject {
    Q_OBJECT

public:
    enum class Source { None, MbTiles, Online };
    Q_ENUM(Source)

    explicit MapTiles(QObject* parent = nullptr);
    ~MapTiles() override;  // stops and joins the loader thread

    // Opens the source in the loader thread; sourceChanged() tells how it went.
    void configure(const TileSettings& settings);
    const TileSettings& settings() const { return m_settings; }

    // The tile if it has arrived; otherwise asks for it (once) and returns a
    // null image. tileArrived() follows when it comes.
    QImage tile(const TileId& id);
    // The source has said it has no such tile (an MBTiles file without it, a
    // server's 404): it is not asked for again, so the view can draw its grid
    // there rather than wait.
    bool isMissing(const TileId& id) const;

    Source source() const { return m_source; }
    QString attribution() const { return m_attribution; }  // empty when none
    QString description() const { return m_description; }  // "MBTiles: area.mbtiles, zoom 0-14", "no map tiles"
    int minZoom() const { return m_minZoom; }
    int maxZoom() const { return m_maxZoom; }
    // An MBTiles file's area (its "bounds"): x west to east longitude, y
    // south to north latitude, in degrees. Null when unknown (online tiles).
    QRectF bounds() const { return m_bounds; }

signals:
    void tileArrived(const TileId& id);
    void sourceChanged();
    // A source that cannot be opened, a server that refuses: once per cause.
    void error(const QString& text);

private:
    // Implementation chosen by the tiles work: the loader and its thread,
    // an in-memory cache, the set of tiles asked for.
    struct Private;
    std::unique_ptr<Private> d;
    TileSettings m_settings;
    Source m_source = Source::None;
    QString m_attribution;
    QString m_description = QStringLiteral("no map tiles");
    int m_minZoom = 0;
    int m_maxZoom = 19;
    QRectF m_bounds;
};
