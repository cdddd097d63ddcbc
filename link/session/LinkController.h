#pragma once

// The GUI side of one link: runs a LinkWorker in a thread of its own and
// relays to it with queued calls. It does no I/O and never waits on the link,
// except for the thread's end when destroyed, and that for a bounded time.
//
// It says, in the GUI thread, everything the worker says (LinkEvents), each
// signal forwarded as it is, none of them named here.

#include "codec/message/Message.h"
#include "link/session/LinkEvents.h"
#include "link/session/LinkStatistics.h"
#include "link/session/LinkWorker.h"

#include <QObject>
#include <QThread>

#include <chrono>
#include <memory>

class LinkController : public LinkEvents {
    Q_OBJECT

public:
    // How long the destructor waits for the link thread to end before it
    // gives up on it (and says so): closing a port or a socket takes far
    // less; a modem's hang-up about 2 s, at most ModemLink::hangUpBound(), 6 s.
    static constexpr std::chrono::milliseconds kJoinTimeout{6000};

    // The link and the log move to the worker's thread with the worker; the
    // caller keeps no access to them (Link::description() and friends are
    // for the worker's thread). The thread starts now; the link opens on start().
    explicit LinkController(std::unique_ptr<Link> link, std::unique_ptr<FrameLog> log = {},
                            LinkWorker::Options options = {}, QObject* parent = nullptr);
    // Stops the link and waits, at most kJoinTimeout, for the thread to finish.
    ~LinkController() override;

    // Ends the link without waiting for it: the worker stops and closes the
    // link in its thread (a modem hangs up there, which takes seconds), the
    // thread ends, and the controller deletes itself. Until then it says
    // only errorOccurred() and transportStatusChanged() (the hang-up's own
    // words); `keeper` owns it meanwhile, so that it is joined, bounded, when
    // the keeper goes first.
    static void retire(std::unique_ptr<LinkController> controller, QObject* keeper);

    LinkController(const LinkController&) = delete;
    LinkController& operator=(const LinkController&) = delete;

    // The latest statistics received from the worker.
    const LinkStatistics& statistics() const { return m_statistics; }
    // The clock the worker stamps its frames on (its utcMicros() may be read
    // from any thread): what the console's preview of the next frame uses.
    const std::shared_ptr<Clock>& clock() const { return m_clock; }
    // The worker's tick interval.
    std::chrono::milliseconds interval() const { return m_interval; }
    // ID_msg of the worker's first frame: Options::firstMessageId, or on a
    // keyed link the send counter's next ID, read before the worker started.
    std::uint32_t firstMessageId() const { return m_firstMessageId; }

public slots:
    void start();
    void stop();
    // Copied and queued: the worker picks it up for its next frame (see
    // LinkWorker::setCommand).
    void setCommand(const rcm::Message& command, bool withPlanSections = true);

private:
    QThread* m_thread;     // owned; let go, to delete itself, if it will not end in time
    LinkWorker* m_worker;  // lives in m_thread, deleted there when it finishes
    std::shared_ptr<Clock> m_clock;
    std::chrono::milliseconds m_interval;
    std::uint32_t m_firstMessageId;
    LinkStatistics m_statistics;
};
