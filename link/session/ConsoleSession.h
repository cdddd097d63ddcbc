#pragma once

// One operator session's link, whichever feeds the console: a live link over
// serial or UDP, a rehearsal against the simulated aircraft (uasim) on
// loopback, a frame log replayed, or another station's session observed
// read only (an Observation, from a broker). It owns each one's lifetime, from
// connect or open to stop, with its key and its frame log, and it does the
// slow parts off the GUI thread: opening the key file (two fsyncs), creating
// the session's frame log and indexing a log for replay. Their results come
// back as signals. It has no widgets: the console binds its own to it, and
// tests drive it without a window.
//
// Each action that starts a link (connectWith, startRehearsal, openReplay,
// observe) is one call that replaces whatever link runs, so that a console can ask
// before calling one while isActive().

#include "codec/message/Airframe.h"
#include "codec/message/Message.h"
#include "link/framelog/FrameLogReader.h"
#include "link/replay/ReplayLink.h"
#include "link/session/CommandHold.h"
#include "link/session/LinkController.h"
#include "link/session/LinkSettings.h"
#include "link/session/LinkStatistics.h"
#include "link/session/LinkWorker.h"
#include "link/session/Observation.h"
#include "link/session/RehearsalLauncher.h"
#include "link/session/StationControl.h"

#include <QList>
#include <QObject>
#include <QPointer>

#include <chrono>
#include <functional>
#include <memory>
#include <optional>

namespace rcm {
class LogKey;
}
namespace rcm::secure {
class SecureCodec;
struct SecureEndpoint;
}

class ConsoleSession : public QObject {
    Q_OBJECT

public:
    // What feeds the console: the link running or being started.
    enum class Kind { None, Live, Rehearsal, Replay, Observation };
    Q_ENUM(Kind)

    // Wraps each transport before it goes to the worker (the console's voice
    // beside the commands, under the link's key when it has one: null for
    // the plain link); unset, the transport goes as it is.
    using LinkWrapper =
        std::function<std::unique_ptr<Link>(std::unique_ptr<Link>, const rcm::secure::SecureEndpoint* key)>;
    // Completes the worker's options for each link, the secure endpoint set
    // already (the flight plan upload's BLOCK 2 hooks, sized for that link).
    using OptionsFilter = std::function<LinkWorker::Options(LinkWorker::Options)>;

    // Live sessions keep their frame log in `frameLogDirectory`. Every link
    // runs on `clock` (its cadence, timeouts, time stamps, replay pace and
    // the frame log's name): null is the SystemClock; tests pass a VirtualClock.
    explicit ConsoleSession(const QString& frameLogDirectory, QObject* parent = nullptr,
                            std::shared_ptr<Clock> clock = nullptr);
    // Stops the link (the link thread's join is bounded) and uasim.
    ~ConsoleSession() override;

    // What the session's links run on, for what follows them (the broker's
    // clients and feeds, the event log).
    const std::shared_ptr<Clock>& clock() const { return m_clock; }

    void setLinkWrapper(LinkWrapper wrapper) { m_wrapLink = std::move(wrapper); }
    void setOptionsFilter(OptionsFilter filter) { m_filterOptions = std::move(filter); }

    // Of the link running; None when none runs.
    Kind kind() const { return m_kind; }
    // Of the link being started (a key or log opening, a log being indexed,
    // uasim starting); None when none is.
    Kind preparing() const { return m_preparing; }
    // A link to an aircraft, real or simulated, runs or is being started:
    // what the console asks about before replacing it (a replay is not one).
    bool isLive() const
    {
        const auto live = [](Kind k) { return k == Kind::Live || k == Kind::Rehearsal; };
        return live(m_kind) || live(m_preparing);
    }
    // A link runs (its thread does; it may be waiting for the far end). Not
    // an observation, which has no link of this console's.
    bool isRunning() const { return m_controller != nullptr; }
    // A link runs or is being started: what a new action would replace.
    bool isActive() const { return m_kind != Kind::None || m_preparing != Kind::None; }
    // The link running, or null; for connecting to its signals.
    const LinkController* controller() const { return m_controller.get(); }
    // The replay running, or null: it lives in the link thread, so connect
    // to its signals only and steer it with the replay slots below.
    const ReplayLink* replay() const { return m_replay.data(); }
    // The observation running, or null; for connecting to its signals.
    const Observation* observation() const { return m_observation; }
    // Statistics of the running link; the default ones when none runs.
    LinkStatistics statistics() const;
    // One datagram a frame (UDP, rehearsal, replay), or a serial stream.
    bool isDatagram() const { return m_datagram; }
    // "UDP 127.0.0.1:5600", "replay of day.pcapng"; empty when none runs.
    QString description() const { return m_description; }
    // The running live session's frame log; empty for a replay, or when it could not be created.
    QString sessionLogPath() const { return m_sessionLogPath; }
    // The running link's key, "" for the plain link.
    QString keyFingerprint() const { return m_keyFingerprint; }
    QString frameLogDirectory() const { return m_frameLogDirectory; }
    bool isReplayPaused() const { return m_replayPaused; }

