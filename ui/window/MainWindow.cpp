#include "ui/window/MainWindow.h"

#include "ui/alerts/Confirmation.h"

#include "codec/message/MessageDecoder.h"
#include "link/framelog/FrameLogCsv.h"
#include "link/replay/ReplayLink.h"
#include "ui/alerts/Confirmation.h"
#include "ui/alerts/ConsoleAlerts.h"
#include "codec/message/CommandChanges.h"
#include "codec/message/TextFormat.h"
#include "ui/control/CommandHoldBar.h"
#include "ui/control/StationControlWidget.h"
#include "ui/panels/CommandJournal.h"
#include "ui/panels/ItemText.h"
#include "ui/alerts/RefusalDigest.h"
#include "codec/receive/LoggedFrameReading.h"
#include "codec/secure/StationSigningKey.h"
#include "link/broker/BrokerObservation.h"
#include "link/broker/BrokerTrust.h"
#include "link/broker/FleetFeed.h"
#include "link/broker/MqttClient.h"
#include "link/broker/SessionBroadcast.h"
#include "ui/fleet/FleetModel.h"
#include "ui/fleet/FleetView.h"
#include "ui/eventlog/EventLogView.h"
#include "ui/overview/OverviewPage.h"
#include "link/airframe/AirframeLoader.h"
#include "ui/panels/CameraPanel.h"
#include "ui/panels/CommandGate.h"
#include "ui/panels/CommandPreview.h"
#include "ui/panels/CommandState.h"
#include "ui/panels/EnginePanel.h"
#include "ui/panels/FlapsPanel.h"
#include "ui/plan/FlightPlanUpload.h"
#include "ui/plan/FlightPlanWidget.h"
#include "ui/framelog/FrameLogModel.h"
#include "ui/framelog/FrameLogView.h"
#include "ui/panels/FuelDumpPanel.h"
#include "ui/panels/GearPanel.h"
#include "ui/panels/HeaderPanel.h"
#include "ui/panels/LightsPanel.h"
#include "ui/window/LinkSettingsWidget.h"
#include "ui/voice/PushToTalkWidget.h"
#include "ui/panels/RadioPanel.h"
#include "ui/framelog/ReplayControls.h"
#include "ui/panels/ReportedState.h"
#include "ui/rehearsal/RehearsalDialog.h"
#include "ui/window/StatusBarWidget.h"
#include "ui/voice/VoiceChannel.h"

#include <QAction>
#include <QActionGroup>
#include <QApplication>
#include <QCloseEvent>
#include <QDateTime>
#include <QDir>
#include <QDockWidget>
#include <QFileDialog>
#include <QFileInfo>
#include <QGroupBox>
#include <QLabel>
#include <QMenuBar>
#include <QMessageBox>
#include <QPushButton>
#include <QSaveFile>
#include <QScrollArea>
#include <QSettings>
#include <QStatusBar>
#include <QScreen>
#include <QScrollBar>
#include <QTabBar>
#include <QTabWidget>
#include <QThread>
#include <QVBoxLayout>

#include <algorithm>
#include <cstdio>
#include <memory>

namespace {

// Every panel at its natural height, top aligned, in a scroll area, so a
// small screen scrolls rather than squeezing the controls and a large one
// does not spread them apart.
QScrollArea* scrolled(QWidget* panel)
{
    auto* page = new QWidget;
    auto* layout = new QVBoxLayout(page);
    layout->setContentsMargins(4, 8, 4, 4);
    layout->addWidget(panel);
    layout->addStretch(1);
    auto* area = new QScrollArea;
    area->setWidget(page);
    area->setWidgetResizable(true);
    area->setFrameShape(QFrame::NoFrame);
    return area;
}

QDockWidget* dock(const QString& title, const QString& name, QWidget* content, QMainWindow* window)
{
    auto* d = new QDockWidget(title, window);
    d->setObjectName(name);  // for saveState()
    // The title as a heading, so the areas of the window read at a glance;
    // the content keeps the normal font.
    QFont body = d->font();
    body.setBold(false);  // explicitly, or the content would inherit the heading's weight
    content->setFont(body);
    QFont heading = d->font();
    heading.setBold(true);
    d->setFont(heading);
    // The content paints its own background, so that a change inside it (a
    // count, the log scrolling) repaints the content alone: the dock's title
    // bar asks the style for its two buttons' icons on every paint.
    content->setAutoFillBackground(true);
    d->setWidget(content);
    d->setFeatures(QDockWidget::DockWidgetMovable | QDockWidget::DockWidgetFloatable | QDockWidget::DockWidgetClosable);
    return d;
}

const QString kTitle = QStringLiteral("RCM ground control station");

// Beside the panels' tabs while a log replays.
QString replayNoteText()
{
    return MainWindow::tr("Replay: the log's commands, read only");
}

// Makes the widgets inside `area` read only while it is installed on the
// application: clicks and keys never reach them, so that a replay's panels
// show the log's command and cannot be edited. Tabs and scroll bars still
// move, to look around.
class ReadOnlyArea : public QObject {
public:
    ReadOnlyArea(QWidget* area, QObject* parent) : QObject(parent), m_area(area) {}

protected:
    bool eventFilter(QObject* watched, QEvent* event) override
    {
        switch (event->type()) {
            case QEvent::MouseButtonPress:
            case QEvent::MouseButtonRelease:
            case QEvent::MouseButtonDblClick:
            case QEvent::KeyPress:
            case QEvent::KeyRelease:
                break;
            default:
                return false;
        }
        auto* widget = qobject_cast<QWidget*>(watched);
        if (!widget || !m_area->isAncestorOf(widget) || qobject_cast<QTabBar*>(widget) ||
            qobject_cast<QScrollBar*>(widget))
            return false;
        return true;
    }

private:
    QWidget* m_area;
};

}  // namespace

