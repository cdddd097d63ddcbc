#include "ui/window/MainWindow.h"

#include "link/broker/BrokerObservation.h"
#include "link/airframe/AirframeLoader.h"
#include "link/eventlog/EventLog.h"
#include "ui/alerts/Confirmation.h"
#include "ui/alerts/ConsoleAlerts.h"
#include "ui/alerts/LinkAlarm.h"
#include "ui/alerts/LinkStateStrip.h"
#include "ui/alerts/ToneAlarmSound.h"
#include "ui/eventlog/EventLogView.h"
#include "ui/framelog/FrameLogCsvExport.h"
#include "ui/framelog/FrameLogModel.h"
#include "ui/framelog/FrameLogView.h"
#include "ui/control/StationControlWidget.h"
#include "ui/panels/CommandPreview.h"
#include "ui/panels/CommandState.h"
#include "ui/panels/ReportedState.h"
#include "ui/plan/FlightPlanUpload.h"
#include "ui/plan/FlightPlanWidget.h"
#include "ui/voice/PushToTalkWidget.h"
#include "ui/voice/VoiceChannel.h"
#include "ui/window/AirframeSelection.h"
#include "ui/window/BrokerConnection.h"
#include "ui/window/CommandBinding.h"
#include "ui/window/ConsoleDocks.h"
#include "ui/window/ConsoleMenus.h"
#include "ui/window/LinkPane.h"
#include "ui/window/LinkSettingsWidget.h"
#include "ui/window/PanelArea.h"
#include "ui/window/ReadOnlyPanels.h"
#include "ui/window/ReplayBinding.h"
#include "ui/window/SessionBinding.h"
#include "ui/window/StatusBarWidget.h"
#include "ui/window/WindowFit.h"

#include <QApplication>
#include <QCloseEvent>
#include <QDir>
#include <QDockWidget>
#include <QFileDialog>
#include <QFileInfo>
#include <QScreen>
#include <QSettings>
#include <QStatusBar>
#include <QTimer>

#include <algorithm>
#include <cstdio>

