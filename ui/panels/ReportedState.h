// What the aircraft last said it is doing: the last reported value of every
// item of every unit, from its status frames, and for each commanded item how
// many status frames in a row have disagreed with the command. A panel shows
// the reported value beside the commanded one and highlights a disagreement
// only once it outlasts what a moving part explains (two frames).
//
// Once no status frame has come for staleAfter() (the link's silence timeout)
// the reported values are stale: they are what the aircraft said some seconds
// ago, not what it does. A panel then marks them with their age, and any
// item the command has changed since (or that disagreed already) shows as a
// mismatch at once: no status frame will count it. Time comes from a clock
// passed in, so that a test can move it.
#pragma once

#include "codec/message/Message.h"
#include "link/session/MessageMetaType.h"
#include "ui/panels/UnitRef.h"

#include <QObject>
#include <QTimer>

#include <array>
#include <chrono>
#include <functional>
#include <optional>
#include <map>
#include <vector>

class CommandState;
struct ReceivedMessage;

class ReportedState : public QObject {
    Q_OBJECT

public:
    // Disagreeing for more than this many consecutive status frames is persistent.
    static constexpr int kTransientFrames = 2;

    // Compares against `command`'s message as it is when each status frame
    // arrives; forgets everything when the command's airframe changes.
    // `command` must outlive this object.
    using Clock = std::function<std::chrono::steady_clock::time_point()>;

    // `clock` null: std::chrono::steady_clock.
    explicit ReportedState(const CommandState* command, QObject* parent = nullptr, Clock clock = {},
                           std::chrono::milliseconds staleAfter = defaultStaleAfter());

    // LinkWorker's silence timeout: when the link calls itself lost, the reports are stale.
    static std::chrono::milliseconds defaultStaleAfter();
    std::chrono::milliseconds staleAfter() const { return m_staleAfter; }
    // Whole seconds since the last status frame, once that is staleAfter() or
    // more; nothing while reports are fresh or before any status frame.
    std::optional<std::chrono::seconds> staleAge() const;
    bool stale() const { return staleAge().has_value(); }

    // The last value reported for the item of the unit `ref` names in the
    // command (matched by key item); nullptr before any report of it.
    const rcm::Value* value(UnitRef ref, rcm::ItemId id) const;
    // The unit as last reported, matched by key item; nullptr before any report.
    const rcm::Unit* unit(UnitRef ref) const;

    // Consecutive status frames, up to the last, in which the reported item
    // (field: only that two-bit field; -1: the whole item) differed from the
    // command. A frame without the item ends the run, and so does a new
    // commanded value: the count is against the command as it stands.
    int mismatchFrames(UnitRef ref, rcm::ItemId id, int field = -1) const;
    bool mismatchPersistent(UnitRef ref, rcm::ItemId id, int field = -1) const
    {
        return mismatchFrames(ref, id, field) > kTransientFrames;
    }

    // While stale: the command differs from the last reported value of the
    // item (field: of that field). False while fresh: mismatchFrames() counts.
    bool mismatchWhileStale(UnitRef ref, rcm::ItemId id, int field = -1) const;

    int statusFrames() const { return m_statusFrames; }
    void clear();

    // The link's one-way delay (a satellite's 1.5 s): for twice that after a
    // commanded value changed, status frames still answer the command before
    // it, and do not count as disagreeing. 0 (the default) for a link whose
    // delay is within a frame.
    void setLinkDelay(std::chrono::milliseconds oneWay) { m_answerTime = 2 * oneWay; }

public slots:
    void onStatus(const rcm::Message& status);
    // LinkController::messageReceived, for a direct connection.
    void onReceived(const ReceivedMessage& received);
    // Reads the clock: emits updated() when the reports turn stale or their
    // age in whole seconds changes. A timer calls it every second.
    void checkAge();

signals:
    void updated();

private:
    struct Comparison {
        rcm::Value commanded;  // what the counts below were counted against
        std::chrono::steady_clock::time_point since;  // when it was first compared
        int frames = 0;
        std::array<int, 4> fieldFrames{};
    };
    struct ReportedUnit {
        rcm::Unit unit;
        std::map<rcm::ItemId, Comparison> comparisons;
    };

    const ReportedUnit* find(UnitRef ref) const;
    ReportedUnit& findOrAdd(const rcm::Unit& like);
    void compare(const rcm::Unit& commanded, const rcm::Unit* reported);

    const CommandState* m_command;
    Clock m_clock;
    std::chrono::milliseconds m_staleAfter;
    std::chrono::milliseconds m_answerTime{0};
    std::vector<ReportedUnit> m_units;
    int m_statusFrames = 0;
    std::optional<std::chrono::steady_clock::time_point> m_lastStatus;
    std::optional<std::chrono::seconds> m_shownAge;  // staleAge() when updated() was last emitted
    QTimer m_ageTimer;
};
