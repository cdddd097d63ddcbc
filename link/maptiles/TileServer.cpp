#include "link/maptiles/TileServer.h"

#include <QNetworkAccessManager>
#include <QNetworkDiskCache>
#include <QNetworkReply>
#include <QNetworkRequest>

#ifndef RCM_GCS_VERSION
#define RCM_GCS_VERSION "0"
#endif

QString TileServer::checkTemplate(const QString& urlTemplate)
{
    if (!urlTemplate.contains(QLatin1String("{z}")) || !urlTemplate.contains(QLatin1String("{x}")) ||
        !(urlTemplate.contains(QLatin1String("{y}")) || urlTemplate.contains(QLatin1String("{-y}"))))
        return QStringLiteral("%1: not a tile URL (it needs {z}, {x} and {y})").arg(urlTemplate);
    const QUrl url = urlFor(urlTemplate, TileId{});
    if (!url.isValid() || url.host().isEmpty())
        return QStringLiteral("%1: not a tile URL (%2)").arg(urlTemplate, url.errorString());
    if (url.scheme() != QLatin1String("http") && url.scheme() != QLatin1String("https"))
        return QStringLiteral("%1: not a tile URL (http or https only)").arg(urlTemplate);
    return {};
}

QString TileServer::hostOf(const QString& urlTemplate)
{
    QString host = urlTemplate;
    const qsizetype schemeEnd = host.indexOf(QLatin1String("://"));
    if (schemeEnd >= 0)
        host.remove(0, schemeEnd + 3);
    const qsizetype pathStart = host.indexOf(QLatin1Char('/'));
    if (pathStart >= 0)
        host.truncate(pathStart);
    if (host.startsWith(QLatin1String("{s}.")))
        host.remove(0, 4);
    return host;
}

QString TileServer::userAgent()
{
    return QStringLiteral("rcm-gcs/" RCM_GCS_VERSION " (ground control station, plan view map) Qt/") +
           QLatin1String(qVersion());
}

TileServer::TileServer(const QString& urlTemplate, const QString& cacheDir, qint64 cacheBytes, QObject* parent)
    : QObject(parent), m_urlTemplate(urlTemplate), m_network(new QNetworkAccessManager(this))
{
    if (!cacheDir.isEmpty()) {
        auto* cache = new QNetworkDiskCache(m_network);
        cache->setCacheDirectory(cacheDir);
        cache->setMaximumCacheSize(cacheBytes);
        m_network->setCache(cache);
    }
}

TileServer::~TileServer()
{
    // Disconnected first: an abort finishes the reply there and then, and
    // nobody is left to hear of it.
    for (auto it = m_replies.begin(); it != m_replies.end(); ++it) {
        it.key()->disconnect(this);
        it.key()->abort();
        delete it.key();
    }
}

QUrl TileServer::urlFor(const QString& urlTemplate, const TileId& id)
{
    static const char subdomains[] = {'a', 'b', 'c'};
    QString url = urlTemplate;
    url.replace(QLatin1String("{z}"), QString::number(id.z));
    url.replace(QLatin1String("{x}"), QString::number(id.x));
    url.replace(QLatin1String("{y}"), QString::number(id.y));
    url.replace(QLatin1String("{-y}"), QString::number((1 << id.z) - 1 - id.y));
    // The same tile always from the same subdomain, so that the disk cache
    // (keyed by URL) finds it again.
    url.replace(QLatin1String("{s}"), QString(QLatin1Char(subdomains[(id.x + id.y) % 3])));
    return QUrl(url);
}

void TileServer::fetch(const TileId& id)
{
    QNetworkRequest request(urlFor(m_urlTemplate, id));
    request.setHeader(QNetworkRequest::UserAgentHeader, userAgent());
    // Offline first: a tile in the cache is used even when the server said
    // it would be stale by now, and the network is asked only for the rest.
    request.setAttribute(QNetworkRequest::CacheLoadControlAttribute, QNetworkRequest::PreferCache);
    request.setTransferTimeout(kStallTimeoutMs);
    QNetworkReply* reply = m_network->get(request);
    m_replies.insert(reply, id);
    connect(reply, &QNetworkReply::finished, this, [this, reply] { finished(reply); });
}

void TileServer::finished(QNetworkReply* reply)
{
    reply->deleteLater();
    const TileId id = m_replies.take(reply);
    const QUrl origin = reply->request().url().adjusted(QUrl::RemovePath | QUrl::RemoveQuery | QUrl::RemoveFragment |
                                                        QUrl::RemoveUserInfo);
    const QString where = QStringLiteral("tile server ") + origin.toString();
    const QVariant status = reply->attribute(QNetworkRequest::HttpStatusCodeAttribute);
    if (reply->error() == QNetworkReply::NoError) {
        emit fetched(id, reply->readAll());
        return;
    }
    if (status.isValid()) {
        const int code = status.toInt();
        const QString reason = reply->attribute(QNetworkRequest::HttpReasonPhraseAttribute).toString();
        const QString cause = QStringLiteral("%1: %2 %3").arg(where).arg(code).arg(reason).trimmed();
        if (code >= 400 && code < 500)
            emit refused(id, cause);
        else
            emit failed(id, cause);
        return;
    }
    // Our own aborts are disconnected first: a cancel that arrives here is
    // the stall timeout's.
    if (reply->error() == QNetworkReply::OperationCanceledError) {
        emit failed(id, QStringLiteral("%1: no data for %2 s").arg(where).arg(kStallTimeoutMs / 1000));
        return;
    }
    emit failed(id, where + QStringLiteral(": ") + reply->errorString());
}
