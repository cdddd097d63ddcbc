#include "link/session/StationControl.h"

#include "codec/message/ItemTable.h"
#include "codec/message/TextFormat.h"
#include "codec/message/ValueCodec.h"
#include "link/common/NameTable.h"

#include <utility>

using namespace rcm;

namespace {

constexpr auto kRoleNames = std::to_array<Named<StationControl::Role>>({
    {StationControl::Role::Unknown, QT_TRANSLATE_NOOP("StationControl", "Control not reported yet")},
    {StationControl::Role::InControl, QT_TRANSLATE_NOOP("StationControl", "In control")},
    {StationControl::Role::Offered, QT_TRANSLATE_NOOP("StationControl", "Given control: not taken")},
    {StationControl::Role::HandingOver, QT_TRANSLATE_NOOP("StationControl", "Handing over")},
    {StationControl::Role::Backup, QT_TRANSLATE_NOOP("StationControl", "Backup")},
    {StationControl::Role::Observing, QT_TRANSLATE_NOOP("StationControl", "Observing")},
});

std::optional<StationId> headerStation(const Message& message, ItemId id)
{
    const Value* v = message.header.find(id);
    if (!v || !checkValue(itemInfo(id), *v).empty())
        return std::nullopt;
    return StationId{static_cast<std::uint16_t>(v->number), static_cast<std::uint16_t>(v->second)};
}

QString text(std::optional<StationId> station)
{
    return station ? QString::fromStdString(formatStation(*station)) : QStringLiteral("no station");
}

void setStationItem(Message& message, ItemId id, std::optional<StationId> station)
{
    if (station)
        message.header.set(id, Value::station(*station));
    else
        message.header.erase(id);
}

}  // namespace

StationControl::StationControl(QObject* parent) : QObject(parent) {}

void StationControl::setStation(std::optional<StationId> station)
{
    if (station == m_station)
        return;
    m_station = station;
    m_reportedControl.reset();
    m_reportedBackup.reset();
    m_claimed = false;
    m_heldControl = false;
    setRole(Role::Unknown);
    emit headerChanged();
}

void StationControl::reset()
{
    // A new link starts from nothing the operator confirmed on this one: it
    // takes control again only by another Take control, after the aircraft
    // has been heard. What the aircraft said last is kept for the alarms.
    m_claimed = false;
    setRole(Role::Unknown);
}

bool StationControl::canHandOver() const
{
    return m_role == Role::InControl && m_reportedBackup && m_reportedBackup != m_station;
}

void StationControl::applyTo(Message& command) const
{
    using enum ItemId;
    if (!m_station) {
        // The stations the header panel sets, but never a claim: only Take
        // control, which follows control, sends one.
        const std::optional<StationId> destination = headerStation(command, ID_GCS_destination);
        if (destination && destination == headerStation(command, ID_GCS_backup))
            command.header.erase(ID_GCS_backup);
        return;
    }
    using Stations = std::pair<std::optional<StationId>, std::optional<StationId>>;  // destination, backup
    const auto [destination, backup] = [&]() -> Stations {
        switch (m_role) {
            case Role::Unknown:
                // Nobody named until the aircraft says who is in control: a
                // frame naming no station is no command and changes no backup.
                return {std::nullopt, std::nullopt};
            case Role::InControl:
                // The claim: only the operator's Take control on this link sends it.
                return {m_station, m_station};
            case Role::Offered:
                // Naming itself, not claiming: taken up or not, the aircraft
                // keeps what it does (the frames hold the command back
                // meanwhile), and naming the backup instead would hand over a
                // control taken up.
                return {m_station, std::nullopt};
            case Role::HandingOver:
                // The aircraft passes control to the backup.
                return {m_reportedBackup, m_station};
            case Role::Backup:
            case Role::Observing:
                break;
        }
        return {m_reportedControl, m_reportedBackup};
    }();
    setStationItem(command, ID_GCS_destination, destination);
    setStationItem(command, ID_GCS_backup, backup);
}

