#include "ui/window/ConsoleDocks.h"

#include "ui/window/WindowAttention.h"

#include <QDockWidget>
#include <QVBoxLayout>
#include <QMainWindow>

#include <algorithm>

namespace {

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

}  // namespace

ConsoleDocks::ConsoleDocks(QMainWindow* window, const Contents& contents)
    : QObject(window),
      m_window(window),
      m_link(dock(tr("Link"), QStringLiteral("linkDock"), contents.link, window)),
      m_preview(dock(tr("Next frame"), QStringLiteral("previewDock"), contents.preview, window)),
      m_log(dock(tr("Frame log"), QStringLiteral("frameLogDock"), contents.frameLog, window)),
      m_voice(dock(tr("Voice"), QStringLiteral("voiceDock"), contents.voice, window)),
      m_events(dock(tr("Events"), QStringLiteral("eventsDock"), contents.events, window))
{
    qRegisterMetaType<QList<QWidget*>>();  // attentionRequested(), also queued and spied on
    m_all = {m_link, m_preview, m_log, m_voice, m_events};
    place();
}

void ConsoleDocks::addLinkStrips(std::function<QWidget*()> make)
{
    m_makeStrip = std::move(make);
    for (QDockWidget* d : m_all)
        addLinkStrip(d);
}

void ConsoleDocks::addLinkStrip(QDockWidget* d)
{
    QWidget* content = d->widget();
    auto* framed = new QWidget;
    framed->setObjectName(d->objectName() + QStringLiteral("Content"));
    framed->setFont(content->font());
    auto* layout = new QVBoxLayout(framed);
    layout->setContentsMargins(0, 0, 0, 0);
    layout->setSpacing(0);
    QWidget* strip = m_makeStrip();
    layout->addWidget(strip);
    layout->addWidget(content, 1);
    d->setWidget(framed);
    // Docked, the main window's banner and status bar say it already.
    strip->setVisible(d->isFloating());
    connect(d, &QDockWidget::topLevelChanged, strip, &QWidget::setVisible);
}

void ConsoleDocks::requestAttention()
{
    QList<QWidget*> windows{m_window};
    for (QDockWidget* d : m_all)
        if (d->isFloating() && d->isVisible())
            windows << d;
    for (QWidget* w : windows)
        WindowAttention::request(w);
    emit attentionRequested(windows);
}

void ConsoleDocks::clearAttention()
{
    WindowAttention::clear(m_window);
    for (QDockWidget* d : m_all)
        WindowAttention::clear(d);
}

void ConsoleDocks::place()
{
    for (QDockWidget* d : {m_link, m_voice, m_log, m_preview, m_events}) {
        d->setFloating(false);
        d->show();
    }
    // The link and the voice down the left, full height, so that neither is
    // squeezed; the panels take the rest of the width, so that their tabs
    // all show at 1366 pixels; the frame log and the events share the bottom.
    m_window->setCorner(Qt::TopLeftCorner, Qt::LeftDockWidgetArea);
    m_window->setCorner(Qt::BottomLeftCorner, Qt::LeftDockWidgetArea);
    m_window->setCorner(Qt::TopRightCorner, Qt::RightDockWidgetArea);
    m_window->setCorner(Qt::BottomRightCorner, Qt::BottomDockWidgetArea);
    m_window->addDockWidget(Qt::LeftDockWidgetArea, m_link);
    m_window->splitDockWidget(m_link, m_voice, Qt::Vertical);
    m_window->addDockWidget(Qt::BottomDockWidgetArea, m_log);
    m_window->splitDockWidget(m_log, m_preview, Qt::Horizontal);
    // The events in front beside the frame log; the next frame behind them.
    m_window->tabifyDockWidget(m_preview, m_events);
    m_events->raise();
    // In proportion to the window: the panels and the plan keep 70 % of
    // the height (the overview's cards all show at 768 pixels), the frame
    // log and the events the rest.
    const QSize area = m_window->size();
    m_window->resizeDocks({m_link}, {std::clamp(area.width() / 5, 250, 320)}, Qt::Horizontal);
    m_window->resizeDocks({m_log, m_preview}, {area.width() * 3 / 5, area.width() * 2 / 5}, Qt::Horizontal);
    m_window->resizeDocks({m_log}, {area.height() * 3 / 10}, Qt::Vertical);
}

void ConsoleDocks::placeOnFirstShow(bool restored)
{
    if (!m_placed && !restored)
        place();
    m_placed = true;
}

void ConsoleDocks::addFleet(QWidget* fleetView)
{
    QDockWidget* fleet = dock(tr("Fleet"), QStringLiteral("fleetDock"), fleetView, m_window);
    m_all << fleet;
    if (m_makeStrip)
        addLinkStrip(fleet);
    m_window->tabifyDockWidget(m_events, fleet);
    fleet->raise();
}
