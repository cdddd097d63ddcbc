// What every command control passes through to change the command: the
// item table's large-change rule (rcm::LargeChange) applied to the value in
// force, the one question the console asks before such a change (a
// Confirmation: Cancel the default, the action named by its verb, from what
// to what), and the one place a control says that what the operator typed
// was not sent. Sliders, spin boxes, field buttons and combo boxes, station
// editors and the photo button all commit through it, so a rule stated once
// in the table holds for every control that can make the change.
//
// There is one gate per CommandState, made on first use as its child: the
// controls and the window find it from the command they already share.
#pragma once

#include "codec/message/ItemTable.h"
#include "codec/message/Message.h"
#include "ui/alerts/Confirmation.h"
#include "ui/panels/UnitRef.h"

#include <QObject>

#include <functional>
#include <optional>

class CommandState;
class QWidget;

class CommandGate : public QObject {
    Q_OBJECT

public:
    // Shows the question and returns whether the operator confirmed it.
    // Confirmation::ask by default; tests answer in its place.
    using Asker = std::function<bool(const Confirmation& question, QWidget* parent)>;

    static CommandGate* of(CommandState* command);

    CommandState* command() const { return m_command; }

    // The question for changing the item to `to` from the value in force,
    // nothing when the table lets one action make it unasked. `detail` is a
    // panel's word on what the change would do, added to the question.
    // `action` names one control's change of several fields at once ("Retract
    // all wheels"): the question then lists every field that asks.
    std::optional<Confirmation> question(UnitRef ref, rcm::ItemId id, const rcm::Value& to,
                                         const QString& detail = {}, const QString& action = {}) const;

    // Commands `to`, asking first when question() has one. False when the
    // operator cancels or CommandState refuses the change: the command is as
    // it was, and the control shows it again (it hears changed() only when
    // the command changes, so a control refreshes itself on false).
    bool setItem(QWidget* control, UnitRef ref, rcm::ItemId id, const rcm::Value& to, const QString& detail = {},
                 const QString& action = {});
    bool setNumber(QWidget* control, UnitRef ref, rcm::ItemId id, std::int64_t number);
    bool setFieldCode(QWidget* control, UnitRef ref, rcm::ItemId id, int field, unsigned code,
                      const QString& detail = {});

    // True while a question is on screen: the control that asked loses the
    // focus to it, and that is not the operator leaving the field.
    bool asking() const { return m_asking; }

    // An empty asker: Confirmation::ask again.
    void setAsker(Asker asker) { m_asker = std::move(asker); }

    // The large-change rule of an item (or of one field) in a sentence, for
    // the tool tips of the controls: "More than 5° in one action asks first."
    // Empty when no change of it asks.
    static QString ruleText(rcm::ItemId id, int field = -1);

    // For a control whose typed value was left unsent (the field lost the
    // focus before Enter) or whose change was cancelled: emits notSent()
    // with the item (and repeated unit) named before `text`.
    void tellNotSent(UnitRef ref, rcm::ItemId id, const QString& text);

signals:
    // "Elevator: Not sent: '-20°' was left unsent; the command stays 0°": for
    // the window's status bar. The control says it in its tool tip as well.
    void notSent(const QString& text);

private:
    explicit CommandGate(CommandState* command);

    CommandState* m_command;
    Asker m_asker;
    bool m_asking = false;
};
