#include "ui/window/ConsoleMenus.h"

#include "link/session/ConsoleSession.h"
#include "ui/plan/FlightPlanWidget.h"
#include "ui/rehearsal/RehearsalDialog.h"
#include "ui/window/AirframeSelection.h"
#include "ui/window/LinkSettingsWidget.h"

#include <QApplication>
#include <QDockWidget>
#include <QMainWindow>
#include <QMenuBar>
#include <QMessageBox>
#include <QTabWidget>

ConsoleMenus::ConsoleMenus(QMainWindow* window, const Parts& parts) : QObject(window), m_window(window)
{
    addFileMenu(parts);
    addLinkMenu(parts);
    addViewMenu(parts);
    addHelpMenu();
}

void ConsoleMenus::addFileMenu(const Parts& parts)
{
    QMenu* file = m_window->menuBar()->addMenu(tr("&File"));
    QAction* open = file->addAction(tr("&Open frame log for replay\u2026"), this, &ConsoleMenus::openLogRequested);
    open->setShortcut(QKeySequence::Open);
    QAction* csv = file->addAction(tr("&Export frame log as CSV\u2026"), this, &ConsoleMenus::exportCsvRequested);
    csv->setShortcut(QKeySequence(tr("Ctrl+E")));
    file->addSeparator();
    QAction* plan = file->addAction(tr("Open flight &plan\u2026"), parts.flightPlan, &FlightPlanWidget::openPlan);
    plan->setShortcut(QKeySequence(tr("Ctrl+Shift+O")));
    parts.airframes->addMenu(file);
    file->addSeparator();
    file->addAction(tr("&Rehearse scenario\u2026"), this, [this] { RehearsalDialog::chooseAndRun(m_window); });
    QAction* quit = file->addAction(tr("&Quit"), m_window, &QWidget::close);
    quit->setShortcut(QKeySequence::Quit);
}

void ConsoleMenus::addLinkMenu(const Parts& parts)
{
    QMenu* link = m_window->menuBar()->addMenu(tr("&Link"));
    m_connect = link->addAction(tr("&Connect"), this, &ConsoleMenus::connectRequested);
    m_connect->setShortcut(QKeySequence(tr("Ctrl+K")));
    m_disconnect = link->addAction(tr("&Disconnect"), this, &ConsoleMenus::disconnectRequested);
    m_disconnect->setShortcut(QKeySequence(tr("Ctrl+Shift+K")));
    QAction* rehearsal = link->addAction(tr("Start &rehearsal with uasim"), this, &ConsoleMenus::rehearsalRequested);
    rehearsal->setShortcut(QKeySequence(tr("Ctrl+R")));
    link->addSeparator();
    m_pause = link->addAction(tr("&Pause or resume replay"), this, &ConsoleMenus::pauseToggleRequested);
    m_pause->setShortcut(QKeySequence(tr("Ctrl+P")));
    m_pause->setEnabled(false);
    link->addAction(tr("Refresh serial ports"), parts.linkSettings, &LinkSettingsWidget::refreshPorts);
}

void ConsoleMenus::addViewMenu(const Parts& parts)
{
    QMenu* view = m_window->menuBar()->addMenu(tr("&View"));
    for (int i = 0; i < parts.panels->count(); ++i) {
        const QString name = parts.panels->tabText(i);
        QAction* a = view->addAction(name, this, [this, i] { emit panelRequested(i); });
        if (i < 10)  // Alt+1 .. Alt+9, Alt+0
            a->setShortcut(QKeySequence(Qt::ALT | Qt::Key(i < 9 ? Qt::Key_1 + i : Qt::Key_0)));
        a->setToolTip(tr("Show the %1 panel").arg(name));
    }
    view->addSeparator();
    int key = 0;
    for (QDockWidget* d : m_window->findChildren<QDockWidget*>()) {
        QAction* toggle = d->toggleViewAction();
        toggle->setShortcut(QKeySequence(Qt::CTRL | Qt::Key(Qt::Key_1 + key++)));
        view->addAction(toggle);
    }
    view->addSeparator();
    QAction* reset = view->addAction(tr("&Reset layout"), this, &ConsoleMenus::resetLayoutRequested);
    reset->setToolTip(tr("Every pane back in its first place, the window at its first size"));
    m_night = view->addAction(tr("&Night theme"));
    m_night->setCheckable(true);
    m_night->setToolTip(tr("Light text on a dark window, for a dim room or a night operation"));
    connect(m_night, &QAction::toggled, this,
            [](bool night) { Theme::apply(*qApp, night ? Theme::Kind::Night : Theme::Kind::Day); });
}

void ConsoleMenus::addHelpMenu()
{
    QMenu* help = m_window->menuBar()->addMenu(tr("&Help"));
    help->addAction(tr("&About"), this, [this] {
        QMessageBox::about(m_window, title(),
                           tr("<p><b>%1</b></p><p>Commands an unmanned aircraft with the Remote Control Message: "
                              "a 600-byte frame once a second over a serial modem, or a 510-byte UDP datagram."
                              "</p>")
                               .arg(title()));
    });
}

QString ConsoleMenus::title()
{
    return QStringLiteral("RCM ground control station");
}

Theme::Kind ConsoleMenus::theme() const
{
    return m_night->isChecked() ? Theme::Kind::Night : Theme::Kind::Day;
}

void ConsoleMenus::setTheme(Theme::Kind kind)
{
    m_night->setChecked(kind == Theme::Kind::Night);
    // The action applies a change; the first call applies the day theme too.
    Theme::apply(*qApp, kind);
}

void ConsoleMenus::update(const ConsoleSession& session)
{
    m_connect->setEnabled(!session.isRunning());
    m_disconnect->setEnabled(session.isActive());
}

void ConsoleMenus::setReplayPausable(bool pausable)
{
    m_pause->setEnabled(pausable);
}
