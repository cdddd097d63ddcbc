#pragma once

// Asking the window manager for the operator's attention to a window, as the
// link is lost: QApplication::alert (the taskbar entry flashes; on X11 the
// _NET_WM_STATE_DEMANDS_ATTENTION state, which Qt gives only a window that is
// not active) and, on X11, the ICCCM urgency hint in WM_HINTS, which window
// managers and panels show whether or not the window is active, until the
// console clears it (the alarm silenced, the link back or closed).

class QWidget;

namespace WindowAttention {

void request(QWidget* window);
void clear(QWidget* window);
// The urgency hint as the X server has it; false on any other platform.
bool isUrgent(QWidget* window);

}  // namespace WindowAttention
