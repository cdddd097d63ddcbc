#pragma once

// The operator console: the command panels in the middle, the link, the
// next frame, the frame log and the flight plan in docks around them, the
// link's health in the status bar. It binds them to a ConsoleSession, which
// owns the link whichever transport feeds it (serial, UDP, a rehearsal
// against uasim, a log replay), and hands it the command whenever the panels
// change it.

#include "codec/message/Airframe.h"
#include "link/eventlog/ConsoleEvent.h"
#include "link/framelog/FrameLog.h"
#include "link/session/ConsoleSession.h"
#include "link/session/LinkSettings.h"
#include "link/session/LinkStatistics.h"
#include "ui/framelog/FrameLogModel.h"
#include "ui/window/Theme.h"

#include <QMainWindow>

#include <memory>
#include <optional>
#include <vector>

class CommandHoldBar;
class CommandJournal;
class CommandPreview;
class ConsoleAlerts;
class OverviewPage;
class CommandState;
class FlightPlanUpload;
class FlightPlanWidget;
class FrameLogModel;
class FrameLogView;
class LinkSettingsWidget;
class QActionGroup;
class QDockWidget;
class QLabel;
class QMenu;
class QPushButton;
class QTabWidget;
class ReplayControls;
class ReplayLink;
class ReportedState;
class StationControlWidget;
class BrokerObservation;
class BrokerTrust;
class FleetFeed;
class FleetModel;
class FleetView;
class LinkEvents;
class MqttClient;
class SessionBroadcast;
struct BrokerSettings;
class StatusBarWidget;
class VoiceChannel;
struct ReceivedMessage;

class MainWindow : public QMainWindow {
    Q_OBJECT

public:
    struct Options {
        // Window layout, link settings and airframe from the last session;
        // off for screenshots and tests, which want the defaults.
        bool restoreSettings = true;
        // An airframe file (or resource) instead of the remembered one.
        QString airframePath;
        // Where live sessions keep their frame log; FrameLog::defaultDirectory() when empty.
        QString frameLogDirectory;
    };

    explicit MainWindow(const Options& options, QWidget* parent = nullptr);
    MainWindow() : MainWindow(Options()) {}
    ~MainWindow() override;

    CommandState* command() const { return m_command; }
    ReportedState* reported() const { return m_reported; }
    QTabWidget* panels() const { return m_panels; }
    FrameLogModel* frameLog() const { return m_logModel; }
    const ReplayControls* replayControls() const { return m_replayControls; }
    FlightPlanWidget* flightPlan() const { return m_flightPlan; }
    StatusBarWidget* linkStatus() const { return m_status; }
    LinkSettingsWidget* linkSettings() const { return m_linkSettings; }
    StationControlWidget* stationControl() const { return m_stationControl; }
    FleetView* fleetView() const { return m_fleetView; }
    SessionBroadcast* broadcast() const { return m_broadcast; }
    BrokerObservation* observation() const { return m_observation; }
    FleetFeed* fleetFeed() const { return m_fleetFeed; }
    ConsoleSession* session() const { return m_session; }
    // The event log, its dock, the error banner and the link-loss alarm.
    ConsoleAlerts* alerts() const { return m_alerts; }
    OverviewPage* overview() const { return m_overview; }
    // The band above the panels while the command is held back.
    CommandHoldBar* commandHold() const { return m_holdBar; }
    // Statistics of the running link; the default ones when none runs.
    LinkStatistics statistics() const { return m_session->statistics(); }
    bool isLinkRunning() const { return m_session->isRunning(); }
    QString sessionLogPath() const { return m_session->sessionLogPath(); }

    Theme::Kind theme() const;
    // The first start's size: the screen's available area, up to 1600x1000.
    QSize defaultSize() const;
    // Applies `kind` to the whole application and ticks View > Night theme to match.
    void setTheme(Theme::Kind kind);

    // False, with the reason, when the airframe file cannot be used. On a
    // live link the command is held until the operator resumes; the units
    // the new airframe lacks are said in the event log.
    bool loadAirframe(const QString& path, QString* error = nullptr);
    // File > Airframe: asks first while a link is live, then loadAirframe().
    void requestAirframe(const QString& path);

public slots:
    // Connect, Start rehearsal, Open log for replay and Quit, as the
    // operator gives them, ask first while a link is live
    // (ConsoleSession::isLive()); the calls named ...With and
    // openFrameLog() do not, for scripts and tests.
    // The actions below start their link in the background (ConsoleSession):
    // isLinkRunning() once it runs, the reason in the status bar if it does not.
    void connectLink();                              // with the settings shown
    void connectWith(const LinkSettings& settings);  // shows them, then connects
    void disconnectLink();
    // The Disconnect (Hang up) button and menu item: asks first when the link is live.
    void requestDisconnect();
    // uasim on the loopback interface, and a UDP link to it; with the key
    // file of the link settings, both ends use it.
    void startRehearsal();
    void startRehearsalWith(const QString& uasimProgram);
    // `keyPath`: the key of a keyed session's log, to decipher it with.
    void openFrameLog(const QString& path, const QString& keyPath = QString());
    void showPanel(int index);
    // gcs --screenshot: at `size`, after the first pass of the event loop
    // (docks and layouts settled) or once the link ran `afterSeconds`, saves
    // a picture of the window to `path` and quits, 0 when it was saved.
    void screenshotAndQuit(const QString& path, QSize size, int afterSeconds);
    // View > Reset layout: every dock in its first place, the window at
    // defaultSize(), and the saved layout forgotten.
    void resetLayout();
    void setReplayPaused(bool paused);
    // 0.25 to 10 times the logged pace.
    void setReplaySpeed(double speed);
    // Joins the broker: the Fleet dock lists every aircraft on it, and with
    // `publish` every link this console runs is published there, signed with
    // settings.signingKey (docs/architecture.md, "Stations and the broker";
    // docs/security.md, "The broker").
    void joinBroker(const BrokerSettings& settings, bool publish);
    // Shows settings.aircraft read-only from the broker: its frames, status
    // and events as the station publishing it logged them; nothing is sent.
    // Ends the running link, without asking (observeRequested() asks).
    void observe(const BrokerSettings& settings);
    // The Fleet dock's double-click: asks first while a link is live.
    void observeRequested(const QString& aircraft);

signals:
    // The replay reached the end of its log.
    void replayFinished();

protected:
    void closeEvent(QCloseEvent* event) override;
    void showEvent(QShowEvent* event) override;

private:
    void buildPanels();
    void buildDocks();
    void placeDocks();
    // Control between stations: its alarms and events to the log, its header to the panels.
    void bindStationControl();
    // The command held back and resumed, adopted from the aircraft's report,
    // and every change of it in the event log.
    void bindCommandHold();
    // The Airframe menu's tick on the airframe loaded.
    void checkAirframeAction();
    // What a link or an observation says, to the status bar, overview, alerts and log view.
    void bindLinkEvents(const LinkEvents* events, bool logRows);
    void endObservation();
    // The broker's own trouble: what waiting mends to the event log, what it
    // does not to the banner too, its return to the event log. Quiet while
    // an observation runs, whose own client says it.
    void followBrokerClient(const MqttClient* client, bool quietWhileObserving = false);
    // Whom the fleet and the observations believe: the command line's trust,
    // this station's own key, the running link's key.
    void updateBrokerTrust();
    void buildMenus();
    void restoreSession(const Options& options);
    void saveSession() const;

