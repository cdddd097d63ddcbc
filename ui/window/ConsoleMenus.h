#pragma once

// The window's menu bar: File, Link, View and Help, with their shortcuts.
// What the window does for an item it hears from the signals; the theme
// and the airframes the menus keep themselves.

#include "ui/window/Theme.h"

#include <QObject>

class AirframeSelection;
class ConsoleSession;
class FlightPlanWidget;
class LinkSettingsWidget;
class QAction;
class QMainWindow;
class QTabWidget;

class ConsoleMenus : public QObject {
    Q_OBJECT

public:
    struct Parts {
        QTabWidget* panels;  // a View item each, Alt+1 ..
        AirframeSelection* airframes;
        FlightPlanWidget* flightPlan;
        LinkSettingsWidget* linkSettings;
    };
    // Fills the menu bar of `window`, whose docks are all made already (a
    // View item each, Ctrl+1 ..).
    ConsoleMenus(QMainWindow* window, const Parts& parts);

    // The console's name, as the window's title and Help > About say it.
    static QString title();

    // View > Night theme's tick.
    Theme::Kind theme() const;
    // Applies `kind` to the whole application and ticks View > Night theme to match.
    void setTheme(Theme::Kind kind);
    // From the session's state: what can be started or stopped now.
    void update(const ConsoleSession& session);
    // Link > Pause or resume replay, while a replay's log is shown.
    void setReplayPausable(bool pausable);

signals:
    void openLogRequested();
    void exportCsvRequested();
    void connectRequested();
    void disconnectRequested();
    void rehearsalRequested();
    void pauseToggleRequested();
    void panelRequested(int index);
    void resetLayoutRequested();

private:
    void addFileMenu(const Parts& parts);
    void addLinkMenu(const Parts& parts);
    void addViewMenu(const Parts& parts);
    void addHelpMenu();

    QMainWindow* m_window;
    QAction* m_connect = nullptr;
    QAction* m_disconnect = nullptr;
    QAction* m_pause = nullptr;
    QAction* m_night = nullptr;
};
