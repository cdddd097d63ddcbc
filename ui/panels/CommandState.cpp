#include "ui/panels/CommandState.h"

#include "codec/message/CommandChanges.h"
#include "codec/message/MessageEncoder.h"

#include <QStringList>

#include <stdexcept>
#include <utility>

namespace {

// The message as the link will send it: the link fills in these header
// items, so they are set to valid placeholders for the size check.
rcm::Message asSent(const rcm::Message& command)
{
    rcm::Message probe = command;
    probe.header.set(rcm::ItemId::ID_msg, 0);
    probe.header.set(rcm::ItemId::time_UTC, 0);
    probe.header.set(rcm::ItemId::date_UTC, 10101);
    return probe;
}

// The unit `ref` names in `message`, without checking that the airframe has it.
rcm::Unit* unitAt(rcm::Message& message, UnitRef ref)
{
    if (auto* units = message.repeated(ref.kind))
        return ref.index >= 0 && ref.index < static_cast<int>(units->size())
                   ? &(*units)[static_cast<std::size_t>(ref.index)]
                   : nullptr;
    return ref.index == 0 ? message.single(ref.kind) : nullptr;
}

QString joined(const rcm::Diagnostics& diagnostics)
{
    QStringList lines;
    for (const rcm::Diagnostic& d : diagnostics)
        lines << QString::fromStdString(d.where + ": " + d.message);
    return lines.join(QLatin1Char('\n'));
}

}  // namespace

CommandState::CommandState(rcm::Airframe airframe, QObject* parent)
    : QObject(parent), m_airframe(std::move(airframe)), m_resting(rcm::restingCommand(m_airframe)), m_message(m_resting)
{
}

std::vector<rcm::Unit> CommandState::setAirframe(rcm::Airframe airframe)
{
    m_airframe = std::move(airframe);
    m_resting = rcm::restingCommand(m_airframe);
    std::vector<rcm::Unit> left = rcm::unitsMissingFrom(m_message, m_resting);
    rcm::Message carried = rcm::withValuesOf(m_resting, m_message);
    carried.header = std::move(m_message.header);
    m_message = std::move(carried);
    emit airframeChanged();
    emit changed();
    return left;
}

int CommandState::unitCount(rcm::UnitKind kind) const
{
    if (const auto* units = m_message.repeated(kind))
        return static_cast<int>(units->size());
    if (kind == rcm::UnitKind::Sense)
        return m_airframe.senseAndAvoid ? 1 : 0;
    return 1;
}

const rcm::Unit* CommandState::unit(UnitRef ref) const
{
    if (ref.index < 0 || ref.index >= unitCount(ref.kind))
        return nullptr;
    if (const auto* units = m_message.repeated(ref.kind))
        return &(*units)[static_cast<std::size_t>(ref.index)];
    return m_message.single(ref.kind);
}

rcm::Unit* CommandState::mutableUnit(UnitRef ref)
{
    return const_cast<rcm::Unit*>(std::as_const(*this).unit(ref));
}

const rcm::Value* CommandState::value(UnitRef ref, rcm::ItemId id) const
{
    const rcm::Unit* u = unit(ref);
    return u ? u->find(id) : nullptr;
}

unsigned CommandState::fieldCode(UnitRef ref, rcm::ItemId id, int field) const
{
    const rcm::Unit* u = unit(ref);
    return u ? u->fieldCode(id, field) : 0u;
}

bool CommandState::editUnit(UnitRef ref, const std::function<void(rcm::Unit&)>& edit)
{
    rcm::Unit* target = mutableUnit(ref);
    if (!target) {
        emit rejected(tr("%1 is not fitted to this airframe").arg(QString::fromUtf8(rcm::unitLabel(ref.kind).data())));
        return false;
    }
    rcm::Unit edited = *target;
    try {
        edit(edited);
    } catch (const std::logic_error&) {
        // Unit::set refuses an item of another unit: a panel's mistake, not the operator's.
        emit rejected(tr("%1 has no such item").arg(QString::fromStdString(rcm::describeUnit(*target))));
        return false;
    }
    if (const auto key = rcm::unitKey(ref.kind); key) {
        const rcm::Value* before = target->find(*key);
        const rcm::Value* after = edited.find(*key);
        if (!after || *after != *before) {
            emit rejected(tr("%1: the key item %2 comes from the airframe and cannot be changed")
                              .arg(QString::fromStdString(rcm::describeUnit(*target)),
                                   QString::fromUtf8(rcm::itemInfo(*key).name.data())));
            return false;
        }
    }
    if (edited == *target)
        return true;

    rcm::Message candidate = m_message;
    *unitAt(candidate, ref) = std::move(edited);
    if (const rcm::Diagnostics errors = rcm::validate(asSent(candidate)); !errors.empty()) {
        emit rejected(joined(errors));
        return false;
    }
    const rcm::Message before = std::exchange(m_message, std::move(candidate));
    emit changedByOperator(before);
    emit changed();
    return true;
}

bool CommandState::setItem(UnitRef ref, rcm::ItemId id, const rcm::Value& value)
{
    return editUnit(ref, [&](rcm::Unit& u) { u.set(id, value); });
}

bool CommandState::setFieldCode(UnitRef ref, rcm::ItemId id, int field, unsigned code)
{
    return editUnit(ref, [&](rcm::Unit& u) { u.setFieldCode(id, field, code); });
}

bool CommandState::eraseItem(UnitRef ref, rcm::ItemId id)
{
    return editUnit(ref, [&](rcm::Unit& u) { u.erase(id); });
}

namespace {

template <typename MessageRef, typename F>
void forEachOneShot(MessageRef& command, const rcm::Message& resting, F&& f)
{
    // The resting command has the command's shape: the airframe made both,
    // and edits never add or remove a unit.
    auto visit = [&](auto& unit, const rcm::Unit& rest) {
        for (rcm::ItemId id : rcm::kOneShotItems) {
            const rcm::Value* now = unit.find(id);
            const rcm::Value* restValue = rest.find(id);
            if (now && restValue && *now != *restValue)
                f(unit, id, *restValue);
        }
    };
    for (int k = 0; k < rcm::kUnitKindCount; ++k) {
        const auto kind = static_cast<rcm::UnitKind>(k);
        if (auto* units = command.repeated(kind)) {
            for (std::size_t i = 0; i < units->size(); ++i)
                visit((*units)[i], (*resting.repeated(kind))[i]);
        } else {
            visit(*command.single(kind), *resting.single(kind));
        }
    }
}

}  // namespace

bool CommandState::oneShotPending() const
{
    bool pending = false;
    forEachOneShot(m_message, m_resting, [&](const rcm::Unit&, rcm::ItemId, const rcm::Value&) { pending = true; });
    return pending;
}

void CommandState::replaceMessage(const rcm::Message& message)
{
    if (message == m_message)
        return;
    m_message = message;
    emit changed();
}

void CommandState::frameSent()
{
    bool reset = false;
    forEachOneShot(m_message, m_resting, [&](rcm::Unit& unit, rcm::ItemId id, const rcm::Value& rest) {
        unit.set(id, rest);
        reset = true;
    });
    if (reset)
        emit changed();
}
