#include "ui/overview/LinkQualityPlot.h"

#include "ui/overview/LinkQualityHistory.h"

#include <QDateTime>
#include <QEvent>
#include <QLocale>
#include <QPainter>

#include <functional>

namespace {

constexpr qint64 kMinuteMicros = 60'000'000;

QString clock(qint64 utcMicros)
{
    return QDateTime::fromMSecsSinceEpoch(utcMicros / 1000, Qt::UTC).toString(QStringLiteral("HH:mm"));
}

}  // namespace

// Saturated enough to tell apart on a light or a dark window, and apart for
// the common red-green colour blindness (blue against red).
const QColor LinkQualityPlot::kCorrectedColour = QColor(0x19, 0x76, 0xd2);
const QColor LinkQualityPlot::kLostColour = QColor(0xd3, 0x2f, 0x2f);

LinkQualityPlot::LinkQualityPlot(const LinkQualityHistory* history, QWidget* parent)
    : QWidget(parent), m_history(history)
{
    setObjectName(QStringLiteral("linkQualityPlot"));
    setAccessibleName(tr("Link quality per minute"));
    setToolTip(tr("Per UTC minute, the last hour: bytes Reed-Solomon corrected (blue) and status frames lost, "
                  "beyond correction, refused or never heard (red)"));
    setSizePolicy(QSizePolicy::Expanding, QSizePolicy::Fixed);
}

QSize LinkQualityPlot::sizeHint() const
{
    return {480, fontMetrics().height() * 6};
}

QSize LinkQualityPlot::minimumSizeHint() const
{
    return {240, fontMetrics().height() * 6};
}

void LinkQualityPlot::setNow(qint64 utcMicros)
{
    // The overview calls this every second, but only the minute at the right
    // edge and the bars are drawn: the same picture is not painted again
    // (a repaint of the plot is some milliseconds of the GUI thread).
    m_now = utcMicros;
    Drawn drawn;
    const auto& minutes = m_history->minutes();
    const qint64 now = m_now ? m_now : (minutes.empty() ? 0 : minutes.back().startUtcMicros);
    drawn.lastMinute = now - now % kMinuteMicros;
    if (!minutes.empty()) {
        drawn.first = minutes.front();
        drawn.last = minutes.back();
        drawn.count = minutes.size();
    }
    if (drawn == m_drawn)
        return;
    m_drawn = drawn;
    m_picture = QPixmap();
    update();
}

void LinkQualityPlot::changeEvent(QEvent* event)
{
    QWidget::changeEvent(event);
    if (event->type() == QEvent::PaletteChange || event->type() == QEvent::FontChange ||
        event->type() == QEvent::StyleChange)
        m_picture = QPixmap();
}

void LinkQualityPlot::paintEvent(QPaintEvent*)
{
    const qreal ratio = devicePixelRatioF();
    if (m_picture.isNull() || m_picture.size() != size() * ratio) {
        m_picture = QPixmap(size() * ratio);
        m_picture.setDevicePixelRatio(ratio);
        m_picture.fill(Qt::transparent);
        QPainter p(&m_picture);
        draw(p);
    }
    QPainter(this).drawPixmap(0, 0, m_picture);
}

void LinkQualityPlot::draw(QPainter& p) const
{
    const QFontMetrics fm = fontMetrics();
    const int line = fm.height();
    const auto& minutes = m_history->minutes();
    const qint64 now = m_now ? m_now : (minutes.empty() ? 0 : minutes.back().startUtcMicros);
    const qint64 last = now - now % kMinuteMicros;
    const qint64 first = last - (LinkQualityHistory::kMinutes - 1) * kMinuteMicros;
    const QColor text = palette().color(QPalette::WindowText);
    QColor axis = text;
    axis.setAlphaF(0.35);

    const int left = fm.horizontalAdvance(QStringLiteral("Corrected bytes/min  ")) + 4;
    const int right = width() - 6;
    const int plotWidth = std::max(60, right - left);
    const double slot = double(plotWidth) / LinkQualityHistory::kMinutes;
    const int stripHeight = (height() - 2 * line - 8) / 2;

    struct Strip {
        QString name;
        QColor colour;
        std::function<quint64(const LinkQualityHistory::Minute&)> value;
    };
    const Strip strips[] = {
        {tr("Corrected bytes/min"), kCorrectedColour, [](const auto& m) { return m.correctedBytes; }},
        {tr("Lost frames/min"), kLostColour, [](const auto& m) { return m.lostFrames; }},
    };
    const QLocale locale;
    int top = 2;
    for (const Strip& strip : strips) {
        quint64 max = 0;
        for (const auto& m : minutes)
            max = std::max(max, strip.value(m));
        const QRect area(left, top, plotWidth, stripHeight);
        p.setPen(text);
        p.drawText(QRect(0, top, left - 6, line), Qt::AlignRight | Qt::AlignVCenter, strip.name);
        p.drawText(QRect(0, top + line, left - 6, line), Qt::AlignRight | Qt::AlignVCenter,
                   max ? tr("max %1").arg(locale.toString(max)) : tr("none"));
        p.setPen(axis);
        p.drawLine(area.bottomLeft(), area.bottomRight());
        p.drawLine(area.topLeft(), area.bottomLeft());
        if (max) {
            p.setPen(Qt::NoPen);
            p.setBrush(strip.colour);
            for (const auto& m : minutes) {
                if (m.startUtcMicros < first || m.startUtcMicros > last)
                    continue;
                const quint64 v = strip.value(m);
                if (!v)
                    continue;
                const int index = int((m.startUtcMicros - first) / kMinuteMicros);
                const int h = std::max(2, int(double(v) / double(max) * (stripHeight - 2)));
                const int x = left + int(index * slot) + 1;
                p.drawRect(QRect(x, area.bottom() - h, std::max(1, int(slot) - 1), h));
            }
        }
        top += stripHeight + 4;
    }
    // The time axis: the hour's first and last minute, and the middle.
    p.setPen(text);
    const int labelTop = top;
    p.drawText(QRect(left, labelTop, plotWidth, line), Qt::AlignLeft | Qt::AlignVCenter, clock(first));
    p.drawText(QRect(left, labelTop, plotWidth, line), Qt::AlignHCenter | Qt::AlignVCenter,
               clock(first + 30 * kMinuteMicros));
    p.drawText(QRect(left, labelTop, plotWidth, line), Qt::AlignRight | Qt::AlignVCenter,
               clock(last) + QStringLiteral(" UTC"));
}
