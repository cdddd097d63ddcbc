#pragma once

// Paints the frame log's cells. Qt's own delegate lays each cell's text out
// afresh on every paint, twice (once to place it, once to draw it), and that
// was most of the log view's paint time: a replay at 10x scrolls the log
// twenty times a second, and every row it shows is painted as it enters, as
// it is played and as the next one is. Most of the log's texts repeat ("sent",
// "decoded", "none"), and every one is painted several times, so this
// delegate keeps each text laid out (QStaticText) for the font it was drawn
// in, up to a bound. The background, selection and focus frame are still the
// style's; the text is the model's, in its colour, font and alignment, elided
// on the right when its column is too narrow.

#include <QFont>
#include <QHash>
#include <QStaticText>
#include <QStyledItemDelegate>

class FrameLogDelegate : public QStyledItemDelegate {
    Q_OBJECT

public:
    using QStyledItemDelegate::QStyledItemDelegate;

    void paint(QPainter* painter, const QStyleOptionViewItem& option, const QModelIndex& index) const override;

    // Texts kept laid out, for tests.
    int laidOutTexts() const { return int(m_texts.size()); }

private:
    static constexpr int kMostTexts = 2048;  // a few screens of rows; then it starts again

    const QStaticText& laidOut(const QString& text, const QFont& font) const;

    mutable QFont m_font;                          // the texts' font
    mutable QFont m_boldFont;                      // the bold texts' font (the last row played)
    mutable QHash<QString, QStaticText> m_texts;   // in m_font
    mutable QHash<QString, QStaticText> m_bold;    // in m_boldFont
};
