#include "ui/window/BrokerConnection.h"

#include "codec/receive/LoggedFrameReading.h"
#include "codec/secure/StationSigningKey.h"
#include "link/broker/BrokerObservation.h"
#include "link/broker/BrokerSettings.h"
#include "link/broker/BrokerTrust.h"
#include "link/broker/FleetFeed.h"
#include "link/broker/MqttClient.h"
#include "link/broker/SessionBroadcast.h"
#include "link/session/ConsoleSession.h"
#include "ui/alerts/ConsoleAlerts.h"
#include "ui/alerts/RefusalDigest.h"
#include "ui/fleet/FleetModel.h"
#include "ui/fleet/FleetView.h"
#include "ui/window/ConsoleDocks.h"

BrokerConnection::BrokerConnection(ConsoleSession* session, const ConsoleNotices& notices, ConsoleDocks* docks,
                                   ConfirmEndingLink confirm, QObject* parent)
    : QObject(parent), m_session(session), m_notices(notices), m_docks(docks), m_confirm(std::move(confirm))
{
}

BrokerConnection::~BrokerConnection() = default;

void BrokerConnection::join(const BrokerSettings& settings, bool publish)
{
    if (m_broker)
        return;  // once a run: the command line's broker
    m_broker = std::make_unique<BrokerSettings>(settings);
    warnOfPlainPassword(settings);
    ConsoleAlerts* alerts = m_notices.alerts();
    if (publish) {
        m_broadcast = new SessionBroadcast(m_session, settings, this);
        m_broadcast->follow(alerts->events());
        followClient(m_broadcast->client());
        const QString station = m_broadcast->stationName();
        alerts->info(EventSource::Link,
                     settings.signingKey
                         ? tr("Broker %1: connecting, to publish every link as %2, signed").arg(settings.url(), station)
                         : tr("Broker %1: connecting, to publish every link as %2, unsigned (no --broker-key): "
                              "observers will show it as unverified")
                               .arg(settings.url(), station));
        // Said once: a reconnection is said by its return.
        connect(m_broadcast->client(), &MqttClient::connected, this, [this, alerts, url = settings.url()] {
            if (std::exchange(m_announced, true))
                return;
            alerts->info(EventSource::Link, tr("Broker %1: connected, publishing every link").arg(url));
        });
    }
    // The fleet has a connection of its own: it reads everything, the publisher only writes.
    BrokerSettings fleetSettings = settings;
    fleetSettings.clientId.clear();
    m_fleetClient = new MqttClient(fleetSettings, this, m_session->clock());
    if (!publish)
        followClient(m_fleetClient, true);
    m_fleetFeed = new FleetFeed(m_fleetClient, this, m_session->clock());
    updateTrust();
    showFleet(settings);
    m_fleetClient->start();
}

void BrokerConnection::showFleet(const BrokerSettings& settings)
{
    m_fleetModel = new FleetModel(this);
    connect(m_fleetFeed, &FleetFeed::aircraftUpdated, m_fleetModel, &FleetModel::update);
    connect(m_fleetFeed, &FleetFeed::aircraftRemoved, m_fleetModel, &FleetModel::remove);
    m_fleetView = new FleetView(m_fleetModel);
    m_fleetView->setBroker(settings.url());
    connect(m_fleetFeed, &FleetFeed::messageRefused, this, [this](const QString& reason) {
        m_notices.alerts()->refusals()->refusedBrokerMessage(reason);
        m_fleetView->setRefusedMessages(m_fleetFeed->refusedPayloads());
    });
    // The broker's state, apart from any link's: this console's own row
    // keeps its link while the broker is away.
    const auto reachable = [this](bool yes) {
        m_fleetView->setBrokerConnected(yes);
        m_fleetFeed->setBrokerReachable(yes);
    };
    connect(m_fleetClient, &MqttClient::connected, this, [reachable] { reachable(true); });
    connect(m_fleetClient, &MqttClient::disconnected, this, [reachable] { reachable(false); });
    connect(m_fleetClient, &MqttClient::errorOccurred, this, [reachable] { reachable(false); });
    connect(m_fleetClient, &MqttClient::setupFailed, this, [reachable] { reachable(false); });
    if (m_broadcast)
        connect(m_broadcast, &SessionBroadcast::stationReportChanged, m_fleetFeed, &FleetFeed::setLocalStation);
    connect(m_fleetView, &FleetView::observeRequested, this, &BrokerConnection::observeRequested);
    m_docks->addFleet(m_fleetView);
}

