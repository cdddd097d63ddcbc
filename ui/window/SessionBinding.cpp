#include "ui/window/SessionBinding.h"

#include "codec/receive/LoggedFrameReading.h"
#include "link/session/ConsoleSession.h"
#include "ui/alerts/ConsoleAlerts.h"
#include "ui/framelog/FrameLogModel.h"
#include "ui/overview/OverviewPage.h"
#include "ui/panels/CommandPreview.h"
#include "ui/panels/ReportedState.h"
#include "ui/plan/FlightPlanUpload.h"
#include "ui/plan/FlightPlanWidget.h"
#include "ui/window/CommandBinding.h"
#include "ui/window/LinkPane.h"
#include "ui/window/LinkSettingsWidget.h"
#include "ui/window/ReadOnlyPanels.h"
#include "ui/window/ReplayBinding.h"
#include "ui/window/StatusBarWidget.h"

#include <QDateTime>
#include <QDir>

#include <utility>

namespace {

// What the console sends is enciphered with this codec of the link's key;
// null for the plain link. It keeps the key alive.
std::shared_ptr<const rcm::secure::SecureCodec> sendingCodec(const std::shared_ptr<const rcm::LogKey>& key)
{
    if (key)
        for (const rcm::secure::SecureCodec* codec : key->codecs())
            if (codec->direction() == rcm::secure::Direction::GcsToUa)
                return std::shared_ptr<const rcm::secure::SecureCodec>(key, codec);
    return nullptr;
}

}  // namespace

SessionBinding::SessionBinding(const Parts& parts, const ConsoleNotices& notices, QObject* parent)
    : QObject(parent), m_parts(parts), m_notices(notices)
{
    ConsoleSession* session = m_parts.session;
    connect(session, &ConsoleSession::linkStarted, this, &SessionBinding::linkStarted);
    connect(session, &ConsoleSession::linkStopped, this, &SessionBinding::linkStopped);
    connect(session, &ConsoleSession::observationStarted, this, &SessionBinding::observationStarted);
    connect(session, &ConsoleSession::observationStopped, this, &SessionBinding::observationStopped);
    connect(session, &ConsoleSession::loggedCommand, m_parts.readOnly, &ReadOnlyPanels::show);
    connect(session, &ConsoleSession::failed, this, &SessionBinding::failed);
    connect(session, &ConsoleSession::warning, this,
            [this](const QString& message) { m_notices.error(message, EventSource::Link); });
    connect(session, &ConsoleSession::notice, this,
            [this](const QString& message) { m_notices.alerts()->warning(EventSource::Link, message); });
    connect(session, &ConsoleSession::starting, m_parts.linkPane, &LinkPane::setNote);
    connect(session, &ConsoleSession::starting, this,
            [this](const QString& what) { m_notices.alerts()->info(EventSource::Link, what); });
}

void SessionBinding::linkStarted(const LinkController* controller)
{
    ConsoleSession* session = m_parts.session;
    const bool replay = session->kind() == ConsoleSession::Kind::Replay;
    const QString logPath = session->sessionLogPath();
    if (!replay) {
        m_parts.logModel->clear();
        m_parts.logModel->setLogKey(session->logKey());
        if (!logPath.isEmpty())
            m_parts.logModel->setSessionLog(logPath);
    }
    m_parts.status->setTransportLabel(tr("Call"),
                                      tr("The satellite phone's call: what the modem does, and for how long"));
    bindEvents(controller, !replay);
    // Also when a live link replaced a log being opened.
    if (const ReplayLink* r = session->replay()) {
        // A replay's panels show what its log commanded, read only; the
        // console's own command comes back when it ends.
        m_parts.readOnly->begin(r->startMicros(), ReadOnlyPanels::replayNote());
        m_parts.replay->follow(r);
    } else {
        m_parts.readOnly->withdraw();
        m_parts.replay->hide();
    }
    // The next frame as this link's send path builds it: its framing, its
    // key, its clock.
    m_parts.preview->setDatagram(session->isDatagram());
    m_parts.preview->setCipher(sendingCodec(session->logKey()));
    m_parts.preview->setClock([clock = controller->clock()] { return clock->utcMicros(); }, controller->interval());
    m_parts.preview->resetSent(controller->firstMessageId());
    m_parts.flightPlan->setLinkReady(!replay && session->commanding());
    // A replay says so, with the log's own time, and raises no link alarm.
    m_notices.alerts()->setReplay(replay);
    m_parts.status->setReplay(replay);
    m_parts.overview->setReplay(replay);
    const QString description = session->description();
    const QString log = QDir::toNativeSeparators(logPath);
    m_notices.alerts()->info(EventSource::Link, logPath.isEmpty()
                                                    ? tr("Started: %1").arg(description)
                                                    : tr("Started: %1; frame log %2").arg(description, log));
    if (!session->keyFingerprint().isEmpty())
        m_notices.alerts()->info(EventSource::Key,
                                 tr("Secure link, key fingerprint %1").arg(session->keyFingerprint()));
    showRunning(logPath.isEmpty() ? description : tr("%1\nFrame log: %2").arg(description, log));
}

void SessionBinding::observationStarted(const Observation* observation)
{
    ConsoleSession* session = m_parts.session;
    // A keyed session's frames are the enciphered bytes: with the aircraft's
    // key the log view reads them as the station's own would.
    m_parts.logModel->clear();
    m_parts.logModel->setLogKey(session->logKey());
    m_parts.status->setTransportLabel(tr("Broker"), tr("The broker the observation comes through, and for how long"));
    bindEvents(observation, true);
    // Read only, as a replay: the panels show what the observed station commands.
    m_parts.readOnly->begin(QDateTime::currentMSecsSinceEpoch() * 1000,
                            tr("Observing %1: read only, nothing is sent").arg(observation->observed()));
    m_parts.flightPlan->setLinkReady(false);
    m_notices.alerts()->info(EventSource::Link, session->description());
    showRunning(tr("%1: read only, nothing is sent to the aircraft").arg(session->description()));
}