    // openReplay(), and `alsoOffThread` runs with the index in the thread
    // that built it, before replayIndexed(): what a view builds from a day's
    // index (its rows) is then not built on the GUI thread either.
    void openReplay(const QString& path, const QString& keyPath,
                    std::function<void(const FrameLogReader&)> alsoOffThread);
    // The index of the log opened for replay, for a log view, after
    // replayIndexed(): handed over once, null after that.
    std::unique_ptr<FrameLogReader> takeReplayIndex() { return std::move(m_replayIndex); }
    // Stops the running link and shows `observation` instead, read only, as
    // `description`; its keyed frames are read with `keys` (the observed
    // aircraft's link keys, any of them), logKey() is the first. Nothing is
    // sent. It runs until stop() or the next action.
    void observe(std::unique_ptr<Observation> observation, const QString& description,
                 const QList<std::shared_ptr<const rcm::LogKey>>& keys);
    // The running link's key (or the replayed log's, or the observed
    // session's first), to read a keyed link's frames in the log with; null
    // for none. Codecs of its own: the GUI
    // thread's, not the link thread's.
    std::shared_ptr<const rcm::LogKey> logKey() const { return m_logKey; }
    // Control between stations (docs/protocol.md section 10): fed by the
    // status frames of a live link, applied to every command sent. Set its
    // station to follow control; hand over and take control through it.
    StationControl* stationControl() const { return m_control; }
    // Whether the frames carry the command or hold it back until the
    // operator resumes: held on every new link, after a loss when the
    // aircraft's report differs, on another airframe, when given control.
    const CommandHold* commandHold() const { return m_hold; }
    bool commanding() const { return !m_hold->holding(); }
    // The command as the console holds it (its panels'), sent or held.
    const std::optional<rcm::Message>& command() const { return m_command; }
    // What starts uasim for a rehearsal, to set it up (its voice) before startRehearsal().
    RehearsalLauncher* rehearsalLauncher() const { return m_rehearsal; }

    // As connectWith(), with a transport made by the caller (in tests, one
    // end of an in-process link to a simulated aircraft), described for
    // people as `description`. Not a slot: moc cannot pass a unique_ptr.
    void connectLink(std::unique_ptr<Link> link, const QString& description, const QString& keyPath = QString());

public slots:
    // Opens the key file (if the settings name one) off the GUI thread, then
    // replaces the running link with this one and a new frame log. A refused
    // key leaves the running link as it was.
    void connectWith(const LinkSettings& settings);
    // Stops the running link, checks the key file (both ends use it), starts
    // uasim for `airframe` on a free loopback port and connects to it.
    void startRehearsal(const rcm::Airframe& airframe, const QString& keyPath = QString(),
                        const QString& uasimProgram = RehearsalLauncher::defaultProgram());
    // Stops the running link, indexes the log off the GUI thread, then plays
    // it; with `keyPath`, a keyed session's log, deciphered with that key
    // (opened off the GUI thread too, its replay state left alone).
    void openReplay(const QString& path, const QString& keyPath = QString()) { openReplay(path, keyPath, {}); }
    // Stops whatever runs or is being started; uasim too. A link's thread
    // ends later, on its own (a modem's hang-up takes seconds).
    void stop();
    // Waits for the links stop() ended to finish closing, each at most
    // LinkController::kJoinTimeout. Their threads call the hooks passed in
    // (setLinkWrapper(), setOptionsFilter(): the flight plan upload's BLOCK 2
    // source and reply) until they end, so whoever owns what those hooks
    // call joins them before it goes.
    void joinStoppedLinks();

    // The state to command, now and for every link started later.
    void setCommand(const rcm::Message& command);
    // Holds the command back from now on (another airframe is being
    // loaded): the next status frame is adopted, as on a new link.
    void holdCommand(CommandHold::Reason reason);
    // The operator confirmed: the frames carry the command from the next one
    // on. Following control, this station must be the one the aircraft names
    // in control: its Take control is sent with it. False, with the reason
    // for people, when it cannot resume.
    bool resumeCommanding(QString* whyNot = nullptr);

