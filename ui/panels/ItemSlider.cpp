#include "ui/panels/ItemSlider.h"

#include "ui/panels/CommandState.h"
#include "ui/panels/DeliberateInput.h"
#include "ui/panels/ItemText.h"

#include <QKeyEvent>
#include <QSignalBlocker>

ItemSlider::ItemSlider(CommandState* command, UnitRef ref, rcm::ItemId id, QWidget* parent)
    : QSlider(Qt::Horizontal, parent), m_command(command), m_ref(ref), m_id(id)
{
    const rcm::ItemInfo& info = rcm::itemInfo(id);
    setObjectName(ItemText::name(id) + QStringLiteral(".slider"));
    setRange(static_cast<int>(info.min), static_cast<int>(info.max));
    setSingleStep(1);
    setPageStep(10);
    setTickPosition(QSlider::TicksBelow);
    // Wide enough to set a surface to the degree by hand.
    setMinimumWidth(360);
    setTickInterval(static_cast<int>(info.max - info.min) / 4);
    setToolTip(ItemText::toolTip(id));
    setAccessibleName(ItemText::label(id));
    // Moved by the mouse only: the spin box beside it takes the keyboard, so
    // an arrow key pressed by mistake while the slider has focus moves nothing.
    setFocusPolicy(Qt::NoFocus);
    DeliberateInput::protect(this);
    refresh();
    connect(this, &QSlider::valueChanged, this, &ItemSlider::commit);
    connect(command, &CommandState::changed, this, &ItemSlider::refresh);
}

void ItemSlider::refresh()
{
    const rcm::Value* v = m_command->value(m_ref, m_id);
    setEnabled(v != nullptr);
    if (v && v->number != value()) {
        const QSignalBlocker block(this);
        setValue(static_cast<int>(v->number));
    }
}

void ItemSlider::commit(int value)
{
    if (!m_command->setNumber(m_ref, m_id, value))
        refresh();
}

void ItemSlider::keyPressEvent(QKeyEvent* event)
{
    event->ignore();
}
