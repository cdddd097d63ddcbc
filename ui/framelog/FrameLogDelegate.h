#pragma once

// Paints the frame log's cells. Qt's own delegate lays each cell's text out
// afresh on every paint, twice (once to place it, once to draw it), and that
// was most of the log view's paint time: a replay at 10x scrolls the log
// twenty times a second, and every row it shows is painted as it enters, as
// it is played and as the next one is. Most of the log's texts repeat ("sent",
// "decoded", "none"), and every one is painted several times, so this
// delegate keeps each text laid out (QStaticText) for the font it was drawn
// in: the most recently drawn few thousand, the least recently drawn given up
// one at a time (all at once, they took milliseconds to free). The background, selection and focus frame are still the
// style's; the text is the model's, in its colour, font and alignment, elided
// on the right when its column is too narrow.

#include <QFont>
#include <QCache>
#include <QStaticText>
#include <QStyledItemDelegate>

class FrameLogDelegate : public QStyledItemDelegate {
    Q_OBJECT

public:
    using QStyledItemDelegate::QStyledItemDelegate;

    void paint(QPainter* painter, const QStyleOptionViewItem& option, const QModelIndex& index) const override;

    // Texts kept laid out, for tests.
    int laidOutTexts() const { return int(m_texts.size() + m_bold.size()); }

private:
    static constexpr int kMostTexts = 2048;  // many screens of rows

    const QStaticText& laidOut(const QString& text, const QFont& font) const;

    mutable QFont m_font;                          // the texts' font
    mutable QFont m_boldFont;                      // the bold texts' font (the last row played)
    mutable QCache<QString, QStaticText> m_texts{kMostTexts};  // in m_font
    mutable QCache<QString, QStaticText> m_bold{kMostTexts};   // in m_boldFont
};