MainWindow::MainWindow(const Options& options, QWidget* parent)
    : QMainWindow(parent),
      m_command(new CommandState(rcm::Airframe::wellEquipped(), this)),
      m_readOnly(new ReadOnlyPanels(m_command, this)),
      // In a replay the reports age in the log's time: a pause or the log's
      // end is not a silence of the aircraft.
      m_reported(new ReportedState(m_command, this, [this] { return m_readOnly->now(); })),
      m_upload(new FlightPlanUpload(this)),
      m_logModel(new FrameLogModel(this)),
      m_session(new ConsoleSession(
          options.frameLogDirectory.isEmpty() ? FrameLog::defaultDirectory() : options.frameLogDirectory, this,
          options.clock)),
      m_alerts(new ConsoleAlerts(nullptr, this)),
      m_status(new StatusBarWidget),
      m_notices(m_status, m_alerts),
      m_airframes(new AirframeSelection(m_command, m_session, m_notices, this)),
      m_voice(new VoiceChannel(this)),
      m_panels(new PanelArea(m_command, m_reported, m_session, m_alerts->banners())),
      m_linkPane(new LinkPane(m_session->stationControl())),
      m_preview(new CommandPreview),
      m_logView(new FrameLogView(m_logModel)),
      m_flightPlan(new FlightPlanWidget(m_upload))
{
    LinkWorker::registerMetaTypes();
    // Events, and the alarm's silences, on the session's time.
    m_alerts->events()->setClock(m_session->clock());
    m_alerts->keepIn(m_session->frameLogDirectory());
    setWindowTitle(ConsoleMenus::title());
    setDockOptions(QMainWindow::AnimatedDocks | QMainWindow::AllowTabbedDocks);
    setCentralWidget(m_panels);
    m_readOnly->attach(m_reported, m_panels->tabs());
    // The flight plan a page of its own, where the map has the panels' room;
    // not a command panel, so a replay leaves it to the operator.
    m_panels->addPage(m_flightPlan, tr("Flight plan"));
    m_flightPlan->setProperty(ReadOnlyPanels::kKeepsInput, true);
    buildDocks();
    m_menus = new ConsoleMenus(this, {m_panels->tabs(), m_airframes, m_flightPlan, m_linkPane->settings()});
    bindMenus();
    // The link's figures fill the bar, so the bar's own message area would
    // have no room: its messages are shown among them.
    statusBar()->addPermanentWidget(m_status, 1);
    statusBar()->setSizeGripEnabled(true);

    connect(m_command, &CommandState::airframeChanged, this, [this] {
        m_reported->clear();
        updateTitle();
    });
    // Every link carries the voice beside the commands (when it is on) and
    // the flight plan upload; the uploader takes the section size of the
    // link: 199 bytes when keyed.
    m_session->setLinkWrapper([this](std::unique_ptr<Link> link, const rcm::secure::SecureEndpoint* key) {
        return m_voice->attach(std::move(link), key);
    });
    m_session->setOptionsFilter([this](LinkWorker::Options o) { return m_upload->linkOptions(std::move(o)); });
    m_commands = new CommandBinding({m_command, m_reported, m_session, m_preview, m_panels->holdBar(),
                                     m_linkPane->stationControl(), m_flightPlan, m_readOnly},
                                    m_notices, this);
    m_replay = new ReplayBinding(
        {m_session, m_logModel, m_logView, m_linkPane->replayControls(), m_status, m_panels->overview(), m_menus},
        m_notices, this);
    connect(m_replay, &ReplayBinding::finished, this, &MainWindow::replayFinished);
    m_binding = new SessionBinding({m_session, m_logModel, m_status, m_panels->overview(), m_reported, m_linkPane,
                                    m_preview, m_flightPlan, m_upload, m_readOnly, m_commands, m_replay},
                                   m_notices, this);
    connect(m_binding, &SessionBinding::changed, this, [this] {
        updateTitle();
        updateLinkControls();
    });
    m_broker = new BrokerConnection(
        m_session, m_notices, m_docks, [this](const QString& action) { return confirmEndingLink(action); }, this);
    // The fleet reads this link's keyed sessions on the broker too.
    connect(m_session, &ConsoleSession::linkStarted, m_broker, &BrokerConnection::updateTrust);

    resize(defaultSize());
    if (screen())
        move(screen()->availableGeometry().topLeft());
    m_defaultGiven = size();
    restoreSession(options);
    m_commands->commandChanged();
    m_linkPane->showNotConnected();
    updateLinkControls();
    updateTitle();
    // Said now, not first when the link is lost.
    m_alerts->checkSound(ToneAlarmSound::hasSoundCard());
}

MainWindow::~MainWindow()
{
    // The link first, and its thread joined: it calls into m_upload (the
    // BLOCK 2 hooks) until it ends, and m_upload, made before the session,
    // is deleted before it. stop() alone leaves the thread closing the link.
    m_session->stop();
    m_session->joinStoppedLinks();
    // Then the docks, whose views use the models made before them: a
    // floating dock is closed as it goes, and its views still ask their
    // models for columns and counts.
    qDeleteAll(findChildren<QDockWidget*>(Qt::FindDirectChildrenOnly));
}

template <typename Source>
void MainWindow::bindLinkRequests(Source* source)
{
    connect(source, &Source::connectRequested, this, &MainWindow::connectLink);
    connect(source, &Source::disconnectRequested, this, &MainWindow::requestDisconnect);
    connect(source, &Source::rehearsalRequested, this, &MainWindow::startRehearsal);
}