    void setReplayPaused(bool paused);
    // 0.25 to 10 times the logged pace; kept for the next replay.
    void setReplaySpeed(double speed);
    void seekReplay(qint64 utcMicros);

signals:
    // A link is being prepared; what happens, for people ("Starting uasim…").
    void starting(const QString& what);
    // The link is made and starts at once: connect to the controller (and
    // to replay() for a replay) in the slot, before its first signal.
    void linkStarted(const LinkController* controller);
    // The link ended: by stop(), or replaced by another one.
    void linkStopped();
    // An observation starts: connect to it in the slot, before it says anything.
    void observationStarted(const Observation* observation);
    // The observation ended: by stop(), or replaced by a link.
    void observationStopped();
    // A replay or an observation, read only: each frame's time as it comes
    // and, for a frame the station sent that reads exactly through the
    // receive path for logged frames (with the session's key when keyed),
    // what it commanded; nothing for any other frame.
    void loggedCommand(qint64 utcMicros, const std::optional<rcm::Message>& commanded);
    // An action did not start its link; the reason for people, naming the
    // file, port or program. Nothing was replaced.
    void failed(const QString& reason);
    // The link starts, but something is amiss: no frame log for the session,
    // a replayed log damaged part-way.
    void warning(const QString& message);
    // Something for the event log alone: the simulated aircraft ended, and
    // its link stays open to be lost as a real aircraft's would be.
    void notice(const QString& message);
    // A log opened for replay is indexed; takeReplayIndex() has it.
    void replayIndexed(const QString& path);
    // The aircraft's report became the command (the first status frame of a
    // hold that adopts it): command() holds it; the panels show it.
    void commandAdopted(const rcm::Message& command);
    // What happened to the command's hold, for the event log: held, resumed,
    // the report adopted and how it differed.
    void commandEvent(const QString& text);

private:
    struct Opened;
    // Runs `work` in the thread pool and `done` back in this thread, unless
    // another action came in meanwhile.
    void offThread(std::function<void()> work, std::function<void()> done);
    // Opens the key and, with `keepLog`, a frame log off the GUI thread, then starts `link`.
    // The key is `key` when given, else opened from `keyPath` (none when empty).
    void prepare(std::unique_ptr<Link> link, Kind kind, const QString& description, const QString& keyPath,
                 std::shared_ptr<rcm::secure::SecureEndpoint> key = nullptr);
    void startController(std::unique_ptr<Link> link, Kind kind, const QString& description, Opened& opened);
    void stopController();
    void stopObservation();
    // Each sent frame of the replay, read in the link thread as it plays.
    void readReplayedCommands(ReplayLink* replay, quint64 request);
    // Plays the log indexed for `request`, unless another action came in since.
    void startReplay(const QString& path, quint64 request, std::shared_ptr<Opened> opened);
    void rehearsalReady(quint16 port);
    void rehearsalFailed(const QString& reason);
    // The command as control wants it named, to the running link; its
    // header alone while it is held.
    void sendCommand();
    // A status frame delivered on the live link.
    void statusReceived(const rcm::Message& status);
    void hold(CommandHold::Reason reason, bool adopt);

    QString m_frameLogDirectory;
    std::shared_ptr<Clock> m_clock;
    LinkWrapper m_wrapLink;
    OptionsFilter m_filterOptions;
    RehearsalLauncher* m_rehearsal;
    StationControl* m_control;
    CommandHold* m_hold;
    // The link came back: the next status frame says whether the command
    // still agrees with the aircraft.
    bool m_checkAfterRegain = false;
    std::unique_ptr<LinkController> m_controller;
    Observation* m_observation = nullptr;                           // a child, deleted later once stopped
    std::vector<const rcm::secure::SecureCodec*> m_observedCodecs;  // of m_observedKeys
    QList<std::shared_ptr<const rcm::LogKey>> m_observedKeys;
    std::unique_ptr<Link> m_preparedLink;  // the transport waiting for its key and log
    QPointer<ReplayLink> m_replay;  // lives in the link thread; only queued calls
    std::unique_ptr<FrameLogReader> m_replayIndex;
    std::shared_ptr<const rcm::LogKey> m_logKey;
    std::shared_ptr<rcm::secure::SecureEndpoint> m_rehearsalKey;  // the console's end, while uasim starts
    std::optional<rcm::Message> m_command;
    Kind m_kind = Kind::None;
    Kind m_preparing = Kind::None;
    quint64 m_request = 0;  // the action whose off-thread work counts; bumped by each action
    QString m_description;
    QString m_sessionLogPath;
    QString m_keyFingerprint;
    double m_replaySpeed = 1.0;
    bool m_replayPaused = false;
    bool m_datagram = true;
    std::chrono::milliseconds m_preparedDelay{0};  // the live link being prepared: its one-way delay
};
