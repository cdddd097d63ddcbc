#pragma once

// The middle of the window, where the operator looks: the link-loss alarm
// and the errors on top, the band of the held command below them, then the
// command panels, a tab each (Overview, Header, Engines, ... Cameras), and
// pages added after them (the flight plan).

#include <QWidget>

class CommandHoldBar;
class CommandState;
class ConsoleSession;
class OverviewPage;
class QTabWidget;
class ReportedState;

class PanelArea : public QWidget {
    Q_OBJECT

public:
    // `banners`: the alerts' banners, taken into the layout.
    PanelArea(CommandState* command, ReportedState* reported, ConsoleSession* session, QWidget* banners,
              QWidget* parent = nullptr);

    QTabWidget* tabs() const { return m_tabs; }
    OverviewPage* overview() const { return m_overview; }
    CommandHoldBar* holdBar() const { return m_holdBar; }
    // Brings up tab `index` and gives its page the focus.
    void showPanel(int index);
    // A page after the panels, as it is (it lays out and scrolls itself).
    void addPage(QWidget* page, const QString& title);

private:
    QTabWidget* m_tabs;
    OverviewPage* m_overview;
    CommandHoldBar* m_holdBar;
};