MainWindow::MainWindow(const Options& options, QWidget* parent)
    : QMainWindow(parent),
      m_command(new CommandState(rcm::Airframe::wellEquipped(), this)),
      // In a replay the reports age in the log's time: a pause or the log's
      // end is not a silence of the aircraft.
      m_reported(new ReportedState(m_command, this,
                                   [this] {
                                       return m_ownCommand ? std::chrono::steady_clock::time_point(
                                                                 std::chrono::microseconds(m_replayMicros))
                                                           : std::chrono::steady_clock::now();
                                   })),
      m_upload(new FlightPlanUpload(this)),
      m_logModel(new FrameLogModel(this)),
      m_session(new ConsoleSession(options.frameLogDirectory.isEmpty() ? FrameLog::defaultDirectory()
                                                                       : options.frameLogDirectory,
                                   this)),
      m_alerts(new ConsoleAlerts(nullptr, this))
{
    LinkWorker::registerMetaTypes();
    m_alerts->keepIn(m_session->frameLogDirectory());
    setWindowTitle(kTitle);
    setDockOptions(QMainWindow::AnimatedDocks | QMainWindow::AllowTabbedDocks);
    buildPanels();
    buildDocks();
    buildMenus();

    m_status = new StatusBarWidget;
    statusBar()->addPermanentWidget(m_status, 1);
    statusBar()->setSizeGripEnabled(true);

    connect(m_command, &CommandState::changed, this, &MainWindow::commandChanged);
    connect(m_command, &CommandState::rejected, this,
            [this](const QString& reason) { statusBar()->showMessage(tr("Not commanded: %1").arg(reason), 8000); });
    connect(CommandGate::of(m_command), &CommandGate::notSent, this,
            [this](const QString& text) { statusBar()->showMessage(text, 8000); });
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
    connect(m_session, &ConsoleSession::linkStarted, this, &MainWindow::linkStarted);
    connect(m_session, &ConsoleSession::linkStopped, this, &MainWindow::linkStopped);
    connect(m_session, &ConsoleSession::replayIndexed, this, &MainWindow::replayIndexed);
    connect(m_session, &ConsoleSession::failed, this, &MainWindow::actionFailed);
    connect(m_session, &ConsoleSession::warning, this,
            [this](const QString& message) { showError(message, EventSource::Link); });
    bindStationControl();
    bindCommandHold();
    connect(m_session, &ConsoleSession::starting, m_linkNote, &QLabel::setText);
    connect(m_session, &ConsoleSession::starting, this,
            [this](const QString& what) { m_alerts->info(EventSource::Link, what); });

    resize(defaultSize());
    restoreSession(options);
    commandChanged();
    showNotConnected();
    updateLinkControls();
    updateTitle();
}

MainWindow::~MainWindow()
{
    // The link first: its thread calls into m_upload until it ends.
    m_session->stop();
}

void MainWindow::buildPanels()
{
    m_panels = new QTabWidget;
    m_panels->setObjectName(QStringLiteral("panels"));
    m_panels->setDocumentMode(true);
    m_panels->setUsesScrollButtons(true);
    // Alt+1 .. Alt+8 in the View menu bring each up; the tabs themselves
    // carry no mnemonic, which would make those shortcuts ambiguous.
    const struct {
        QWidget* panel;
        QString title;
    } panels[] = {
        {m_overview = new OverviewPage(m_command, m_reported), tr("Overview")},
        {new HeaderPanel(m_command, m_reported), tr("Header")},
        {new EnginePanel(m_command, m_reported), tr("Engines")},
        {new FlapsPanel(m_command, m_reported), tr("Flaps")},
        {new GearPanel(m_command, m_reported), tr("Landing gear")},
        {new LightsPanel(m_command, m_reported), tr("Lights")},
        {new FuelDumpPanel(m_command, m_reported), tr("Fuel dump")},
        {new RadioPanel(m_command, m_reported), tr("Radios")},
        {new CameraPanel(m_command, m_reported), tr("Cameras")},
    };
    for (const auto& p : panels) {
        // The overview fits itself to the width and scrolls its own cards.
        const int index = m_panels->addTab(p.panel == m_overview ? p.panel : scrolled(p.panel), p.title);
        m_panels->setTabToolTip(index, tr("%1 (Alt+%2)").arg(p.title).arg(index + 1));
    }
    m_replayNote = new QLabel(replayNoteText());
    m_replayNote->setContentsMargins(8, 0, 8, 0);
    m_replayNote->hide();
    m_panels->setCornerWidget(m_replayNote, Qt::TopRightCorner);
    // The link-loss alarm and the errors above the panels, where the operator is looking.
    auto* centre = new QWidget;
    auto* centreLayout = new QVBoxLayout(centre);
    centreLayout->setContentsMargins(0, 0, 0, 0);
    centreLayout->setSpacing(0);
    centreLayout->addWidget(m_alerts->banners());
    m_holdBar = new CommandHoldBar(m_session, m_command);
    centreLayout->addWidget(m_holdBar);
    centreLayout->addWidget(m_panels, 1);
    setCentralWidget(centre);
}

void MainWindow::buildDocks()
{
    // Link: where to, and the buttons that start and stop it.
    auto* linkBox = new QWidget;
    auto* linkLayout = new QVBoxLayout(linkBox);
    linkLayout->setContentsMargins(8, 8, 8, 8);
    m_linkSettings = new LinkSettingsWidget;
    linkLayout->addWidget(m_linkSettings);
    m_connectButton = new QPushButton(tr("Connect"));
    m_connectButton->setToolTip(tr("Open the link and start sending the command once a second (Ctrl+K)"));
    m_disconnectButton = new QPushButton(tr("Disconnect"));
    m_disconnectButton->setToolTip(tr("Stop sending and close the link (Ctrl+Shift+K)"));
    // Buttons that start or end a link never hold the focus, so that a
    // stray Space or Enter cannot press one (after Connect the focus would
    // move on to Start rehearsal); their shortcuts and the mouse remain.
    for (QPushButton* b : {m_connectButton, m_disconnectButton})
        b->setFocusPolicy(Qt::NoFocus);
    auto* buttons = new QHBoxLayout;
    buttons->addWidget(m_connectButton);
    buttons->addWidget(m_disconnectButton);
    linkLayout->addLayout(buttons);
    m_rehearsalButton = new QPushButton(tr("Start rehearsal"));
    m_rehearsalButton->setToolTip(
        tr("Start the simulated aircraft (uasim) on this computer and connect to it "
           "(Ctrl+R)"));
    m_rehearsalButton->setFocusPolicy(Qt::NoFocus);
    linkLayout->addWidget(m_rehearsalButton);
    m_stationControl = new StationControlWidget(m_session->stationControl());
    linkLayout->addWidget(m_stationControl);
    m_linkNote = new QLabel;
    m_linkNote->setWordWrap(true);
    m_linkNote->setTextInteractionFlags(Qt::TextSelectableByMouse);
    linkLayout->addWidget(m_linkNote);
    m_replayControls = new ReplayControls;
    m_replayControls->hide();
    linkLayout->addWidget(m_replayControls);
    linkLayout->addStretch(1);
    connect(m_connectButton, &QPushButton::clicked, this, &MainWindow::connectLink);
    connect(m_disconnectButton, &QPushButton::clicked, this, &MainWindow::requestDisconnect);
    connect(m_linkSettings, &LinkSettingsWidget::changed, this, &MainWindow::updateLinkControls);
    connect(m_rehearsalButton, &QPushButton::clicked, this, &MainWindow::startRehearsal);

    connect(m_replayControls, &ReplayControls::pauseRequested, this, &MainWindow::setReplayPaused);
    connect(m_replayControls, &ReplayControls::speedRequested, this, &MainWindow::setReplaySpeed);
    connect(m_replayControls, &ReplayControls::seekRequested, this,
            [this](qint64 utc) { m_session->seekReplay(utc); });

    m_preview = new CommandPreview;
    m_logView = new FrameLogView(m_logModel);
    m_flightPlan = new FlightPlanWidget(m_upload);
    connect(m_flightPlan, &FlightPlanWidget::message, this, [this](const QString& text) {
        statusBar()->showMessage(text, 8000);
        m_alerts->info(EventSource::Plan, text);
    });
    connect(m_flightPlan, &FlightPlanWidget::problem, this,
            [this](const QString& text) { m_alerts->error(EventSource::Plan, text); });

    QDockWidget* link = dock(tr("Link"), QStringLiteral("linkDock"), linkBox, this);
    QDockWidget* preview = dock(tr("Next frame"), QStringLiteral("previewDock"), m_preview, this);
    QDockWidget* log = dock(tr("Frame log"), QStringLiteral("frameLogDock"), m_logView, this);
    QDockWidget* plan = dock(tr("Flight plan"), QStringLiteral("flightPlanDock"), m_flightPlan, this);
    m_voice = new VoiceChannel(this);
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
    QDockWidget* voice = dock(tr("Voice"), QStringLiteral("voiceDock"), new PushToTalkWidget(m_voice), this);
    QDockWidget* events = dock(tr("Events"), QStringLiteral("eventsDock"), m_alerts->eventView(), this);
    for (QDockWidget* d : {link, voice, log, plan, preview, events})
        m_docks.push_back(d);
    // A plan opened (gcs --plan, File > Open flight plan) is shown.
    connect(m_flightPlan, &FlightPlanWidget::planOpened, this, [this, plan] {
        m_planInFront = true;
        plan->show();
        plan->raise();
    });
    placeDocks();
}

