#include "ui/window/CommandBinding.h"

#include "codec/message/TextFormat.h"
#include "link/session/ConsoleSession.h"
#include "ui/alerts/ConsoleAlerts.h"
#include "ui/control/CommandHoldBar.h"
#include "ui/control/StationControlWidget.h"
#include "ui/panels/CommandGate.h"
#include "ui/panels/CommandJournal.h"
#include "ui/panels/CommandPreview.h"
#include "ui/panels/CommandState.h"
#include "ui/panels/ReportedState.h"
#include "ui/plan/FlightPlanWidget.h"
#include "ui/window/ReadOnlyPanels.h"

#include <utility>

CommandBinding::CommandBinding(const Parts& parts, const ConsoleNotices& notices, QObject* parent)
    : QObject(parent), m_parts(parts), m_notices(notices)
{
    CommandState* command = m_parts.command;
    connect(command, &CommandState::changed, this, &CommandBinding::commandChanged);
    m_journal = new CommandJournal(command, this);  // hears of each change after the session
    connect(command, &CommandState::rejected, this,
            [this](const QString& reason) { m_notices.flash(tr("Not commanded: %1").arg(reason)); });
    connect(CommandGate::of(command), &CommandGate::notSent, this,
            [this](const QString& text) { m_notices.flash(text); });
    bindStationControl();
    bindHold();
}

void CommandBinding::bindStationControl()
{
    StationControl* control = m_parts.session->stationControl();
    // Control moving unasked is an error for the banner and the log; as asked, an event.
    connect(control, &StationControl::alarm, this, [this](const QString& reason) {
        m_notices.error(reason, EventSource::Control);
        // Said as the role changes, before it is set: an offer waits for Take control.
        m_controlAlarms << reason;
    });
    // Once the role moves on, the alarms that asked for it are stale: control
    // was taken, or went elsewhere (which says so with its own alarm).
    connect(control, &StationControl::roleChanged, this, [this](StationControl::Role role) {
        QStringList alarms = std::exchange(m_controlAlarms, {});
        if (role == StationControl::Role::Offered) {
            m_offerAlarms << alarms;  // shown until this station takes control or loses the offer
            return;
        }
        for (const QString& alarm : std::exchange(m_offerAlarms, {}))
            m_notices.alerts()->withdraw(alarm, role == StationControl::Role::InControl
                                                    ? tr("control was taken")
                                                    : tr("the offer of control ended"));
    });
    connect(control, &StationControl::event, this,
            [this](const QString& text) { m_notices.info(EventSource::Control, text); });
    connect(m_parts.stationControl, &StationControlWidget::stationRefused, this,
            [this](const QString& reason) { m_notices.error(reason, EventSource::Control); });
    // The header panel shows the stations the frames name, as sent.
    connect(control, &StationControl::headerChanged, this, [this, control] {
        rcm::Message named = m_parts.command->message();
        control->applyTo(named);
        m_parts.command->editUnit({rcm::UnitKind::Header, 0}, [&](rcm::Unit& header) { header = named.header; });
    });
}

void CommandBinding::bindHold()
{
    ConsoleSession* session = m_parts.session;
    connect(m_journal, &CommandJournal::entry, this, [this](const QString& text, bool warning) {
        if (warning)
            m_notices.alerts()->warning(EventSource::Command, text);
        else
            m_notices.alerts()->info(EventSource::Command, text);
    });
    StationControl* control = session->stationControl();
    connect(control, &StationControl::headerChanged, m_journal, [this, control] {
        m_journal->setStation(control->station() ? QString::fromStdString(rcm::formatStation(*control->station()))
                                                 : QString());
    });
    // The report taken into the panels is not the operator's change.
    connect(session, &ConsoleSession::commandAdopted, m_parts.command, &CommandState::replaceMessage);
    connect(session, &ConsoleSession::commandEvent, this,
            [this](const QString& text) { m_notices.info(EventSource::Command, text); });
    connect(session->commandHold(), &CommandHold::changed, this, [this, session] {
        commandChanged();
        m_parts.flightPlan->setLinkReady(session->isLive() && session->kind() != ConsoleSession::Kind::Replay &&
                                         session->commanding());
    });
    connect(m_parts.stationControl, &StationControlWidget::takeControlRequested, m_parts.holdBar,
            &CommandHoldBar::requestResume);
    connect(m_parts.holdBar, &CommandHoldBar::refused, this,
            [this](const QString& reason) { m_notices.error(reason, EventSource::Command); });
}

void CommandBinding::commandChanged()
{
    // What the next frame carries: the header alone while the command is held.
    ConsoleSession* session = m_parts.session;
    const rcm::Message& command = m_parts.command->message();
    const bool held = session->isLive() && !session->commanding();
    m_parts.preview->setCommand(held ? rcm::heldCommand(command) : command);
    session->setCommand(command);
}

void CommandBinding::messageReceived(const ReceivedMessage& received)
{
    m_parts.reported->onReceived(received);
    if (!m_parts.readOnly->isActive())
        m_journal->statusReceived(received.message);
}

void CommandBinding::frameSent(quint32 messageId)
{
    // A frame that held the command back carried no photograph to return from.
    if (m_parts.session->commanding()) {
        m_parts.command->frameSent();
        m_journal->frameSent(messageId);
    }
    m_parts.preview->frameSent(messageId);
}

void CommandBinding::linkEnded()
{
    m_journal->linkEnded();
}
