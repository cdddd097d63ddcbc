#include "ui/panels/DeliberateInput.h"

#include <QEvent>
#include <QWidget>

namespace {

// Handled, so the control never sees it, but not accepted, so that
// QApplication passes it on to the parent: the scroll area scrolls.
class WheelPassOn : public QObject {
public:
    using QObject::QObject;

protected:
    bool eventFilter(QObject*, QEvent* event) override
    {
        if (event->type() != QEvent::Wheel)
            return false;
        event->ignore();
        return true;
    }
};

}  // namespace

void DeliberateInput::protect(QWidget* control)
{
    if (control->focusPolicy() != Qt::NoFocus)
        control->setFocusPolicy(Qt::StrongFocus);
    control->installEventFilter(new WheelPassOn(control));
}

QString DeliberateInput::editedStyle(const char* className)
{
    return QStringLiteral("%1 { background-color: #bcd7ff; color: black; }").arg(QLatin1String(className));
}

QString DeliberateInput::invalidStyle(const char* className)
{
    return QStringLiteral("%1 { background-color: #ffbf00; color: black; }").arg(QLatin1String(className));
}
