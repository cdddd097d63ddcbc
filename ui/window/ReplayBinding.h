#pragma once

// A frame log replayed: the log opened (its rows built off the GUI thread,
// where ConsoleSession indexes it), the replay's controls in the Link dock
// asking the session to pause, seek and change speed, and where the replay
// stands fed back to the controls, the log view, the status bar and the
// overview.

#include "ui/framelog/FrameLogModel.h"
#include "ui/window/ConsoleNotices.h"

#include <QObject>

#include <memory>

class ConsoleMenus;
class ConsoleSession;
class FrameLogView;
class OverviewPage;
class ReplayControls;
class ReplayLink;
class StatusBarWidget;

class ReplayBinding : public QObject {
    Q_OBJECT

public:
    struct Parts {
        ConsoleSession* session;
        FrameLogModel* logModel;
        FrameLogView* logView;
        ReplayControls* controls;
        StatusBarWidget* status;
        OverviewPage* overview;
        ConsoleMenus* menus;
    };
    ReplayBinding(const Parts& parts, const ConsoleNotices& notices, QObject* parent = nullptr);

    // `keyPath`: the key of a keyed session's log, to decipher it with.
    void open(const QString& path, const QString& keyPath);
    void setPaused(bool paused);
    // 0.25 to 10 times the logged pace.
    void setSpeed(double speed);
    // The replay started by the session: its progress to the widgets.
    void follow(const ReplayLink* replay);
    // Any link ended, or one other than a replay started.
    void hide();

signals:
    // The replay reached the end of its log.
    void finished();

private:
    void indexed(const QString& path);

    Parts m_parts;
    ConsoleNotices m_notices;
    // The rows of the log being opened for replay, filled in the pool.
    std::shared_ptr<std::shared_ptr<FrameLogModel::PreparedRows>> m_preparedRows;
};
