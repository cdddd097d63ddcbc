// Map tiles for the plan view: an MBTiles file written by the sqlite3 program
// (TMS rows, metadata, tiles it has not got, files that are no MBTiles), and a
// tile server on loopback (what it is told, errors once per cause, its tiles
// still there from the disk cache once it is gone).

#include "link/maptiles/MapTiles.h"
#include "link/maptiles/TileLoader.h"
#include "link/maptiles/TileServer.h"

#include <QBuffer>
#include <QFile>
#include <QProcess>
#include <QSignalSpy>
#include <QSqlDatabase>
#include <QSqlError>
#include <QSqlQuery>
#include <QStandardPaths>
#include <QTcpServer>
#include <QTcpSocket>
#include <QTemporaryDir>
#include <QTest>

#include <memory>

namespace {

QByteArray imageOf(const QColor& colour, const char* format = "PNG")
{
    QImage image(256, 256, QImage::Format_RGB32);
    image.fill(colour);
    QByteArray bytes;
    QBuffer buffer(&bytes);
    buffer.open(QIODevice::WriteOnly);
    image.save(&buffer, format);
    return bytes;
}

QByteArray pngOf(const QColor& colour)
{
    return imageOf(colour);
}

QString sqlText(const QString& text)
{
    return QLatin1Char('\'') + QString(text).replace(QLatin1Char('\''), QLatin1String("''")) + QLatin1Char('\'');
}

// Runs SQL statements on a new SQLite file: with the sqlite3 program when
// there is one, so that the file is one another program wrote; else with Qt.
QString runSql(const QString& path, const QStringList& statements)
{
    const QString sqlite3 = QStandardPaths::findExecutable(QStringLiteral("sqlite3"));
    if (!sqlite3.isEmpty()) {
        QProcess process;
        process.start(sqlite3, {QStringLiteral("-bail"), path});
        process.write(statements.join(QStringLiteral(";\n")).toUtf8() + ";\n");
        process.closeWriteChannel();
        if (!process.waitForFinished(60000) || process.exitStatus() != QProcess::NormalExit || process.exitCode() != 0)
            return QStringLiteral("sqlite3 %1: %2").arg(path, QString::fromLocal8Bit(process.readAllStandardError()));
        return {};
    }
    QString failure;
    {
        QSqlDatabase database = QSqlDatabase::addDatabase(QStringLiteral("QSQLITE"), QStringLiteral("tst_maptiles"));
        database.setDatabaseName(path);
        if (!database.open()) {
            failure = database.lastError().text();
        } else {
            QSqlQuery query(database);
            for (const QString& statement : statements) {
                if (!query.exec(statement)) {
                    failure = statement + QStringLiteral(": ") + query.lastError().text();
                    break;
                }
            }
        }
        database.close();
    }
    QSqlDatabase::removeDatabase(QStringLiteral("tst_maptiles"));
    return failure;
}

struct StoredTile {
    TileId id;  // XYZ, rows from the north
    QColor colour;
    const char* format = "PNG";
};

// An MBTiles file holding the tiles, stored in TMS rows as the spec says.
QString writeMbTiles(const QString& path, const QList<StoredTile>& tiles,
                     const QList<std::pair<QString, QString>>& metadata)
{
    QStringList sql = {
        QStringLiteral("CREATE TABLE metadata (name TEXT, value TEXT)"),
        QStringLiteral(
            "CREATE TABLE tiles (zoom_level INTEGER, tile_column INTEGER, tile_row INTEGER, tile_data BLOB)"),
        QStringLiteral("CREATE UNIQUE INDEX tile_index ON tiles (zoom_level, tile_column, tile_row)"),
    };
    for (const auto& [name, value] : metadata)
        sql << QStringLiteral("INSERT INTO metadata VALUES (%1, %2)").arg(sqlText(name), sqlText(value));
    for (const StoredTile& tile : tiles) {
        const int tmsRow = (1 << tile.id.z) - 1 - tile.id.y;
        sql << QStringLiteral("INSERT INTO tiles VALUES (%1, %2, %3, X'%4')")
                   .arg(tile.id.z)
                   .arg(tile.id.x)
                   .arg(tmsRow)
                   .arg(QString::fromLatin1(imageOf(tile.colour, tile.format).toHex()));
    }
    return runSql(path, sql);
}

// TileSettings by field, without designated initialisers (GCC warns of
// the fields they leave out).
TileSettings fileSettings(const QString& path, const QString& urlTemplate = {})
{
    TileSettings settings;
    settings.mbtilesPath = path;
    settings.urlTemplate = urlTemplate;
    return settings;
}

TileSettings onlineSettings(const QString& urlTemplate, const QString& cacheDir = {}, const QString& attribution = {})
{
    TileSettings settings;
    settings.urlTemplate = urlTemplate;
    settings.cacheDir = cacheDir;
    settings.attribution = attribution;
    return settings;
}

const QColor kRed(200, 30, 30);
const QColor kGreen(30, 200, 30);
const QColor kBlue(30, 30, 200);
const QColor kYellow(220, 220, 40);

QColor centreOf(const QImage& image)
{
    return image.pixelColor(image.width() / 2, image.height() / 2);
}

// A tile server on loopback: GET /z/x/y.png for the tiles it holds, 404 for
// anything else, one request a connection. Cacheable answers, as real tile
// servers give.
class TileHttpServer : public QObject {
public:
    QHash<QString, QColor> tiles;  // "/1/0/0.png"
    QStringList requests;          // paths, in the order asked
    QString userAgent;             // the last one sent