void MainWindow::buildDocks()
{
    bindLinkRequests(m_linkPane);
    connect(m_linkPane->settings(), &LinkSettingsWidget::changed, this, &MainWindow::updateLinkControls);
    connect(m_flightPlan, &FlightPlanWidget::message, this,
            [this](const QString& text) { m_notices.info(EventSource::Plan, text); });
    connect(m_flightPlan, &FlightPlanWidget::problem, this,
            [this](const QString& text) { m_alerts->error(EventSource::Plan, text); });
    // Not the banner, as for refused frames: a forger could send fifty a
    // second. At most a line a second, with the totals.
    connect(m_voice, &VoiceChannel::voiceIgnored, this, [this] {
        m_alerts->info(EventSource::Link, tr("The aircraft sends voice, set aside: voice is off in this console "
                                             "(\"Voice on the link\" in the Voice pane, then connect again)"));
    });
    connect(m_voice, &VoiceChannel::voiceRefused, this, [this](quint64 forged, quint64 replayed) {
        m_alerts->warning(EventSource::Link, tr("Voice refused, never played: %1 forged (no valid tag), %2 replayed "
                                                "(authentic but not new), since the link started")
                                                 .arg(forged)
                                                 .arg(replayed));
    });
    m_docks = new ConsoleDocks(
        this, {m_linkPane, new PushToTalkWidget(m_voice), m_logView, m_preview, m_alerts->eventView()});
    // A floating dock is a window of its own: it shows the link's state and
    // alarm too, and asks for attention with the main window when the link is lost.
    m_docks->addLinkStrips([this] { return m_alerts->newLinkStrip(); });
    connect(m_alerts->alarm(), &LinkAlarm::changed, this, [this] {
        const bool active = m_alerts->alarm()->isActive();
        if (active && !m_alarmShown)
            m_docks->requestAttention();
        else if (!m_alerts->alarm()->isSounding())
            m_docks->clearAttention();  // heard (silenced), or over
        m_alarmShown = active;
    });
    // A plan opened (gcs --plan, File > Open flight plan) is shown.
    connect(m_flightPlan, &FlightPlanWidget::planOpened, this,
            [this] { m_panels->showPanel(m_panels->tabs()->indexOf(m_flightPlan)); });
}

void MainWindow::bindMenus()
{
    bindLinkRequests(m_menus);
    connect(m_menus, &ConsoleMenus::openLogRequested, this, &MainWindow::chooseFrameLog);
    connect(m_menus, &ConsoleMenus::exportCsvRequested, this, &MainWindow::exportCsv);
    connect(m_menus, &ConsoleMenus::panelRequested, this, &MainWindow::showPanel);
    connect(m_menus, &ConsoleMenus::resetLayoutRequested, this, &MainWindow::resetLayout);
}

QTabWidget* MainWindow::panels() const
{
    return m_panels->tabs();
}

const ReplayControls* MainWindow::replayControls() const
{
    return m_linkPane->replayControls();
}

LinkSettingsWidget* MainWindow::linkSettings() const
{
    return m_linkPane->settings();
}

StationControlWidget* MainWindow::stationControl() const
{
    return m_linkPane->stationControl();
}

const BrokerObservation* MainWindow::observation() const
{
    return qobject_cast<const BrokerObservation*>(m_session->observation());
}

OverviewPage* MainWindow::overview() const
{
    return m_panels->overview();
}

CommandHoldBar* MainWindow::commandHold() const
{
    return m_panels->holdBar();
}

void MainWindow::fitToScreen()
{
    // Only the size given by default: a restored layout, a size asked for
    // (gcs --screenshot --size, a test) or one the operator dragged stays.
    if (!isMaximized() && !isFullScreen() && !m_layoutRestored && size() == m_defaultGiven)
        WindowFit::fitIntoScreen(*this);
}

void MainWindow::resetLayout()
{
    QSettings settings;
    settings.remove(QStringLiteral("window/geometry"));
    settings.remove(QStringLiteral("window/state"));
    showNormal();
    resize(defaultSize());
    if (screen())
        move(screen()->availableGeometry().topLeft());
    m_docks->place();
    // Again: the layout before place() may have held the window taller.
    resize(defaultSize());
}

