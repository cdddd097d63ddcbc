#include "link/session/LinkController.h"

#include "codec/secure/SecureCodec.h"

#include <QDeadlineTimer>
#include <QMetaMethod>

LinkController::LinkController(std::unique_ptr<Link> link, std::unique_ptr<FrameLog> log, LinkWorker::Options options,
                               QObject* parent)
    : LinkEvents(parent),
      m_thread(new QThread),
      m_worker(new LinkWorker(std::move(link), std::move(log), std::move(options))),
      m_clock(m_worker->sharedClock()),
      m_interval(m_worker->options().interval),
      m_firstMessageId(m_worker->options().secure ? m_worker->options().secure->counter->peek()
                                                  : m_worker->options().firstMessageId % LinkWorker::kMessageIdModulus)
{
    LinkWorker::registerMetaTypes();
    m_thread->setObjectName(QStringLiteral("link"));
    m_worker->moveToThread(m_thread);
    // Deleted in its own thread, where its sockets and timers live; QThread
    // runs deferred deletes posted from finished() before it ends.
    connect(m_thread, &QThread::finished, m_worker, &QObject::deleteLater);
    // Connected first, so that anyone told of new statistics finds them in
    // statistics() already.
    connect(this, &LinkEvents::statisticsChanged, this,
            [this](const LinkStatistics& statistics) { m_statistics = statistics; });
    // Worker to GUI, every signal of LinkEvents: queued by thread affinity.
    const QMetaObject& events = LinkEvents::staticMetaObject;
    for (int i = events.methodOffset(); i < events.methodCount(); ++i) {
        const QMetaMethod signal = events.method(i);
        if (signal.methodType() == QMetaMethod::Signal)
            connect(m_worker, signal, this, signal);
    }
    m_thread->start();
}

LinkController::~LinkController()
{
    // No stop() first: a call queued now may never run once the loop is told
    // to quit. The worker's deletion in its own thread closes the link.
    m_thread->quit();
    // Connected before waiting, so that a thread that ends just after the
    // wait gave up still deletes itself; a thread that ended in time is
    // deleted here, and its queued deleteLater() with it.
    connect(m_thread, &QThread::finished, m_thread, &QObject::deleteLater);
    if (m_thread->wait(QDeadlineTimer(kJoinTimeout))) {
        delete m_thread;
        return;
    }
    // A transport stuck in the kernel (a serial driver that does not return
    // from close) must not freeze the console: the thread is let go, to
    // delete itself (and the worker) whenever it does end.
    qWarning("LinkController: waited %lld ms for the link thread to close its transport and end; it has not, "
             "going on without it",
             static_cast<long long>(kJoinTimeout.count()));
}

void LinkController::retire(std::unique_ptr<LinkController> controller, QObject* keeper)
{
    LinkController* retired = controller.release();
    retired->setParent(keeper);
    const QMetaObject& events = LinkEvents::staticMetaObject;
    const QMetaMethod errors = QMetaMethod::fromSignal(&LinkEvents::errorOccurred);
    const QMetaMethod status = QMetaMethod::fromSignal(&LinkEvents::transportStatusChanged);
    for (int i = events.methodOffset(); i < events.methodCount(); ++i) {
        const QMetaMethod signal = events.method(i);
        if (signal.methodType() == QMetaMethod::Signal && signal != errors && signal != status)
            QObject::disconnect(retired, signal, nullptr, QMetaMethod());
    }
    connect(retired->m_thread, &QThread::finished, retired, &QObject::deleteLater);
    // One queued call, so that the quit cannot overtake the stop.
    QMetaObject::invokeMethod(
        retired->m_worker,
        [worker = retired->m_worker] {
            worker->stop();
            worker->thread()->quit();
        },
        Qt::QueuedConnection);
}

void LinkController::start()
{
    QMetaObject::invokeMethod(m_worker, &LinkWorker::start, Qt::QueuedConnection);
}

void LinkController::stop()
{
    QMetaObject::invokeMethod(m_worker, &LinkWorker::stop, Qt::QueuedConnection);
}

void LinkController::setCommand(const rcm::Message& command, bool withPlanSections)
{
    QMetaObject::invokeMethod(
        m_worker, [worker = m_worker, command, withPlanSections] { worker->setCommand(command, withPlanSections); },
        Qt::QueuedConnection);
}
