#include "link/broker/BrokerTrust.h"

#include "codec/receive/LoggedFrameReading.h"
#include "codec/secure/BrokerSeal.h"
#include "link/broker/OwnedFile.h"

#include <QFile>

namespace {

std::span<const std::uint8_t> bytesOf(const QByteArray& b)
{
    return {reinterpret_cast<const std::uint8_t*>(b.constData()), std::size_t(b.size())};
}

// The trust file's lines are short; anything longer is not one.
constexpr qint64 kMaxTrustFileBytes = 1024 * 1024;

}  // namespace

std::optional<BrokerTrust> BrokerTrust::fromFile(const QString& path, QString* error)
{
    const auto fail = [&](const QString& what) -> std::optional<BrokerTrust> {
        if (error)
            *error = what;
        return std::nullopt;
    };
    QFile file(path);
    if (const std::optional<QString> refusal =
            OwnedFile::open(file, QStringLiteral("trust"), 022, QStringLiteral("may change whom this console trusts"),
                            QStringLiteral("644")))
        return fail(*refusal);
    if (file.size() > kMaxTrustFileBytes)
        return fail(QStringLiteral("the trust file %1 is over 1 MiB: not a trust file").arg(path));
    BrokerTrust trust;
    const QList<QByteArray> lines = file.readAll().split('\n');
    for (qsizetype i = 0; i < lines.size(); ++i) {
        const QString line = QString::fromUtf8(lines[i]).trimmed();
        if (line.isEmpty() || line.startsWith(u'#'))
            continue;
        const QStringList fields = line.split(u' ', Qt::SkipEmptyParts);
        const QString where = QStringLiteral("the trust file %1 line %2: ").arg(path).arg(i + 1);
        if (fields.size() != 2)
            return fail(where + QStringLiteral("must be a station and its public key (64 hex digits), "
                                               "as `rcm stationkey` prints it"));
        if (!BrokerTopics::isTopicLevel(fields[0]))
            return fail(where + QStringLiteral("\"%1\" is not a station's name").arg(fields[0]));
        const std::optional<rcm::secure::StationPublicKey> key =
            rcm::secure::parseStationPublicKey(fields[1].toStdString());
        if (!key)
            return fail(where + QStringLiteral("the public key must be 64 hex digits"));
        trust.trustStation(fields[0], *key);
    }
    return trust;
}

void BrokerTrust::trustStation(const QString& station, const rcm::secure::StationPublicKey& key)
{
    m_stations.insert(station, std::make_shared<const rcm::secure::StationVerifier>(key));
}

void BrokerTrust::addLinkKey(const rcm::LogKey& key)
{
    m_sealKeys.insert(QString::fromStdString(key.fingerprint()), key.brokerKey());
}

void BrokerTrust::addLinkKey(std::shared_ptr<const rcm::LogKey> key)
{
    if (!key)
        return;
    addLinkKey(*key);
    m_linkKeys.append(std::move(key));
}

QStringList BrokerTrust::trustedStations() const
{
    QStringList names = m_stations.keys();
    names.sort();
    return names;
}

OpenedMessage BrokerTrust::open(const QString& topic, const QByteArray& payload, bool retained) const
{
    OpenedMessage m;
    m.topic = topic;
    m.retained = retained;
    m.where = BrokerTopics::parseTopic(topic);
    if (!m.where) {
        m.refuse(QStringLiteral("malformed: %1 is not a topic of the rcm schema").arg(topic));
        return m;
    }
    m.station = m.where->station;
    if (payload.isEmpty()) {
        // Clearing a retained message takes an empty one, which nobody can sign.
        m.trust = OpenedMessage::Trust::Unverified;
        m.cleared = true;
        return m;
    }
    const qsizetype limit = BrokerTopics::maxPayloadBytes(m.where->kind);
    if (payload.size() > limit) {
        m.refuse(QStringLiteral("too large: %1 bytes on %2, at most %3").arg(payload.size()).arg(topic).arg(limit));
        return m;
    }
    QString error;
    const std::optional<BrokerEnvelope> e = BrokerEnvelope::fromJson(payload, &error);
    if (!e) {
        m.refuse(QStringLiteral("malformed: %1: %2").arg(topic, error));
        return m;
    }
    if (e->station != m.where->station) {
        m.refuse(QStringLiteral("forged: a message naming %1 on %2's topic %3").arg(e->station, m.station, topic));
        return m;
    }
    m.seq = e->seq;
    m.will = e->will;
    m.willSeq = e->willSeq;
    m.sealed = e->sealed;
    m.keyFingerprint = e->keyFingerprint;

    const auto key = m_stations.constFind(m.station);
    if (key == m_stations.cend()) {
        // Signed or not, nothing here can check it.
        m.trust = OpenedMessage::Trust::Unverified;
    } else if (e->signature.isEmpty()) {
        m.refuse(
            QStringLiteral("unsigned: a message in the name of %1, whose key is trusted, on %2").arg(m.station, topic));
        return m;
    } else if (!(*key)->verify(bytesOf(e->signedBytes(topic)), bytesOf(e->signature))) {
        m.refuse(QStringLiteral("forged: %1's signature does not verify on %2").arg(m.station, topic));
        return m;
    } else {
        m.trust = OpenedMessage::Trust::Verified;
    }

    if (!e->sealed) {
        m.body = e->body;
        return m;
    }
    const auto sealKey = m_sealKeys.constFind(e->keyFingerprint);
    if (sealKey == m_sealKeys.cend()) {
        m.opened = false;
        return m;
    }
    const QByteArray associated = topic.toUtf8();
    const std::optional<std::vector<std::uint8_t>> plain =
        rcm::secure::openBrokerPayload(*sealKey, bytesOf(associated), bytesOf(e->body));
    if (!plain) {
        m.refuse(QStringLiteral("forged: %1's sealed message on %2 does not open under the key %3")
                     .arg(m.station, topic, e->keyFingerprint));
        return m;
    }
    m.body = QByteArray(reinterpret_cast<const char*>(plain->data()), qsizetype(plain->size()));
    return m;
}
