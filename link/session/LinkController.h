#pragma once

// The GUI side of one link: runs a LinkWorker in a thread of its own and
// relays between them with queued calls and signals. It does no I/O and
// never waits on the link, except for the thread's end when destroyed.

#include "codec/message/Message.h"
#include "link/session/LinkStatistics.h"
#include "link/session/LinkWorker.h"
#include "link/session/ReceivedMessage.h"

#include <QObject>
#include <QThread>

#include <memory>

class LinkController : public QObject {
    Q_OBJECT

public:
    // The link and the log move to the worker's thread with the worker; the
    // caller keeps no access to them (Link::description() and friends are
    // for the worker's thread). The thread starts now; the link opens on start().
    explicit LinkController(std::unique_ptr<Link> link, std::unique_ptr<FrameLog> log = {},
                            LinkWorker::Options options = {}, QObject* parent = nullptr);
    // Stops the link and waits for the thread to finish.
    ~LinkController() override;

    LinkController(const LinkController&) = delete;
    LinkController& operator=(const LinkController&) = delete;

    // The latest statistics received from the worker.
    const LinkStatistics& statistics() const { return m_statistics; }

public slots:
    void start();
    void stop();
    // Copied and queued: the worker picks it up for its next frame.
    void setCommand(const rcm::Message& command);

signals:
    void started();
    void stopped();
    void messageReceived(const ReceivedMessage& received);
    void frameSent(quint32 messageId);
    // LinkWorker::frameLogged, queued to this thread: one per frame logged.
    void frameLogged(const LoggedFrame& frame);
    void statisticsChanged(const LinkStatistics& statistics);
    void stateChanged(LinkState state);
    void linkLost();
    void linkRegained();
    void errorOccurred(const QString& message);
    void commandRejected(const QString& reasons);

private:
    QThread m_thread;
    LinkWorker* m_worker;  // lives in m_thread, deleted there when it finishes
    LinkStatistics m_statistics;
};
