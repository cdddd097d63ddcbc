#pragma once

// The link's quality over the last hour as two bar strips sharing a time
// axis, one bar per UTC minute: bytes Reed-Solomon corrected (blue) and
// status frames lost (red), each with its own scale. Drawn with QPainter
// from a LinkQualityHistory; the window's palette gives the text and axes,
// so it reads in the day and night themes alike.

#include <QColor>
#include <QWidget>

class LinkQualityHistory;

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
    void paintEvent(QPaintEvent* event) override;

private:
    const LinkQualityHistory* m_history;
    qint64 m_now = 0;
};