    bool start() { return m_server.listen(QHostAddress::LocalHost, 0); }
    void stop() { m_server.close(); }
    quint16 port() const { return m_server.serverPort(); }
    QString urlTemplate() const { return QStringLiteral("http://127.0.0.1:%1/{z}/{x}/{y}.png").arg(port()); }

    TileHttpServer()
    {
        connect(&m_server, &QTcpServer::newConnection, this, [this] {
            while (QTcpSocket* socket = m_server.nextPendingConnection()) {
                connect(socket, &QTcpSocket::disconnected, socket, &QObject::deleteLater);
                connect(socket, &QTcpSocket::readyRead, this, [this, socket] { read(socket); });
            }
        });
    }

private:
    void read(QTcpSocket* socket)
    {
        QByteArray& buffer = m_buffers[socket];
        buffer += socket->readAll();
        const qsizetype end = buffer.indexOf("\r\n\r\n");
        if (end < 0)
            return;
        const QList<QByteArray> lines = buffer.left(end).split('\n');
        m_buffers.remove(socket);
        const QList<QByteArray> requestLine = lines.value(0).trimmed().split(' ');
        const QString path = QString::fromLatin1(requestLine.value(1));
        requests << path;
        for (const QByteArray& line : lines) {
            if (line.toLower().startsWith("user-agent:"))
                userAgent = QString::fromLatin1(line.mid(11).trimmed());
        }
        QByteArray answer;
        if (requestLine.value(0) == "GET" && tiles.contains(path)) {
            const QByteArray body = pngOf(tiles.value(path));
            answer =
                "HTTP/1.1 200 OK\r\nContent-Type: image/png\r\nCache-Control: max-age=86400\r\n"
                "Connection: close\r\nContent-Length: " +
                QByteArray::number(body.size()) + "\r\n\r\n" + body;
        } else {
            answer =
                "HTTP/1.1 404 Not Found\r\nContent-Type: text/plain\r\nConnection: close\r\n"
                "Content-Length: 9\r\n\r\nno tile\r\n";
        }
        socket->write(answer);
        socket->disconnectFromHost();
    }

    QTcpServer m_server;
    QHash<QTcpSocket*, QByteArray> m_buffers;
};

}  // namespace

class TestMapTiles : public QObject {
    Q_OBJECT

private slots:
    void initTestCase();
    void tileIdHashes();
    void urlTemplates();
    void noSettingsNoTiles();
    void mbtilesRowsFromTheSouth();
    void mbtilesJpegTile();
    void mbtilesMetadata();
    void mbtilesMissingTileStaysMissing();
    void mbtilesZoomOutsideRangeNotAsked();
    void mbtilesBeforeUrl();
    void notMbTiles_data();
    void notMbTiles();
    void newSourceForgetsOldTiles();
    void loaderReadsNewestFirst();
    void loaderLetsOldestGo();
    void onlineTile();
    void onlineNotFoundOnce();
    void onlineBadTemplate();
    void onlineOfflineFromDiskCache();
    void onlineUnansweredLetGo();

private:
    QTemporaryDir m_dir;
    QString m_area;  // the MBTiles file most cases read
};

