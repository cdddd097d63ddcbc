// A slider bound to one integer item of one commanded unit, for the surfaces
// an operator moves rather than types. It and an ItemSpinBox on the same item
// stay in step through CommandState, not through each other.
#pragma once

#include "codec/message/ItemTable.h"
#include "ui/panels/UnitRef.h"

#include <QSlider>

class CommandState;

class ItemSlider : public QSlider {
    Q_OBJECT

public:
    ItemSlider(CommandState* command, UnitRef ref, rcm::ItemId id, QWidget* parent = nullptr);

    rcm::ItemId item() const { return m_id; }

private:
    void refresh();
    void commit(int value);

    CommandState* m_command;
    UnitRef m_ref;
    rcm::ItemId m_id;
};
