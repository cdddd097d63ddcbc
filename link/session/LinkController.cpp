#include "link/session/LinkController.h"

LinkController::LinkController(std::unique_ptr<Link> link, std::unique_ptr<FrameLog> log, LinkWorker::Options options,
                               QObject* parent)
    : QObject(parent), m_worker(new LinkWorker(std::move(link), std::move(log), std::move(options)))
{
    LinkWorker::registerMetaTypes();
    m_thread.setObjectName(QStringLiteral("link"));
    m_worker->moveToThread(&m_thread);
    // Deleted in its own thread, where its sockets and timers live; QThread
    // runs deferred deletes posted from finished() before it ends.
    connect(&m_thread, &QThread::finished, m_worker, &QObject::deleteLater);

    // Worker to GUI: queued by thread affinity.
    connect(m_worker, &LinkWorker::started, this, &LinkController::started);
    connect(m_worker, &LinkWorker::stopped, this, &LinkController::stopped);
    connect(m_worker, &LinkWorker::messageReceived, this, &LinkController::messageReceived);
    connect(m_worker, &LinkWorker::frameSent, this, &LinkController::frameSent);
    connect(m_worker, &LinkWorker::frameLogged, this, &LinkController::frameLogged);
    connect(m_worker, &LinkWorker::statisticsChanged, this, [this](const LinkStatistics& statistics) {
        m_statistics = statistics;
        emit statisticsChanged(statistics);
    });
    connect(m_worker, &LinkWorker::stateChanged, this, &LinkController::stateChanged);
    connect(m_worker, &LinkWorker::linkLost, this, &LinkController::linkLost);
    connect(m_worker, &LinkWorker::linkRegained, this, &LinkController::linkRegained);
    connect(m_worker, &LinkWorker::errorOccurred, this, &LinkController::errorOccurred);
    connect(m_worker, &LinkWorker::commandRejected, this, &LinkController::commandRejected);

    m_thread.start();
}

LinkController::~LinkController()
{
    // No stop() first: a call queued now may never run once the loop is told
    // to quit. The worker's deletion in its own thread closes the link.
    m_thread.quit();
    m_thread.wait();
}

void LinkController::start()
{
    QMetaObject::invokeMethod(m_worker, &LinkWorker::start, Qt::QueuedConnection);
}

void LinkController::stop()
{
    QMetaObject::invokeMethod(m_worker, &LinkWorker::stop, Qt::QueuedConnection);
}

void LinkController::setCommand(const rcm::Message& command)
{
    QMetaObject::invokeMethod(
        m_worker, [worker = m_worker, command] { worker->setCommand(command); }, Qt::QueuedConnection);
}