void TestMapTiles::initTestCase()
{
    QVERIFY(m_dir.isValid());
    if (QStandardPaths::findExecutable(QStringLiteral("sqlite3")).isEmpty())
        qWarning("no sqlite3 program: the MBTiles files are written with Qt SQL instead");
    m_area = m_dir.filePath(QStringLiteral("area.mbtiles"));
    // Zoom 1: red at the north-west, green at the south-east; zoom 2: blue
    // at x 2, y 1, and yellow, in JPEG as aerial imagery comes, at the
    // south-west corner. Zoom 3's one tile is outside the range the metadata gives.
    const QString failure = writeMbTiles(m_area,
                                         {{{1, 0, 0}, kRed},
                                          {{1, 1, 1}, kGreen},
                                          {{2, 2, 1}, kBlue},
                                          {{3, 0, 0}, kYellow},
                                          {{2, 0, 3}, kYellow, "JPEG"}},
                                         {{QStringLiteral("name"), QStringLiteral("Test area")},
                                          {QStringLiteral("format"), QStringLiteral("png")},
                                          {QStringLiteral("minzoom"), QStringLiteral("1")},
                                          {QStringLiteral("maxzoom"), QStringLiteral("2")},
                                          {QStringLiteral("bounds"), QStringLiteral("-10.5,40,5,52.25")},
                                          {QStringLiteral("attribution"), QStringLiteral("Tiles © test's own")}});
    QVERIFY2(failure.isEmpty(), qPrintable(failure));
}

void TestMapTiles::tileIdHashes()
{
    QSet<TileId> ids;
    for (int z = 0; z < 4; ++z)
        for (int x = 0; x < (1 << z); ++x)
            for (int y = 0; y < (1 << z); ++y)
                ids.insert(TileId{z, x, y});
    QCOMPARE(ids.size(), 1 + 4 + 16 + 64);
    QVERIFY(ids.contains(TileId{2, 3, 1}));
    QVERIFY(!ids.contains(TileId{4, 0, 0}));
    QCOMPARE(qHash(TileId{5, 6, 7}, 11), qHash(TileId{5, 6, 7}, 11));
}

void TestMapTiles::urlTemplates()
{
    QCOMPARE(TileServer::urlFor(QStringLiteral("https://tile.example/{z}/{x}/{y}.png"), {3, 2, 1}),
             QUrl(QStringLiteral("https://tile.example/3/2/1.png")));
    // {-y}: rows from the south; {s}: the same subdomain for the same tile.
    QCOMPARE(TileServer::urlFor(QStringLiteral("https://{s}.tile.example/{z}/{x}/{-y}.png"), {3, 2, 1}),
             QUrl(QStringLiteral("https://a.tile.example/3/2/6.png")));
    QCOMPARE(TileServer::urlFor(QStringLiteral("https://{s}.tile.example/{z}/{x}/{y}.png"), {3, 2, 2}),
             QUrl(QStringLiteral("https://b.tile.example/3/2/2.png")));
    QCOMPARE(TileServer::hostOf(QStringLiteral("https://{s}.tile.example/{z}/{x}/{y}.png")),
             QStringLiteral("tile.example"));
    QVERIFY(TileServer::checkTemplate(QStringLiteral("https://{s}.tile.example/{z}/{x}/{y}.png")).isEmpty());
    QCOMPARE(TileServer::checkTemplate(QStringLiteral("https://tile.example/{z}/{x}.png")),
             QStringLiteral("https://tile.example/{z}/{x}.png: not a tile URL (it needs {z}, {x} and {y})"));
}

void TestMapTiles::noSettingsNoTiles()
{
    MapTiles tiles;
    QCOMPARE(tiles.source(), MapTiles::Source::None);
    QCOMPARE(tiles.description(), QStringLiteral("no map tiles"));
    QVERIFY(tiles.tile({0, 0, 0}).isNull());
    QSignalSpy changed(&tiles, &MapTiles::sourceChanged);
    QSignalSpy errors(&tiles, &MapTiles::error);
    tiles.configure({});
    QTRY_COMPARE(changed.size(), 1);
    QCOMPARE(tiles.source(), MapTiles::Source::None);
    QCOMPARE(tiles.description(), QStringLiteral("no map tiles"));
    QVERIFY(tiles.attribution().isEmpty());
    QVERIFY(tiles.tile({0, 0, 0}).isNull());
    QCOMPARE(errors.size(), 0);
}

