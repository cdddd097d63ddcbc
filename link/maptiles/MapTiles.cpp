#include "link/maptiles/MapTiles.h"

#include "link/maptiles/TileLoader.h"

#include <QCache>
#include <QSettings>
#include <QSet>
#include <QThread>

size_t qHash(const TileId& id, size_t seed)
{
    return qHashMulti(seed, id.z, id.x, id.y);
}

namespace {

// Tiles kept in memory, counted in KiB: 128 MiB, some 512 tiles of 256 by
// 256 pixels, a few screens' worth of panning back and forth.
constexpr qsizetype kTileCacheKiB = qsizetype(128) * 1024;

}  // namespace

struct MapTiles::Private {
    QThread thread;
    TileLoader* loader = nullptr;  // lives in `thread`, deleted there when it finishes
    // Tells the loader's answers about the current settings from those about
    // earlier ones, still on their way.
    quint64 generation = 0;
    QCache<TileId, QImage> tiles{kTileCacheKiB};
    QSet<TileId> asked;    // asked of the loader, not yet answered
    QSet<TileId> missing;  // the source has not got them
};

MapTiles::MapTiles(QObject* parent) : QObject(parent), d(std::make_unique<Private>())
{
    TileLoader::registerMetaTypes();
    d->thread.setObjectName(QStringLiteral("map tiles"));
    d->loader = new TileLoader;
    d->loader->moveToThread(&d->thread);
    // Deleted in its own thread, where its SQL connection and network live;
    // QThread runs deferred deletes posted from finished() before it ends.
    connect(&d->thread, &QThread::finished, d->loader, &QObject::deleteLater);

    // Loader to GUI: queued, the loader living in the other thread.
    connect(d->loader, &TileLoader::opened, this, [this](quint64 generation, const TileSourceInfo& info) {
        if (generation != d->generation)
            return;
        m_source = info.source;
        m_description = info.description;
        m_attribution = info.attribution;
        m_minZoom = info.minZoom;
        m_maxZoom = info.maxZoom;
        m_bounds = info.bounds;
        emit sourceChanged();
    });
    connect(d->loader, &TileLoader::tileLoaded, this,
            [this](quint64 generation, const TileId& id, const QImage& image) {
                if (generation != d->generation)
                    return;
                d->asked.remove(id);
                d->tiles.insert(id, new QImage(image), qMax<qsizetype>(1, image.sizeInBytes() / 1024));
                emit tileArrived(id);
            });
    connect(d->loader, &TileLoader::tileMissing, this, [this](quint64 generation, const TileId& id) {
        if (generation != d->generation)
            return;
        d->asked.remove(id);
        d->missing.insert(id);
    });
    connect(d->loader, &TileLoader::tileDropped, this, [this](quint64 generation, const TileId& id) {
        if (generation == d->generation)
            d->asked.remove(id);
    });
    connect(d->loader, &TileLoader::failed, this, [this](quint64 generation, const QString& text) {
        if (generation == d->generation)
            emit error(text);
    });
    d->thread.start();
}

MapTiles::~MapTiles()
{
    // Without waiting on the loader's queue: what it has not begun is
    // dropped with it. A tile being read or fetched finishes or is aborted.
    d->thread.quit();
    d->thread.wait();
}

TileSettings TileSettings::load(const QSettings& settings)
{
    TileSettings tiles;
    tiles.mbtilesPath = settings.value(QStringLiteral("map/mbtiles")).toString();
    tiles.urlTemplate = settings.value(QStringLiteral("map/url")).toString();
    tiles.attribution = settings.value(QStringLiteral("map/attribution")).toString();
    return tiles;
}

void TileSettings::save(QSettings& settings) const
{
    settings.setValue(QStringLiteral("map/mbtiles"), mbtilesPath);
    settings.setValue(QStringLiteral("map/url"), urlTemplate);
    settings.setValue(QStringLiteral("map/attribution"), attribution);
}

void MapTiles::configure(const TileSettings& settings)
{
    m_settings = settings;
    ++d->generation;
    d->tiles.clear();
    d->asked.clear();
    d->missing.clear();
    // No tiles until the loader says what it opened.
    m_source = Source::None;
    m_description = QStringLiteral("no map tiles");
    m_attribution.clear();
    m_minZoom = 0;
    m_maxZoom = TileLoader::kOnlineMaxZoom;
    m_bounds = QRectF();
    QMetaObject::invokeMethod(
        d->loader, [loader = d->loader, generation = d->generation, settings] { loader->open(generation, settings); },
        Qt::QueuedConnection);
}

QImage MapTiles::tile(const TileId& id)
{
    if (m_source == Source::None || id.z < m_minZoom || id.z > m_maxZoom)
        return {};
    const int tilesPerSide = 1 << id.z;
    if (id.x < 0 || id.x >= tilesPerSide || id.y < 0 || id.y >= tilesPerSide)
        return {};
    if (const QImage* image = d->tiles.object(id))
        return *image;
    if (d->asked.contains(id) || d->missing.contains(id))
        return {};
    d->asked.insert(id);
    QMetaObject::invokeMethod(
        d->loader, [loader = d->loader, generation = d->generation, id] { loader->load(generation, id); },
        Qt::QueuedConnection);
    return {};
}

bool MapTiles::isMissing(const TileId& id) const
{
    return d->missing.contains(id);
}
