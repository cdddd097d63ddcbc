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
#include "ui/window/ConsoleNotices.h"
#include "ui/window/Theme.h"
#include "ui/window/WindowFit.h"

#include <QMainWindow>

#include <memory>
#include <optional>
#include <vector>

class AirframeSelection;
class BrokerConnection;
class BrokerObservation;
class CommandBinding;
class CommandHoldBar;
class CommandPreview;
class CommandState;
class ConsoleAlerts;
class ConsoleDocks;
class ConsoleMenus;
class FlightPlanUpload;
class FlightPlanWidget;
class FrameLogModel;
class FrameLogView;
class LinkPane;
class LinkSettingsWidget;
class OverviewPage;
class PanelArea;
class QTabWidget;
class ReadOnlyPanels;
class ReplayBinding;
class ReplayControls;
class ReportedState;
class SessionBinding;
class StationControlWidget;
class StatusBarWidget;
class VoiceChannel;
struct BrokerSettings;

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
        // The time the session's links run on (ConsoleSession): null is the
        // system's; tests pass a VirtualClock.
        std::shared_ptr<Clock> clock;
    };

    explicit MainWindow(const Options& options, QWidget* parent = nullptr);
    MainWindow() : MainWindow(Options()) {}
    ~MainWindow() override;

    CommandState* command() const { return m_command; }
    ReportedState* reported() const { return m_reported; }
    QTabWidget* panels() const;
    FrameLogModel* frameLog() const { return m_logModel; }
    const ReplayControls* replayControls() const;
    FlightPlanWidget* flightPlan() const { return m_flightPlan; }
    StatusBarWidget* linkStatus() const { return m_status; }
    LinkSettingsWidget* linkSettings() const;
    StationControlWidget* stationControl() const;
    // The observation running (observe()), or null.
    const BrokerObservation* observation() const;
    ConsoleSession* session() const { return m_session; }
    ConsoleDocks* docks() const { return m_docks; }
    // The event log, its dock, the error banner and the link-loss alarm.
    ConsoleAlerts* alerts() const { return m_alerts; }
    OverviewPage* overview() const;
    // The band above the panels while the command is held back.
    CommandHoldBar* commandHold() const;
    // Statistics of the running link; the default ones when none runs.
    LinkStatistics statistics() const { return m_session->statistics(); }
    bool isLinkRunning() const { return m_session->isRunning(); }
    QString sessionLogPath() const { return m_session->sessionLogPath(); }

    Theme::Kind theme() const;
    // The first start's size: the screen's available area less the window
    // manager's frame, up to 1600x1000.
    QSize defaultSize() const { return WindowFit::defaultSize(*this); }
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
    // Ends the running link, without asking (observeRequested() asks). The
    // session runs it as its Observation kind.
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
    void buildDocks();
    // The Link pane's and the Link menu's requests (both name them alike) to the same slots.
    template <typename Source>
    void bindLinkRequests(Source* source);
    void bindMenus();
    void restoreSession(const Options& options);
    void saveSession() const;
    // From the session's state: what can be started or stopped now.
    void updateLinkControls();
    // True to go on with `action`, which would end the live link: asked
    // first while one is live (or being started), Cancel the default.
    bool confirmEndingLink(const QString& action);
    void updateTitle();
    // Shrinks and moves the window into the screen's available area when
    // its frame (known once shown) makes it overhang.
    void fitToScreen();
    void chooseFrameLog();
    void exportCsv();

    CommandState* m_command;
    ReadOnlyPanels* m_readOnly;
    ReportedState* m_reported;
    FlightPlanUpload* m_upload;
    FrameLogModel* m_logModel;
    ConsoleSession* m_session;
    ConsoleAlerts* m_alerts;
    StatusBarWidget* m_status;
    ConsoleNotices m_notices;
    AirframeSelection* m_airframes;
    VoiceChannel* m_voice;  // voice beside the commands, when the operator turns it on
    PanelArea* m_panels;
    LinkPane* m_linkPane;
    CommandPreview* m_preview;
    FrameLogView* m_logView;
    FlightPlanWidget* m_flightPlan;
    ConsoleDocks* m_docks = nullptr;
    ConsoleMenus* m_menus = nullptr;
    CommandBinding* m_commands = nullptr;
    ReplayBinding* m_replay = nullptr;
    SessionBinding* m_binding = nullptr;
    BrokerConnection* m_broker = nullptr;
    bool m_layoutRestored = false;
    bool m_shown = false;
    QSize m_defaultGiven;  // the size the window was given at construction, defaultSize() or its least
    bool m_alarmShown = false;  // the link-loss alarm, as last seen: attention is asked as it goes off
};
