#pragma once

// One station's side of BrokerEnvelope: numbers each message, seals it when
// the session is keyed, signs it when the station has a signing key. A
// console without a signing key publishes unsigned envelopes, which readers
// show as unverified and never as control.

#include "codec/secure/SecureCodec.h"
#include "codec/secure/StationSigningKey.h"
#include "link/broker/BrokerEnvelope.h"
#include "link/clock/Clock.h"

#include <QString>

#include <memory>
#include <optional>

class EnvelopeWriter {
public:
    explicit EnvelopeWriter(QString station, std::shared_ptr<const rcm::secure::StationSigningKey> signingKey = {});

    QString station() const { return m_station; }
    bool signs() const { return m_signingKey != nullptr; }
    bool seals() const { return m_sealKey.has_value(); }
    QString sealKeyFingerprint() const { return m_sealFingerprint; }

    // A keyed session: every body is sealed under the link key's broker key
    // (LogKey::brokerKey()), named by the link key's fingerprint.
    void setSealKey(const rcm::secure::SecretKey& brokerKey, const QString& fingerprint);
    // What the numbers follow: the session's clock (null: the SystemClock).
    void setClock(std::shared_ptr<const Clock> clock);

    // The next number: more than the last, and no less than the clock's now,
    // so that a console started again goes on above what it said before.
    qint64 nextSeq();
    // The envelope's JSON of `body` on `topic`, with the next number.
    QByteArray wrap(const QString& topic, const QByteArray& body, bool will = false, qint64 willSeq = 0);
    // The same with a number taken before (nextSeq()), for a will made now
    // and announced in the reports that follow.
    QByteArray wrapNumbered(const QString& topic, const QByteArray& body, qint64 seq, bool will, qint64 willSeq) const;

private:
    QString m_station;
    std::shared_ptr<const rcm::secure::StationSigningKey> m_signingKey;
    std::optional<rcm::secure::SecretKey> m_sealKey;
    QString m_sealFingerprint;
    std::shared_ptr<const Clock> m_clock;
    qint64 m_lastSeq = 0;
};