void MainWindow::placeDocks()
{
    QDockWidget* const link = m_docks[0];
    QDockWidget* const voice = m_docks[1];
    QDockWidget* const log = m_docks[2];
    QDockWidget* const plan = m_docks[3];
    QDockWidget* const preview = m_docks[4];
    QDockWidget* const events = m_docks[5];
    for (QDockWidget* d : m_docks) {
        d->setFloating(false);
        d->show();
    }
    // The link and the voice down the left, full height, so that neither is
    // squeezed; the panels take the rest of the width, so that their tabs
    // all show at 1366 pixels; the frame log and the events share the bottom.
    setCorner(Qt::TopLeftCorner, Qt::LeftDockWidgetArea);
    setCorner(Qt::BottomLeftCorner, Qt::LeftDockWidgetArea);
    setCorner(Qt::TopRightCorner, Qt::RightDockWidgetArea);
    setCorner(Qt::BottomRightCorner, Qt::BottomDockWidgetArea);
    addDockWidget(Qt::LeftDockWidgetArea, link);
    splitDockWidget(link, voice, Qt::Vertical);
    addDockWidget(Qt::BottomDockWidgetArea, log);
    splitDockWidget(log, preview, Qt::Horizontal);
    tabifyDockWidget(log, plan);
    // The events in front beside the frame log; the next frame behind them.
    tabifyDockWidget(preview, events);
    (m_planInFront ? plan : log)->raise();
    events->raise();
    // In proportion to the window: the panels keep the larger part of the
    // height, the frame log enough for a dozen rows.
    const QSize area = size();
    resizeDocks({link}, {std::clamp(area.width() / 5, 250, 320)}, Qt::Horizontal);
    resizeDocks({log, preview}, {area.width() * 3 / 5, area.width() * 2 / 5}, Qt::Horizontal);
    resizeDocks({log}, {area.height() * 2 / 5}, Qt::Vertical);
}

QSize MainWindow::defaultSize() const
{
    // Most of the screen, up to what the console can use.
    const QRect screen = this->screen() ? this->screen()->availableGeometry() : QRect(0, 0, 1366, 768);
    return QSize(std::min(screen.width(), 1600), std::min(screen.height(), 1000));
}

void MainWindow::resetLayout()
{
    QSettings settings;
    settings.remove(QStringLiteral("window/geometry"));
    settings.remove(QStringLiteral("window/state"));
    showNormal();
    resize(defaultSize());
    placeDocks();
}

void MainWindow::showEvent(QShowEvent* event)
{
    QMainWindow::showEvent(event);
    // The first time at the window's real size, unless the last session's layout was restored.
    if (!m_layoutPlaced && !m_layoutRestored)
        placeDocks();
    m_layoutPlaced = true;
}

void MainWindow::buildMenus()
{
    QMenu* file = menuBar()->addMenu(tr("&File"));
    QAction* open = file->addAction(tr("&Open frame log for replay\u2026"), this, &MainWindow::chooseFrameLog);
    open->setShortcut(QKeySequence::Open);
    QAction* csv = file->addAction(tr("&Export frame log as CSV\u2026"), this, &MainWindow::exportCsv);
    csv->setShortcut(QKeySequence(tr("Ctrl+E")));
    file->addSeparator();
    QAction* plan = file->addAction(tr("Open flight &plan\u2026"), m_flightPlan, &FlightPlanWidget::openPlan);
    plan->setShortcut(QKeySequence(tr("Ctrl+Shift+O")));
    QMenu* airframes = file->addMenu(tr("&Airframe"));
    m_airframeActions = new QActionGroup(this);
    for (const QString& path : AirframeLoader::builtIn()) {
        const auto airframe = AirframeLoader::load(path);
        QAction* a = airframes->addAction(airframe ? QString::fromStdString(airframe->name) : path);
        a->setCheckable(true);
        a->setData(path);
        m_airframeActions->addAction(a);
        connect(a, &QAction::triggered, this, [this, path] { requestAirframe(path); });
    }
    airframes->addSeparator();
    airframes->addAction(tr("From a &file\u2026"), this, &MainWindow::chooseAirframe);
    file->addSeparator();
    file->addAction(tr("&Rehearse scenario\u2026"), this, [this] { RehearsalDialog::chooseAndRun(this); });
    QAction* quit = file->addAction(tr("&Quit"), this, &QWidget::close);
    quit->setShortcut(QKeySequence::Quit);

    QMenu* linkMenu = menuBar()->addMenu(tr("&Link"));
    m_connectAction = linkMenu->addAction(tr("&Connect"), this, &MainWindow::connectLink);
    m_connectAction->setShortcut(QKeySequence(tr("Ctrl+K")));
    m_disconnectAction = linkMenu->addAction(tr("&Disconnect"), this, &MainWindow::requestDisconnect);
    m_disconnectAction->setShortcut(QKeySequence(tr("Ctrl+Shift+K")));
    m_rehearsalAction = linkMenu->addAction(tr("Start &rehearsal with uasim"), this, &MainWindow::startRehearsal);
    m_rehearsalAction->setShortcut(QKeySequence(tr("Ctrl+R")));
    linkMenu->addSeparator();
    m_pauseAction =
        linkMenu->addAction(tr("&Pause or resume replay"), this, [this] { setReplayPaused(!m_session->isReplayPaused()); });
    m_pauseAction->setShortcut(QKeySequence(tr("Ctrl+P")));
    m_pauseAction->setEnabled(false);
    linkMenu->addAction(tr("Refresh serial ports"), m_linkSettings, &LinkSettingsWidget::refreshPorts);

    m_viewMenu = menuBar()->addMenu(tr("&View"));
    for (int i = 0; i < m_panels->count(); ++i) {
        const QString name = m_panels->tabText(i);
        QAction* a = m_viewMenu->addAction(name, this, [this, i] { showPanel(i); });
        a->setShortcut(QKeySequence(Qt::ALT | Qt::Key(Qt::Key_1 + i)));
        a->setToolTip(tr("Show the %1 panel").arg(name));
    }
    m_viewMenu->addSeparator();
    int key = 0;
    for (QDockWidget* d : findChildren<QDockWidget*>()) {
        QAction* toggle = d->toggleViewAction();
        toggle->setShortcut(QKeySequence(Qt::CTRL | Qt::Key(Qt::Key_1 + key++)));
        m_viewMenu->addAction(toggle);
    }

    m_viewMenu->addSeparator();
    QAction* reset = m_viewMenu->addAction(tr("&Reset layout"), this, &MainWindow::resetLayout);
    reset->setToolTip(tr("Every pane back in its first place, the window at its first size"));
    m_nightAction = m_viewMenu->addAction(tr("&Night theme"));
    m_nightAction->setCheckable(true);
    m_nightAction->setToolTip(tr("Light text on a dark window, for a dim room or a night operation"));
    connect(m_nightAction, &QAction::toggled, this,
            [](bool night) { Theme::apply(*qApp, night ? Theme::Kind::Night : Theme::Kind::Day); });

    QMenu* help = menuBar()->addMenu(tr("&Help"));
    help->addAction(tr("&About"), this, [this] {
        QMessageBox::about(this, kTitle,
                           tr("<p><b>%1</b></p><p>Commands an unmanned aircraft with the Remote Control Message: "
                              "a 600-byte frame once a second over a serial modem, or a 510-byte UDP datagram."
                              "</p>")
                               .arg(kTitle));
    });
}

