// A slider bound to one integer item of one commanded unit, for the surfaces
// an operator moves rather than types: by the mouse only, never the wheel or
// the keyboard (the ItemSpinBox beside it is the keyboard's way in). It and an ItemSpinBox on the same item
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

protected:
    void keyPressEvent(QKeyEvent* event) override;

private:
    void refresh();
    void commit(int value);

    CommandState* m_command;
    UnitRef m_ref;
    rcm::ItemId m_id;
};
