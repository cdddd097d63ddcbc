#pragma once

// A tile server reached by a URL template ("https://{s}.tile.example/{z}/{x}/{y}.png"),
// with a disk cache that is read first: a tile fetched once is there when the
// network is not. Made, used and destroyed in the loader thread; it fetches
// what it is asked to at once, the loader deciding how many at a time.

#include "link/maptiles/MapTiles.h"

#include <QByteArray>
#include <QHash>
#include <QObject>
#include <QString>
#include <QUrl>

class QNetworkAccessManager;
class QNetworkReply;

class TileServer : public QObject {
    Q_OBJECT

public:
    // A tile that has sent nothing for this long is given up (a satellite
    // phone's link carries a tile in tens of seconds, but it does carry).
    static constexpr int kStallTimeoutMs = 60000;

    // Why the template is no tile URL ("...: not a tile URL (it needs {z}, {x}
    // and {y})"); empty when it is one.
    static QString checkTemplate(const QString& urlTemplate);
    // The template filled in for one tile; {-y} counts rows from the south
    // (TMS servers), {s} is a subdomain, a, b or c.
    static QUrl urlFor(const QString& urlTemplate, const TileId& id);
    // "tile.example" for "https://{s}.tile.example/{z}/{x}/{y}.png".
    static QString hostOf(const QString& urlTemplate);
    // What the server is told the program is: tile servers (OpenStreetMap's
    // among them) refuse anonymous clients.
    static QString userAgent();

    TileServer(const QString& urlTemplate, const QString& cacheDir, qint64 cacheBytes, QObject* parent = nullptr);
    ~TileServer() override;  // abandons the fetches in flight, telling nobody

    void fetch(const TileId& id);
    int inFlight() const { return int(m_replies.size()); }

signals:
    void fetched(const TileId& id, const QByteArray& data);
    // The server answered that it has no such tile, or will not give it (4xx):
    // asking again would get the same.
    void refused(const TileId& id, const QString& cause);
    // No answer (no network, a server error, a stall): it may come later.
    void failed(const TileId& id, const QString& cause);

private:
    void finished(QNetworkReply* reply);

    QString m_urlTemplate;
    QNetworkAccessManager* m_network;  // child
    QHash<QNetworkReply*, TileId> m_replies;
};
