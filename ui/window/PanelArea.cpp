#include "ui/window/PanelArea.h"

#include "ui/control/CommandHoldBar.h"
#include "ui/overview/OverviewPage.h"
#include "ui/panels/CameraPanel.h"
#include "ui/panels/EnginePanel.h"
#include "ui/panels/FlapsPanel.h"
#include "ui/panels/FuelDumpPanel.h"
#include "ui/panels/GearPanel.h"
#include "ui/panels/HeaderPanel.h"
#include "ui/panels/LightsPanel.h"
#include "ui/panels/RadioPanel.h"

#include <QScrollArea>
#include <QTabWidget>
#include <QVBoxLayout>

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

}  // namespace

PanelArea::PanelArea(CommandState* command, ReportedState* reported, ConsoleSession* session, QWidget* banners,
                     QWidget* parent)
    : QWidget(parent),
      m_tabs(new QTabWidget),
      m_overview(new OverviewPage(command, reported)),
      m_holdBar(new CommandHoldBar(session, command))
{
    m_tabs->setObjectName(QStringLiteral("panels"));
    m_tabs->setDocumentMode(true);
    m_tabs->setUsesScrollButtons(true);
    // Alt+1 .. Alt+8 in the View menu bring each up; the tabs themselves
    // carry no mnemonic, which would make those shortcuts ambiguous.
    const struct {
        QWidget* panel;
        QString title;
    } panels[] = {
        {m_overview, tr("Overview")},
        {new HeaderPanel(command, reported), tr("Header")},
        {new EnginePanel(command, reported), tr("Engines")},
        {new FlapsPanel(command, reported), tr("Flaps")},
        {new GearPanel(command, reported), tr("Landing gear")},
        {new LightsPanel(command, reported), tr("Lights")},
        {new FuelDumpPanel(command, reported), tr("Fuel dump")},
        {new RadioPanel(command, reported), tr("Radios")},
        {new CameraPanel(command, reported), tr("Cameras")},
    };
    for (const auto& p : panels) {
        // The overview fits itself to the width and scrolls its own cards.
        if (p.panel == m_overview)
            addPage(p.panel, p.title);
        else
            addPage(scrolled(p.panel), p.title);
    }
    // The link-loss alarm and the errors above the panels, where the operator is looking.
    auto* layout = new QVBoxLayout(this);
    layout->setContentsMargins(0, 0, 0, 0);
    layout->setSpacing(0);
    layout->addWidget(banners);
    layout->addWidget(m_holdBar);
    layout->addWidget(m_tabs, 1);
}

void PanelArea::addPage(QWidget* page, const QString& title)
{
    const int index = m_tabs->addTab(page, title);
    // Alt+1 .. Alt+9, then Alt+0 for the tenth (ConsoleMenus).
    m_tabs->setTabToolTip(index, tr("%1 (Alt+%2)").arg(title).arg((index + 1) % 10));
}

void PanelArea::showPanel(int index)
{
    m_tabs->setCurrentIndex(index);
    if (QWidget* page = m_tabs->currentWidget())
        page->setFocus(Qt::ShortcutFocusReason);
}