void TestMapTiles::mbtilesRowsFromTheSouth()
{
    MapTiles tiles;
    QSignalSpy changed(&tiles, &MapTiles::sourceChanged);
    QSignalSpy arrived(&tiles, &MapTiles::tileArrived);
    tiles.configure(fileSettings(m_area));
    QTRY_COMPARE(changed.size(), 1);
    QCOMPARE(tiles.source(), MapTiles::Source::MbTiles);

    const QList<StoredTile> expected = {{{1, 0, 0}, kRed}, {{1, 1, 1}, kGreen}, {{2, 2, 1}, kBlue}};
    for (const StoredTile& tile : expected)
        QVERIFY(tiles.tile(tile.id).isNull());  // asked for, not there yet
    QTRY_COMPARE(arrived.size(), expected.size());
    for (const StoredTile& tile : expected) {
        const QImage image = tiles.tile(tile.id);
        QVERIFY2(!image.isNull(), qPrintable(QStringLiteral("%1/%2/%3").arg(tile.id.z).arg(tile.id.x).arg(tile.id.y)));
        QCOMPARE(image.size(), QSize(256, 256));
        QCOMPARE(centreOf(image), tile.colour);
    }
    // Each asked for once, and each arrived once.
    QSet<TileId> arrivedIds;
    for (const QList<QVariant>& signal : arrived)
        arrivedIds.insert(signal.at(0).value<TileId>());
    QCOMPARE(arrivedIds.size(), expected.size());
}

void TestMapTiles::mbtilesJpegTile()
{
    MapTiles tiles;
    QSignalSpy changed(&tiles, &MapTiles::sourceChanged);
    QSignalSpy arrived(&tiles, &MapTiles::tileArrived);
    tiles.configure(fileSettings(m_area));
    QTRY_COMPARE(changed.size(), 1);
    QVERIFY(tiles.tile({2, 0, 3}).isNull());
    QTRY_COMPARE(arrived.size(), 1);
    const QColor colour = centreOf(tiles.tile({2, 0, 3}));
    // JPEG is lossy: near the colour stored, not equal to it.
    QVERIFY2(qAbs(colour.red() - kYellow.red()) < 8 && qAbs(colour.green() - kYellow.green()) < 8 &&
                 qAbs(colour.blue() - kYellow.blue()) < 8,
             qPrintable(colour.name()));
}

void TestMapTiles::mbtilesMetadata()
{
    MapTiles tiles;
    QSignalSpy changed(&tiles, &MapTiles::sourceChanged);
    QSignalSpy errors(&tiles, &MapTiles::error);
    tiles.configure([this] {
        TileSettings settings = fileSettings(m_area);
        settings.attribution = QStringLiteral("not this one");
        return settings;
    }());
    QTRY_COMPARE(changed.size(), 1);
    QCOMPARE(tiles.source(), MapTiles::Source::MbTiles);
    QCOMPARE(tiles.attribution(), QStringLiteral("Tiles © test's own"));
    QCOMPARE(tiles.minZoom(), 1);
    QCOMPARE(tiles.maxZoom(), 2);
    QCOMPARE(tiles.bounds(), QRectF(QPointF(-10.5, 40), QPointF(5, 52.25)));
    QCOMPARE(tiles.description(), QStringLiteral("MBTiles: area.mbtiles, zoom 1-2"));
    QCOMPARE(errors.size(), 0);
}

void TestMapTiles::mbtilesMissingTileStaysMissing()
{
    MapTiles tiles;
    QSignalSpy changed(&tiles, &MapTiles::sourceChanged);
    QSignalSpy arrived(&tiles, &MapTiles::tileArrived);
    QSignalSpy errors(&tiles, &MapTiles::error);
    tiles.configure(fileSettings(m_area));
    QTRY_COMPARE(changed.size(), 1);
    // Row 1 from the north at zoom 1 is TMS row 0: column 0 of it is not stored
    // (column 1 is, green); read without the flip it would be the red tile.
    const TileId absent{1, 0, 1};
    QVERIFY(tiles.tile(absent).isNull());
    QVERIFY(!tiles.isMissing(absent));
    QTRY_VERIFY(tiles.isMissing(absent));
    QVERIFY(tiles.tile(absent).isNull());
    QVERIFY(tiles.isMissing(absent));
    // A tile asked for after it arrives, and so after the file answered for the absent one.
    QVERIFY(tiles.tile({1, 1, 1}).isNull());
    QTRY_COMPARE(arrived.size(), 1);
    QCOMPARE(arrived.at(0).at(0).value<TileId>(), (TileId{1, 1, 1}));
    QVERIFY(tiles.isMissing(absent));
    QCOMPARE(errors.size(), 0);
}

