#include "link/session/ConsoleSession.h"

#include "codec/receive/LoggedFrameReading.h"
#include "codec/secure/SecureCodec.h"
#include "link/framelog/FrameLog.h"

#include "codec/message/TextFormat.h"

#include <QDateTime>
#include <QDir>
#include <QFileInfo>
#include <QTimer>
#include <QtConcurrent/QtConcurrentRun>

// What the off-thread part of starting a link opened, for this thread to
// take once it is done: the thread pool writes it, then this thread reads it.
struct ConsoleSession::Opened {
    std::shared_ptr<rcm::secure::SecureEndpoint> key;
    std::shared_ptr<const rcm::LogKey> logKey;  // the same key's codecs for the GUI thread
    QString keyError;
    std::unique_ptr<FrameLog> log;
    QString logPath;
    QString logError;
};

namespace {

// The console's end of the secure link, its time window on `clock`; null
// with `error` set when refused. `persistState` false for a replay: its
// frames were checked for replays when they were live, and replaying them
// must not touch that state.
std::shared_ptr<rcm::secure::SecureEndpoint> openKey(const QString& keyPath, const std::shared_ptr<Clock>& clock,
                                                     QString* error, bool persistState = true)
{
    std::string reason;
    rcm::secure::SecureEndpoint::Options options;
    options.persistState = persistState;
    options.clock = [clock] { return clock->utcMicros() / 1'000'000; };
    std::shared_ptr<rcm::secure::SecureEndpoint> endpoint = rcm::secure::SecureEndpoint::open(
        QDir::fromNativeSeparators(keyPath).toStdString(), rcm::secure::Direction::GcsToUa, reason, options);
    // The reason names the file and the fix ("run: chmod 600 ..."); it never holds key bytes.
    if (!endpoint)
        *error = QString::fromStdString(reason);
    return endpoint;
}

QString keyRefused(const QString& reason)
{
    return ConsoleSession::tr("Not connected: the key file is refused: %1").arg(reason);
}

// What a frame the station sent commanded, as its log holds it: read
// through the receive path for logged frames, and only when exact (and
// authentic, keyed). A keyed session's frame without its key reads as
// nothing rather than as noise.
std::optional<rcm::Message> commandIn(const QByteArray& bytes, bool enciphered,
                                      const std::vector<const rcm::secure::SecureCodec*>& codecs)
{
    const auto frame = std::span(reinterpret_cast<const std::uint8_t*>(bytes.constData()), std::size_t(bytes.size()));
    rcm::LoggedFrameReading reading = rcm::readLoggedFrame(frame, enciphered, codecs);
    if (!reading.read())
        return std::nullopt;
    return std::move(reading.decoded.message);
}

const std::vector<const rcm::secure::SecureCodec*>& codecsOf(const rcm::LogKey* key)
{
    static const std::vector<const rcm::secure::SecureCodec*> none;
    return key ? key->codecs() : none;
}

}  // namespace

ConsoleSession::ConsoleSession(const QString& frameLogDirectory, QObject* parent, std::shared_ptr<Clock> clock)
    : QObject(parent),
      m_frameLogDirectory(frameLogDirectory),
      m_clock(clock ? std::move(clock) : std::make_shared<SystemClock>()),
      m_rehearsal(new RehearsalLauncher(this)),
      m_control(new StationControl(this)),
      m_hold(new CommandHold(this))
{
    LinkWorker::registerMetaTypes();
    connect(m_control, &StationControl::headerChanged, this, &ConsoleSession::sendCommand);
    connect(m_control, &StationControl::roleChanged, this, [this](StationControl::Role role) {
        using Role = StationControl::Role;
        if (role == Role::Offered && !(m_hold->holding() && m_hold->reason() == CommandHold::Reason::NewLink &&
                                       !m_hold->reportHeard()))
            hold(CommandHold::Reason::ControlGiven, true);
        else if ((role == Role::Backup || role == Role::Observing || role == Role::HandingOver) && commanding())
            hold(CommandHold::Reason::NotInControl, true);
    });
    connect(m_rehearsal, &RehearsalLauncher::ready, this, &ConsoleSession::rehearsalReady);
    connect(m_rehearsal, &RehearsalLauncher::failed, this, &ConsoleSession::rehearsalFailed);
}

ConsoleSession::~ConsoleSession()
{
    stop();
    // Now, not among the children QObject deletes after the members: a
    // replay's thread posts to this session until it ends.
    joinStoppedLinks();
}

