#include "link/maptiles/TileLoader.h"

#include "link/maptiles/MbTilesFile.h"
#include "link/maptiles/TileServer.h"

#include <QFileInfo>

TileLoader::TileLoader(QObject* parent) : QObject(parent) {}

TileLoader::~TileLoader()
{
    close();
}

void TileLoader::registerMetaTypes()
{
    qRegisterMetaType<TileId>();
    qRegisterMetaType<TileSettings>();
    qRegisterMetaType<TileSourceInfo>();
}

void TileLoader::close()
{
    m_file.reset();
    delete m_server;
    m_server = nullptr;
    m_waiting.clear();
    m_reported.clear();
}

void TileLoader::report(const QString& text)
{
    if (m_reported.contains(text))
        return;
    m_reported.insert(text);
    emit failed(m_generation, text);
}

void TileLoader::open(quint64 generation, const TileSettings& settings)
{
    close();
    m_generation = generation;
    TileSourceInfo info;
    if (!settings.mbtilesPath.isEmpty()) {
        auto file = std::make_unique<MbTilesFile>(settings.mbtilesPath);
        if (!file->open()) {
            report(file->errorString());
        } else if (file->format() == QLatin1String("pbf")) {
            report(settings.mbtilesPath + QStringLiteral(": holds vector tiles (pbf), which the map cannot draw"));
        } else {
            info.source = MapTiles::Source::MbTiles;
            info.description = QStringLiteral("MBTiles: %1, zoom %2-%3")
                                   .arg(QFileInfo(settings.mbtilesPath).fileName())
                                   .arg(file->minZoom())
                                   .arg(file->maxZoom());
            info.attribution = file->attribution();
            info.minZoom = file->minZoom();
            info.maxZoom = file->maxZoom();
            info.bounds = file->bounds();
            m_file = std::move(file);
        }
    } else if (!settings.urlTemplate.isEmpty()) {
        const QString wrong = TileServer::checkTemplate(settings.urlTemplate);
        if (!wrong.isEmpty()) {
            report(wrong);
        } else {
            const QString host = TileServer::hostOf(settings.urlTemplate);
            m_server = new TileServer(settings.urlTemplate, settings.cacheDir, settings.cacheBytes, this);
            connect(m_server, &TileServer::fetched, this, [this, host](const TileId& id, const QByteArray& data) {
                decoded(id, data, QStringLiteral("tile server ") + host);
                scheduleNext();
            });
            connect(m_server, &TileServer::refused, this, [this](const TileId& id, const QString& cause) {
                report(cause);
                emit tileMissing(m_generation, id);
                scheduleNext();
            });
            connect(m_server, &TileServer::failed, this, [this](const TileId& id, const QString& cause) {
                report(cause);
                emit tileDropped(m_generation, id);
                scheduleNext();
            });
            info.source = MapTiles::Source::Online;
            info.description = settings.cacheDir.isEmpty()
                                   ? QStringLiteral("Online: %1 (not cached)").arg(host)
                                   : QStringLiteral("Online: %1 (cached in %2)").arg(host, settings.cacheDir);
            info.attribution = settings.attribution;
            info.maxZoom = kOnlineMaxZoom;
        }
    }
    emit opened(m_generation, info);
}

void TileLoader::load(quint64 generation, const TileId& id)
{
    // Asked of a source since closed: MapTiles has forgotten it already.
    if (generation != m_generation)
        return;
    if (!m_file && !m_server) {
        emit tileDropped(m_generation, id);
        return;
    }
    m_waiting.append(id);
    while (m_waiting.size() > kMaxWaiting)
        emit tileDropped(m_generation, m_waiting.takeFirst());
    scheduleNext();
}

// Through the event loop rather than at once: tiles asked for meanwhile
// join the stack first, and the newest of them is read next.
void TileLoader::scheduleNext()
{
    if (m_nextScheduled || m_waiting.isEmpty())
        return;
    m_nextScheduled = true;
    QMetaObject::invokeMethod(this, &TileLoader::loadNext, Qt::QueuedConnection);
}

void TileLoader::loadNext()
{
    m_nextScheduled = false;
    if (m_file) {
        // One at a time, so that a request that arrives meanwhile goes first.
        if (!m_waiting.isEmpty())
            loadFromFile(m_waiting.takeLast());
        scheduleNext();
    } else if (m_server) {
        // The server's answers schedule the next ones.
        while (m_server->inFlight() < kMaxInFlight && !m_waiting.isEmpty())
            m_server->fetch(m_waiting.takeLast());
    } else {
        m_waiting.clear();
    }
}

void TileLoader::loadFromFile(const TileId& id)
{
    QByteArray data;
    switch (m_file->read(id, &data)) {
        case MbTilesFile::Read::Found:
            decoded(id, data, m_file->path());
            break;
        case MbTilesFile::Read::Missing:
            emit tileMissing(m_generation, id);
            break;
        case MbTilesFile::Read::Failed:
            report(m_file->errorString());
            emit tileDropped(m_generation, id);
            break;
    }
}

void TileLoader::decoded(const TileId& id, const QByteArray& data, const QString& where)
{
    QImage image = QImage::fromData(data);
    if (image.isNull()) {
        report(where + QStringLiteral(": a tile that is not an image (PNG or JPEG)"));
        emit tileMissing(m_generation, id);
        return;
    }
    // Converted here rather than at each paint in the GUI thread: indexed
    // PNGs and the like are slow to draw.
    image.convertTo(image.hasAlphaChannel() ? QImage::Format_ARGB32_Premultiplied : QImage::Format_RGB32);
    emit tileLoaded(m_generation, id, image);
}
