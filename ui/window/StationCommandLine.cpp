#include "ui/window/StationCommandLine.h"

#include "codec/message/TextFormat.h"
#include "codec/receive/LoggedFrameReading.h"
#include "codec/secure/StationSigningKey.h"
#include "link/broker/BrokerSettings.h"
#include "link/broker/BrokerTrust.h"
#include "ui/control/StationControlWidget.h"
#include "ui/window/MainWindow.h"

StationCommandLine::StationCommandLine(QCommandLineParser& parser)
    : m_parser(parser),
      m_station(QStringLiteral("station"),
                QStringLiteral("This console's station ID, e.g. GB_30226: it follows which station the aircraft "
                               "says is in control, and can hand over or take control (docs/protocol.md section 10)."),
                QStringLiteral("id")),
      m_broker(QStringLiteral("broker"),
               QStringLiteral("Publish every link on an MQTT broker, mqtt://HOST[:PORT] or mqtts:// for TLS, and "
                              "list its aircraft in the Fleet dock."),
               QStringLiteral("url")),
      m_observe(QStringLiteral("observe"),
                QStringLiteral("Watch an aircraft read-only through a broker: mqtt://HOST[:PORT]/AIRCRAFT. Nothing is "
                               "sent to the aircraft."),
                QStringLiteral("url")),
      m_user(QStringLiteral("broker-user"), QStringLiteral("The broker's user name."), QStringLiteral("name")),
      m_passwordFile(QStringLiteral("broker-password-file"),
                     QStringLiteral("A file holding the broker's password (its first line)."), QStringLiteral("file")),
      m_caFile(QStringLiteral("broker-cafile"),
               QStringLiteral("The certificate authority the broker's TLS certificate is checked against (default, "
                              "for mqtts://: the system's CA certificates in /etc/ssl/certs)."),
               QStringLiteral("file")),
      m_signingKey(QStringLiteral("broker-key"),
                   QStringLiteral("This station's signing key (rcm stationkey ID FILE; mode 0600): everything it "
                                  "publishes on the broker is signed, so that observers can verify it. Needs "
                                  "--station."),
                   QStringLiteral("file")),
      m_trust(QStringLiteral("broker-trust"),
              QStringLiteral("The stations whose broker messages this console believes: lines of STATION PUBLICKEY "
                             "as rcm stationkey prints them. Others are shown as unverified, never in control."),
              QStringLiteral("file"))
{
    parser.addOptions({m_station, m_broker, m_observe, m_user, m_passwordFile, m_caFile, m_signingKey, m_trust});
}

bool StationCommandLine::check(QString* error) const
{
    if (m_parser.isSet(m_station)) {
        std::string reason;
        if (!rcm::parseStation(m_parser.value(m_station).toStdString(), &reason)) {
            *error = QStringLiteral("--station: %1").arg(QString::fromStdString(reason));
            return false;
        }
    }
    if (m_parser.isSet(m_broker) && m_parser.isSet(m_observe)) {
        *error = QStringLiteral("give --broker or --observe, not both: an observer publishes nothing");
        return false;
    }
    for (const QCommandLineOption* o : {&m_broker, &m_observe}) {
        QString reason;
        if (m_parser.isSet(*o) && !BrokerSettings::fromUrl(m_parser.value(*o), &reason)) {
            *error = QStringLiteral("--%1: %2").arg(o->names().constFirst(), reason);
            return false;
        }
    }
    if (m_parser.isSet(m_observe) && BrokerSettings::fromUrl(m_parser.value(m_observe))->aircraft.isEmpty()) {
        *error = QStringLiteral("--observe: name the aircraft, mqtt://HOST:PORT/AIRCRAFT");
        return false;
    }
    for (const QCommandLineOption* o : {&m_user, &m_passwordFile, &m_caFile, &m_trust})
        if (m_parser.isSet(*o) && !m_parser.isSet(m_broker) && !m_parser.isSet(m_observe)) {
            *error = QStringLiteral("--%1 goes with --broker or --observe").arg(o->names().constFirst());
            return false;
        }
    if (m_parser.isSet(m_signingKey) && !m_parser.isSet(m_broker)) {
        *error = QStringLiteral("--broker-key goes with --broker: an observer publishes nothing");
        return false;
    }
    if (m_parser.isSet(m_signingKey) && !m_parser.isSet(m_station)) {
        *error = QStringLiteral("--broker-key needs --station: the key signs in the station's name");
        return false;
    }
    return true;
}

bool StationCommandLine::apply(MainWindow& window, QString* error) const
{
    if (m_parser.isSet(m_station))
        window.stationControl()->setStationText(m_parser.value(m_station));
    const QCommandLineOption& url = m_parser.isSet(m_observe) ? m_observe : m_broker;
    if (!m_parser.isSet(url))
        return true;
    BrokerSettings settings = *BrokerSettings::fromUrl(m_parser.value(url));
    if (m_parser.isSet(m_user))
        settings.user = m_parser.value(m_user);
    if (m_parser.isSet(m_caFile)) {
        settings.tls = true;
        settings.caFile = m_parser.value(m_caFile);
    }
    if (m_parser.isSet(m_passwordFile)) {
        QString reason;
        const std::optional<QString> password =
            BrokerSettings::readPasswordFile(m_parser.value(m_passwordFile), &reason);
        if (!password) {
            *error = QStringLiteral("--broker-password-file: %1").arg(reason);
            return false;
        }
        settings.password = *password;
    }
    if (m_parser.isSet(m_signingKey)) {
        std::string reason;
        std::optional<rcm::secure::StationSigningKey> key =
            rcm::secure::StationSigningKey::fromFile(m_parser.value(m_signingKey).toStdString(), reason);
        if (!key) {
            *error = QStringLiteral("--broker-key: %1").arg(QString::fromStdString(reason));
            return false;
        }
        settings.signingKey = std::make_shared<const rcm::secure::StationSigningKey>(std::move(*key));
    }
    auto trust = std::make_shared<BrokerTrust>();
    if (m_parser.isSet(m_trust)) {
        QString reason;
        std::optional<BrokerTrust> read = BrokerTrust::fromFile(m_parser.value(m_trust), &reason);
        if (!read) {
            *error = QStringLiteral("--broker-trust: %1").arg(reason);
            return false;
        }
        *trust = std::move(*read);
    }
    // An observer opens keyed sessions with the aircraft's keys it is given.
    if (m_parser.isSet(m_observe))
        for (const QString& path : m_parser.values(QStringLiteral("key"))) {
            std::string reason;
            std::shared_ptr<const rcm::LogKey> key = rcm::LogKey::open(path.toStdString(), reason);
            if (!key) {
                *error = QStringLiteral("--key: %1").arg(QString::fromStdString(reason));
                return false;
            }
            trust->addLinkKey(std::move(key));
        }
    settings.trust = trust;
    window.joinBroker(settings, !m_parser.isSet(m_observe));
    if (m_parser.isSet(m_observe))
        window.observe(settings);
    return true;
}