void TestMapTiles::mbtilesZoomOutsideRangeNotAsked()
{
    MapTiles tiles;
    QSignalSpy changed(&tiles, &MapTiles::sourceChanged);
    QSignalSpy arrived(&tiles, &MapTiles::tileArrived);
    tiles.configure(fileSettings(m_area));
    QTRY_COMPARE(changed.size(), 1);
    // The file holds a zoom 3 tile, but its metadata says zoom 1 to 2.
    QVERIFY(tiles.tile({3, 0, 0}).isNull());
    QVERIFY(tiles.tile({0, 0, 0}).isNull());
    // Nor tiles that do not exist at any zoom.
    QVERIFY(tiles.tile({1, 2, 0}).isNull());
    QVERIFY(tiles.tile({1, 0, -1}).isNull());
    QVERIFY(tiles.tile({2, 2, 1}).isNull());
    QTRY_COMPARE(arrived.size(), 1);
    QCOMPARE(arrived.at(0).at(0).value<TileId>(), (TileId{2, 2, 1}));
    QVERIFY(tiles.tile({3, 0, 0}).isNull());
    QVERIFY(!tiles.isMissing({3, 0, 0}));
    QVERIFY(!tiles.isMissing({0, 0, 0}));
}

void TestMapTiles::mbtilesBeforeUrl()
{
    MapTiles tiles;
    QSignalSpy changed(&tiles, &MapTiles::sourceChanged);
    tiles.configure(fileSettings(m_area, QStringLiteral("http://127.0.0.1:9/{z}/{x}/{y}.png")));
    QTRY_COMPARE(changed.size(), 1);
    QCOMPARE(tiles.source(), MapTiles::Source::MbTiles);
    QCOMPARE(tiles.settings().mbtilesPath, m_area);
}

void TestMapTiles::notMbTiles_data()
{
    QTest::addColumn<QString>("path");
    QTest::addColumn<QString>("expectedError");

    const QString otherDatabase = m_dir.filePath(QStringLiteral("other.sqlite"));
    const QString failure = runSql(otherDatabase, {QStringLiteral("CREATE TABLE waypoints (lat REAL, lon REAL)")});
    QVERIFY2(failure.isEmpty(), qPrintable(failure));
    QTest::newRow("SQLite without tiles")
        << otherDatabase << otherDatabase + QStringLiteral(": not an MBTiles file (no \"tiles\" table)");

    const QString text = m_dir.filePath(QStringLiteral("notes.mbtiles"));
    QFile file(text);
    QVERIFY(file.open(QIODevice::WriteOnly));
    file.write(QByteArray("These are not the tiles you are looking for.\n").repeated(40));
    file.close();
    QTest::newRow("not SQLite") << text << text + QStringLiteral(": file is not a database");

    const QString vector = m_dir.filePath(QStringLiteral("vector.mbtiles"));
    const QString vectorFailure = writeMbTiles(vector, {}, {{QStringLiteral("format"), QStringLiteral("pbf")}});
    QVERIFY2(vectorFailure.isEmpty(), qPrintable(vectorFailure));
    QTest::newRow("vector tiles") << vector
                                  << vector + QStringLiteral(": holds vector tiles (pbf), which the map cannot draw");

    const QString missing = m_dir.filePath(QStringLiteral("nowhere.mbtiles"));
    QTest::newRow("missing") << missing << missing + QStringLiteral(": no such file");
}

void TestMapTiles::notMbTiles()
{
    QFETCH(QString, path);
    QFETCH(QString, expectedError);
    MapTiles tiles;
    QSignalSpy changed(&tiles, &MapTiles::sourceChanged);
    QSignalSpy errors(&tiles, &MapTiles::error);
    tiles.configure(fileSettings(path));
    QTRY_COMPARE(changed.size(), 1);
    QCOMPARE(errors.size(), 1);
    QCOMPARE(errors.at(0).at(0).toString(), expectedError);
    QCOMPARE(tiles.source(), MapTiles::Source::None);
    QCOMPARE(tiles.description(), QStringLiteral("no map tiles"));
    QVERIFY(tiles.tile({1, 0, 0}).isNull());
}