LinkStatistics ConsoleSession::statistics() const
{
    return m_controller ? m_controller->statistics() : LinkStatistics();
}

void ConsoleSession::offThread(std::function<void()> work, std::function<void()> done)
{
    const quint64 request = ++m_request;
    // With `this` as the context, `done` runs in this thread, and not at all
    // once this is gone; the work touches only what it captured. Work that
    // is over before then() is called would have `done` run inside the
    // action's own call: posted instead, it always comes from the event loop.
    QtConcurrent::run(std::move(work)).then(this, [this, request, done = std::move(done)] {
        QMetaObject::invokeMethod(
            this,
            [this, request, done] {
                if (request == m_request)
                    done();
            },
            Qt::QueuedConnection);
    });
}

void ConsoleSession::connectWith(const LinkSettings& settings)
{
    QString error;
    std::unique_ptr<Link> link = settings.createLink(&error, m_clock);
    if (!link) {
        emit failed(error);
        return;
    }
    // The running link goes on until the key is accepted.
    m_preparedDelay = settings.oneWayDelay();
    prepare(std::move(link), Kind::Live, settings.summary(), settings.keyPath);
}

void ConsoleSession::connectLink(std::unique_ptr<Link> link, const QString& description, const QString& keyPath)
{
    m_preparedDelay = std::chrono::milliseconds(0);
    prepare(std::move(link), Kind::Live, description, keyPath);
}

void ConsoleSession::startRehearsal(const rcm::Airframe& airframe, const QString& keyPath,
                                    const QString& uasimProgram)
{
    stop();
    m_preparing = Kind::Rehearsal;
    // The key is checked before uasim starts, so that a refused key file is
    // the console's message and not uasim's exit code.
    auto key = std::make_shared<std::shared_ptr<rcm::secure::SecureEndpoint>>();
    auto error = std::make_shared<QString>();
    offThread(
        [keyPath, key, error, clock = m_clock] {
            if (!keyPath.isEmpty())
                *key = openKey(keyPath, clock, error.get());
        },
        [this, airframe, keyPath, uasimProgram, key, error] {
            if (!error->isEmpty()) {
                m_preparing = Kind::None;
                emit failed(keyRefused(*error));
                return;
            }
            m_rehearsalKey = *key;
            emit starting(tr("Starting uasim\u2026"));
            // ready() connects; failed() says why not.
            m_rehearsal->start(airframe, uasimProgram, QDir::fromNativeSeparators(keyPath));
        });
}

void ConsoleSession::rehearsalReady(quint16 port)
{
    LinkSettings s;
    s.transport = LinkSettings::Transport::Udp;
    s.localAddress = QStringLiteral("127.0.0.1");
    s.localPort = 0;
    s.remoteAddress = QStringLiteral("127.0.0.1");
    s.remotePort = port;
    prepare(s.createLink(nullptr, m_clock), Kind::Rehearsal, tr("rehearsal with uasim on %1:%2").arg(s.remoteAddress).arg(port),
            QString(), m_rehearsalKey);
}

void ConsoleSession::rehearsalFailed(const QString& reason)
{
    if (m_kind == Kind::Rehearsal && m_preparing == Kind::None && isRunning() && m_rehearsal->isConfirmed()) {
        // The aircraft answered, then went: killed, crashed or ended. That is
        // the aircraft falling silent, which the link's silence timeout turns
        // into the link-loss alarm with its counts, as for a real one; the
        // link is not stopped under the operator.
        emit notice(tr("The simulated aircraft ended (%1): the link stays open, and is lost as a real "
                       "aircraft's would be")
                        .arg(reason));
        return;
    }
    m_rehearsalKey.reset();
    if (m_kind == Kind::Rehearsal || m_preparing == Kind::Rehearsal)
        stop();
    emit failed(tr("Rehearsal: %1").arg(reason));
}