void MainWindow::restoreSession(const Options& options)
{
    QString airframe = options.airframePath;
    Theme::Kind theme = Theme::Kind::Day;
    if (options.restoreSettings) {
        QSettings settings;
        m_layoutRestored = restoreGeometry(settings.value(QStringLiteral("window/geometry")).toByteArray()) &&
                           restoreState(settings.value(QStringLiteral("window/state")).toByteArray());
        m_linkSettings->setSettings(LinkSettings::load(settings));
        m_stationControl->setStationText(settings.value(QStringLiteral("control/station")).toString());
        TileSettings tiles;
        tiles.mbtilesPath = settings.value(QStringLiteral("map/mbtiles")).toString();
        tiles.urlTemplate = settings.value(QStringLiteral("map/url")).toString();
        tiles.attribution = settings.value(QStringLiteral("map/attribution")).toString();
        m_flightPlan->setTileSettings(tiles);
        theme = Theme::fromName(settings.value(QStringLiteral("theme")).toString()).value_or(Theme::Kind::Day);
        if (airframe.isEmpty())
            airframe = settings.value(QStringLiteral("airframe")).toString();
    }
    setTheme(theme);
    if (airframe.isEmpty())
        airframe = AirframeLoader::kDefaultPath;
    QString error;
    if (!loadAirframe(airframe, &error) && airframe != AirframeLoader::kDefaultPath) {
        showError(error);
        loadAirframe(AirframeLoader::kDefaultPath);
    }
}

void MainWindow::saveSession() const
{
    QSettings settings;
    settings.setValue(QStringLiteral("window/geometry"), saveGeometry());
    settings.setValue(QStringLiteral("window/state"), saveState());
    m_linkSettings->settings().save(settings);
    settings.setValue(QStringLiteral("control/station"), m_stationControl->stationText());
    const TileSettings& tiles = m_flightPlan->tiles()->settings();
    settings.setValue(QStringLiteral("map/mbtiles"), tiles.mbtilesPath);
    settings.setValue(QStringLiteral("map/url"), tiles.urlTemplate);
    settings.setValue(QStringLiteral("map/attribution"), tiles.attribution);
    settings.setValue(QStringLiteral("airframe"), m_airframePath);
    settings.setValue(QStringLiteral("theme"), Theme::name(theme()));
}

Theme::Kind MainWindow::theme() const
{
    return m_nightAction->isChecked() ? Theme::Kind::Night : Theme::Kind::Day;
}

void MainWindow::setTheme(Theme::Kind kind)
{
    m_nightAction->setChecked(kind == Theme::Kind::Night);
    // The action applies a change; the first call applies the day theme too.
    Theme::apply(*qApp, kind);
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
    QString reason;
    const std::optional<rcm::Airframe> airframe = AirframeLoader::load(path, &reason);
    if (!airframe) {
        if (error)
            *error = reason;
        else
            showError(reason);
        return false;
    }
    const QString was = QString::fromStdString(m_command->airframe().name);
    const bool live = m_session->isLive();
    // Another airframe on a live link: nothing goes out until the aircraft's
    // report is in the panels and the operator resumes.
    if (live)
        m_session->holdCommand(CommandHold::Reason::Airframe);
    m_airframePath = path;
    const std::vector<rcm::Unit> left = m_command->setAirframe(*airframe);
    checkAirframeAction();
    updateTitle();
    if (live || !left.empty()) {
        const QString name = QString::fromStdString(airframe->name);
        m_alerts->info(EventSource::Console, tr("Airframe %1 (was %2): the command's values carried over unit by unit")
                                                 .arg(name, was));
        if (!left.empty())
            m_alerts->warning(EventSource::Console, tr("Not in airframe %1, so no longer commanded: %2")
                                                        .arg(name, ItemText::unitNames(left)));
    }
    return true;
}

void MainWindow::checkAirframeAction()
{
    for (QAction* a : m_airframeActions->actions())
        a->setChecked(a->data().toString() == m_airframePath);
}

void MainWindow::requestAirframe(const QString& path)
{
    QString reason;
    const std::optional<rcm::Airframe> airframe = AirframeLoader::load(path, &reason);
    if (!airframe) {
        showError(reason);
        checkAirframeAction();
        return;
    }
    if (m_session->isLive()) {
        const std::vector<rcm::Unit> left =
            rcm::unitsMissingFrom(m_command->message(), rcm::restingCommand(*airframe));
        Confirmation ask;
        ask.title = tr("Airframe");
        ask.text = tr("Load the airframe %1 while the link is live?").arg(QString::fromStdString(airframe->name));
        ask.informativeText =
            tr("The command's values are carried over unit by unit. The console then holds the command back until "
               "the aircraft's report is in the panels and you resume commanding.") +
            (left.empty() ? QString()
                          : QLatin1Char('\n') + tr("Not in this airframe, so no longer commanded: %1")
                                                    .arg(ItemText::unitNames(left)));
        ask.action = tr("Load airframe");
        if (!ask.ask(this)) {
            checkAirframeAction();
            return;
        }
    }
    loadAirframe(path);
}

