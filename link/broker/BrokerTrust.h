#pragma once

// Whom a console believes on a broker, and what it can read there: the
// public keys of the stations it trusts (a trust file, made of the lines
// `rcm stationkey` prints) and the link keys it holds, which open what a
// keyed session sealed. open() judges one message against them; it keeps no
// state, so it runs in the broker client's network thread, off the GUI
// thread, and a BrokerTrust shared between threads is never changed
// (std::shared_ptr<const BrokerTrust>).
//
// The trust file: one station a line, its name and its public key in 64 hex
// digits; blank lines and lines beginning with '#' are skipped:
//     # the stations of the northern fleet
//     GB_30226 3d4017c3e843895a92b70aa74d1b7ebc9c982ccf2ec4968cc0cd55f12af4660c
// It holds no secret, but whoever may change it decides whom the console
// believes: a file that group or others may write is refused.

#include "codec/secure/SecureCodec.h"
#include "codec/secure/StationSigningKey.h"
#include "link/broker/BrokerEnvelope.h"

#include <QHash>
#include <QList>
#include <QString>
#include <QStringList>

#include <memory>
#include <optional>

namespace rcm {
class LogKey;
}

class BrokerTrust {
public:
    // Nothing, with an error that names the file and the line, for a file
    // that cannot be read, is writable by others, or has a line that is not
    // "STATION HEX".
    static std::optional<BrokerTrust> fromFile(const QString& path, QString* error);

    // A station's key; replaces one trusted before for it.
    void trustStation(const QString& station, const rcm::secure::StationPublicKey& key);
    // What a keyed session sealed with this link key opens.
    void addLinkKey(const rcm::LogKey& key);
    // The same, and the key is kept: a reader deciphers the session's frames
    // with it (linkKeys()).
    void addLinkKey(std::shared_ptr<const rcm::LogKey> key);
    const QList<std::shared_ptr<const rcm::LogKey>>& linkKeys() const { return m_linkKeys; }

    bool trusts(const QString& station) const { return m_stations.contains(station); }
    QStringList trustedStations() const;
    bool canOpen(const QString& keyFingerprint) const { return m_sealKeys.contains(keyFingerprint); }

    // One message as the broker delivered it: its size against its kind's
    // limit, its envelope, its signature against the station's trusted key,
    // its seal against the link keys held. Not its number: that needs to
    // know what came before (SequenceCheck).
    OpenedMessage open(const QString& topic, const QByteArray& payload, bool retained) const;

private:
    // Shared between copies: a trust copied to add a link key keeps its keys.
    QHash<QString, std::shared_ptr<const rcm::secure::StationVerifier>> m_stations;
    QHash<QString, rcm::secure::SecretKey> m_sealKeys;  // by the link key's fingerprint: its broker key
    QList<std::shared_ptr<const rcm::LogKey>> m_linkKeys;
};
