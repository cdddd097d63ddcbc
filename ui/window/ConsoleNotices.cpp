#include "ui/window/ConsoleNotices.h"

#include "ui/alerts/ConsoleAlerts.h"

#include "ui/window/StatusBarWidget.h"

namespace {
constexpr int kShownMs = 8000;
constexpr int kErrorShownMs = 10000;
}  // namespace

void ConsoleNotices::flash(const QString& text) const
{
    m_bar->showMessage(text, kShownMs);
}

void ConsoleNotices::info(EventSource source, const QString& text) const
{
    m_bar->showMessage(text, kShownMs);
    m_alerts->info(source, text);
}

void ConsoleNotices::error(const QString& message, EventSource source) const
{
    m_bar->showMessage(message, kErrorShownMs);
    m_alerts->error(source, message);
}
