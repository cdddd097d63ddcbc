#include "link/maptiles/MbTilesFile.h"

#include <QFileInfo>
#include <QSqlDatabase>
#include <QSqlError>
#include <QSqlQuery>
#include <QStringList>

#include <atomic>

namespace {

// Connection names are global to the process, and more than one MapTiles
// (and so more than one loader thread) may have a file open.
std::atomic<quint64> connectionCount{0};

// SQLite's own words ("file is not a database") when it has any, rather than
// Qt's wrapper around them ("Unable to execute statement").
QString sqliteError(const QSqlError& error)
{
    return error.databaseText().isEmpty() ? error.text() : error.databaseText();
}

}  // namespace

MbTilesFile::MbTilesFile(const QString& path)
    : m_path(path), m_connectionName(QStringLiteral("rcm-mbtiles-%1").arg(++connectionCount))
{
}

MbTilesFile::~MbTilesFile()
{
    // removeDatabase() wants every query and handle on the connection gone.
    m_tileQuery.reset();
    if (!QSqlDatabase::contains(m_connectionName))
        return;
    {
        QSqlDatabase database = QSqlDatabase::database(m_connectionName, false);
        database.close();
    }
    QSqlDatabase::removeDatabase(m_connectionName);
}

bool MbTilesFile::fail(const QString& what)
{
    m_error = m_path + QStringLiteral(": ") + what;
    return false;
}

bool MbTilesFile::open()
{
    // Checked first: SQLite says "unable to open database file" for a file
    // that is not there, which does not say why.
    const QFileInfo info(m_path);
    if (!info.exists())
        return fail(QStringLiteral("no such file"));
    if (!info.isFile())
        return fail(QStringLiteral("not a file"));

    QSqlDatabase database = QSqlDatabase::addDatabase(QStringLiteral("QSQLITE"), m_connectionName);
    if (!database.isValid())
        return fail(
            QStringLiteral("cannot be read: Qt's SQLite driver (QSQLITE, package libqt6sql6-sqlite) is missing"));
    database.setDatabaseName(m_path);
    // Read-only: field crews' files may sit on write-protected media, and a
    // map view has no business changing them.
    database.setConnectOptions(QStringLiteral("QSQLITE_OPEN_READONLY"));
    if (!database.open())
        return fail(sqliteError(database.lastError()));

    // SQLite opens anything lazily; the first query finds out whether it is
    // a database at all. "tiles" may be a view (files that share repeated
    // images between tiles store them in other tables).
    {
        QSqlQuery query(database);
        if (!query.exec(
                QStringLiteral("SELECT 1 FROM sqlite_master WHERE name = 'tiles' AND type IN ('table', 'view')")))
            return fail(sqliteError(query.lastError()));
        if (!query.next())
            return fail(QStringLiteral("not an MBTiles file (no \"tiles\" table)"));
    }

    if (!readMetadata())
        return false;

    m_tileQuery = std::make_unique<QSqlQuery>(database);
    m_tileQuery->setForwardOnly(true);
    if (!m_tileQuery->prepare(QStringLiteral(
            "SELECT tile_data FROM tiles WHERE zoom_level = ? AND tile_column = ? AND tile_row = ? LIMIT 1")))
        return fail(sqliteError(m_tileQuery->lastError()));
    return true;
}

bool MbTilesFile::readMetadata()
{
    QSqlDatabase database = QSqlDatabase::database(m_connectionName, false);
    bool minZoomKnown = false;
    bool maxZoomKnown = false;
    {
        // Required by the spec, but files made by hand sometimes lack it, and
        // the tiles alone are still a map: a missing table leaves the defaults.
        QSqlQuery query(database);
        query.setForwardOnly(true);
        if (query.exec(QStringLiteral("SELECT name, value FROM metadata"))) {
            while (query.next()) {
                const QString name = query.value(0).toString().trimmed();
                const QString value = query.value(1).toString().trimmed();
                if (name == QLatin1String("name")) {
                    m_name = value;
                } else if (name == QLatin1String("attribution")) {
                    m_attribution = value;
                } else if (name == QLatin1String("format")) {
                    m_format = value.toLower();
                } else if (name == QLatin1String("minzoom")) {
                    m_minZoom = value.toInt(&minZoomKnown);
                } else if (name == QLatin1String("maxzoom")) {
                    m_maxZoom = value.toInt(&maxZoomKnown);
                } else if (name == QLatin1String("bounds")) {
                    // "left,bottom,right,top" in degrees
                    const QStringList parts = value.split(QLatin1Char(','));
                    double edges[4];
                    bool valid = parts.size() == 4;
                    for (int i = 0; valid && i < 4; ++i)
                        edges[i] = parts[i].trimmed().toDouble(&valid);
                    if (valid && edges[2] > edges[0] && edges[3] > edges[1])
                        m_bounds = QRectF(QPointF(edges[0], edges[1]), QPointF(edges[2], edges[3]));
                }
            }
        }
    }
    if (!minZoomKnown || !maxZoomKnown) {
        // Optional in the spec: then the tiles themselves say.
        QSqlQuery query(database);
        if (!query.exec(QStringLiteral("SELECT MIN(zoom_level), MAX(zoom_level) FROM tiles")))
            return fail(sqliteError(query.lastError()));
        if (query.next() && !query.value(0).isNull()) {
            if (!minZoomKnown)
                m_minZoom = query.value(0).toInt();
            if (!maxZoomKnown)
                m_maxZoom = query.value(1).toInt();
        }
    }
    // Beyond 30 a tile's row no longer fits an int; below 0 means nothing.
    m_minZoom = qBound(0, m_minZoom, 30);
    m_maxZoom = qBound(m_minZoom, m_maxZoom, 30);
    return true;
}

MbTilesFile::Read MbTilesFile::read(const TileId& id, QByteArray* data)
{
    if (!m_tileQuery) {
        m_error = m_path + QStringLiteral(": not open");
        return Read::Failed;
    }
    const int tmsRow = (1 << id.z) - 1 - id.y;
    m_tileQuery->bindValue(0, id.z);
    m_tileQuery->bindValue(1, id.x);
    m_tileQuery->bindValue(2, tmsRow);
    if (!m_tileQuery->exec()) {
        fail(sqliteError(m_tileQuery->lastError()));
        return Read::Failed;
    }
    Read result = Read::Missing;
    if (m_tileQuery->next()) {
        *data = m_tileQuery->value(0).toByteArray();
        result = Read::Found;
    }
    // Lets go of the statement's read lock until the next tile.
    m_tileQuery->finish();
    return result;
}