void ConsoleSession::openReplay(const QString& path, const QString& keyPath,
                                std::function<void(const FrameLogReader&)> alsoOffThread)
{
    stop();
    m_preparing = Kind::Replay;
    // Constructed here, indexed in the pool (a day's log is 86,400 records),
    // read here afterwards.
    auto reader = std::make_shared<std::unique_ptr<FrameLogReader>>(std::make_unique<FrameLogReader>());
    auto complete = std::make_shared<bool>(false);
    auto opened = std::make_shared<Opened>();
    offThread(
        [path, keyPath, reader, complete, opened, clock = m_clock, alsoOffThread = std::move(alsoOffThread)] {
            if (!keyPath.isEmpty()) {
                opened->key = openKey(keyPath, clock, &opened->keyError, false);
                if (!opened->key)
                    return;
                std::string error;
                opened->logKey = rcm::LogKey::open(QDir::fromNativeSeparators(keyPath).toStdString(), error);
            }
            *complete = (*reader)->open(path);
            if (alsoOffThread && (*reader)->count() > 0)
                alsoOffThread(**reader);
        },
        [this, path, reader, complete, opened] {
            if (!opened->keyError.isEmpty()) {
                m_preparing = Kind::None;
                emit failed(keyRefused(opened->keyError));
                return;
            }
            std::unique_ptr<FrameLogReader> index = std::move(*reader);
            if (!*complete && index->count() == 0) {
                m_preparing = Kind::None;
                emit failed(tr("Cannot open the frame log: %1").arg(index->errorString()));
                return;
            }
            const QString damage = *complete ? QString() : index->errorString();
            m_replayIndex = std::move(index);
            m_logKey = opened->logKey;
            emit replayIndexed(path);
            if (!damage.isEmpty())
                emit warning(tr("The frame log is damaged part-way; replaying what comes before: %1").arg(damage));
            // In a pass of the event loop of its own, so that showing a
            // day's index and starting the link are two short stalls,
            // not one long one. A timer, not a queued call: Qt delivers a
            // call queued now in the same sweep of posted events as the
            // repaint of the index, before any input or timer in between.
            QTimer::singleShot(1, this,
                               [this, path, request = m_request, opened] { startReplay(path, request, opened); });
        });
}

void ConsoleSession::startReplay(const QString& path, quint64 request, std::shared_ptr<Opened> opened)
{
    if (request != m_request)
        return;
    m_preparing = Kind::None;
    auto replay = std::make_unique<ReplayLink>(path, m_clock);
    replay->setSpeed(m_replaySpeed);
    m_replayPaused = false;
    m_replay = replay.get();
    readReplayedCommands(replay.get(), request);
    connect(replay.get(), &ReplayLink::stateChanged, this,
            [this](ReplayLink::State state) { m_replayPaused = state == ReplayLink::State::Paused; });
    opened->log.reset();  // a replay writes no log of its own
    startController(std::move(replay), Kind::Replay, tr("replay of %1").arg(QFileInfo(path).fileName()), *opened);
}

void ConsoleSession::readReplayedCommands(ReplayLink* replay, quint64 request)
{
    // In the link thread, as each record plays: the session hears of every
    // record (its time) before the worker's report of the same frame.
    connect(
        replay, &ReplayLink::frameReplayed, replay,
        [this, request, key = m_logKey](const FrameRecord& record) {
            std::optional<rcm::Message> commanded;
            if (record.direction == FrameDirection::Sent)
                commanded = commandIn(record.bytes, record.enciphered, codecsOf(key.get()));
            QMetaObject::invokeMethod(
                this,
                [this, request, utc = record.utcMicros, commanded] {
                    if (request == m_request)  // else the replay ended meanwhile
                        emit loggedCommand(utc, commanded);
                },
                Qt::QueuedConnection);
        },
        Qt::DirectConnection);
}

void ConsoleSession::observe(std::unique_ptr<Observation> observation, const QString& description,
                             const QList<std::shared_ptr<const rcm::LogKey>>& keys)
{
    stop();
    m_observation = observation.release();
    m_observation->setParent(this);
    m_observedKeys = keys;
    m_observedCodecs.clear();
    for (const std::shared_ptr<const rcm::LogKey>& key : keys)
        m_observedCodecs.insert(m_observedCodecs.end(), key->codecs().begin(), key->codecs().end());
    m_kind = Kind::Observation;
    m_description = description;
    m_logKey = keys.isEmpty() ? nullptr : keys.front();
    m_keyFingerprint = m_logKey ? QString::fromStdString(m_logKey->fingerprint()) : QString();
    connect(m_observation, &LinkEvents::frameLogged, this, [this](const LoggedFrame& frame) {
        std::optional<rcm::Message> commanded;
        if (frame.entry.direction == FrameDirection::Sent)
            commanded = commandIn(frame.bytes, frame.entry.enciphered, m_observedCodecs);
        emit loggedCommand(frame.entry.utcMicros, commanded);
    });
    emit observationStarted(m_observation);
    m_observation->start();
}

