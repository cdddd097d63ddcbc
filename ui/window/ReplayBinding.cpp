#include "ui/window/ReplayBinding.h"

#include "link/replay/ReplayLink.h"
#include "link/session/ConsoleSession.h"
#include "ui/framelog/FrameLogView.h"
#include "ui/overview/OverviewPage.h"
#include "ui/window/ConsoleMenus.h"
#include "ui/window/ReplayControls.h"
#include "ui/window/StatusBarWidget.h"

ReplayBinding::ReplayBinding(const Parts& parts, const ConsoleNotices& notices, QObject* parent)
    : QObject(parent), m_parts(parts), m_notices(notices)
{
    connect(m_parts.session, &ConsoleSession::replayIndexed, this, &ReplayBinding::indexed);
    connect(m_parts.controls, &ReplayControls::pauseRequested, this, &ReplayBinding::setPaused);
    connect(m_parts.controls, &ReplayControls::speedRequested, this, &ReplayBinding::setSpeed);
    connect(m_parts.controls, &ReplayControls::seekRequested, m_parts.session, &ConsoleSession::seekReplay);
    connect(m_parts.menus, &ConsoleMenus::pauseToggleRequested, this,
            [this] { setPaused(!m_parts.session->isReplayPaused()); });
}

void ReplayBinding::open(const QString& path, const QString& keyPath)
{
    // The log view's rows are built where the log is indexed.
    auto rows = std::make_shared<std::shared_ptr<FrameLogModel::PreparedRows>>();
    m_preparedRows = rows;
    m_parts.session->openReplay(path, keyPath,
                                [rows](const FrameLogReader& index) { *rows = FrameLogModel::prepareRows(index); });
    // Shown now, saying the log is being opened (a long log takes seconds):
    // their new layouts are then done and painted before the log comes, not
    // together with it or with the replay's start.
    m_parts.controls->showOpening();
    m_parts.controls->setPaused(false);
    m_parts.controls->show();
}

void ReplayBinding::indexed(const QString& path)
{
    FrameLogModel* model = m_parts.logModel;
    model->setLogKey(m_parts.session->logKey());
    const auto prepared = std::exchange(m_preparedRows, {});
    model->showLog(m_parts.session->takeReplayIndex(), path, prepared ? *prepared : nullptr);
    const int rows = model->rowCount();
    model->setPlayedRows(0);
    m_parts.controls->setRange(rows ? model->utcMicros(0) : 0, rows ? model->utcMicros(rows - 1) : 0);
    m_parts.controls->setPaused(false);
    m_parts.controls->show();
    m_parts.menus->setReplayPausable(true);
}

void ReplayBinding::setPaused(bool paused)
{
    if (!m_parts.session->replay())
        return;
    m_parts.session->setReplayPaused(paused);
    m_parts.controls->setPaused(paused);
}

void ReplayBinding::setSpeed(double speed)
{
    m_parts.controls->setSpeed(speed);
    m_parts.session->setReplaySpeed(speed);
}

void ReplayBinding::follow(const ReplayLink* replay)
{
    m_parts.controls->show();
    connect(replay, &ReplayLink::positionChanged, this, [this](qint64 utc, int next) {
        m_parts.logModel->setPlayedRows(next);
        m_parts.controls->setPosition(utc);
        m_parts.status->setReplayTime(utc);
        m_parts.overview->setReplayTime(utc);
        if (m_parts.logView->isFollowing() && next > 0)
            m_parts.logView->scrollToSourceRow(next - 1);
    });
    connect(replay, &ReplayLink::stateChanged, this, [this](ReplayLink::State state) {
        m_parts.controls->setPaused(state == ReplayLink::State::Paused);
        m_parts.controls->setFinished(state == ReplayLink::State::Finished);
    });
    connect(replay, &ReplayLink::endOfLog, this, [this] {
        m_notices.flash(tr("Replay: end of the frame log"));
        emit finished();
    });
}

void ReplayBinding::hide()
{
    m_parts.controls->hide();
    m_parts.menus->setReplayPausable(false);
}