bool MainWindow::confirmEndingLink(const QString& action)
{
    if (!m_session->isLive())
        return true;
    Confirmation ending;
    ending.title = kTitle;
    ending.text = tr("%1 ends the live link: %2.")
                      .arg(action, m_session->description().isEmpty() ? tr("a link being started")
                                                                      : m_session->description());
    ending.informativeText = tr("The aircraft stops receiving this console's commands.");
    ending.action = action;
    return ending.ask(this);
}

void MainWindow::connectLink()
{
    if (confirmEndingLink(m_connectButton->text()))
        connectWith(m_linkSettings->settings());
}

void MainWindow::connectWith(const LinkSettings& settings)
{
    m_linkSettings->setSettings(settings);
    m_session->connectWith(settings);
    updateLinkControls();
}

void MainWindow::requestDisconnect()
{
    // One click must not drop a live link (nor hang up a call that took a minute to set up).
    if (confirmEndingLink(m_disconnectButton->text()))
        disconnectLink();
}

void MainWindow::disconnectLink()
{
    m_session->stop();
    endObservation();
    showNotConnected();
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
    m_session->startRehearsal(m_command->airframe(), m_linkSettings->settings().keyPath, uasimProgram);
    updateLinkControls();
}

void MainWindow::openFrameLog(const QString& path, const QString& keyPath)
{
    // The log view's rows are built where the log is indexed.
    auto rows = std::make_shared<std::shared_ptr<FrameLogModel::PreparedRows>>();
    m_preparedRows = rows;
    m_session->openReplay(path, keyPath,
                          [rows](const FrameLogReader& index) { *rows = FrameLogModel::prepareRows(index); });
    // Shown now, saying the log is being opened (a long log takes seconds):
    // their new layouts are then done and painted before the log comes, not
    // together with it or with the replay's start.
    m_replayControls->showOpening();
    m_replayControls->setPaused(false);
    m_replayControls->show();
    if (!m_observation) {
        m_replayNote->setText(replayNoteText());
        m_replayNote->show();
    }
    updateLinkControls();
}

void MainWindow::replayIndexed(const QString& path)
{
    m_logModel->setLogKey(m_session->logKey());
    const auto prepared = std::exchange(m_preparedRows, {});
    m_logModel->showLog(m_session->takeReplayIndex(), path, prepared ? *prepared : nullptr);
    const int rows = m_logModel->rowCount();
    m_logModel->setPlayedRows(0);
    m_replayControls->setRange(rows ? m_logModel->utcMicros(0) : 0, rows ? m_logModel->utcMicros(rows - 1) : 0);
    m_replayControls->setPaused(false);
    m_replayControls->show();
    m_pauseAction->setEnabled(true);
}

void MainWindow::setReplayPaused(bool paused)
{
    if (!m_session->replay())
        return;
    m_session->setReplayPaused(paused);
    m_replayControls->setPaused(paused);
}

void MainWindow::setReplaySpeed(double speed)
{
    m_replayControls->setSpeed(speed);
    m_session->setReplaySpeed(speed);
}

