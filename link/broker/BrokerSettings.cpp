#include "link/broker/BrokerSettings.h"

#include "link/broker/BrokerTopics.h"
#include "link/broker/OwnedFile.h"

#include <QFile>

namespace {

const QString kScheme = QStringLiteral("mqtt");
const QString kTlsScheme = QStringLiteral("mqtts");

}  // namespace

std::optional<BrokerSettings> BrokerSettings::fromUrl(const QString& url, QString* error)
{
    BrokerSettings s;
    // What errors quote: the URL as given, but with a password cut out, so
    // that a mistaken one never reaches a log.
    QString quoted = url.trimmed();
    const auto fail = [&](const QString& what) -> std::optional<BrokerSettings> {
        if (error)
            *error = (quoted.isEmpty() ? QStringLiteral("broker URL") : quoted) + QStringLiteral(": ") + what;
        return std::nullopt;
    };

    const qsizetype schemeEnd = quoted.indexOf(QStringLiteral("://"));
    if (schemeEnd < 0)
        return fail(QStringLiteral("must be mqtt://HOST[:PORT][/AIRCRAFT] or mqtts://..."));
    const QString scheme = quoted.left(schemeEnd).toLower();
    if (scheme == kTlsScheme) {
        s.tls = true;
        s.port = kDefaultTlsPort;
    } else if (scheme != kScheme) {
        return fail(QStringLiteral("scheme must be mqtt or mqtts, not \"%1\"").arg(quoted.left(schemeEnd)));
    }
    const QString rest = quoted.mid(schemeEnd + 3);
    const qsizetype pathStart = rest.indexOf(u'/');
    QString authority = pathStart < 0 ? rest : rest.left(pathStart);
    const QString path = pathStart < 0 ? QString() : rest.mid(pathStart + 1);

    const qsizetype at = authority.lastIndexOf(u'@');
    if (at >= 0) {
        const QString userInfo = authority.left(at);
        if (userInfo.contains(u':')) {
            const QString user = userInfo.left(userInfo.indexOf(u':'));
            quoted = quoted.left(schemeEnd + 3) + user + QStringLiteral(":***") + quoted.mid(schemeEnd + 3 + at);
            return fail(QStringLiteral("give the password in a file, not in the URL"));
        }
        if (userInfo.isEmpty())
            return fail(QStringLiteral("empty user before '@'"));
        s.user = userInfo;
        authority = authority.mid(at + 1);
    }

    QString portText;
    if (authority.startsWith(u'[')) {
        // An IPv6 address: [::1]:1883.
        const qsizetype close = authority.indexOf(u']');
        if (close < 0)
            return fail(QStringLiteral("'[' without ']' around the IPv6 address"));
        s.host = authority.mid(1, close - 1);
        const QString after = authority.mid(close + 1);
        if (!after.isEmpty() && !after.startsWith(u':'))
            return fail(QStringLiteral("expected ':PORT' after the IPv6 address"));
        if (!after.isEmpty())
            portText = after.mid(1);
        if (after == QStringLiteral(":"))
            return fail(QStringLiteral("port must be 1..65535"));
    } else {
        const qsizetype colon = authority.indexOf(u':');
        s.host = colon < 0 ? authority : authority.left(colon);
        if (colon >= 0) {
            portText = authority.mid(colon + 1);
            if (portText.isEmpty())
                return fail(QStringLiteral("port must be 1..65535"));
        }
    }
    if (s.host.isEmpty())
        return fail(QStringLiteral("no host"));
    for (const QChar c : s.host)
        if (c.isSpace() || c == u'?' || c == u'#')
            return fail(QStringLiteral("\"%1\" is not a host name").arg(s.host));
    if (!portText.isEmpty()) {
        bool ok = false;
        const uint port = portText.toUInt(&ok);
        if (!ok || port < 1 || port > 65535)
            return fail(QStringLiteral("port must be 1..65535"));
        s.port = quint16(port);
    }

    if (!path.isEmpty()) {
        if (!BrokerTopics::isTopicLevel(path))
            return fail(QStringLiteral("aircraft \"%1\" must be one topic level (no '/', '+' or '#')").arg(path));
        s.aircraft = path;
    }
    return s;
}

QString BrokerSettings::url() const
{
    QString out = (tls ? kTlsScheme : kScheme) + QStringLiteral("://");
    if (!user.isEmpty())
        out += user + u'@';
    out += hostAndPort();
    if (!aircraft.isEmpty())
        out += u'/' + aircraft;
    return out;
}

QString BrokerSettings::hostAndPort() const
{
    const QString h = host.contains(u':') ? u'[' + host + u']' : host;
    return h + u':' + QString::number(port);
}

std::optional<QString> BrokerSettings::readPasswordFile(const QString& path, QString* error)
{
    const auto fail = [&](const QString& what) -> std::optional<QString> {
        if (error)
            *error = what;
        return std::nullopt;
    };
    QFile file(path);
    if (const std::optional<QString> refusal = OwnedFile::open(
            file, QStringLiteral("password"), 077, QStringLiteral("may read or write it"), QStringLiteral("600")))
        return fail(*refusal);
    return QString::fromUtf8(file.readLine(4096)).trimmed();
}
