#pragma once

// The window's docks around the panels, and where they go: the link and
// the voice down the left, the frame log at the bottom beside the next frame
// and the events; the fleet beside the events once a broker is joined.
// place() puts each back in its first place. (The flight plan is a page of
// the panels, where its map has room: PanelArea.)

#include <QObject>

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

private:
    QMainWindow* m_window;
    // In the order they were first made, which the View menu's Ctrl+1 .. Ctrl+6 follow.
    QDockWidget* m_link;
    QDockWidget* m_preview;
    QDockWidget* m_log;
    QDockWidget* m_voice;
    QDockWidget* m_events;
    bool m_placed = false;
};
