// A spin box bound to one numeric item of one commanded unit: range, unit,
// decimals and tool tip from the item table, shown as people read the item
// (rcm::presentation: MHz for a kHz frequency, percent for a 0..255 setting),
// the value from CommandState. value() is the number on the wire.
//
// Only a complete, valid value is commanded, and only on Enter or when the
// box loses the focus: typing 120 does not command 1 and 12 on the way, and
// an arrow key steps the text without sending it. Until then the box is
// marked: "edited" (typed or stepped, not sent yet; Esc goes back to the
// command) or "invalid" (not a value the item takes; never sent, and Enter
// leaves it on show for correction). The wheel never changes it.
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
    bool edited() const { return property("edited").toBool(); }
    bool invalid() const { return property("invalid").toBool(); }

    QValidator::State validate(QString& text, int& pos) const override;
    QString textFromValue(double wire) const override;
    double valueFromText(const QString& text) const override;
    void stepBy(int steps) override;

protected:
    void keyPressEvent(QKeyEvent* event) override;

private:
    void refresh();
    void commit();
    void showState();

    CommandState* m_command;
    UnitRef m_ref;
    rcm::ItemId m_id;
    bool m_edited = false;  // typed in or stepped since the command was last shown
};
