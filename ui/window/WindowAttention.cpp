#include "ui/window/WindowAttention.h"

#include <QApplication>
#include <QWidget>

#ifdef RCM_HAVE_XCB
#include <QtGui/qguiapplication_platform.h>

#include <xcb/xcb.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#endif

namespace {

#ifdef RCM_HAVE_XCB
constexpr std::uint32_t kUrgencyHint = 1u << 8;  // XUrgencyHint, ICCCM 4.1.2.4
constexpr std::uint32_t kHintsWords = 9;         // the WM_HINTS property's length

xcb_connection_t* x11Connection()
{
    auto* x11 = qApp->nativeInterface<QNativeInterface::QX11Application>();
    return x11 ? x11->connection() : nullptr;
}

// The window's WM_HINTS as the server has them; all zero when it has none.
bool readHints(xcb_connection_t* c, xcb_window_t id, std::uint32_t (&hints)[kHintsWords])
{
    std::fill(std::begin(hints), std::end(hints), 0u);
    xcb_get_property_reply_t* reply = xcb_get_property_reply(
        c, xcb_get_property(c, 0, id, XCB_ATOM_WM_HINTS, XCB_ATOM_WM_HINTS, 0, kHintsWords), nullptr);
    if (!reply)
        return false;
    const int length = std::min<int>(xcb_get_property_value_length(reply), int(sizeof hints));
    if (length > 0)
        std::memcpy(hints, xcb_get_property_value(reply), std::size_t(length));
    std::free(reply);
    return true;
}

void setUrgency(QWidget* window, bool urgent)
{
    xcb_connection_t* c = x11Connection();
    if (!c || !window->testAttribute(Qt::WA_WState_Created))
        return;
    const auto id = xcb_window_t(window->winId());
    std::uint32_t hints[kHintsWords];
    readHints(c, id, hints);
    const std::uint32_t flags = urgent ? hints[0] | kUrgencyHint : hints[0] & ~kUrgencyHint;
    if (flags == hints[0])
        return;
    hints[0] = flags;
    xcb_change_property(c, XCB_PROP_MODE_REPLACE, id, XCB_ATOM_WM_HINTS, XCB_ATOM_WM_HINTS, 32, kHintsWords, hints);
    xcb_flush(c);
}
#endif

}  // namespace

namespace WindowAttention {

void request(QWidget* window)
{
    QApplication::alert(window);
#ifdef RCM_HAVE_XCB
    setUrgency(window, true);
#endif
}

void clear(QWidget* window)
{
#ifdef RCM_HAVE_XCB
    setUrgency(window, false);
#else
    Q_UNUSED(window);
#endif
}

bool isUrgent(QWidget* window)
{
#ifdef RCM_HAVE_XCB
    xcb_connection_t* c = x11Connection();
    if (!c || !window->testAttribute(Qt::WA_WState_Created))
        return false;
    std::uint32_t hints[kHintsWords];
    return readHints(c, xcb_window_t(window->winId()), hints) && (hints[0] & kUrgencyHint);
#else
    Q_UNUSED(window);
    return false;
#endif
}

}  // namespace WindowAttention
