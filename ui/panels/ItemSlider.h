// A slider bound to one integer item of one commanded unit, for the surfaces
// an operator moves rather than types. It moves in two ways only, each one
// deliberate action that is sent once:
// - the handle dragged with the left button: the value under the handle is
//   shown as not sent while dragging and commanded once, on release;
// - an arrow key while it has the focus: one single step (a degree) a key
//   press; a held key does not repeat.
// A click or a held button on the track, PageUp/PageDown, Home/End and the
// wheel change nothing. A release or key that makes a large change (the
// item table's rule: more than 5 degrees for a control surface) asks first,
// through CommandGate; cancelled, the handle goes back to the command.
// It and an ItemSpinBox on the same item stay in step through CommandState,
// not through each other.
#pragma once

#include "codec/message/ItemTable.h"
#include "ui/panels/UnitRef.h"

#include <QSlider>

#include <optional>

class CommandState;

class ItemSlider : public QSlider {
    Q_OBJECT

public:
    ItemSlider(CommandState* command, UnitRef ref, rcm::ItemId id, QWidget* parent = nullptr);

    rcm::ItemId item() const { return m_id; }
    // While the handle is dragged: the value under it, not sent yet.
    std::optional<int> dragged() const { return m_dragged; }
    // What the operator is told while dragging: "Rudder 12° not sent: release to send".
    QString draggedText() const;

protected:
    void mousePressEvent(QMouseEvent* event) override;
    void mouseReleaseEvent(QMouseEvent* event) override;
    void keyPressEvent(QKeyEvent* event) override;
    // Keeps the held key's bookkeeping (repeated()): its release, or the focus going.
    bool event(QEvent* event) override;

private:
    bool onHandle(QPoint pos) const;
    bool repeated(const QKeyEvent* event) const;
    void refresh();
    void commit(int value);
    void showDragged(int position);

    CommandState* m_command;
    UnitRef m_ref;
    rcm::ItemId m_id;
    std::optional<int> m_dragged;
    // The arrow key held down, and the last one let go and when: a held key
    // repeats as presses flagged isAutoRepeat(), or on X11 as presses
    // without a release, or as releases and presses with one timestamp.
    int m_keyDown = 0;
    int m_keyReleased = 0;
    quint64 m_releasedAt = 0;
};
