// Exclusive buttons bound to one two-bit field of one commanded unit, one per
// valid code from the item table, in words (Out (down) | Retracted, Off | On):
// for the switches an operator must see the position of at a glance. The
// buttons are named after their codes (objectName "RETRACTED"). Only a click
// or Space on a button changes the field, never an arrow key or the wheel. A guard, when set, may refuse a change
// before it reaches the command (the fuel dump's confirmation).
#pragma once

#include "codec/message/ItemTable.h"
#include "ui/panels/UnitRef.h"

#include <QWidget>

#include <functional>

class CommandState;
class QAbstractButton;
class QButtonGroup;

class FieldButtonGroup : public QWidget {
    Q_OBJECT

public:
    // Called with the code about to be commanded; false leaves the command as it was.
    using Guard = std::function<bool(unsigned code)>;

    FieldButtonGroup(CommandState* command, UnitRef ref, rcm::ItemId id, int field, QWidget* parent = nullptr);

    void setGuard(Guard guard) { m_guard = std::move(guard); }
    // The button for a code, nullptr for a code that is not valid in this field.
    QAbstractButton* button(unsigned code) const;
    rcm::ItemId item() const { return m_id; }
    int field() const { return m_field; }

protected:
    bool eventFilter(QObject* watched, QEvent* event) override;

private:
    void refresh();
    void commit(int code);

    CommandState* m_command;
    UnitRef m_ref;
    rcm::ItemId m_id;
    int m_field;
    QButtonGroup* m_group;
    Guard m_guard;
};