void ConsoleSession::stopObservation()
{
    if (!m_observation)
        return;
    Observation* observation = std::exchange(m_observation, nullptr);
    observation->stop();
    observation->deleteLater();
    m_kind = Kind::None;
    m_description.clear();
    m_keyFingerprint.clear();
    m_observedCodecs.clear();
    m_observedKeys.clear();
    emit observationStopped();
}

void ConsoleSession::prepare(std::unique_ptr<Link> link, Kind kind, const QString& description,
                             const QString& keyPath, std::shared_ptr<rcm::secure::SecureEndpoint> key)
{
    m_preparing = kind;
    m_preparedLink = std::move(link);
    auto opened = std::make_shared<Opened>();
    opened->key = std::move(key);
    opened->log = std::make_unique<FrameLog>();
    const QDateTime started = QDateTime::fromMSecsSinceEpoch(m_clock->utcMicros() / 1000, Qt::UTC);
    offThread(
        [opened, keyPath, started, clock = m_clock, directory = QDir(m_frameLogDirectory)] {
            if (!opened->key && !keyPath.isEmpty()) {
                opened->key = openKey(keyPath, clock, &opened->keyError);
                if (!opened->key)
                    return;
                std::string error;
                opened->logKey = rcm::LogKey::open(QDir::fromNativeSeparators(keyPath).toStdString(), error);
            }
            // Never over another session's log: the next free name of that second.
            constexpr int kMaxSessionsASecond = 100;
            for (int attempt = 1; attempt <= kMaxSessionsASecond; ++attempt) {
                opened->logPath = directory.filePath(FrameLog::sessionFileName(started, attempt));
                if (!QFileInfo::exists(opened->logPath))
                    break;
            }
            if (!opened->log->open(opened->logPath, &opened->logError))
                opened->log.reset();
        },
        [this, opened, kind, description] {
            m_preparing = Kind::None;
            std::unique_ptr<Link> link = std::move(m_preparedLink);
            if (!opened->keyError.isEmpty()) {
                emit failed(keyRefused(opened->keyError));
                return;
            }
            startController(std::move(link), kind, description, *opened);
        });
}

void ConsoleSession::startController(std::unique_ptr<Link> link, Kind kind, const QString& description,
                                     Opened& opened)
{
    stopController();
    if (kind != Kind::Rehearsal) {
        m_rehearsal->stop();
        m_rehearsalKey.reset();
    }
    m_kind = kind;
    m_datagram = !link->isStream();
    m_description = description;
    m_sessionLogPath = opened.log ? opened.logPath : QString();
    if (!opened.logError.isEmpty())
        emit warning(tr("No frame log for this session: %1").arg(opened.logError));
    m_keyFingerprint = opened.key ? QString::fromStdString(opened.key->fingerprint) : QString();
    m_logKey = opened.logKey;

    LinkWorker::Options options;
    options.clock = m_clock;
    options.secure = std::move(opened.key);
    // Over a satellite the first frame comes a one-way delay later than over a cable.
    options.silenceTimeout += kind == Kind::Live ? m_preparedDelay : std::chrono::milliseconds(0);
    if (m_filterOptions)
        options = m_filterOptions(std::move(options));
    if (m_wrapLink)
        link = m_wrapLink(std::move(link), options.secure.get());
    m_controller = std::make_unique<LinkController>(std::move(link), std::move(opened.log), std::move(options));
    if (kind == Kind::Rehearsal)
        // Frames came back: from now on an exit of uasim is a failure, not a port clash.
        connect(m_controller.get(), &LinkController::messageReceived, m_rehearsal, [this] { m_rehearsal->confirm(); });
    m_control->reset();
    m_hold->forgetReports();
    m_checkAfterRegain = false;
    if (kind != Kind::Replay) {
        // Nothing the panels hold goes out before the aircraft is heard and
        // the operator resumes.
        hold(CommandHold::Reason::NewLink, true);
        // Who is in control is what the aircraft says now, not what a log said.
        connect(m_controller.get(), &LinkController::messageReceived, this,
                [this](const ReceivedMessage& received) { statusReceived(received.message); });
        connect(m_controller.get(), &LinkController::linkRegained, this, [this] { m_checkAfterRegain = true; });
    }
    sendCommand();
    emit linkStarted(m_controller.get());
    m_controller->start();
}

void ConsoleSession::stopController()
{
    stopObservation();
    if (!m_controller)
        return;
    m_replay.clear();
    // The worker closes the link in its thread, and the thread ends, without
    // the GUI waiting: a modem's hang-up takes seconds.
    LinkController::retire(std::move(m_controller), this);
    m_kind = Kind::None;
    m_description.clear();
    m_sessionLogPath.clear();
    m_keyFingerprint.clear();
    m_control->reset();
    emit linkStopped();
}

