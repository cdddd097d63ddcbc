// The state the console commands: one rcm::Message for the chosen airframe,
// changed only through this object so that every change is checked as the
// encoder would check it and every panel hears of it. The main window hands
// message() to LinkController::setCommand whenever changed() is emitted.
#pragma once

#include "codec/message/Airframe.h"
#include "codec/message/Message.h"
#include "link/session/MessageMetaType.h"
#include "ui/panels/UnitRef.h"

#include <QObject>
#include <QString>

#include <functional>

class CommandState : public QObject {
    Q_OBJECT

public:
    // Starts from restingCommand(airframe): the safe state to send first.
    explicit CommandState(rcm::Airframe airframe = rcm::Airframe::wellEquipped(), QObject* parent = nullptr);

    const rcm::Airframe& airframe() const { return m_airframe; }
    // A different aircraft: the command becomes its resting state with every
    // value of the units both airframes have carried over (matched by key:
    // engine 1 stays engine 1); the header (aircraft ID, GCS stations) is
    // kept, it names who talks to whom. Returns the units of the command
    // the new airframe has none of.
    std::vector<rcm::Unit> setAirframe(rcm::Airframe airframe);

    // The command to send. ID_msg, time_UTC and date_UTC are left to the link.
    const rcm::Message& message() const { return m_message; }
    // restingCommand(airframe()): what is safe, and what one-shot commands return to.
    const rcm::Message& resting() const { return m_resting; }

    // Units of a kind in the command: the airframe's count for repeated
    // kinds, 1 for the single ones (0 for sense and avoid when not fitted).
    int unitCount(rcm::UnitKind kind) const;
    // nullptr when `ref` names no unit of the present airframe.
    const rcm::Unit* unit(UnitRef ref) const;
    const rcm::Value* value(UnitRef ref, rcm::ItemId id) const;
    // Code of one two-bit field; 0 when the item is not commanded.
    unsigned fieldCode(UnitRef ref, rcm::ItemId id, int field) const;

    // Each change is all or nothing: refused, with the reason in rejected(),
    // when the value is out of the table's range, the item is a unit's key
    // (keys come from the airframe) or the message would no longer encode.
    // Returns whether the command holds the change; changed() only when it
    // actually differs.
    bool setItem(UnitRef ref, rcm::ItemId id, const rcm::Value& value);
    bool setNumber(UnitRef ref, rcm::ItemId id, std::int64_t number)
    {
        return setItem(ref, id, rcm::Value::of(number));
    }
    bool setFieldCode(UnitRef ref, rcm::ItemId id, int field, unsigned code);
    // For optional items (the header's stations): not sent any more.
    bool eraseItem(UnitRef ref, rcm::ItemId id);
    // Several items of one unit as one change.
    bool editUnit(UnitRef ref, const std::function<void(rcm::Unit&)>& edit);

    // `message` whole as the command, unchecked: what a replayed log
    // commanded, to show while it plays, and the console's own command
    // again afterwards. changed() when it differs.
    void replaceMessage(const rcm::Message& message);

    // One-shot commands (take_one_photo TAKE) waiting for a frame to carry them.
    bool oneShotPending() const;

public slots:
    // A frame carrying the command went out (LinkController::frameSent):
    // one-shot commands go back to their resting value, so that one click
    // is one photograph.
    void frameSent();

signals:
    void changed();
    // An edit of the operator's (setItem() and the rest, not replaceMessage(),
    // setAirframe() or a one-shot's return): the command before it;
    // message() is the command after it. Emitted before changed().
    void changedByOperator(const rcm::Message& before);
    // Emitted before the changed() of the new resting command; panels rebuild their cards.
    void airframeChanged();
    void rejected(const QString& reason);

private:
    rcm::Unit* mutableUnit(UnitRef ref);

    rcm::Airframe m_airframe;
    rcm::Message m_resting;
    rcm::Message m_message;
};
