// A spin box bound to one numeric item of one commanded unit: range, unit,
// decimals and tool tip from the item table, shown as people read the item
// (rcm::presentation: MHz for a kHz frequency, percent for a 0..255 setting),
// the value from CommandState. value() is the number on the wire.
//
// Only a complete, valid value is commanded, and only on Enter: typing 120
// does not command 1 and 12 on the way, and an arrow key, PageUp/PageDown or
// the buttons step the text without sending it. Until then the box is
// marked: "edited" (typed or stepped, not sent yet; Esc goes back to the
// command) or "invalid" (not a value the item takes; never sent, and Enter
// leaves it on show for correction). Leaving the box before Enter (Tab, a
// click elsewhere, a tab switch, another window) sends nothing: the box shows
// the command again and says so, in its tool tip and through
// CommandGate::notSent(). Enter on a large change (the item table's rule)
// asks first; cancelled, the box shows the command. The wheel never changes it.
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
    // What the box last said was not sent, empty after a commit or an edit.
    QString notSentText() const { return m_notSent; }

    QValidator::State validate(QString& text, int& pos) const override;
    QString textFromValue(double wire) const override;
    double valueFromText(const QString& text) const override;
    void stepBy(int steps) override;

protected:
    void keyPressEvent(QKeyEvent* event) override;
    void focusOutEvent(QFocusEvent* event) override;

private:
    void refresh();
    void commit();
    void showState();
    void restoreUnsent(const QString& left);
    QString defaultToolTip() const;

    CommandState* m_command;
    UnitRef m_ref;
    rcm::ItemId m_id;
    bool m_edited = false;  // typed in or stepped since the command was last shown
    QString m_notSent;
};
