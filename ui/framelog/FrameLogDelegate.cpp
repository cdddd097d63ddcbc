#include "ui/framelog/FrameLogDelegate.h"

#include <QApplication>
#include <QPainter>
#include <QStyle>

const QStaticText& FrameLogDelegate::laidOut(const QString& text, const QFont& font) const
{
    const bool bold = font.bold();
    QFont& kept = bold ? m_boldFont : m_font;
    QCache<QString, QStaticText>& texts = bold ? m_bold : m_texts;
    if (font != kept) {
        texts.clear();
        kept = font;
    }
    if (QStaticText* known = texts.object(text))
        return *known;
    auto* laid = new QStaticText(text);
    laid->setTextFormat(Qt::PlainText);
    laid->prepare(QTransform(), font);
    texts.insert(text, laid);
    return *laid;
}

void FrameLogDelegate::paint(QPainter* painter, const QStyleOptionViewItem& option, const QModelIndex& index) const
{
    QStyleOptionViewItem opt = option;
    initStyleOption(&opt, index);
    const QWidget* widget = opt.widget;
    QStyle* style = widget ? widget->style() : QApplication::style();
    // The row's background: alternate rows, selection, hover.
    style->drawPrimitive(QStyle::PE_PanelItemViewItem, &opt, painter, widget);

    // As Qt's delegate places it: a focus frame's margin and a pixel each side.
    const int margin = style->pixelMetric(QStyle::PM_FocusFrameHMargin, nullptr, widget) + 1;
    const QRect room = opt.rect.adjusted(margin, 0, -margin, 0);
    const QPalette::ColorGroup group = !(opt.state & QStyle::State_Enabled) ? QPalette::Disabled
                                       : (opt.state & QStyle::State_Active) ? QPalette::Normal
                                                                             : QPalette::Inactive;
    painter->save();
    painter->setPen(opt.palette.color(group, (opt.state & QStyle::State_Selected) ? QPalette::HighlightedText
                                                                                    : QPalette::Text));
    painter->setFont(opt.font);
    const QStaticText& text = laidOut(opt.text, opt.font);
    const QSizeF size = text.size();
    if (size.width() > room.width()) {
        // Too narrow a column (the operator made it so): drawn as Qt would, elided.
        painter->drawText(room, int(opt.displayAlignment),
                          opt.fontMetrics.elidedText(opt.text, Qt::ElideRight, room.width()));
    } else {
        const qreal x = (opt.displayAlignment & Qt::AlignRight) ? room.right() + 1 - size.width()
                        : (opt.displayAlignment & Qt::AlignHCenter) ? room.left() + (room.width() - size.width()) / 2
                                                                    : room.left();
        const qreal y = (opt.displayAlignment & Qt::AlignTop)      ? room.top()
                        : (opt.displayAlignment & Qt::AlignBottom) ? room.bottom() + 1 - size.height()
                                                                   : room.top() + (room.height() - size.height()) / 2;
        painter->drawStaticText(QPointF(x, y), text);
    }
    painter->restore();

    if (opt.state & QStyle::State_HasFocus) {
        QStyleOptionFocusRect focus;
        focus.QStyleOption::operator=(opt);
        focus.state |= QStyle::State_KeyboardFocusChange | QStyle::State_Item;
        focus.backgroundColor = opt.palette.color(group, (opt.state & QStyle::State_Selected) ? QPalette::Highlight
                                                                                               : QPalette::Window);
        style->drawPrimitive(QStyle::PE_FrameFocusRect, &focus, painter, widget);
    }
}
