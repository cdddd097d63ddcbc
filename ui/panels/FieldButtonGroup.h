// Exclusive buttons bound to one two-bit field of one commanded unit, one per
// valid code from the item table, in words (Out (down) | Retracted, Off | On):
// for the switches an operator must see the position of at a glance. The
// buttons are named after their codes (objectName "RETRACTED"). Only a click
// or Space on a button changes the field, never an arrow key or the wheel.
// A change to the code the item table asks about (a wheel to RETRACTED)
// goes through CommandGate's question; a panel may add to it what the change
// would do (the fuel dump: which tanks start dumping).
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
    // What commanding `code` would do, for the question; empty: nothing to add.
    using Detail = std::function<QString(unsigned code)>;

    FieldButtonGroup(CommandState* command, UnitRef ref, rcm::ItemId id, int field, QWidget* parent = nullptr);

    void setDetail(Detail detail) { m_detail = std::move(detail); }
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
    Detail m_detail;
};
