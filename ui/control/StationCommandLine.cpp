#include "ui/control/StationCommandLine.h"

#include "codec/message/TextFormat.h"
#include "link/broker/BrokerSettings.h"
#include "ui/control/StationControlWidget.h"
#include "ui/window/MainWindow.h"

#include <QFile>

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
               QStringLiteral("The certificate authority the broker's TLS certificate is checked against."),
               QStringLiteral("file"))
{
    parser.addOptions({m_station, m_broker, m_observe, m_user, m_passwordFile, m_caFile});
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
    for (const QCommandLineOption* o : {&m_user, &m_passwordFile, &m_caFile})
        if (m_parser.isSet(*o) && !m_parser.isSet(m_broker) && !m_parser.isSet(m_observe)) {
            *error = QStringLiteral("--%1 goes with --broker or --observe").arg(o->names().constFirst());
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
        QFile file(m_parser.value(m_passwordFile));
        if (!file.open(QIODevice::ReadOnly)) {
            *error = QStringLiteral("--broker-password-file %1: %2").arg(file.fileName(), file.errorString());
            return false;
        }
        settings.password = QString::fromUtf8(file.readLine()).trimmed();
    }
    window.joinBroker(settings, !m_parser.isSet(m_observe));
    if (m_parser.isSet(m_observe))
        window.observe(settings);
    return true;
}
