// A combo box bound to one two-bit field of one commanded unit: its entries
// are the field's valid codes from the item table, in words ("Automatic",
// "Ground station", "RC transmitter"), so no corrupt code (00, or 11 where it
// has no meaning) can be chosen. A change is a choice from the open
// list: neither the wheel nor a stray arrow or letter key changes the field
// (Space, F4 or Alt+Down open the list).
#pragma once

#include "codec/message/ItemTable.h"
#include "ui/panels/UnitRef.h"

#include <QComboBox>

class CommandState;

class FieldComboBox : public QComboBox {
    Q_OBJECT

public:
    FieldComboBox(CommandState* command, UnitRef ref, rcm::ItemId id, int field, QWidget* parent = nullptr);

    rcm::ItemId item() const { return m_id; }
    int field() const { return m_field; }

protected:
    void keyPressEvent(QKeyEvent* event) override;

private:
    void refresh();
    void commit(int index);

    CommandState* m_command;
    UnitRef m_ref;
    rcm::ItemId m_id;
    int m_field;
};
