// A spin box bound to one numeric item of one commanded unit: range, unit,
// decimals and tool tip from the item table, the value from CommandState,
// and back to it on every step or on Enter (not on every key typed, which
// would command 1, 12, 120 on the way to 120). Integer items too: a double
// holds the 32-bit frequencies that an int spin box cannot.
#pragma once

#include "codec/message/ItemTable.h"
#include "ui/panels/UnitRef.h"

#include <QDoubleSpinBox>

class CommandState;

class ItemSpinBox : public QDoubleSpinBox {
    Q_OBJECT

public:
    ItemSpinBox(CommandState* command, UnitRef ref, rcm::ItemId id, QWidget* parent = nullptr);

    UnitRef unitRef() const { return m_ref; }
    rcm::ItemId item() const { return m_id; }

private:
    void refresh();
    void commit(double shown);

    CommandState* m_command;
    UnitRef m_ref;
    rcm::ItemId m_id;
};
