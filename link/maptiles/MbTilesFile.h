#pragma once

// One MBTiles file (spec 1.3: an SQLite database with a "metadata" table of
// names and values and a "tiles" table or view of zoom_level, tile_column,
// tile_row, tile_data), opened read-only through Qt SQL's SQLite driver.
//
// A Qt SQL connection belongs to the thread that made it: an MbTilesFile is
// made, used and destroyed in the loader thread alone.

#include "link/maptiles/MapTiles.h"

#include <QByteArray>
#include <QRectF>
#include <QString>

#include <memory>

class QSqlQuery;

class MbTilesFile {
public:
    explicit MbTilesFile(const QString& path);  // does no I/O; open() does
    ~MbTilesFile();                             // closes the connection and removes it
    MbTilesFile(const MbTilesFile&) = delete;
    MbTilesFile& operator=(const MbTilesFile&) = delete;

    // Opens the file and reads its metadata. False, with errorString(), for a
    // missing file, one SQLite cannot read, or a database without "tiles".
    bool open();
    QString errorString() const { return m_error; }

    QString path() const { return m_path; }
    QString name() const { return m_name; }                // metadata "name"; may be empty
    QString attribution() const { return m_attribution; }  // metadata "attribution"; may be empty
    QString format() const { return m_format; }            // "png", "jpg", "webp", "pbf"; may be empty
    int minZoom() const { return m_minZoom; }
    int maxZoom() const { return m_maxZoom; }
    QRectF bounds() const { return m_bounds; }  // degrees, x longitude, y latitude; null when not given

    enum class Read { Found, Missing, Failed };
    // The tile's stored bytes (an encoded image) for an XYZ id; the file's
    // rows count from the south (TMS), which this converts. Failed leaves
    // the reason in errorString().
    Read read(const TileId& id, QByteArray* data);

private:
    bool fail(const QString& what);
    bool readMetadata();

    QString m_path;
    QString m_connectionName;
    std::unique_ptr<QSqlQuery> m_tileQuery;  // prepared once; gone before the connection is removed
    QString m_error;
    QString m_name;
    QString m_attribution;
    QString m_format;
    int m_minZoom = 0;
    int m_maxZoom = 0;
    QRectF m_bounds;
};
