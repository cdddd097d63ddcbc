#include "link/broker/EnvelopeWriter.h"

#include "codec/secure/BrokerSeal.h"

#include <algorithm>
#include <utility>

namespace {

std::span<const std::uint8_t> bytesOf(const QByteArray& b)
{
    return {reinterpret_cast<const std::uint8_t*>(b.constData()), std::size_t(b.size())};
}

}  // namespace

EnvelopeWriter::EnvelopeWriter(QString station, std::shared_ptr<const rcm::secure::StationSigningKey> signingKey)
    : m_station(std::move(station)),
      m_signingKey(std::move(signingKey)),
      m_clock(std::make_shared<SystemClock>())
{
}

void EnvelopeWriter::setSealKey(const rcm::secure::SecretKey& brokerKey, const QString& fingerprint)
{
    m_sealKey = brokerKey;
    m_sealFingerprint = fingerprint;
}

void EnvelopeWriter::setClock(std::shared_ptr<const Clock> clock)
{
    m_clock = clock ? std::move(clock) : std::make_shared<SystemClock>();
}

qint64 EnvelopeWriter::nextSeq()
{
    // In whole milliseconds, as the numbers always went.
    m_lastSeq = std::max<qint64>(m_lastSeq + 1, m_clock->utcMicros() / 1000 * 1000);
    return m_lastSeq;
}

QByteArray EnvelopeWriter::wrap(const QString& topic, const QByteArray& body, bool will, qint64 willSeq)
{
    return wrapNumbered(topic, body, nextSeq(), will, willSeq);
}

QByteArray EnvelopeWriter::wrapNumbered(const QString& topic, const QByteArray& body, qint64 seq, bool will,
                                        qint64 willSeq) const
{
    BrokerEnvelope e;
    e.station = m_station;
    e.seq = seq;
    e.will = will;
    e.willSeq = willSeq;
    if (m_sealKey) {
        const QByteArray associated = topic.toUtf8();
        const std::vector<std::uint8_t> sealed =
            rcm::secure::sealBrokerPayload(*m_sealKey, bytesOf(associated), bytesOf(body));
        e.sealed = true;
        e.keyFingerprint = m_sealFingerprint;
        e.body = QByteArray(reinterpret_cast<const char*>(sealed.data()), qsizetype(sealed.size()));
    } else {
        e.body = body;
    }
    if (m_signingKey) {
        const rcm::secure::StationSignature signature = m_signingKey->sign(bytesOf(e.signedBytes(topic)));
        e.signature = QByteArray(reinterpret_cast<const char*>(signature.data()), qsizetype(signature.size()));
    }
    return e.toJson();
}