void TestMapTiles::newSourceForgetsOldTiles()
{
    const QString other = m_dir.filePath(QStringLiteral("other-colours.mbtiles"));
    const QString failure = writeMbTiles(other, {{{1, 0, 0}, kYellow}}, {});
    QVERIFY2(failure.isEmpty(), qPrintable(failure));

    MapTiles tiles;
    QSignalSpy changed(&tiles, &MapTiles::sourceChanged);
    QSignalSpy arrived(&tiles, &MapTiles::tileArrived);
    tiles.configure(fileSettings(m_area));
    QTRY_COMPARE(changed.size(), 1);
    QVERIFY(tiles.tile({1, 0, 0}).isNull());
    QTRY_COMPARE(arrived.size(), 1);
    QCOMPARE(centreOf(tiles.tile({1, 0, 0})), kRed);
    // Asked of the first file and switched before it answers: its answer,
    // if it comes, is not taken for the second file's.
    QVERIFY(tiles.tile({1, 1, 1}).isNull());
    tiles.configure(fileSettings(other));
    QVERIFY(tiles.tile({1, 0, 0}).isNull());
    QTRY_COMPARE(changed.size(), 2);
    // No metadata: the zoom range comes from the tiles.
    QCOMPARE(tiles.description(), QStringLiteral("MBTiles: other-colours.mbtiles, zoom 1-1"));
    arrived.clear();
    QVERIFY(tiles.tile({1, 0, 0}).isNull());
    QTRY_COMPARE(arrived.size(), 1);
    QCOMPARE(arrived.at(0).at(0).value<TileId>(), (TileId{1, 0, 0}));
    QCOMPARE(centreOf(tiles.tile({1, 0, 0})), kYellow);
    QVERIFY(tiles.tile({1, 1, 1}).isNull());
    QTRY_VERIFY(tiles.isMissing({1, 1, 1}));
}

void TestMapTiles::loaderReadsNewestFirst()
{
    // The loader alone, in this thread: what the view asked for last comes first.
    TileLoader loader;
    QSignalSpy opened(&loader, &TileLoader::opened);
    QSignalSpy loaded(&loader, &TileLoader::tileLoaded);
    loader.open(7, fileSettings(m_area));
    QCOMPARE(opened.size(), 1);
    QCOMPARE(opened.at(0).at(1).value<TileSourceInfo>().source, MapTiles::Source::MbTiles);
    const QList<TileId> asked = {{1, 0, 0}, {1, 1, 1}, {2, 2, 1}};
    for (const TileId& id : asked)
        loader.load(7, id);
    loader.load(6, {1, 0, 0});  // an earlier source's: ignored
    QTRY_COMPARE(loaded.size(), 3);
    for (int i = 0; i < 3; ++i) {
        QCOMPARE(loaded.at(i).at(0).toULongLong(), 7u);
        QCOMPARE(loaded.at(i).at(1).value<TileId>(), asked.at(2 - i));
    }
}

void TestMapTiles::loaderLetsOldestGo()
{
    TileLoader loader;
    QSignalSpy dropped(&loader, &TileLoader::tileDropped);
    QSignalSpy loaded(&loader, &TileLoader::tileLoaded);
    QSignalSpy missing(&loader, &TileLoader::tileMissing);
    loader.open(1, fileSettings(m_area));
    for (int i = 0; i < TileLoader::kMaxWaiting + 2; ++i)
        loader.load(1, {10, i, 0});  // outside the file: all missing, if read
    QCOMPARE(dropped.size(), 2);
    QCOMPARE(dropped.at(0).at(1).value<TileId>(), (TileId{10, 0, 0}));
    QCOMPARE(dropped.at(1).at(1).value<TileId>(), (TileId{10, 1, 0}));
    QTRY_COMPARE(missing.size(), TileLoader::kMaxWaiting);
    QCOMPARE(loaded.size(), 0);
}