void MainWindow::showPanel(int index)
{
    m_panels->setCurrentIndex(index);
    if (QWidget* page = m_panels->currentWidget())
        page->setFocus(Qt::ShortcutFocusReason);
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

void MainWindow::linkStarted(const LinkController* controller)
{
    const bool replay = m_session->kind() == ConsoleSession::Kind::Replay;
    const QString logPath = m_session->sessionLogPath();
    if (!replay) {
        m_logModel->clear();
        m_logModel->setLogKey(m_session->logKey());
        if (!logPath.isEmpty())
            m_logModel->setSessionLog(logPath);
    }
    endObservation();
    // The fleet reads this link's keyed sessions on the broker too.
    updateBrokerTrust();
    m_status->setTransportLabel(tr("Call"), tr("The satellite phone's call: what the modem does, and for how long"));
    bindLinkEvents(controller, !replay);
    // Also when a live link replaced a log being opened.
    m_replayControls->setVisible(replay);
    m_replayNote->setVisible(replay);
    if (const ReplayLink* r = m_session->replay()) {
        beginReplay(r);
        connect(r, &ReplayLink::positionChanged, this, [this](qint64 utc, int next) {
            m_logModel->setPlayedRows(next);
            m_replayControls->setPosition(utc);
            m_status->setReplayTime(utc);
            m_overview->setReplayTime(utc);
            if (m_logView->isFollowing() && next > 0)
                m_logView->scrollToSourceRow(next - 1);
        });
        connect(r, &ReplayLink::stateChanged, this, [this](ReplayLink::State state) {
            m_replayControls->setPaused(state == ReplayLink::State::Paused);
            m_replayControls->setFinished(state == ReplayLink::State::Finished);
        });
        connect(r, &ReplayLink::endOfLog, this, [this] {
            statusBar()->showMessage(tr("Replay: end of the frame log"), 8000);
            emit replayFinished();
        });
    }

    const QString description = m_session->description();
    m_preview->setDatagram(m_session->isDatagram());
    m_preview->resetSent();
    m_status->setLinkDescription(description);
    m_status->setKeyFingerprint(m_session->keyFingerprint());
    m_status->setStatistics(LinkStatistics());
    m_flightPlan->setLinkReady(!replay && m_session->commanding());
    // A replay says so, with the log's own time, and raises no link alarm.
    m_alerts->setReplay(replay);
    m_status->setReplay(replay);
    m_overview->setReplay(replay);
    m_alerts->info(EventSource::Link, logPath.isEmpty() ? tr("Started: %1").arg(description)
                                                        : tr("Started: %1; frame log %2")
                                                              .arg(description, QDir::toNativeSeparators(logPath)));
    if (!m_session->keyFingerprint().isEmpty())
        m_alerts->info(EventSource::Key, tr("Secure link, key fingerprint %1").arg(m_session->keyFingerprint()));
    m_linkNote->setText(logPath.isEmpty()
                            ? description
                            : tr("%1\nFrame log: %2").arg(description, QDir::toNativeSeparators(logPath)));
    updateTitle();
    updateLinkControls();
}

void MainWindow::bindLinkEvents(const LinkEvents* events, bool logRows)
{
    connect(events, &LinkEvents::statisticsChanged, m_status, &StatusBarWidget::setStatistics);
    connect(events, &LinkEvents::statisticsChanged, m_overview, &OverviewPage::setStatistics);
    // Its errors to the event log and the banner, its silences to the alarm.
    m_alerts->follow(events);
    // A modem's call: dialling, connected, redialling, hung up. Its failures
    // come as errors too (once an outage), and are logged once, as errors.
    m_status->setTransportStatus(QString());
    m_status->setModemService(-1, false, QString());
    m_reported->setLinkDelay(m_session->kind() == ConsoleSession::Kind::Live ? m_linkSettings->settings().oneWayDelay()
                                                                              : std::chrono::milliseconds(0));
    connect(events, &LinkEvents::errorOccurred, this, [this](const QString& error) { m_lastLinkError = error; });
    connect(events, &LinkEvents::transportStatusChanged, this, [this](const QString& status) {
        m_status->setTransportStatus(status);
        if (status != m_lastLinkError)
            m_alerts->info(EventSource::Link, status);
    });
    // The phone's registration and signal: bars in the status bar, and each
    // change of registration in the event log.
    connect(events, &LinkEvents::modemServiceChanged, this, [this](int bars, bool registered, const QString& text) {
        const bool wasRegistered = m_status->modemServiceText().isEmpty() ? !registered : m_modemRegistered;
        m_status->setModemService(bars, registered, text);
        if (registered != wasRegistered)
            m_alerts->info(EventSource::Link, tr("The satellite phone: %1").arg(text));
        m_modemRegistered = registered;
    });
    // A live session's frames become rows as the link logs them; a replay's
    // rows are its log file, opened already.
    if (logRows)
        connect(events, &LinkEvents::frameLogged, m_logModel, &FrameLogModel::appendLogged);
    connect(events, &LinkEvents::stateChanged, m_status, &StatusBarWidget::setState);
    connect(events, &LinkEvents::messageReceived, this, &MainWindow::messageReceived);
    connect(events, &LinkEvents::frameSent, this, &MainWindow::frameSent);
    connect(events, &LinkEvents::commandRejected, this, [this](const QString& reasons) {
        showError(tr("The link refused the command: %1").arg(reasons), EventSource::Link);
    });
    // Not the banner: a forger could send one a second. The status bar
    // counts them by reason; the event log has them through m_alerts
    // (RefusalDigest).
    connect(events, &LinkEvents::frameRejected, this, [this](const QString& reason) {
        statusBar()->showMessage(tr("A frame was refused: %1").arg(reason), 8000);
    });
}

void MainWindow::joinBroker(const BrokerSettings& settings, bool publish)
{
    if (m_broker)
        return;  // once a run: the command line's broker
    m_broker = std::make_unique<BrokerSettings>(settings);
    if (!settings.tls && !settings.password.isEmpty())
        m_alerts->warning(EventSource::Link,
                          tr("The broker password goes to %1 over plain mqtt://, unencrypted: anyone on the path "
                             "reads it; use mqtts://")
                              .arg(settings.hostAndPort()));
    if (publish) {
        m_broadcast = new SessionBroadcast(m_session, settings, this);
        m_broadcast->follow(m_alerts->events());
        followBrokerClient(m_broadcast->client());
        const QString station = m_broadcast->stationName();
        m_alerts->info(
            EventSource::Link,
            settings.signingKey
                ? tr("Broker %1: connecting, to publish every link as %2, signed").arg(settings.url(), station)
                : tr("Broker %1: connecting, to publish every link as %2, unsigned (no --broker-key): "
                     "observers will show it as unverified")
                      .arg(settings.url(), station));
        // Said once: a reconnection is said by its return.
        connect(m_broadcast->client(), &MqttClient::connected, this, [this, url = settings.url()] {
            if (std::exchange(m_brokerAnnounced, true))
                return;
            m_alerts->info(EventSource::Link, tr("Broker %1: connected, publishing every link").arg(url));
        });
    }
    // The fleet has a connection of its own: it reads everything, the publisher only writes.
    BrokerSettings fleetSettings = settings;
    fleetSettings.clientId.clear();
    m_fleetClient = new MqttClient(fleetSettings, this);
    if (!publish)
        followBrokerClient(m_fleetClient, true);
    m_fleetFeed = new FleetFeed(m_fleetClient, this);
    updateBrokerTrust();
    m_fleetModel = new FleetModel(this);
    connect(m_fleetFeed, &FleetFeed::aircraftUpdated, m_fleetModel, &FleetModel::update);
    connect(m_fleetFeed, &FleetFeed::aircraftRemoved, m_fleetModel, &FleetModel::remove);
    m_fleetView = new FleetView(m_fleetModel);
    m_fleetView->setBroker(settings.url());
    connect(m_fleetFeed, &FleetFeed::messageRefused, this, [this](const QString& reason) {
        m_alerts->refusals()->refusedBrokerMessage(reason);
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
    connect(m_fleetView, &FleetView::observeRequested, this, &MainWindow::observeRequested);
    QDockWidget* fleet = dock(tr("Fleet"), QStringLiteral("fleetDock"), m_fleetView, this);
    tabifyDockWidget(m_docks[5], fleet);
    fleet->raise();
    m_fleetClient->start();
}

void MainWindow::followBrokerClient(const MqttClient* client, bool quietWhileObserving)
{
    // An observation's own client says the same of the same broker.
    const auto heard = [this, quietWhileObserving] { return !(quietWhileObserving && m_observation); };
    connect(client, &MqttClient::errorOccurred, this, [this, heard](const QString& error) {
        if (heard())
            m_alerts->warning(EventSource::Link, error);
    });
    connect(client, &MqttClient::setupFailed, this, [this, heard](const QString& error) {
        if (heard())
            m_alerts->error(EventSource::Link, error);
    });
    connect(client, &MqttClient::refusedByBroker, this, [this, heard](const QString& error) {
        if (heard())
            m_alerts->error(EventSource::Link, error);
    });
    connect(client, &MqttClient::restored, this, [this, heard](const QString& message) {
        if (heard())
            m_alerts->info(EventSource::Link, message);
    });
}

void MainWindow::updateBrokerTrust()
{
    if (!m_broker)
        return;
    auto trust = std::make_shared<BrokerTrust>(m_broker->trust ? *m_broker->trust : BrokerTrust());
    // This station believes itself, and reads its own keyed sessions.
    if (m_broadcast && m_broker->signingKey)
        trust->trustStation(m_broadcast->stationName(), m_broker->signingKey->publicKey());
    if (std::shared_ptr<const rcm::LogKey> key = m_session->logKey())
        trust->addLinkKey(std::move(key));
    m_brokerTrust = trust;
    if (m_fleetFeed)
        m_fleetFeed->setTrust(m_brokerTrust);
}

void MainWindow::observeRequested(const QString& aircraft)
{
    if (!m_broker || !confirmEndingLink(tr("Observe %1").arg(aircraft)))
        return;
    BrokerSettings settings = *m_broker;
    settings.aircraft = aircraft;
    settings.clientId.clear();
    settings.trust = m_brokerTrust;
    observe(settings);
}

void MainWindow::observe(const BrokerSettings& settings)
{
    m_session->stop();
    endObservation();
    m_observation = new BrokerObservation(settings, this);
    // A keyed session's frames are the enciphered bytes: with the aircraft's
    // key the log view and the panels read them as the station's own would.
    const QList<std::shared_ptr<const rcm::LogKey>> keys =
        settings.trust ? settings.trust->linkKeys() : QList<std::shared_ptr<const rcm::LogKey>>();
    m_logModel->clear();
    m_logModel->setLogKey(keys.isEmpty() ? nullptr : keys.front());
    m_status->setTransportLabel(tr("Broker"), tr("The broker the observation comes through, and for how long"));
    bindLinkEvents(m_observation, true);
    // Refused messages are counted as refused frames are; what is worth
    // knowing (frames missed, stations unverified or sealed) is a warning.
    connect(m_observation, &BrokerObservation::messageRefused, m_alerts->refusals(),
            &RefusalDigest::refusedBrokerMessage);
    connect(m_observation, &BrokerObservation::messageRefused, this, [this](const QString& reason) {
        statusBar()->showMessage(tr("A broker message was refused: %1").arg(reason), 8000);
    });
    connect(m_observation, &BrokerObservation::warning, this,
            [this](const QString& text) { m_alerts->warning(EventSource::Link, text); });
    // Read only, as a replay: the panels show what the observed station commands.
    m_ownCommand = m_command->message();
    m_replayMicros = QDateTime::currentMSecsSinceEpoch() * 1000;
    m_reported->clear();
    m_replayNote->setText(tr("Observing %1: read only, nothing is sent").arg(m_observation->aircraft()));
    m_replayNote->show();
    m_replayReadOnly = new ReadOnlyArea(m_panels, this);
    qApp->installEventFilter(m_replayReadOnly);
    connect(m_observation, &LinkEvents::frameLogged, this, [this, keys](const LoggedFrame& frame) {
        m_replayMicros = frame.entry.utcMicros;
        if (frame.entry.direction != FrameDirection::Sent)
            return;
        const auto bytes =
            std::span(reinterpret_cast<const std::uint8_t*>(frame.bytes.constData()), std::size_t(frame.bytes.size()));
        if (frame.entry.enciphered) {
            // Read only when a key of ours authenticates it.
            for (const std::shared_ptr<const rcm::LogKey>& key : keys)
                if (const rcm::LoggedFrameReading reading = rcm::readLoggedFrame(bytes, true, key.get());
                    reading.read()) {
                    m_command->replaceMessage(reading.decoded.message);
                    return;
                }
            return;
        }
        rcm::DecodeResult r = rcm::decodeFrame(bytes);
        if (r.ok() && r.diagnostics.empty())
            m_command->replaceMessage(r.message);
    });
    const QString description = tr("Observing %1 on %2").arg(m_observation->aircraft(), settings.url());
    m_status->setLinkDescription(description);
    m_status->setKeyFingerprint(keys.isEmpty() ? QString() : QString::fromStdString(keys.front()->fingerprint()));
    m_status->setStatistics(LinkStatistics());
    m_flightPlan->setLinkReady(false);
    m_linkNote->setText(tr("%1: read only, nothing is sent to the aircraft").arg(description));
    m_alerts->info(EventSource::Link, description);
    const QStringList trusted = settings.trust ? settings.trust->trustedStations() : QStringList();
    if (trusted.isEmpty())
        m_alerts->warning(EventSource::Link, tr("No station's key is trusted (--broker-trust): nothing %1's stations "
                                                "publish can be verified, and nothing unverified is shown")
                                                 .arg(m_observation->aircraft()));
    else
        m_alerts->info(EventSource::Link, tr("Trusting the keys of %1").arg(trusted.join(QStringLiteral(", "))));
    if (!settings.tls && !settings.password.isEmpty() && !m_broker)
        m_alerts->warning(EventSource::Link,
                          tr("The broker password goes to %1 over plain mqtt://, unencrypted: anyone on the path "
                             "reads it; use mqtts://")
                              .arg(settings.hostAndPort()));
    m_observation->start();
    updateLinkControls();
}

void MainWindow::endObservation()
{
    if (!m_observation)
        return;
    m_observation->stop();
    m_observation->deleteLater();
    m_observation = nullptr;
    m_replayNote->setText(replayNoteText());
    endReplay();
    m_status->setLinkDescription(QString());
    m_status->setKeyFingerprint(QString());
    m_status->setStatistics(LinkStatistics());
    m_alerts->setStatistics(LinkStatistics());  // closed: no alarm
    m_alerts->info(EventSource::Link, tr("Stopped observing"));
}

void MainWindow::linkStopped()
{
    endReplay();
    m_upload->cancel();
    m_replayControls->hide();
    m_pauseAction->setEnabled(false);
    m_logModel->setPlayedRows(-1);
    m_flightPlan->setLinkReady(false);
    m_status->setLinkDescription(QString());
    m_status->setKeyFingerprint(QString());
    m_status->setStatistics(LinkStatistics());
    m_status->setReplay(false);
    m_overview->setStatistics(LinkStatistics());
    m_overview->setReplay(false);
    m_alerts->setStatistics(LinkStatistics());  // closed: no alarm
    m_alerts->setReplay(false);
    m_alerts->info(EventSource::Link, tr("Stopped"));
    m_journal->linkEnded();
    showNotConnected();
    updateTitle();
    updateLinkControls();
}

void MainWindow::beginReplay(const ReplayLink* replay)
{
    m_ownCommand = m_command->message();
    m_replayMicros = replay->startMicros();
    m_reported->clear();
    m_replayNote->show();
    m_replayReadOnly = new ReadOnlyArea(m_panels, this);
    qApp->installEventFilter(m_replayReadOnly);
    // On the link's thread, as each record plays: a sent frame is decoded
    // there, and the window hears of every record (its time) before the
    // worker's report of the same frame.
    connect(
        replay, &ReplayLink::frameReplayed, replay,
        [this](const FrameRecord& record) {
            std::optional<rcm::Message> commanded;
            if (record.direction == FrameDirection::Sent) {
                rcm::DecodeResult r = rcm::decodeFrame(std::span(
                    reinterpret_cast<const std::uint8_t*>(record.bytes.constData()), std::size_t(record.bytes.size())));
                // A keyed log's frames read as noise without the key: shown only when read cleanly.
                if (r.ok() && r.diagnostics.empty())
                    commanded = std::move(r.message);
            }
            QMetaObject::invokeMethod(
                this, [this, utc = record.utcMicros, commanded] { replayedFrame(utc, commanded); },
                Qt::QueuedConnection);
        },
        Qt::DirectConnection);
}

void MainWindow::replayedFrame(qint64 utcMicros, const std::optional<rcm::Message>& commanded)
{
    if (!m_ownCommand)
        return;  // the replay ended meanwhile
    m_replayMicros = utcMicros;
    if (commanded)
        m_command->replaceMessage(*commanded);
}

void MainWindow::endReplay()
{
    if (!m_ownCommand)
        return;
    delete m_replayReadOnly;  // removes itself from the application
    m_replayReadOnly = nullptr;
    m_replayNote->hide();
    m_reported->clear();
    m_command->replaceMessage(*m_ownCommand);
    m_ownCommand.reset();
}

void MainWindow::actionFailed(const QString& reason)
{
    if (!m_session->replay()) {
        // A log that could not be opened.
        m_replayControls->hide();
        if (!m_observation)
            m_replayNote->hide();
    }
    m_linkNote->setText(reason);
    // Key files are refused here too ("the key file is refused: ..."): said as the key's.
    showError(reason, reason.contains(QStringLiteral("key file")) ? EventSource::Key : EventSource::Link);
    updateLinkControls();
}

void MainWindow::commandChanged()
{
    // What the next frame carries: the header alone while the command is held.
    const bool held = m_session->isLive() && !m_session->commanding();
    m_preview->setCommand(held ? rcm::heldCommand(m_command->message()) : m_command->message());
    m_session->setCommand(m_command->message());
}

void MainWindow::messageReceived(const ReceivedMessage& received)
{
    m_reported->onReceived(received);
    if (!m_ownCommand)
        m_journal->statusReceived(received.message);
}

void MainWindow::frameSent(quint32 messageId)
{
    // A frame that held the command back carried no photograph to return from.
    if (m_session->commanding()) {
        m_command->frameSent();
        m_journal->frameSent(messageId);
    }
    m_preview->frameSent(messageId);
}

void MainWindow::updateLinkControls()
{
    const bool running = m_session->isRunning();
    const bool active = m_session->isActive() || m_observation;
    m_linkSettings->setEnabled(!running);
    m_stationControl->setStationEditable(!running);
    m_connectButton->setEnabled(!running);
    m_connectAction->setEnabled(!running);
    m_disconnectButton->setEnabled(active);
    m_disconnectAction->setEnabled(active);
    // A satellite phone's modem: Connect dials and Disconnect hangs up, and says so.
    const bool dials = m_linkSettings->settings().dialsModem();
    m_connectButton->setText(dials ? tr("Dial") : tr("Connect"));
    const bool inCall = dials && m_session->kind() == ConsoleSession::Kind::Live;
    m_disconnectButton->setText(inCall ? tr("Hang up") : tr("Disconnect"));
}

void MainWindow::showNotConnected()
{
    m_linkNote->setText(
        tr("Not connected. Connect to the aircraft's link, start a rehearsal against the "
           "simulated aircraft, or open a frame log to replay it (Ctrl+O)."));
}

void MainWindow::updateTitle()
{
    QString title = kTitle + QStringLiteral(" \u2014 ") + QString::fromStdString(m_command->airframe().name);
    if (!m_session->description().isEmpty())
        title += QStringLiteral(" \u2014 ") + m_session->description();
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
        showError(tr("No frame log to export: connect, or open a log first"));
        return;
    }
    const QString target = QFileDialog::getSaveFileName(this, tr("Export the frame log as CSV"),
                                                        QFileInfo(source).completeBaseName() + QStringLiteral(".csv"),
                                                        tr("CSV files (*.csv)"));
    if (target.isEmpty())
        return;
    // A day's log takes seconds to export: a thread of its own, so the
    // console keeps sending and drawing meanwhile. The thread only touches
    // `result`; the GUI reads it once the thread has finished.
    struct Result {
        bool ok = false;
        QString error;
    };
    auto result = std::make_shared<Result>();
    // The log's key (HCTR2 is safe from several threads): a keyed session's
    // frames export as their items, not as "enciphered".
    auto* thread = QThread::create([source, target, result, key = m_session->logKey()] {
        QSaveFile out(target);
        result->ok = out.open(QIODevice::WriteOnly) && exportFrameLogCsv(source, out, &result->error, key.get()) &&
                     out.commit();
        if (!result->ok && result->error.isEmpty())
            result->error = out.errorString();
    });
    connect(thread, &QThread::finished, this, [this, result, target] {
        if (result->ok)
            statusBar()->showMessage(tr("Exported %1").arg(QDir::toNativeSeparators(target)), 8000);
        else
            showError(tr("CSV export failed: %1").arg(result->error));
    });
    connect(thread, &QThread::finished, thread, &QObject::deleteLater);
    statusBar()->showMessage(tr("Exporting %1\u2026").arg(QDir::toNativeSeparators(target)));
    thread->start();
}

void MainWindow::chooseAirframe()
{
    const QString path =
        QFileDialog::getOpenFileName(this, tr("Open an airframe"), QString(), tr("Airframes (*.json);;All files (*)"));
    if (!path.isEmpty())
        requestAirframe(path);
}

void MainWindow::bindStationControl()
{
    StationControl* control = m_session->stationControl();
    // Control moving unasked is an error for the banner and the log; as asked, an event.
    connect(control, &StationControl::alarm, this,
            [this](const QString& reason) { showError(reason, EventSource::Control); });
    connect(control, &StationControl::event, this, [this](const QString& text) {
        statusBar()->showMessage(text, 8000);
        m_alerts->info(EventSource::Control, text);
    });
    connect(m_stationControl, &StationControlWidget::stationRefused, this,
            [this](const QString& reason) { showError(reason, EventSource::Control); });
    // The header panel shows the stations the frames name, as sent.
    connect(control, &StationControl::headerChanged, this, [this, control] {
        rcm::Message named = m_command->message();
        control->applyTo(named);
        m_command->editUnit({rcm::UnitKind::Header, 0}, [&](rcm::Unit& header) { header = named.header; });
    });
}

void MainWindow::bindCommandHold()
{
    m_journal = new CommandJournal(m_command, this);
    connect(m_journal, &CommandJournal::entry, this, [this](const QString& text, bool warning) {
        if (warning)
            m_alerts->warning(EventSource::Command, text);
        else
            m_alerts->info(EventSource::Command, text);
    });
    StationControl* control = m_session->stationControl();
    connect(control, &StationControl::headerChanged, m_journal, [this, control] {
        m_journal->setStation(control->station() ? QString::fromStdString(rcm::formatStation(*control->station()))
                                                 : QString());
    });
    // The report taken into the panels is not the operator's change.
    connect(m_session, &ConsoleSession::commandAdopted, m_command, &CommandState::replaceMessage);
    connect(m_session, &ConsoleSession::commandEvent, this, [this](const QString& text) {
        statusBar()->showMessage(text, 8000);
        m_alerts->info(EventSource::Command, text);
    });
    connect(m_session->commandHold(), &CommandHold::changed, this, [this] {
        commandChanged();
        m_flightPlan->setLinkReady(m_session->isLive() && m_session->kind() != ConsoleSession::Kind::Replay &&
                                   m_session->commanding());
    });
    connect(m_stationControl, &StationControlWidget::takeControlRequested, m_holdBar, &CommandHoldBar::requestResume);
    connect(m_holdBar, &CommandHoldBar::refused, this,
            [this](const QString& reason) { showError(reason, EventSource::Command); });
}

void MainWindow::showError(const QString& message, EventSource source)
{
    statusBar()->showMessage(message, 10000);
    m_alerts->error(source, message);
}