void MainWindow::showEvent(QShowEvent* event)
{
    QMainWindow::showEvent(event);
    const bool first = !m_shown;
    m_shown = true;
    m_docks->placeOnFirstShow(m_layoutRestored);
    // The frame is known a moment after the first show (the window manager
    // sets it): then the window is made to fit inside the screen.
    if (first)
        QTimer::singleShot(300, this, &MainWindow::fitToScreen);
}

void MainWindow::restoreSession(const Options& options)
{
    QString airframe = options.airframePath;
    Theme::Kind theme = Theme::Kind::Day;
    if (options.restoreSettings) {
        QSettings settings;
        m_layoutRestored = restoreGeometry(settings.value(QStringLiteral("window/geometry")).toByteArray()) &&
                           restoreState(settings.value(QStringLiteral("window/state")).toByteArray());
        m_linkPane->settings()->setSettings(LinkSettings::load(settings));
        m_linkPane->stationControl()->setStationText(settings.value(QStringLiteral("control/station")).toString());
        m_flightPlan->setTileSettings(TileSettings::load(settings));
        theme = Theme::fromName(settings.value(QStringLiteral("theme")).toString()).value_or(Theme::Kind::Day);
        if (airframe.isEmpty())
            airframe = settings.value(QStringLiteral("airframe")).toString();
    }
    setTheme(theme);
    if (airframe.isEmpty())
        airframe = AirframeLoader::kDefaultPath;
    QString error;
    if (!loadAirframe(airframe, &error) && airframe != AirframeLoader::kDefaultPath) {
        m_notices.error(error);
        loadAirframe(AirframeLoader::kDefaultPath);
    }
}

void MainWindow::saveSession() const
{
    QSettings settings;
    settings.setValue(QStringLiteral("window/geometry"), saveGeometry());
    settings.setValue(QStringLiteral("window/state"), saveState());
    m_linkPane->settings()->settings().save(settings);
    settings.setValue(QStringLiteral("control/station"), m_linkPane->stationControl()->stationText());
    m_flightPlan->tiles()->settings().save(settings);
    settings.setValue(QStringLiteral("airframe"), m_airframes->path());
    settings.setValue(QStringLiteral("theme"), Theme::name(theme()));
}

Theme::Kind MainWindow::theme() const
{
    return m_menus->theme();
}

void MainWindow::setTheme(Theme::Kind kind)
{
    m_menus->setTheme(kind);
}

void MainWindow::closeEvent(QCloseEvent* event)
{
    if (!confirmEndingLink(tr("Quit"))) {
        event->ignore();
        return;
    }
    saveSession();
    m_session->stop();
    event->accept();
}

bool MainWindow::loadAirframe(const QString& path, QString* error)
{
    return m_airframes->load(path, error);
}

void MainWindow::requestAirframe(const QString& path)
{
    m_airframes->request(path);
}

bool MainWindow::confirmEndingLink(const QString& action)
{
    return !m_session->isLive() ||
           Confirmation::endingLink(ConsoleMenus::title(), action, m_session->description()).ask(this);
}

void MainWindow::connectLink()
{
    if (confirmEndingLink(m_linkPane->connectText()))
        connectWith(m_linkPane->settings()->settings());
}

void MainWindow::connectWith(const LinkSettings& settings)
{
    m_linkPane->settings()->setSettings(settings);
    m_session->connectWith(settings);
    updateLinkControls();
}

void MainWindow::requestDisconnect()
{
    // One click must not drop a live link (nor hang up a call that took a minute to set up).
    if (confirmEndingLink(m_linkPane->disconnectText()))
        disconnectLink();
}

void MainWindow::disconnectLink()
{
    m_session->stop();
    m_linkPane->showNotConnected();
    updateLinkControls();
}