void TestMapTiles::onlineTile()
{
    TileHttpServer server;
    QVERIFY(server.start());
    server.tiles.insert(QStringLiteral("/1/0/0.png"), kRed);
    server.tiles.insert(QStringLiteral("/1/1/0.png"), kBlue);
    QTemporaryDir cache;
    QVERIFY(cache.isValid());

    MapTiles tiles;
    QSignalSpy changed(&tiles, &MapTiles::sourceChanged);
    QSignalSpy arrived(&tiles, &MapTiles::tileArrived);
    QSignalSpy errors(&tiles, &MapTiles::error);
    tiles.configure([&] {
        TileSettings settings = onlineSettings(server.urlTemplate(), cache.path(), QStringLiteral("© test server"));
        settings.cacheBytes = 10 << 20;
        return settings;
    }());
    QTRY_COMPARE(changed.size(), 1);
    QCOMPARE(tiles.source(), MapTiles::Source::Online);
    QCOMPARE(tiles.attribution(), QStringLiteral("© test server"));
    QCOMPARE(tiles.description(),
             QStringLiteral("Online: 127.0.0.1:%1 (cached in %2)").arg(server.port()).arg(cache.path()));
    QCOMPARE(tiles.minZoom(), 0);
    QCOMPARE(tiles.maxZoom(), 19);

    QVERIFY(tiles.tile({1, 0, 0}).isNull());
    QVERIFY(tiles.tile({1, 1, 0}).isNull());
    QVERIFY(tiles.tile({1, 0, 0}).isNull());   // asked once only
    QVERIFY(tiles.tile({20, 0, 0}).isNull());  // beyond zoom 19: not asked
    QTRY_COMPARE(arrived.size(), 2);
    QCOMPARE(centreOf(tiles.tile({1, 0, 0})), kRed);
    QCOMPARE(centreOf(tiles.tile({1, 1, 0})), kBlue);
    QCOMPARE(server.requests.size(), 2);
    QVERIFY2(server.userAgent.startsWith(QStringLiteral("rcm-gcs/")), qPrintable(server.userAgent));
    QCOMPARE(server.userAgent, TileServer::userAgent());
    QCOMPARE(errors.size(), 0);
}

void TestMapTiles::onlineNotFoundOnce()
{
    TileHttpServer server;
    QVERIFY(server.start());
    server.tiles.insert(QStringLiteral("/2/1/1.png"), kGreen);
    QTemporaryDir cache;
    QVERIFY(cache.isValid());

    MapTiles tiles;
    QSignalSpy changed(&tiles, &MapTiles::sourceChanged);
    QSignalSpy arrived(&tiles, &MapTiles::tileArrived);
    QSignalSpy errors(&tiles, &MapTiles::error);
    tiles.configure(onlineSettings(server.urlTemplate(), cache.path()));
    QTRY_COMPARE(changed.size(), 1);
    const QList<TileId> absent = {{3, 0, 0}, {3, 1, 0}, {3, 2, 0}, {3, 3, 0}};
    for (const TileId& id : absent)
        QVERIFY(tiles.tile(id).isNull());
    for (const TileId& id : absent)
        QTRY_VERIFY(tiles.isMissing(id));
    QCOMPARE(server.requests.size(), absent.size());
    QCOMPARE(errors.size(), 1);
    QCOMPARE(errors.at(0).at(0).toString(),
             QStringLiteral("tile server http://127.0.0.1:%1: 404 Not Found").arg(server.port()));

    // Not asked again; the server's other tiles still come.
    for (const TileId& id : absent)
        QVERIFY(tiles.tile(id).isNull());
    QVERIFY(tiles.tile({2, 1, 1}).isNull());
    QTRY_COMPARE(arrived.size(), 1);
    QCOMPARE(centreOf(tiles.tile({2, 1, 1})), kGreen);
    QCOMPARE(server.requests.size(), absent.size() + 1);
    QCOMPARE(errors.size(), 1);
}

void TestMapTiles::onlineBadTemplate()
{
    MapTiles tiles;
    QSignalSpy changed(&tiles, &MapTiles::sourceChanged);
    QSignalSpy errors(&tiles, &MapTiles::error);
    tiles.configure(onlineSettings(QStringLiteral("http://127.0.0.1:9/tiles.png")));
    QTRY_COMPARE(changed.size(), 1);
    QCOMPARE(tiles.source(), MapTiles::Source::None);
    QCOMPARE(errors.size(), 1);
    QCOMPARE(errors.at(0).at(0).toString(),
             QStringLiteral("http://127.0.0.1:9/tiles.png: not a tile URL (it needs {z}, {x} and {y})"));
}

