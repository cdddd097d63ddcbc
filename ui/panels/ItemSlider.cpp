#include "ui/panels/ItemSlider.h"

#include "ui/panels/CommandGate.h"
#include "ui/panels/CommandState.h"
#include "ui/panels/DeliberateInput.h"
#include "ui/panels/ItemText.h"

#include <QKeyEvent>
#include <QMouseEvent>
#include <QSignalBlocker>
#include <QStyle>
#include <QStyleOptionSlider>
#include <QToolTip>

namespace {

QString sliderToolTip(rcm::ItemId id)
{
    const QString step = ItemText::number(id, 1) + ItemText::unitSuffix(id);
    QStringList tip{ItemText::toolTip(id), ItemSlider::tr("Drag the handle: sent once, on release."),
                    ItemSlider::tr("Left/Right arrow: %1 a key press, sent at once.").arg(step),
                    ItemSlider::tr("A click on the track changes nothing.")};
    if (const QString rule = CommandGate::ruleText(id); !rule.isEmpty())
        tip << rule;
    return tip.join(QLatin1Char('\n'));
}

}  // namespace

ItemSlider::ItemSlider(CommandState* command, UnitRef ref, rcm::ItemId id, QWidget* parent)
    : QSlider(Qt::Horizontal, parent), m_command(command), m_ref(ref), m_id(id)
{
    const rcm::ItemInfo& info = rcm::itemInfo(id);
    setObjectName(ItemText::name(id) + QStringLiteral(".slider"));
    setRange(static_cast<int>(info.min), static_cast<int>(info.max));
    setSingleStep(1);
    setPageStep(1);  // never used: the track and PageUp/PageDown do nothing
    // A drag is one action: valueChanged() once, on release.
    setTracking(false);
    setTickPosition(QSlider::TicksBelow);
    // Wide enough to set a surface to the degree by hand.
    setMinimumWidth(360);
    setTickInterval(static_cast<int>(info.max - info.min) / 4);
    setToolTip(sliderToolTip(id));
    setAccessibleName(ItemText::label(id));
    DeliberateInput::protect(this);
    refresh();
    connect(this, &QSlider::valueChanged, this, &ItemSlider::commit);
    connect(this, &QSlider::sliderMoved, this, &ItemSlider::showDragged);
    connect(command, &CommandState::changed, this, &ItemSlider::refresh);
}

QString ItemSlider::draggedText() const
{
    if (!m_dragged)
        return {};
    return tr("%1 %2 not sent: release to send")
        .arg(ItemText::label(m_id), ItemText::value(m_id, rcm::Value::of(*m_dragged)));
}

bool ItemSlider::onHandle(QPoint pos) const
{
    QStyleOptionSlider option;
    initStyleOption(&option);
    return style()->subControlRect(QStyle::CC_Slider, &option, QStyle::SC_SliderHandle, this).contains(pos);
}

void ItemSlider::mousePressEvent(QMouseEvent* event)
{
    // Only the handle, with the left button, starts a drag. A press on the
    // track would page-step, and held, repeat; the middle button would jump.
    if (event->button() == Qt::LeftButton && onHandle(event->position().toPoint())) {
        QSlider::mousePressEvent(event);
        return;
    }
    event->accept();
}

void ItemSlider::mouseReleaseEvent(QMouseEvent* event)
{
    // QSlider commits the drag here (valueChanged, through the gate); after
    // that, or a drag back to where it started, the handle shows the command.
    const bool dragging = isSliderDown();
    QSlider::mouseReleaseEvent(event);
    if (!dragging)
        return;
    m_dragged.reset();
    QToolTip::hideText();
    refresh();
}

void ItemSlider::keyPressEvent(QKeyEvent* event)
{
    switch (event->key()) {
        case Qt::Key_Left:
        case Qt::Key_Right:
        case Qt::Key_Up:
        case Qt::Key_Down:
            if (event->modifiers() & ~Qt::KeypadModifier)
                break;
            // One step a press: a held key is not a series of deliberate steps.
            if (!repeated(event) && !isSliderDown())
                QSlider::keyPressEvent(event);
            m_keyDown = event->key();
            event->accept();
            return;
        default:
            break;
    }
    // PageUp/PageDown, Home/End and the rest are not the slider's.
    event->ignore();
}

bool ItemSlider::repeated(const QKeyEvent* event) const
{
    // Qt's X11 backend flags a repeat only when it finds the next press
    // already queued at the release; often it is not, and the pair then
    // looks like a new press, except that both carry the same time.
    // (Events made by a program may carry no time at all: 0 is no time.)
    return event->isAutoRepeat() || event->key() == m_keyDown ||
           (event->key() == m_keyReleased && m_releasedAt != 0 && event->timestamp() == m_releasedAt);
}

bool ItemSlider::event(QEvent* event)
{
    if (event->type() == QEvent::KeyRelease) {
        const auto* key = static_cast<const QKeyEvent*>(event);
        if (key->key() == m_keyDown && !key->isAutoRepeat()) {
            m_keyDown = 0;
            m_keyReleased = key->key();
            m_releasedAt = key->timestamp();
        }
    } else if (event->type() == QEvent::FocusOut) {
        m_keyDown = 0;  // its release goes elsewhere
    }
    return QSlider::event(event);
}

void ItemSlider::showDragged(int position)
{
    m_dragged = position;
    QStyleOptionSlider option;
    initStyleOption(&option);
    const QRect handle = style()->subControlRect(QStyle::CC_Slider, &option, QStyle::SC_SliderHandle, this);
    QToolTip::showText(mapToGlobal(handle.topLeft()), draggedText(), this);
}

void ItemSlider::refresh()
{
    const rcm::Value* v = m_command->value(m_ref, m_id);
    setEnabled(v != nullptr);
    // The handle under the operator's hand stays there; the release compares with the command.
    if (v && !isSliderDown() && (v->number != value() || sliderPosition() != value())) {
        const QSignalBlocker block(this);
        setValue(static_cast<int>(v->number));
        setSliderPosition(static_cast<int>(v->number));
    }
}

void ItemSlider::commit(int value)
{
    if (!CommandGate::of(m_command)->setNumber(this, m_ref, m_id, value))
        refresh();
}
