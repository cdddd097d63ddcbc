#pragma once

// This console on an MQTT broker (docs/architecture.md, "Stations and the
// broker"; docs/security.md, "The broker"): every link it runs published,
// signed with this station's key; the Fleet dock listing every aircraft on
// the broker; an aircraft observed read only, as a ConsoleSession
// observation. Whom the fleet and the observations believe: the command
// line's trust, this station's own key, the running link's key.

#include "ui/window/ConsoleNotices.h"

#include <QObject>

#include <functional>
#include <memory>

class BrokerObservation;
class BrokerTrust;
class ConsoleDocks;
class ConsoleSession;
class FleetFeed;
class FleetModel;
class FleetView;
class MqttClient;
class SessionBroadcast;
struct BrokerSettings;

class BrokerConnection : public QObject {
    Q_OBJECT

public:
    // True to go on with an action that ends the live link (asked first).
    using ConfirmEndingLink = std::function<bool(const QString& action)>;

    BrokerConnection(ConsoleSession* session, const ConsoleNotices& notices, ConsoleDocks* docks,
                     ConfirmEndingLink confirm, QObject* parent = nullptr);
    ~BrokerConnection() override;

    // Once a run: the Fleet dock lists every aircraft on the broker, and
    // with `publish` every link this console runs is published there.
    void join(const BrokerSettings& settings, bool publish);
    // Ends the running link, without asking, and shows settings.aircraft
    // read only from the broker.
    void observe(const BrokerSettings& settings);
    // The Fleet dock's double-click: asks first while a link is live.
    void observeRequested(const QString& aircraft);
    // The running link's key changed: the fleet reads its keyed sessions too.
    void updateTrust();

    SessionBroadcast* broadcast() const { return m_broadcast; }
    FleetFeed* fleetFeed() const { return m_fleetFeed; }
    FleetView* fleetView() const { return m_fleetView; }

private:
    void showFleet(const BrokerSettings& settings);
    // The broker's own trouble: what waiting mends to the event log, what it
    // does not to the banner too, its return to the event log. Quiet while
    // an observation runs, whose own client says it.
    void followClient(const MqttClient* client, bool quietWhileObserving = false);
    void warnOfPlainPassword(const BrokerSettings& settings);

    ConsoleSession* m_session;
    ConsoleNotices m_notices;
    ConsoleDocks* m_docks;
    ConfirmEndingLink m_confirm;
    std::unique_ptr<BrokerSettings> m_broker;  // joined: where fleet and observations go
    std::shared_ptr<const BrokerTrust> m_trust;
    SessionBroadcast* m_broadcast = nullptr;
    MqttClient* m_fleetClient = nullptr;
    FleetFeed* m_fleetFeed = nullptr;
    FleetModel* m_fleetModel = nullptr;
    FleetView* m_fleetView = nullptr;
    bool m_announced = false;  // "connected, publishing" said once
};
