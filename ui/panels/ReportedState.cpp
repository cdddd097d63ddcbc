#include "ui/panels/ReportedState.h"

#include "link/session/LinkWorker.h"
#include "link/session/ReceivedMessage.h"
#include "ui/panels/CommandState.h"

#include <algorithm>

namespace {

// The same unit: same kind and, for repeated kinds, the same key value.
bool sameUnit(const rcm::Unit& a, const rcm::Unit& b)
{
    if (a.kind() != b.kind())
        return false;
    const auto key = rcm::unitKey(a.kind());
    if (!key)
        return true;
    const rcm::Value* ka = a.find(*key);
    const rcm::Value* kb = b.find(*key);
    return ka && kb && *ka == *kb;
}

const rcm::Unit* findIn(const rcm::Message& message, const rcm::Unit& like)
{
    if (const auto* units = message.repeated(like.kind())) {
        const auto it =
            std::find_if(units->begin(), units->end(), [&](const rcm::Unit& u) { return sameUnit(u, like); });
        return it == units->end() ? nullptr : &*it;
    }
    return message.single(like.kind());
}

}  // namespace

ReportedState::ReportedState(const CommandState* command, QObject* parent, Clock clock,
                             std::chrono::milliseconds staleAfter)
    : QObject(parent),
      m_command(command),
      m_clock(clock ? std::move(clock) : Clock(&std::chrono::steady_clock::now)),
      m_staleAfter(staleAfter)
{
    connect(command, &CommandState::airframeChanged, this, &ReportedState::clear);
    m_ageTimer.setInterval(std::chrono::seconds(1));
    connect(&m_ageTimer, &QTimer::timeout, this, &ReportedState::checkAge);
    m_ageTimer.start();
}

std::chrono::milliseconds ReportedState::defaultStaleAfter()
{
    return LinkWorker::Options{}.silenceTimeout;
}

void ReportedState::clear()
{
    m_units.clear();
    m_statusFrames = 0;
    m_lastStatus.reset();
    m_shownAge.reset();
    emit updated();
}

std::optional<std::chrono::seconds> ReportedState::staleAge() const
{
    if (!m_lastStatus)
        return std::nullopt;
    const auto age = m_clock() - *m_lastStatus;
    if (age < m_staleAfter)
        return std::nullopt;
    return std::chrono::duration_cast<std::chrono::seconds>(age);
}

void ReportedState::checkAge()
{
    const auto age = staleAge();
    if (age == m_shownAge)
        return;
    m_shownAge = age;
    emit updated();
}

bool ReportedState::mismatchWhileStale(UnitRef ref, rcm::ItemId id, int field) const
{
    const rcm::Value* commanded = m_command->value(ref, id);
    const rcm::Value* reported = value(ref, id);
    if (!stale() || !commanded || !reported || field >= 4)
        return false;
    if (field < 0)
        return *commanded != *reported;
    return rcm::fieldCode(static_cast<std::uint8_t>(commanded->number), field) !=
           rcm::fieldCode(static_cast<std::uint8_t>(reported->number), field);
}

const ReportedState::ReportedUnit* ReportedState::find(UnitRef ref) const
{
    const rcm::Unit* commanded = m_command->unit(ref);
    if (!commanded)
        return nullptr;
    const auto it = std::find_if(m_units.begin(), m_units.end(),
                                 [&](const ReportedUnit& r) { return sameUnit(r.unit, *commanded); });
    return it == m_units.end() ? nullptr : &*it;
}

ReportedState::ReportedUnit& ReportedState::findOrAdd(const rcm::Unit& like)
{
    const auto it =
        std::find_if(m_units.begin(), m_units.end(), [&](const ReportedUnit& r) { return sameUnit(r.unit, like); });
    if (it != m_units.end())
        return *it;
    return m_units.emplace_back(ReportedUnit{rcm::Unit(like.kind()), {}});
}

const rcm::Unit* ReportedState::unit(UnitRef ref) const
{
    const ReportedUnit* r = find(ref);
    return r ? &r->unit : nullptr;
}

const rcm::Value* ReportedState::value(UnitRef ref, rcm::ItemId id) const
{
    const ReportedUnit* r = find(ref);
    return r ? r->unit.find(id) : nullptr;
}

int ReportedState::mismatchFrames(UnitRef ref, rcm::ItemId id, int field) const
{
    const ReportedUnit* r = find(ref);
    const rcm::Value* commanded = m_command->value(ref, id);
    if (!r || !commanded || field >= 4)
        return 0;
    const auto it = r->comparisons.find(id);
    if (it == r->comparisons.end())
        return 0;
    const Comparison& c = it->second;
    // Counted against an earlier command: the present one has not been answered yet.
    if (field < 0)
        return *commanded == c.commanded ? c.frames : 0;
    const bool same = rcm::fieldCode(static_cast<std::uint8_t>(commanded->number), field) ==
                      rcm::fieldCode(static_cast<std::uint8_t>(c.commanded.number), field);
    return same ? c.fieldFrames[static_cast<std::size_t>(field)] : 0;
}

void ReportedState::onReceived(const ReceivedMessage& received)
{
    onStatus(received.message);
}

void ReportedState::onStatus(const rcm::Message& status)
{
    status.forEachUnit([&](const rcm::Unit& reported) {
        if (reported.empty())
            return;
        ReportedUnit& r = findOrAdd(reported);
        for (const rcm::ItemValue& item : reported.items())
            r.unit.set(item.id, item.value);
    });
    m_command->message().forEachUnit(
        [&](const rcm::Unit& commanded) { compare(commanded, findIn(status, commanded)); });
    ++m_statusFrames;
    m_lastStatus = m_clock();
    m_shownAge.reset();
    emit updated();
}

void ReportedState::compare(const rcm::Unit& commanded, const rcm::Unit* reported)
{
    if (commanded.empty())
        return;
    ReportedUnit& r = findOrAdd(commanded);
    const auto key = rcm::unitKey(commanded.kind());
    for (const rcm::ItemValue& item : commanded.items()) {
        if (key && item.id == *key)
            continue;
        Comparison& c = r.comparisons[item.id];
        const bool fields = rcm::itemInfo(item.id).kind == rcm::ValueKind::Fields;
        const auto commandedByte = static_cast<std::uint8_t>(item.value.number);
        const auto countedByte = static_cast<std::uint8_t>(c.commanded.number);
        if (item.value != c.commanded) {
            c.frames = 0;
            c.since = m_clock();
        }
        for (int f = 0; f < 4; ++f)
            if (!fields || rcm::fieldCode(commandedByte, f) != rcm::fieldCode(countedByte, f))
                c.fieldFrames[static_cast<std::size_t>(f)] = 0;
        c.commanded = item.value;

        const rcm::Value* now = reported ? reported->find(item.id) : nullptr;
        // Within the link's round trip the aircraft cannot have heard the change yet.
        if (!now || m_clock() - c.since < m_answerTime) {
            c.frames = 0;
            c.fieldFrames.fill(0);
            continue;
        }
        c.frames = *now == item.value ? 0 : c.frames + 1;
        if (!fields)
            continue;
        const auto reportedByte = static_cast<std::uint8_t>(now->number);
        for (int f = 0; f < 4; ++f) {
            int& n = c.fieldFrames[static_cast<std::size_t>(f)];
            n = rcm::fieldCode(reportedByte, f) == rcm::fieldCode(commandedByte, f) ? 0 : n + 1;
        }
    }
}
