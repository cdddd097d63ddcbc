#pragma once

// The operator console: the command panels in the middle, the link, the
// next frame, the frame log and the flight plan in docks around them, the
// link's health in the status bar. It owns the one LinkController, whichever
// transport feeds it (serial, UDP, a rehearsal against uasim, a log replay),
// and hands it the command whenever the panels change it.

#include "codec/message/Airframe.h"
#include "link/framelog/FrameLog.h"
#include "link/session/LinkStatistics.h"
#include "ui/window/LinkSettings.h"

#include <QMainWindow>
#include <QPointer>

#include <memory>

namespace rcm::secure {
struct SecureEndpoint;
}

class CommandPreview;
class CommandState;
class FlightPlanUpload;
class FlightPlanWidget;
class FrameLogModel;
class FrameLogView;
class LinkController;
class LinkSettingsWidget;
class QActionGroup;
class QLabel;
class QMenu;
class QPushButton;
class QTabWidget;
class RehearsalLauncher;
class ReplayControls;
class ReplayLink;
class ReportedState;
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
    FrameLogModel* frameLog() const { return m_logModel; }
    FlightPlanWidget* flightPlan() const { return m_flightPlan; }
    StatusBarWidget* linkStatus() const { return m_status; }
    LinkSettingsWidget* linkSettings() const { return m_linkSettings; }
    // Statistics of the running link; the default ones when none runs.
    LinkStatistics statistics() const;
    bool isLinkRunning() const { return m_controller != nullptr; }
    QString sessionLogPath() const { return m_sessionLogPath; }

    // False, with the reason, when the airframe file cannot be used.
    bool loadAirframe(const QString& path, QString* error = nullptr);

public slots:
    void connectLink();                              // with the settings shown
    bool connectWith(const LinkSettings& settings);  // shows them, then connects
    void disconnectLink();
    // uasim on the loopback interface, and a UDP link to it; with the key
    // file of the link settings, both ends use it.
    void startRehearsal();
    void startRehearsalWith(const QString& uasimProgram);
    bool openFrameLog(const QString& path);
    void showPanel(int index);
    void setReplayPaused(bool paused);
    // 0.25 to 10 times the logged pace.
    void setReplaySpeed(double speed);

signals:
    // The replay reached the end of its log.
    void replayFinished();

protected:
    void closeEvent(QCloseEvent* event) override;

private:
    void buildPanels();
    void buildDocks();
    void buildMenus();
    void restoreSession(const Options& options);
    void saveSession() const;

    void startController(std::unique_ptr<class Link> link, bool datagram, const QString& description, bool keepLog,
                         std::shared_ptr<rcm::secure::SecureEndpoint> secure = nullptr);
    void stopController();
    // The console's end of the secure link for the key file at `keyPath`;
    // null with `ok` true for no key file, null with `ok` false (and the
    // reason shown) when the key file is refused.
    std::shared_ptr<rcm::secure::SecureEndpoint> openKey(const QString& keyPath, bool* ok);
    void commandChanged();
    void messageReceived(const ReceivedMessage& received);
    void frameSent(quint32 messageId);
    void setLinkControlsRunning(bool running);
    void updateTitle();
    void chooseFrameLog();
    void exportCsv();
    void chooseAirframe();
    void showError(const QString& message);

    CommandState* m_command;
    ReportedState* m_reported;
    FlightPlanUpload* m_upload;
    FrameLogModel* m_logModel;
    std::unique_ptr<LinkController> m_controller;
    QPointer<ReplayLink> m_replay;  // lives in the link thread; only queued calls
    RehearsalLauncher* m_rehearsal;
    VoiceChannel* m_voice = nullptr;  // voice beside the commands, when the operator turns it on

    QTabWidget* m_panels = nullptr;
    FrameLogView* m_logView = nullptr;
    CommandPreview* m_preview = nullptr;
    FlightPlanWidget* m_flightPlan = nullptr;
    LinkSettingsWidget* m_linkSettings = nullptr;
    ReplayControls* m_replayControls = nullptr;
    StatusBarWidget* m_status = nullptr;
    QPushButton* m_connectButton = nullptr;
    QPushButton* m_disconnectButton = nullptr;
    QPushButton* m_rehearsalButton = nullptr;
    QLabel* m_linkNote = nullptr;
    QMenu* m_viewMenu = nullptr;
    QActionGroup* m_airframeActions = nullptr;
    QAction* m_connectAction = nullptr;
    QAction* m_disconnectAction = nullptr;
    QAction* m_rehearsalAction = nullptr;
    QAction* m_pauseAction = nullptr;

    QString m_airframePath;
    QString m_sessionLogPath;
    QString m_linkDescription;
    QString m_frameLogDirectory;
    std::shared_ptr<rcm::secure::SecureEndpoint> m_rehearsalKey;  // the console's end, while uasim starts
    bool m_rehearsing = false;
    bool m_replayPaused = false;
};
