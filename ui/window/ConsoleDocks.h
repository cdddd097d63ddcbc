#pragma once

// The window's docks around the panels, and where they go: the link and
// the voice down the left, the frame log at the bottom beside the next frame
// and the events; the fleet beside the events once a broker is joined.
// place() puts each back in its first place. (The flight plan is a page of
// the panels, where its map has room: PanelArea.)

#include <QList>
#include <QObject>

#include <functional>

#include <vector>

class QDockWidget;
class QMainWindow;
class QWidget;

class ConsoleDocks : public QObject {
    Q_OBJECT

public:
    struct Contents {
        QWidget* link;
        QWidget* voice;
        QWidget* frameLog;
        QWidget* preview;
        QWidget* events;
    };
    // Docks `contents` in `window`, placed at its present size.
    ConsoleDocks(QMainWindow* window, const Contents& contents);

    // Every dock shown, in its first place, sized in proportion to the window.
    void place();
    // The first time the window shows, at its real size, unless `restored`
    // (the last session's layout) placed them already.
    void placeOnFirstShow(bool restored);
    // The Fleet dock, in front beside the events.
    void addFleet(QWidget* fleetView);

    // Puts `make()`'s strip (the link's state and alarm) at the top of each
    // dock, this one and those added later, shown while the dock floats: a
    // window of its own must show the alarm too.
    void addLinkStrips(std::function<QWidget*()> make);
    QList<QDockWidget*> docks() const { return m_all; }
    // The main window and every floating dock ask the window manager for
    // the operator's attention (WindowAttention: the urgency hint on X11,
    // a flashing taskbar entry elsewhere) until clearAttention().
    void requestAttention();
    // The urgency hint off every window: the alarm silenced, the link back or closed.
    void clearAttention();

signals:
    // What requestAttention() alerted.
    void attentionRequested(const QList<QWidget*>& windows);

private:
    void addLinkStrip(QDockWidget* dock);

    QMainWindow* m_window;
    QList<QDockWidget*> m_all;
    std::function<QWidget*()> m_makeStrip;
    // In the order they were first made, which the View menu's Ctrl+1 .. Ctrl+6 follow.
    QDockWidget* m_link;
    QDockWidget* m_preview;
    QDockWidget* m_log;
    QDockWidget* m_voice;
    QDockWidget* m_events;
    bool m_placed = false;
};
