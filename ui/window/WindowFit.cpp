#include "ui/window/WindowFit.h"

#include <QRect>
#include <QScreen>
#include <QWidget>

#include <algorithm>

namespace WindowFit {

QSize fittingSize(const QSize& available, const QMargins& frame)
{
    return QSize(std::min(available.width() - frame.left() - frame.right(), 1600),
                 std::min(available.height() - frame.top() - frame.bottom(), 1000));
}

QMargins frameMargins(const QWidget& window)
{
    // Not known before the window manager framed it.
    QMargins margins(4, 32, 4, 4);
    const QRect frame = window.frameGeometry();
    const QRect inside = window.geometry();
    if (window.isVisible()) {
        margins.setLeft(std::max(margins.left(), inside.left() - frame.left()));
        margins.setTop(std::max(margins.top(), inside.top() - frame.top()));
        margins.setRight(std::max(margins.right(), frame.right() - inside.right()));
        margins.setBottom(std::max(margins.bottom(), frame.bottom() - inside.bottom()));
    }
    return margins;
}

QSize defaultSize(const QWidget& window)
{
    // Most of the screen, up to what the console can use; the status bar
    // must not fall below the screen's edge.
    const QRect screen = window.screen() ? window.screen()->availableGeometry() : QRect(0, 0, 1366, 768);
    return fittingSize(screen.size(), frameMargins(window));
}

bool fitIntoScreen(QWidget& window)
{
    if (!window.screen())
        return false;
    const QRect available = window.screen()->availableGeometry();
    if (available.contains(window.frameGeometry()))
        return false;
    window.resize(window.size().boundedTo(fittingSize(available.size(), frameMargins(window))));
    window.move(available.topLeft());
    return true;
}

}  // namespace WindowFit
