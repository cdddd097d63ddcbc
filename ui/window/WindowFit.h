#pragma once

// How big a top-level window may be on the screen it is on: the screen's
// available area less the window manager's frame, up to what the console
// can use (1600x1000). Apart from MainWindow, which asks it at start,
// after the first show (when the frame is known) and on Reset layout.

#include <QMargins>
#include <QSize>

class QWidget;

namespace WindowFit {

// What of `available` a window framed by `frame` can take, up to 1600x1000.
QSize fittingSize(const QSize& available, const QMargins& frame);
// The frame the window manager puts around `window`: a usual title bar and
// border, or the one measured once shown when larger. The same before and
// after the first show, so that Reset layout gives the first size again.
QMargins frameMargins(const QWidget& window);
// The first start's size of `window` on its screen (1366x768 without one).
QSize defaultSize(const QWidget& window);
// Shrinks and moves `window` into its screen's available area when its
// frame makes it overhang; false when it already fits (or has no screen).
bool fitIntoScreen(QWidget& window);

}  // namespace WindowFit
