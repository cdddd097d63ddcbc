#include "link/broker/SessionBroadcast.h"

#include "codec/message/TextFormat.h"
#include "codec/receive/LoggedFrameReading.h"
#include "link/broker/EnvelopeWriter.h"
#include "link/broker/MqttClient.h"
#include "link/broker/SessionPublisher.h"
#include "link/eventlog/EventLog.h"
#include "link/session/ConsoleSession.h"
#include "link/session/StationControl.h"

#include <QSysInfo>

namespace {

QString stationText(std::optional<rcm::StationId> station)
{
    return station ? QString::fromStdString(rcm::formatStation(*station)) : QString();
}

// BrokerTopics' roles: whom the aircraft names, whether or not this station took it up yet.
QString brokerRole(StationControl::Role role)
{
    switch (role) {
        case StationControl::Role::InControl:
        case StationControl::Role::Offered:
        case StationControl::Role::HandingOver:
            return QStringLiteral("control");
        case StationControl::Role::Backup:
            return QStringLiteral("backup");
        case StationControl::Role::Observing:
            return QStringLiteral("observing");
        case StationControl::Role::Unknown:
            break;
    }
    return QStringLiteral("unknown");
}

}  // namespace

SessionBroadcast::SessionBroadcast(ConsoleSession* session, const BrokerSettings& settings, QObject* parent)
    : QObject(parent), m_session(session), m_settings(settings), m_client(new MqttClient(settings, this, session->clock()))
{
    connect(m_client, &MqttClient::errorOccurred, this, &SessionBroadcast::errorOccurred);
    connect(m_client, &MqttClient::setupFailed, this, &SessionBroadcast::setupFailed);
    connect(m_client, &MqttClient::restored, this, [this](const QString& message) { emit restored(message); });
    connect(m_client, &MqttClient::refusedByBroker, this, &SessionBroadcast::refusedByBroker);
    connect(m_session, &ConsoleSession::linkStarted, this, &SessionBroadcast::linkStarted);
    connect(m_session, &ConsoleSession::linkStopped, this, &SessionBroadcast::linkStopped);
    StationControl* control = m_session->stationControl();
    connect(control, &StationControl::roleChanged, this, &SessionBroadcast::publishRole);
    connect(control, &StationControl::headerChanged, this, &SessionBroadcast::publishRole);
    m_client->start();
    if (const LinkController* running = m_session->controller())
        linkStarted(running);
}

SessionBroadcast::~SessionBroadcast()
{
    if (m_publisher)
        m_publisher->finish();
}

SessionPublisher* SessionBroadcast::publisher() const
{
    return m_publisher.data();
}

void SessionBroadcast::follow(const EventLog* events)
{
    connect(events, &EventLog::recorded, this, &SessionBroadcast::publishEvent);
}

QString SessionBroadcast::stationName() const
{
    const QString station = stationText(m_session->stationControl()->station());
    // A console with no station ID is still told apart from others on the broker.
    return station.isEmpty() ? QStringLiteral("gcs-%1").arg(QSysInfo::machineHostName()) : station;
}

void SessionBroadcast::linkStarted(const LinkController* controller)
{
    delete m_publisher;
    EnvelopeWriter envelopes(stationName(), m_settings.signingKey);
    // A keyed link: what goes on the broker is sealed for its key's holders.
    if (const std::shared_ptr<const rcm::LogKey> key = m_session->logKey())
        envelopes.setSealKey(key->brokerKey(), QString::fromStdString(key->fingerprint()));
    envelopes.setClock(controller->clock());
    m_publisher = new SessionPublisher(m_client, std::move(envelopes), controller, this, controller->clock());
    connect(m_publisher.data(), &SessionPublisher::stationReportChanged, this, &SessionBroadcast::stationReportChanged);
    m_publisher->setDescription(m_session->description());
    // Gone with the link: a publisher must not outlive the events it follows.
    connect(controller, &QObject::destroyed, m_publisher.data(), &QObject::deleteLater);
    publishRole();
}

void SessionBroadcast::linkStopped()
{
    if (m_publisher)
        m_publisher->setDescription(QString());
}

void SessionBroadcast::publishRole()
{
    if (!m_publisher)
        return;
    const StationControl* control = m_session->stationControl();
    m_publisher->setRole(brokerRole(control->role()), stationText(control->reportedControl()),
                         stationText(control->reportedBackup()));
}

void SessionBroadcast::publishEvent(const ConsoleEvent& event)
{
    if (m_publisher)
        m_publisher->publishEvent(eventSeverityName(event.severity),
                                  eventSourceName(event.source) + QStringLiteral(": ") + event.text);
}
