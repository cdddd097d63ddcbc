#pragma once

// The frame log's scroll bar. A replay moves the log one row a frame, and a
// QScrollBar repaints itself whole on every new value, although over a day's
// log (86,400 rows) its slider moves one pixel every few hundred rows. The
// Fusion style fills its groove with a gradient and hands the rows of a tall
// fill to Qt's GUI thread pool, so the GUI thread waits on other threads too:
// a millisecond or two of its time every frame. This bar repaints on a new
// value only when the slider is drawn elsewhere, or an end is reached or
// left (the arrows then change); every other change repaints it as before.

#include <QScrollBar>

class SteadyScrollBar : public QScrollBar {
    Q_OBJECT

public:
    explicit SteadyScrollBar(Qt::Orientation orientation, QWidget* parent = nullptr);

protected:
    void sliderChange(SliderChange change) override;
    void paintEvent(QPaintEvent* event) override;

private:
    struct Look {
        QRect slider;
        bool atMinimum = false;
        bool atMaximum = false;
        bool operator==(const Look&) const = default;
    };
    Look look() const;

    Look m_shown;  // as last painted
    bool m_painted = false;
};
