#include "ui/window/SignalBars.h"

#include <QPainter>

namespace {
constexpr int kBars = 5;
}  // namespace

SignalBars::SignalBars(QWidget* parent) : QWidget(parent)
{
    setSizePolicy(QSizePolicy::Fixed, QSizePolicy::Fixed);
}

QSize SignalBars::sizeHint() const
{
    const int h = fontMetrics().height();
    return {h * 3 / 2, h};
}

void SignalBars::setService(int bars, bool registered, const QString& text)
{
    if (bars == m_bars && registered == m_registered && text == m_text)
        return;
    m_bars = bars;
    m_registered = registered;
    m_text = text;
    setToolTip(text);
    setAccessibleName(text);
    update();
}

void SignalBars::paintEvent(QPaintEvent*)
{
    QPainter painter(this);
    painter.setRenderHint(QPainter::Antialiasing);
    const QRectF area = QRectF(rect()).adjusted(1, 2, -1, -2);
    const double step = area.width() / kBars;
    const double gap = std::max(1.0, step / 4);
    const QColor on = !m_registered ? QColor(0xb0, 0x1c, 0x1c)
                      : m_bars <= 1 ? QColor(0xc9, 0x8a, 0x00)
                                    : palette().color(QPalette::WindowText);
    const QColor off = palette().color(QPalette::Mid);
    for (int i = 0; i < kBars; ++i) {
        const double height = area.height() * (i + 1) / kBars;
        const QRectF bar(area.left() + i * step, area.bottom() - height, step - gap, height);
        const bool filled = m_registered && i < m_bars;
        painter.setPen(QPen(filled ? on : off, 1));
        painter.setBrush(filled ? on : Qt::NoBrush);
        painter.drawRect(bar);
    }
    if (!m_registered && m_bars >= 0) {
        // No network: the bars crossed out, as phones show it.
        painter.setPen(QPen(on, 1.5));
        painter.drawLine(area.bottomLeft(), area.topRight());
    }
}