    // Binds the widgets to the link the session just started, and unbinds them.
    void linkStarted(const LinkController* controller);
    void linkStopped();
    void replayIndexed(const QString& path);
    // A replay's panels show what its log commanded, read only; the
    // console's own command comes back when it ends.
    void beginReplay(const ReplayLink* replay);
    void endReplay();
    void replayedFrame(qint64 utcMicros, const std::optional<rcm::Message>& commanded);
    void actionFailed(const QString& reason);
    void commandChanged();
    void messageReceived(const ReceivedMessage& received);
    void frameSent(quint32 messageId);
    // From the session's state: what can be started or stopped now.
    void updateLinkControls();
    void showNotConnected();
    // True to go on with `action`, which would end the live link: asked
    // first while one is live (or being started), Cancel the default.
    bool confirmEndingLink(const QString& action);
    void updateTitle();
    void chooseFrameLog();
    void exportCsv();
    void chooseAirframe();
    // On the error banner and in the event log (and, briefly, the status bar).
    void showError(const QString& message, EventSource source = EventSource::Console);

    CommandState* m_command;
    ReportedState* m_reported;
    FlightPlanUpload* m_upload;
    FrameLogModel* m_logModel;
    // The rows of the log being opened for replay, filled in the pool.
    std::shared_ptr<std::shared_ptr<FrameLogModel::PreparedRows>> m_preparedRows;
    ConsoleSession* m_session;
    ConsoleAlerts* m_alerts;
    VoiceChannel* m_voice = nullptr;  // voice beside the commands, when the operator turns it on

    QTabWidget* m_panels = nullptr;
    OverviewPage* m_overview = nullptr;
    FrameLogView* m_logView = nullptr;
    CommandPreview* m_preview = nullptr;
    CommandHoldBar* m_holdBar = nullptr;
    CommandJournal* m_journal = nullptr;
    FlightPlanWidget* m_flightPlan = nullptr;
    LinkSettingsWidget* m_linkSettings = nullptr;
    ReplayControls* m_replayControls = nullptr;
    StatusBarWidget* m_status = nullptr;
    QPushButton* m_connectButton = nullptr;
    QPushButton* m_disconnectButton = nullptr;
    QPushButton* m_rehearsalButton = nullptr;
    QLabel* m_linkNote = nullptr;
    StationControlWidget* m_stationControl = nullptr;
    SessionBroadcast* m_broadcast = nullptr;
    MqttClient* m_fleetClient = nullptr;
    FleetFeed* m_fleetFeed = nullptr;
    std::shared_ptr<const BrokerTrust> m_brokerTrust;
    bool m_brokerAnnounced = false;  // "connected, publishing" said once
    FleetModel* m_fleetModel = nullptr;
    FleetView* m_fleetView = nullptr;
    BrokerObservation* m_observation = nullptr;
    std::unique_ptr<BrokerSettings> m_broker;  // joined: where fleet and observations go
    QMenu* m_viewMenu = nullptr;
    QActionGroup* m_airframeActions = nullptr;
    QAction* m_connectAction = nullptr;
    QAction* m_disconnectAction = nullptr;
    QAction* m_rehearsalAction = nullptr;
    QAction* m_pauseAction = nullptr;
    QAction* m_nightAction = nullptr;

    QString m_airframePath;
    std::vector<QDockWidget*> m_docks;  // in placeDocks()' order
    bool m_layoutRestored = false;
    bool m_layoutPlaced = false;
    bool m_planInFront = false;  // a plan was opened: the flight plan, not the frame log, in front
    // While a replay plays: the console's own command, kept aside, and the
    // log's time, which the reports' age is counted in.
    std::optional<rcm::Message> m_ownCommand;
    qint64 m_replayMicros = 0;
    QObject* m_replayReadOnly = nullptr;  // an application event filter
    QLabel* m_replayNote = nullptr;
    QString m_lastLinkError;  // the link's last error, not logged again when its status repeats it
    bool m_modemRegistered = false;  // the satellite phone's registration, as last said
};