void BrokerConnection::followClient(const MqttClient* client, bool quietWhileObserving)
{
    // An observation's own client says the same of the same broker.
    const auto heard = [this, quietWhileObserving] {
        return !(quietWhileObserving && m_session->kind() == ConsoleSession::Kind::Observation);
    };
    ConsoleAlerts* alerts = m_notices.alerts();
    const auto say = [alerts, heard](void (ConsoleAlerts::*severity)(EventSource, const QString&)) {
        return [alerts, heard, severity](const QString& text) {
            if (heard())
                (alerts->*severity)(EventSource::Link, text);
        };
    };
    connect(client, &MqttClient::errorOccurred, this, say(&ConsoleAlerts::warning));
    connect(client, &MqttClient::setupFailed, this, say(&ConsoleAlerts::error));
    connect(client, &MqttClient::refusedByBroker, this, say(&ConsoleAlerts::error));
    connect(client, &MqttClient::restored, this, say(&ConsoleAlerts::info));
}

void BrokerConnection::updateTrust()
{
    if (!m_broker)
        return;
    auto trust = std::make_shared<BrokerTrust>(m_broker->trust ? *m_broker->trust : BrokerTrust());
    // This station believes itself, and reads its own keyed sessions.
    if (m_broadcast && m_broker->signingKey)
        trust->trustStation(m_broadcast->stationName(), m_broker->signingKey->publicKey());
    if (std::shared_ptr<const rcm::LogKey> key = m_session->logKey())
        trust->addLinkKey(std::move(key));
    m_trust = trust;
    if (m_fleetFeed)
        m_fleetFeed->setTrust(m_trust);
}

void BrokerConnection::observeRequested(const QString& aircraft)
{
    if (!m_broker || !m_confirm(tr("Observe %1").arg(aircraft)))
        return;
    BrokerSettings settings = *m_broker;
    settings.aircraft = aircraft;
    settings.clientId.clear();
    settings.trust = m_trust;
    observe(settings);
}

void BrokerConnection::observe(const BrokerSettings& settings)
{
    auto observation = std::make_unique<BrokerObservation>(settings, nullptr, m_session->clock());
    // Refused messages are counted as refused frames are; what is worth
    // knowing (frames missed, stations unverified or sealed) is a warning.
    ConsoleAlerts* alerts = m_notices.alerts();
    connect(observation.get(), &BrokerObservation::messageRefused, alerts->refusals(),
            &RefusalDigest::refusedBrokerMessage);
    connect(observation.get(), &BrokerObservation::messageRefused, this,
            [this](const QString& reason) { m_notices.flash(tr("A broker message was refused: %1").arg(reason)); });
    connect(observation.get(), &BrokerObservation::warning, alerts,
            [alerts](const QString& text) { alerts->warning(EventSource::Link, text); });
    const QString aircraft = observation->aircraft();
    // A keyed session's frames are the enciphered bytes: with the aircraft's
    // key the log view and the panels read them as the station's own would.
    m_session->observe(std::move(observation), tr("Observing %1 on %2").arg(aircraft, settings.url()),
                       settings.trust ? settings.trust->linkKeys() : QList<std::shared_ptr<const rcm::LogKey>>());
    const QStringList trusted = settings.trust ? settings.trust->trustedStations() : QStringList();
    if (trusted.isEmpty())
        alerts->warning(EventSource::Link, tr("No station's key is trusted (--broker-trust): nothing %1's stations "
                                              "publish can be verified, and nothing unverified is shown")
                                               .arg(aircraft));
    else
        alerts->info(EventSource::Link, tr("Trusting the keys of %1").arg(trusted.join(QStringLiteral(", "))));
    if (!m_broker)
        warnOfPlainPassword(settings);
}

void BrokerConnection::warnOfPlainPassword(const BrokerSettings& settings)
{
    if (!settings.tls && !settings.password.isEmpty())
        m_notices.alerts()->warning(EventSource::Link,
                                    tr("The broker password goes to %1 over plain mqtt://, unencrypted: anyone on "
                                       "the path reads it; use mqtts://")
                                        .arg(settings.hostAndPort()));
}