void SessionBinding::showRunning(const QString& note)
{
    m_parts.status->setLinkDescription(m_parts.session->description());
    m_parts.status->setKeyFingerprint(m_parts.session->keyFingerprint());
    m_parts.status->setStatistics(LinkStatistics());
    m_parts.linkPane->setNote(note);
    emit changed();
}

void SessionBinding::bindEvents(const LinkEvents* events, bool logRows)
{
    StatusBarWidget* status = m_parts.status;
    connect(events, &LinkEvents::statisticsChanged, status, &StatusBarWidget::setStatistics);
    connect(events, &LinkEvents::statisticsChanged, m_parts.overview, &OverviewPage::setStatistics);
    // Its errors to the event log and the banner, its silences to the alarm.
    m_notices.alerts()->follow(events);
    // A modem's call: dialling, connected, redialling, hung up. Its failures
    // come as errors too (once an outage), and are logged once, as errors.
    status->setTransportStatus(QString());
    status->setModemService(-1, false, QString());
    m_parts.reported->setLinkDelay(m_parts.session->kind() == ConsoleSession::Kind::Live
                                       ? m_parts.linkPane->settings()->settings().oneWayDelay()
                                       : std::chrono::milliseconds(0));
    connect(events, &LinkEvents::errorOccurred, this, [this](const QString& error) { m_lastLinkError = error; });
    connect(events, &LinkEvents::transportStatusChanged, this, [this](const QString& text) {
        m_parts.status->setTransportStatus(text);
        if (text != m_lastLinkError)
            m_notices.alerts()->info(EventSource::Link, text);
        else if (!m_transportErrors.contains(text))
            m_transportErrors << text;
    });
    connect(events, &LinkEvents::stateChanged, this, [this](LinkState state) {
        if (state == LinkState::Connected)
            withdrawTransportErrors(tr("frames from the aircraft again"));
    });
    // The phone's registration and signal: bars in the status bar, and each
    // change of registration in the event log.
    connect(events, &LinkEvents::modemServiceChanged, this, [this](int bars, bool registered, const QString& text) {
        const bool wasRegistered = m_parts.status->modemServiceText().isEmpty() ? !registered : m_modemRegistered;
        m_parts.status->setModemService(bars, registered, text);
        if (registered != wasRegistered)
            m_notices.alerts()->info(EventSource::Link, tr("The satellite phone: %1").arg(text));
        m_modemRegistered = registered;
    });
    // A live session's frames become rows as the link logs them; a replay's
    // rows are its log file, opened already.
    if (logRows)
        connect(events, &LinkEvents::frameLogged, m_parts.logModel, &FrameLogModel::appendLogged);
    connect(events, &LinkEvents::stateChanged, status, &StatusBarWidget::setState);
    // The window's title says the state too.
    connect(events, &LinkEvents::stateChanged, this, &SessionBinding::changed);
    connect(events, &LinkEvents::messageReceived, m_parts.commands, &CommandBinding::messageReceived);
    connect(events, &LinkEvents::frameSent, m_parts.commands, &CommandBinding::frameSent);
    connect(events, &LinkEvents::commandRejected, this, [this](const QString& reasons) {
        m_notices.error(tr("The link refused the command: %1").arg(reasons), EventSource::Link);
    });
    // Not the banner: a forger could send one a second. The status bar
    // counts them by reason; the event log has them through the alerts
    // (RefusalDigest).
    connect(events, &LinkEvents::frameRejected, this,
            [this](const QString& reason) { m_notices.flash(tr("A frame was refused: %1").arg(reason)); });
}

void SessionBinding::withdrawTransportErrors(const QString& why)
{
    for (const QString& error : std::exchange(m_transportErrors, {}))
        m_notices.alerts()->withdraw(error, why);
}

void SessionBinding::showStopped()
{
    withdrawTransportErrors(tr("the link was closed"));
    m_parts.readOnly->end();
    m_parts.status->setLinkDescription(QString());
    m_parts.status->setKeyFingerprint(QString());
    m_parts.status->setStatistics(LinkStatistics());
    m_notices.alerts()->setStatistics(LinkStatistics());  // closed: no alarm
    m_parts.linkPane->showNotConnected();
}

void SessionBinding::observationStopped()
{
    showStopped();
    m_notices.alerts()->info(EventSource::Link, tr("Stopped observing"));
    emit changed();
}

void SessionBinding::linkStopped()
{
    m_parts.upload->cancel();
    m_parts.replay->hide();
    m_parts.logModel->setPlayedRows(-1);
    m_parts.flightPlan->setLinkReady(false);
    showStopped();
    m_parts.status->setReplay(false);
    m_parts.overview->setStatistics(LinkStatistics());
    m_parts.overview->setReplay(false);
    m_notices.alerts()->setReplay(false);
    m_notices.alerts()->info(EventSource::Link, tr("Stopped"));
    m_parts.commands->linkEnded();
    emit changed();
}

void SessionBinding::failed(const QString& reason)
{
    if (!m_parts.session->replay()) {
        // A log that could not be opened.
        m_parts.replay->hide();
        m_parts.readOnly->withdraw();
    }
    m_parts.linkPane->setNote(reason);
    // Key files are refused here too ("the key file is refused: ..."): said as the key's.
    m_notices.error(reason, reason.contains(QStringLiteral("key file")) ? EventSource::Key : EventSource::Link);
    emit changed();
}
