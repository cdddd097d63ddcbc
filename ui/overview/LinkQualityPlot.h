#pragma once

// The link's quality over the last hour as two bar strips sharing a time
// axis, one bar per UTC minute: bytes Reed-Solomon corrected (blue) and
// status frames lost (red), each with its own scale. Drawn with QPainter
// from a LinkQualityHistory; the window's palette gives the text and axes,
// so it reads in the day and night themes alike.

#include "ui/overview/LinkQualityHistory.h"

#include <QColor>
#include <QPixmap>
#include <QWidget>

#include <cstddef>

class QPainter;

class LinkQualityPlot : public QWidget {
    Q_OBJECT

public:
    static const QColor kCorrectedColour;
    static const QColor kLostColour;

    explicit LinkQualityPlot(const LinkQualityHistory* history, QWidget* parent = nullptr);

    QSize sizeHint() const override;
    QSize minimumSizeHint() const override;
    // The UTC minute drawn at the right edge; the latest sample's when 0.
    void setNow(qint64 utcMicros);

protected:
    // The picture is drawn once into a pixmap and copied from it: the page
    // around the plot is repainted more often than its picture changes, and
    // drawing it is a millisecond of the GUI thread, copying it a few
    // microseconds.
    void paintEvent(QPaintEvent* event) override;
    void changeEvent(QEvent* event) override;

private:
    // What a picture shows: the minutes change only at the ends.
    struct Drawn {
        qint64 lastMinute = -1;
        LinkQualityHistory::Minute first;
        LinkQualityHistory::Minute last;
        std::size_t count = 0;
        friend bool operator==(const Drawn&, const Drawn&) = default;
    };

    void draw(QPainter& p) const;

    const LinkQualityHistory* m_history;
    QPixmap m_picture;  // null when it is to be drawn again
    qint64 m_now = 0;
    Drawn m_drawn;
};
