#pragma once

// A group box whose frame and title are drawn once per size and look, and
// then copied. Its labels are transparent, so a value that changes inside it
// repaints the box behind the value too, and the Fusion style draws a group
// box's frame by stretching a picture over the whole box (with large fills
// handed to Qt's GUI thread pool and waited for): a fifth to a third of a
// millisecond per box per frame, and a status frame changes values in a dozen
// boxes at once. Copying the part to be repainted costs next to nothing. A
// checkable box (with hover and press states) is drawn as QGroupBox draws it.

#include <QGroupBox>
#include <QPixmap>

class SteadyGroupBox : public QGroupBox {
    Q_OBJECT

public:
    explicit SteadyGroupBox(const QString& title, QWidget* parent = nullptr);

    // Times the frame was drawn, for tests.
    int framesDrawn() const { return m_framesDrawn; }

protected:
    void paintEvent(QPaintEvent* event) override;
    void changeEvent(QEvent* event) override;

private:
    struct Look {
        QSize size;
        qreal pixelRatio = 1;
        QString title;
        bool enabled = true;
        bool active = true;
        bool operator==(const Look&) const = default;
    };

    QPixmap m_frame;  // drawn for m_look; null when a change of style, font or palette voided it
    Look m_look;
    int m_framesDrawn = 0;
};
