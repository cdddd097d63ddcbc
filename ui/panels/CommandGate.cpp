#include "ui/panels/CommandGate.h"

#include "codec/message/ValueCodec.h"
#include "ui/panels/CommandState.h"
#include "ui/panels/ItemText.h"

#include <QStringList>
#include <QWidget>

namespace {

QString fromView(std::string_view s)
{
    return QString::fromUtf8(s.data(), static_cast<qsizetype>(s.size()));
}

}  // namespace

CommandGate::CommandGate(CommandState* command) : QObject(command), m_command(command)
{
    setObjectName(QStringLiteral("CommandGate"));
}

CommandGate* CommandGate::of(CommandState* command)
{
    if (auto* gate = command->findChild<CommandGate*>(QString(), Qt::FindDirectChildrenOnly))
        return gate;
    return new CommandGate(command);
}

std::optional<Confirmation> CommandGate::question(UnitRef ref, rcm::ItemId id, const rcm::Value& to,
                                                  const QString& detail, const QString& action) const
{
    const rcm::ItemInfo& info = rcm::itemInfo(id);
    const rcm::Value* from = m_command->value(ref, id);
    const auto found = rcm::findLargeChange(info, from, to);
    if (!found)
        return std::nullopt;
    using Rule = rcm::LargeChangeFound::Rule;
    const int field = found->field;
    const auto shown = [&](const rcm::Value& v) {
        return field >= 0 ? ItemText::fieldValue(id, field, v, m_command->unit(ref)) : ItemText::value(id, v);
    };
    const QString before = from ? shown(*from) : tr("nothing");
    const QString after = shown(to);
    QString what = fromView(found->action);
    if (rcm::isRepeated(ref.kind))
        if (const rcm::Unit* unit = m_command->unit(ref))
            what = tr("%1 of %2").arg(what, QString::fromStdString(rcm::describeUnit(*unit)));

    // Every field this one change moves to the code that asks, when it is more than one.
    QStringList fieldsAsking;
    if (found->rule == Rule::FieldCode) {
        const auto code = [](const rcm::Value& v, int f) { return rcm::fieldCode(std::uint8_t(v.number), f); };
        for (int f = 0; f < int(info.fields.size()); ++f) {
            const rcm::FieldConfirmation& asks = info.largeChange.fields[std::size_t(f)];
            if (asks.code != 0 && code(to, f) == asks.code && (!from || code(*from, f) != asks.code))
                fieldsAsking << tr("%1: %2 to %3")
                                    .arg(ItemText::label(id, f),
                                         from ? ItemText::fieldValue(id, f, *from, m_command->unit(ref)) : tr("nothing"),
                                         ItemText::fieldValue(id, f, to, m_command->unit(ref)));
        }
    }
    if (fieldsAsking.size() > 1) {
        Confirmation ask;
        ask.title = ItemText::label(id);
        ask.action = action.isEmpty() ? fromView(found->action) : action;
        ask.text = tr("%1?").arg(ask.action);
        QStringList lines = fieldsAsking;
        if (!info.largeChange.note.empty())
            lines << fromView(info.largeChange.note);
        if (!detail.isEmpty())
            lines << detail;
        lines << tr("Cancel keeps the %1 as it is.").arg(ItemText::label(id).toLower());
        ask.informativeText = lines.join(QLatin1Char('\n'));
        return ask;
    }

    QStringList why;
    switch (found->rule) {
        case Rule::Step:
            why << tr("A change of more than %1 in one action is confirmed first.")
                       .arg(ItemText::number(id, info.largeChange.step) + ItemText::unitSuffix(id));
            break;
        case Rule::Extreme:
            why << tr("%1 is an end of the range (%2): confirmed first.")
                       .arg(after, ItemText::number(id, info.min) + QStringLiteral("..") +
                                       ItemText::number(id, info.max) + ItemText::unitSuffix(id));
            break;
        case Rule::FieldCode:
            why << tr("%1 to %2 is confirmed first.").arg(ItemText::label(id, field), after);
            break;
    }
    if (!info.largeChange.note.empty())
        why << fromView(info.largeChange.note);
    if (!detail.isEmpty())
        why << detail;
    why << tr("Cancel keeps %1.").arg(before);

    Confirmation ask;
    ask.title = ItemText::label(id);
    ask.text = tr("%1 from %2 to %3?").arg(what, before, after);
    ask.informativeText = why.join(QLatin1Char('\n'));
    ask.action = action.isEmpty() ? fromView(found->action) : action;
    return ask;
}

bool CommandGate::setItem(QWidget* control, UnitRef ref, rcm::ItemId id, const rcm::Value& to, const QString& detail,
                          const QString& action)
{
    if (const auto ask = question(ref, id, to, detail, action)) {
        m_asking = true;
        QWidget* parent = control ? control->window() : nullptr;
        const bool confirmed = m_asker ? m_asker(*ask, parent) : ask->ask(parent);
        m_asking = false;
        if (!confirmed) {
            const rcm::Value* v = m_command->value(ref, id);
            tellNotSent(ref, id,
                        tr("Not sent: %1 cancelled; the command stays %2")
                            .arg(ask->action, v ? ItemText::value(id, *v) : tr("as it was")));
            return false;
        }
    }
    return m_command->setItem(ref, id, to);
}

bool CommandGate::setNumber(QWidget* control, UnitRef ref, rcm::ItemId id, std::int64_t number)
{
    return setItem(control, ref, id, rcm::Value::of(number));
}

bool CommandGate::setFieldCode(QWidget* control, UnitRef ref, rcm::ItemId id, int field, unsigned code,
                               const QString& detail)
{
    const rcm::Unit* unit = m_command->unit(ref);
    if (!unit || rcm::itemInfo(id).owner != ref.kind)
        return m_command->setFieldCode(ref, id, field, code);  // refused, and says why
    rcm::Unit changed = *unit;
    changed.setFieldCode(id, field, code);
    return setItem(control, ref, id, *changed.find(id), detail);
}

QString CommandGate::ruleText(rcm::ItemId id, int field)
{
    const rcm::LargeChange& rule = rcm::itemInfo(id).largeChange;
    if (field >= 0) {
        const rcm::FieldConfirmation& asks = rule.fields[static_cast<std::size_t>(field)];
        return asks.code == 0 ? QString() : tr("%1 asks first.").arg(ItemText::fieldCodeWord(id, field, asks.code));
    }
    const rcm::ItemInfo& info = rcm::itemInfo(id);
    const auto shown = [id](std::int64_t wire) { return ItemText::number(id, wire) + ItemText::unitSuffix(id); };
    const bool step = rule.step != rcm::kAnyStep;
    if (step && rule.extremes)
        return tr("Setting %1 or %2, or a change of more than %3 in one action, asks first.")
            .arg(shown(info.min), shown(info.max), shown(rule.step));
    if (step)
        return tr("A change of more than %1 in one action asks first.").arg(shown(rule.step));
    if (rule.extremes)
        return tr("Setting %1 or %2 asks first.").arg(shown(info.min), shown(info.max));
    return {};
}

void CommandGate::tellNotSent(UnitRef ref, rcm::ItemId id, const QString& text)
{
    QString item = ItemText::label(id);
    if (rcm::isRepeated(ref.kind))
        if (const rcm::Unit* unit = m_command->unit(ref))
            item = tr("%1 of %2").arg(item, QString::fromStdString(rcm::describeUnit(*unit)));
    emit notSent(tr("%1: %2").arg(item, text));
}
