#include "link/broker/BrokerEnvelope.h"

#include <QJsonDocument>
#include <QJsonObject>
#include <QJsonParseError>
#include <QtEndian>

#include <limits>

namespace {

constexpr char kSignedPrefix[] = "RCM-GCS v1 broker message";
constexpr quint8 kFlagSealed = 1;
constexpr quint8 kFlagWill = 2;

// Integers go big-endian, in as many bytes as their type has.
template <typename Integer>
void appendBigEndian(QByteArray& out, Integer v)
{
    char b[sizeof v];
    qToBigEndian(v, b);
    out.append(b, sizeof b);
}

void appendSized(QByteArray& out, const QByteArray& bytes)
{
    appendBigEndian(out, quint32(bytes.size()));
    out.append(bytes);
}

// A whole number in [min, max] held exactly by a JSON double.
std::optional<qint64> wholeNumber(const QJsonValue& v, qint64 min, qint64 max)
{
    if (!v.isDouble())
        return std::nullopt;
    const qint64 n = v.toInteger(std::numeric_limits<qint64>::min());
    if (n == std::numeric_limits<qint64>::min() || double(n) != v.toDouble() || n < min || n > max)
        return std::nullopt;
    return n;
}

std::optional<QByteArray> base64(const QJsonValue& v)
{
    if (!v.isString() || v.toString().size() % 4 != 0)
        return std::nullopt;
    auto decoded = QByteArray::fromBase64Encoding(v.toString().toLatin1(), QByteArray::AbortOnBase64DecodingErrors);
    if (!decoded)
        return std::nullopt;
    return *decoded;
}

}  // namespace

QByteArray BrokerEnvelope::toJson() const
{
    QJsonObject o{
        {QStringLiteral("v"), kVersion},
        {QStringLiteral("station"), station},
        {QStringLiteral("seq"), seq},
    };
    if (sealed) {
        o.insert(QStringLiteral("sealed"), QString::fromLatin1(body.toBase64()));
        o.insert(QStringLiteral("key"), keyFingerprint);
    } else {
        o.insert(QStringLiteral("body"), QString::fromUtf8(body));
    }
    if (will)
        o.insert(QStringLiteral("will"), true);
    if (willSeq)
        o.insert(QStringLiteral("willSeq"), willSeq);
    if (!signature.isEmpty())
        o.insert(QStringLiteral("sig"), QString::fromLatin1(signature.toBase64()));
    return QJsonDocument(o).toJson(QJsonDocument::Compact);
}

std::optional<BrokerEnvelope> BrokerEnvelope::fromJson(const QByteArray& json, QString* error)
{
    const auto fail = [error](const QString& what) -> std::optional<BrokerEnvelope> {
        if (error)
            *error = QStringLiteral("envelope: ") + what;
        return std::nullopt;
    };
    QJsonParseError parseError;
    const QJsonDocument doc = QJsonDocument::fromJson(json, &parseError);
    if (parseError.error != QJsonParseError::NoError)
        return fail(QStringLiteral("not JSON: %1 at byte %2").arg(parseError.errorString()).arg(parseError.offset));
    if (!doc.isObject())
        return fail(QStringLiteral("not a JSON object"));
    const QJsonObject o = doc.object();
    if (!o.contains(QLatin1String("v")))
        return fail(QStringLiteral("v is missing: not an envelope (a report published bare is refused)"));
    if (wholeNumber(o.value(QLatin1String("v")), 0, 1 << 30) != kVersion)
        return fail(QStringLiteral("v must be %1").arg(kVersion));

    BrokerEnvelope e;
    const QJsonValue station = o.value(QLatin1String("station"));
    if (!station.isString() || !BrokerTopics::isTopicLevel(station.toString()))
        return fail(QStringLiteral("station must be a station's name"));
    e.station = station.toString();
    const std::optional<qint64> seq = wholeNumber(o.value(QLatin1String("seq")), 1, std::numeric_limits<qint64>::max());
    if (!seq)
        return fail(QStringLiteral("seq must be a whole number from 1"));
    e.seq = *seq;

    const bool hasBody = o.contains(QLatin1String("body"));
    const bool hasSealed = o.contains(QLatin1String("sealed"));
    if (hasBody == hasSealed)
        return fail(QStringLiteral("must hold either body or sealed"));
    if (hasBody) {
        const QJsonValue body = o.value(QLatin1String("body"));
        if (!body.isString())
            return fail(QStringLiteral("body must be a string"));
        e.body = body.toString().toUtf8();
    } else {
        const std::optional<QByteArray> sealed = base64(o.value(QLatin1String("sealed")));
        if (!sealed)
            return fail(QStringLiteral("sealed must be base64"));
        const QJsonValue key = o.value(QLatin1String("key"));
        if (!key.isString() || key.toString().size() != 16)
            return fail(QStringLiteral("key must be a key's fingerprint, 16 hex digits"));
        e.sealed = true;
        e.body = *sealed;
        e.keyFingerprint = key.toString();
    }
    if (o.contains(QLatin1String("will"))) {
        if (!o.value(QLatin1String("will")).isBool())
            return fail(QStringLiteral("will must be true or false"));
        e.will = o.value(QLatin1String("will")).toBool();
    }
    if (o.contains(QLatin1String("willSeq"))) {
        const std::optional<qint64> willSeq =
            wholeNumber(o.value(QLatin1String("willSeq")), 0, std::numeric_limits<qint64>::max());
        if (!willSeq)
            return fail(QStringLiteral("willSeq must be a whole number"));
        e.willSeq = *willSeq;
    }
    if (o.contains(QLatin1String("sig"))) {
        const std::optional<QByteArray> sig = base64(o.value(QLatin1String("sig")));
        if (!sig || sig->size() != 64)
            return fail(QStringLiteral("sig must be 64 bytes in base64"));
        e.signature = *sig;
    }
    return e;
}

QByteArray BrokerEnvelope::signedBytes(const QString& topic) const
{
    QByteArray out;
    out.reserve(int(sizeof kSignedPrefix) + 64 + topic.size() + station.size() + body.size());
    out.append(kSignedPrefix, sizeof kSignedPrefix);  // with its NUL
    appendSized(out, topic.toUtf8());
    appendSized(out, station.toUtf8());
    appendBigEndian(out, qint64(seq));
    out.append(char((sealed ? kFlagSealed : 0) | (will ? kFlagWill : 0)));
    appendBigEndian(out, qint64(willSeq));
    appendSized(out, sealed ? keyFingerprint.toLatin1() : QByteArray());
    out.append(body);
    return out;
}
