#pragma once

// A label whose text changes with the frames: counters, figures, the values
// the aircraft reports. A plain QLabel asks its layout for room on every new
// text; the layouts above it are then worked out again up to the window, and
// any widget the new sizes move is repainted: at 10x replay, whole pages many
// times a second, the GUI thread's longest stalls. This label keeps the size
// it has grown to as a fixed size, so a new text repaints the label alone. It
// grows when a text does not fit (one pass of the event loop later, once per
// new widest text), never shrinks for a shorter text, and is fitted anew when
// its font or style changes. It is first fitted when shown, painted or not
// (a label scrolled out of view would otherwise ask for room with every new
// text). A minimum width set before it is first shown is kept as its least
// width. Not for word-wrapped text.

#include <QLabel>

class SteadyLabel : public QLabel {
    Q_OBJECT

public:
    explicit SteadyLabel(QWidget* parent = nullptr);
    explicit SteadyLabel(const QString& text, QWidget* parent = nullptr);

protected:
    void showEvent(QShowEvent* event) override;
    void paintEvent(QPaintEvent* event) override;
    void changeEvent(QEvent* event) override;

private:
    void queueFit();
    void fit();

    QSize m_least;         // the minimum size set before the first fit
    QString m_fittedText;  // the text the size was last checked against
    bool m_fitted = false;
    bool m_fitQueued = false;
};