void MainWindow::startRehearsal()
{
    if (confirmEndingLink(tr("Start rehearsal")))
        startRehearsalWith(RehearsalLauncher::defaultProgram());
}

void MainWindow::startRehearsalWith(const QString& uasimProgram)
{
    // uasim with voice when the console has it, saying back what it hears.
    m_session->rehearsalLauncher()->setVoice(m_voice->isEnabled());
    m_session->startRehearsal(m_command->airframe(), m_linkPane->settings()->settings().keyPath, uasimProgram);
    updateLinkControls();
}

void MainWindow::openFrameLog(const QString& path, const QString& keyPath)
{
    m_replay->open(path, keyPath);
    m_readOnly->announce(ReadOnlyPanels::replayNote());
    updateLinkControls();
}

void MainWindow::setReplayPaused(bool paused)
{
    m_replay->setPaused(paused);
}

void MainWindow::setReplaySpeed(double speed)
{
    m_replay->setSpeed(speed);
}

void MainWindow::joinBroker(const BrokerSettings& settings, bool publish)
{
    m_broker->join(settings, publish);
}

void MainWindow::observe(const BrokerSettings& settings)
{
    m_broker->observe(settings);
}

void MainWindow::observeRequested(const QString& aircraft)
{
    m_broker->observeRequested(aircraft);
}

void MainWindow::showPanel(int index)
{
    m_panels->showPanel(index);
}

void MainWindow::screenshotAndQuit(const QString& path, QSize size, int afterSeconds)
{
    resize(size);
    QTimer::singleShot(afterSeconds * 1000, this, [this, path] {
        const bool saved = grab().save(path);
        if (!saved)
            std::fprintf(stderr, "gcs: cannot save %s\n", qPrintable(path));
        QCoreApplication::exit(saved ? 0 : 1);
    });
}

void MainWindow::updateLinkControls()
{
    m_linkPane->update(*m_session);
    m_menus->update(*m_session);
}

void MainWindow::updateTitle()
{
    QString title =
        ConsoleMenus::title() + QStringLiteral(" \u2014 ") + QString::fromStdString(m_command->airframe().name);
    if (!m_session->description().isEmpty())
        title += QStringLiteral(" \u2014 ") + m_session->description();
    // The link's state in the title too: in the taskbar, and above a window
    // whose status bar is out of sight. "Connected", "Lost", "Replay"...
    if (m_session->isRunning() || m_session->observation())
        title += QStringLiteral(" \u2014 ") + m_status->stateName();
    setWindowTitle(title);
}

void MainWindow::chooseFrameLog()
{
    if (!confirmEndingLink(tr("Open log for replay")))
        return;
    const QString path = QFileDialog::getOpenFileName(this, tr("Replay a frame log"), m_session->frameLogDirectory(),
                                                      tr("Frame logs (*.pcapng);;All files (*)"));
    if (!path.isEmpty())
        openFrameLog(path);
}

void MainWindow::exportCsv()
{
    const QString source = m_logModel->logPath().isEmpty() ? m_session->sessionLogPath() : m_logModel->logPath();
    if (source.isEmpty()) {
        m_notices.error(tr("No frame log to export: connect, or open a log first"));
        return;
    }
    const QString target = QFileDialog::getSaveFileName(this, tr("Export the frame log as CSV"),
                                                        QFileInfo(source).completeBaseName() + QStringLiteral(".csv"),
                                                        tr("CSV files (*.csv)"));
    if (target.isEmpty())
        return;
    const QString shown = QDir::toNativeSeparators(target);
    FrameLogCsvExport* job = FrameLogCsvExport::start(source, target, m_session->logKey(), this);
    connect(job, &FrameLogCsvExport::finished, this, [this, shown](bool written, const QString& error) {
        if (written)
            m_notices.flash(tr("Exported %1").arg(shown));
        else
            m_notices.error(tr("CSV export failed: %1").arg(error));
    });
    m_notices.flash(tr("Exporting %1\u2026").arg(shown));
}
