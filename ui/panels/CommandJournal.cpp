#include "ui/panels/CommandJournal.h"

#include "ui/panels/CommandState.h"
#include "ui/panels/ItemText.h"

#include <algorithm>

namespace {

bool sameItem(const rcm::ItemChange& a, const rcm::ItemChange& b)
{
    return a.kind == b.kind && a.key == b.key && a.id == b.id && a.field == b.field;
}

}  // namespace

CommandJournal::CommandJournal(const CommandState* command, QObject* parent) : QObject(parent), m_command(command)
{
    connect(command, &CommandState::changedByOperator, this, &CommandJournal::edited);
    // Another airframe: the changes pending were for units that may be gone.
    connect(command, &CommandState::airframeChanged, this, [this] { m_pending.clear(); });
}

QString CommandJournal::by() const
{
    return m_station.isEmpty() ? QString() : tr(" (by %1)").arg(m_station);
}

void CommandJournal::edited(const rcm::Message& before)
{
    for (rcm::ItemChange& change : rcm::commandChanges(before, m_command->message())) {
        emit entry(tr("Command changed%1: %2").arg(by(), ItemText::change(change)), false);
        // A newer value of the same item is what is awaited now.
        std::erase_if(m_pending, [&](const Pending& p) { return sameItem(p.change, change); });
        m_pending.push_back(Pending{std::move(change), std::nullopt, 0});
    }
}

void CommandJournal::frameSent(quint32 messageId)
{
    for (Pending& p : m_pending)
        if (!p.sentIn)
            p.sentIn = messageId;
}

void CommandJournal::statusReceived(const rcm::Message& status)
{
    if (m_pending.empty())
        return;
    std::erase_if(m_pending, [&](Pending& p) {
        if (!p.sentIn)
            return false;
        ++p.statusFrames;
        const QString item = ItemText::changeWhere(p.change) + QStringLiteral(" ") +
                             ItemText::changeValue(p.change, p.change.to);
        if (rcm::holdsChange(status, p.change)) {
            emit entry(tr("Command confirmed: %1, sent in frame %2, reported by the aircraft %n status frame(s) "
                          "later",
                          nullptr, p.statusFrames)
                           .arg(item)
                           .arg(*p.sentIn),
                       false);
            return true;
        }
        if (p.statusFrames < kConfirmFrames)
            return false;
        emit entry(tr("Command not confirmed: %1, sent in frame %2; the aircraft reports %3 %n status frame(s) later",
                      nullptr, p.statusFrames)
                       .arg(item)
                       .arg(*p.sentIn)
                       .arg(ItemText::changeValue(p.change, rcm::valueAt(status, p.change)
                                                                ? std::optional(*rcm::valueAt(status, p.change))
                                                                : std::nullopt)),
                   true);
        return true;
    });
}

void CommandJournal::linkEnded()
{
    for (const Pending& p : m_pending) {
        const QString item =
            ItemText::changeWhere(p.change) + QStringLiteral(" ") + ItemText::changeValue(p.change, p.change.to);
        emit entry(p.sentIn ? tr("Command not confirmed: %1, sent in frame %2; the link ended before the aircraft "
                                 "reported it")
                                  .arg(item)
                                  .arg(*p.sentIn)
                            : tr("Command not sent: %1; the link ended while it was held").arg(item),
                   true);
    }
    m_pending.clear();
}