void ConsoleSession::stop()
{
    ++m_request;  // what is being started is not any more
    m_preparing = Kind::None;
    m_preparedLink.reset();
    stopController();
    m_rehearsal->stop();
    m_rehearsalKey.reset();
}

void ConsoleSession::joinStoppedLinks()
{
    // The running link has no parent: the children are the links retired.
    qDeleteAll(findChildren<LinkController*>(Qt::FindDirectChildrenOnly));
}

void ConsoleSession::setCommand(const rcm::Message& command)
{
    m_command = command;
    sendCommand();
}

void ConsoleSession::sendCommand()
{
    if (!m_controller || !m_command)
        return;
    const bool held = m_hold->holding();
    rcm::Message named = held ? rcm::heldCommand(*m_command) : *m_command;
    m_control->applyTo(named);
    // A flight plan section is a command too: none while held.
    m_controller->setCommand(named, !held);
}

void ConsoleSession::hold(CommandHold::Reason reason, bool adopt)
{
    m_hold->hold(reason, adopt);
    emit commandEvent(tr("Commands held: %1; the frames carry none until the operator resumes")
                          .arg(CommandHold::reasonText(reason)));
    sendCommand();
}

void ConsoleSession::holdCommand(CommandHold::Reason reason)
{
    hold(reason, true);
}

bool ConsoleSession::resumeCommanding(QString* whyNot)
{
    using Role = StationControl::Role;
    const auto refuse = [whyNot](const QString& reason) {
        if (whyNot)
            *whyNot = reason;
        return false;
    };
    if (!m_command)
        return refuse(tr("there is no command to send"));
    if (m_control->station()) {
        switch (m_control->role()) {
            case Role::Offered:
                m_control->takeControl();
                break;
            case Role::InControl:
                break;
            case Role::Unknown:
                return refuse(tr("the aircraft has not said yet which station is in control"));
            case Role::HandingOver:
                return refuse(tr("this station is handing control over"));
            case Role::Backup:
            case Role::Observing:
                return refuse(tr("%1 is in control, not this station")
                                  .arg(QString::fromStdString(rcm::formatStation(*m_control->reportedControl()))));
        }
    }
    if (!m_hold->holding())
        return true;
    m_hold->resume();
    emit commandEvent(m_hold->reportHeard() || m_hold->lastReport()
                          ? tr("Commanding resumed: the frames carry the panels' command")
                          : tr("Commanding resumed before any report from the aircraft: the frames carry the panels' "
                               "command"));
    sendCommand();
    return true;
}

void ConsoleSession::statusReceived(const rcm::Message& status)
{
    m_control->statusReceived(status);
    if (!m_command)
        return;
    if (std::exchange(m_checkAfterRegain, false) && !m_hold->holding()) {
        // Back after a loss (an outage, a redial): the command goes on only
        // if the aircraft still does what it says.
        const std::vector<rcm::ItemChange> changes = rcm::commandChanges(*m_command, status);
        if (changes.empty())
            emit commandEvent(tr("Link back: the aircraft's report agrees with the command; commanding goes on"));
        else
            hold(CommandHold::Reason::LinkRegained, false);
    }
    if (std::optional<rcm::Message> adopted = m_hold->statusReceived(status, *m_command)) {
        const std::size_t differences = m_hold->differences().size();
        m_command = std::move(*adopted);
        emit commandAdopted(*m_command);
        emit commandEvent(differences == 0
                              ? tr("The aircraft's report is in the panels: it agreed with them")
                              : tr("The aircraft's report is in the panels: %n item(s) differed from what they held",
                                   nullptr, int(differences)));
        sendCommand();
    }
}

void ConsoleSession::setReplayPaused(bool paused)
{
    if (!m_replay)
        return;
    m_replayPaused = paused;
    QMetaObject::invokeMethod(m_replay, [replay = m_replay.data(), paused] { replay->setPaused(paused); });
}

void ConsoleSession::setReplaySpeed(double speed)
{
    m_replaySpeed = speed;
    if (m_replay)
        QMetaObject::invokeMethod(m_replay, [replay = m_replay.data(), speed] { replay->setSpeed(speed); });
}

void ConsoleSession::seekReplay(qint64 utcMicros)
{
    if (m_replay)
        QMetaObject::invokeMethod(m_replay, [replay = m_replay.data(), utcMicros] { replay->seek(utcMicros); });
}