void TestMapTiles::onlineOfflineFromDiskCache()
{
    auto server = std::make_unique<TileHttpServer>();
    QVERIFY(server->start());
    server->tiles.insert(QStringLiteral("/4/9/5.png"), kBlue);
    const QString urlTemplate = server->urlTemplate();
    QTemporaryDir cache;
    QVERIFY(cache.isValid());
    const TileSettings settings = onlineSettings(urlTemplate, cache.path());
    const TileId id{4, 9, 5};

    {
        MapTiles online;
        QSignalSpy changed(&online, &MapTiles::sourceChanged);
        QSignalSpy arrived(&online, &MapTiles::tileArrived);
        online.configure(settings);
        QTRY_COMPARE(changed.size(), 1);
        QVERIFY(online.tile(id).isNull());
        QTRY_COMPARE(arrived.size(), 1);
        QCOMPARE(centreOf(online.tile(id)), kBlue);
        QCOMPARE(server->requests.size(), 1);
    }

    // The network gone: nothing listens on the port any more.
    server->stop();
    server.reset();

    MapTiles offline;
    QSignalSpy changed(&offline, &MapTiles::sourceChanged);
    QSignalSpy arrived(&offline, &MapTiles::tileArrived);
    QSignalSpy errors(&offline, &MapTiles::error);
    offline.configure(settings);
    QTRY_COMPARE(changed.size(), 1);
    QVERIFY(offline.tile(id).isNull());
    QTRY_COMPARE(arrived.size(), 1);
    QCOMPARE(centreOf(offline.tile(id)), kBlue);
    QCOMPARE(errors.size(), 0);

    // A tile it never had: one error, that the server cannot be reached, and
    // it may be asked for again (the network may come back).
    const TileId unseen{4, 9, 6};
    QVERIFY(offline.tile(unseen).isNull());
    QTRY_COMPARE(errors.size(), 1);
    QVERIFY2(errors.at(0).at(0).toString().startsWith(
                 urlTemplate.section(QLatin1Char('/'), 0, 2).prepend(QStringLiteral("tile server "))),
             qPrintable(errors.at(0).at(0).toString()));
    QVERIFY(!offline.isMissing(unseen));
}

void TestMapTiles::onlineUnansweredLetGo()
{
    // A server that takes the connection and never answers, as over a link
    // that has just dropped: neither a new source nor the end waits for it.
    QTcpServer silent;
    QVERIFY(silent.listen(QHostAddress::LocalHost, 0));
    const QString urlTemplate = QStringLiteral("http://127.0.0.1:%1/{z}/{x}/{y}.png").arg(silent.serverPort());
    QTemporaryDir cache;
    QVERIFY(cache.isValid());

    auto tiles = std::make_unique<MapTiles>();
    QSignalSpy changed(tiles.get(), &MapTiles::sourceChanged);
    QSignalSpy arrived(tiles.get(), &MapTiles::tileArrived);
    QSignalSpy errors(tiles.get(), &MapTiles::error);
    tiles->configure(onlineSettings(urlTemplate, cache.path()));
    QTRY_COMPARE(changed.size(), 1);
    QVERIFY(tiles->tile({1, 0, 0}).isNull());
    QVERIFY(tiles->tile({1, 1, 0}).isNull());
    QTRY_VERIFY(silent.hasPendingConnections());
    // Taken and kept open (children of the server), so that the next wait
    // is for a new one.
    while (silent.hasPendingConnections())
        silent.nextPendingConnection();

    tiles->configure(fileSettings(m_area));
    QTRY_COMPARE(changed.size(), 2);
    QCOMPARE(tiles->source(), MapTiles::Source::MbTiles);
    QVERIFY(tiles->tile({1, 0, 0}).isNull());
    QTRY_COMPARE(arrived.size(), 1);
    QCOMPARE(centreOf(tiles->tile({1, 0, 0})), kRed);

    tiles->configure(onlineSettings(urlTemplate, cache.path()));
    QTRY_COMPARE(changed.size(), 3);
    QVERIFY(tiles->tile({2, 0, 0}).isNull());
    QTRY_VERIFY(silent.hasPendingConnections());
    tiles.reset();
    QCOMPARE(errors.size(), 0);
}

QTEST_GUILESS_MAIN(TestMapTiles)
#include "tst_maptiles.moc"
