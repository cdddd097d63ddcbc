#include "ui/panels/SteadyGroupBox.h"

#include <QEvent>
#include <QPaintEvent>
#include <QPainter>
#include <QStyle>
#include <QStyleOptionGroupBox>

SteadyGroupBox::SteadyGroupBox(const QString& title, QWidget* parent) : QGroupBox(title, parent) {}

void SteadyGroupBox::paintEvent(QPaintEvent* event)
{
    if (isCheckable()) {
        QGroupBox::paintEvent(event);
        return;
    }
    const qreal ratio = devicePixelRatioF();
    const Look look{size(), ratio, title(), isEnabled(), isActiveWindow()};
    if (m_frame.isNull() || look != m_look) {
        m_look = look;
        m_frame = QPixmap(size() * ratio);
        m_frame.setDevicePixelRatio(ratio);
        m_frame.fill(Qt::transparent);
        // As QGroupBox::paintEvent draws it, into the picture.
        QPainter painter(&m_frame);
        QStyleOptionGroupBox option;
        initStyleOption(&option);
        style()->drawComplexControl(QStyle::CC_GroupBox, &option, &painter, this);
        ++m_framesDrawn;
    }
    QPainter painter(this);
    const QRect dirty = event->rect();
    painter.drawPixmap(dirty, m_frame, QRectF(QPointF(dirty.topLeft()) * ratio, QSizeF(dirty.size()) * ratio));
}

void SteadyGroupBox::changeEvent(QEvent* event)
{
    QGroupBox::changeEvent(event);
    switch (event->type()) {
        case QEvent::FontChange:
        case QEvent::PaletteChange:
        case QEvent::StyleChange:
        case QEvent::LayoutDirectionChange:
            m_frame = QPixmap();
            break;
        default:
            break;
    }
}