void StationControl::statusReceived(const Message& status)
{
    if (!m_station)
        return;
    const std::optional<StationId> control = headerStation(status, ItemId::ID_GCS_destination);
    const std::optional<StationId> backup = headerStation(status, ItemId::ID_GCS_backup);
    const bool changed = control != m_reportedControl || backup != m_reportedBackup;
    const std::optional<StationId> previousControl = m_reportedControl;
    m_reportedControl = control;
    m_reportedBackup = backup;

    Role next;
    if (m_role == Role::HandingOver && control == previousControl)
        next = Role::HandingOver;  // the aircraft has not seen it yet
    else if (control == m_station)
        next = m_claimed ? Role::InControl : Role::Offered;
    else
        next = backup == m_station ? Role::Backup : Role::Observing;

    if (next != m_role) {
        const Role previous = m_role;
        if (next == Role::Offered && previous == Role::Unknown && previousControl != control) {
            // A new link (or a console started) finding itself in control, by
            // the aircraft's start-up configuration or a control it kept.
            emit event(tr("The aircraft names this station in control: check what it reports, "
                          "then Take control to command it"));
        } else if (next == Role::Offered && previous == Role::Unknown) {
            emit event(tr("The aircraft still names this station in control: check what it reports, "
                          "then Take control to command it again"));
        } else if (next == Role::Offered) {
            emit alarm(tr("The aircraft gave control to this station (%1 was in control): "
                          "check what it reports, then Take control to command it")
                           .arg(text(previousControl ? previousControl : backup)));
        } else if (previous == Role::Offered) {
            emit alarm(tr("Control went to %1: this station did not take it within the aircraft's failover time")
                           .arg(text(control)));
        } else if (previous == Role::InControl || (previous == Role::Unknown && m_heldControl)) {
            emit alarm(tr("Control lost: the aircraft names %1 in control, and this station did not hand over")
                           .arg(text(control)));
        } else if (previous == Role::HandingOver && control != m_station) {
            emit event(tr("Handed over: %1 is in control, this station is %2")
                           .arg(text(control), next == Role::Backup ? tr("its backup") : tr("observing")));
        } else if (previous == Role::Unknown && next != Role::InControl) {
            emit event(tr("This station is %1; %2 in control")
                           .arg(next == Role::Backup ? tr("the backup") : tr("observing"), text(control)));
        } else if (next == Role::InControl && previous == Role::Unknown) {
            emit event(tr("This station is in control; backup %1").arg(text(backup)));
        } else if (next == Role::InControl) {
            emit event(tr("Took control: the aircraft acts on this station's commands; backup %1").arg(text(backup)));
        }
        if (next != Role::InControl && next != Role::Unknown)
            m_claimed = false;
        if (next == Role::InControl || next == Role::Offered)
            m_heldControl = true;
        else if (next != Role::HandingOver)
            m_heldControl = false;
        setRole(next);
    }
    if (changed)
        emit headerChanged();
}

void StationControl::handOver()
{
    if (!canHandOver())
        return;
    m_claimed = false;
    emit event(tr("Handing over to %1").arg(text(m_reportedBackup)));
    setRole(Role::HandingOver);
    emit headerChanged();
}

void StationControl::takeControl()
{
    if (!canTakeControl())
        return;
    m_claimed = true;
    emit event(tr("Taking control: the next frames claim control for this station"));
    // The role follows the aircraft's next status, which names this station in control.
    setRole(Role::InControl);
    emit headerChanged();
}

QString StationControl::roleName(Role role)
{
    return tr(nameOf(kRoleNames, role));
}

QString StationControl::describe() const
{
    if (!m_station)
        return {};
    const QString me = text(m_station);
    switch (m_role) {
        case Role::Unknown:
            return tr("%1: control not reported yet").arg(me);
        case Role::InControl:
            return m_reportedBackup ? tr("%1: in control, backup %2").arg(me, text(m_reportedBackup))
                                    : tr("%1: in control, no backup").arg(me);
        case Role::Offered:
            return tr("%1: given control, not taken: Take control to command").arg(me);
        case Role::HandingOver:
            return tr("%1: handing over to %2").arg(me, text(m_reportedBackup));
        case Role::Backup:
            return tr("%1: backup, %2 in control").arg(me, text(m_reportedControl));
        case Role::Observing:
            return tr("%1: observing, %2 in control").arg(me, text(m_reportedControl));
    }
    return {};
}

void StationControl::setRole(Role role)
{
    if (role == m_role)
        return;
    m_role = role;
    emit roleChanged(role);
}
