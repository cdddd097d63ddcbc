#pragma once

// Play, pause, speed and position of a frame log replay. The widget only
// shows and asks: ReplayBinding passes its requests on to the ReplayLink in the
// link thread and feeds back where playback stands.

#include <QWidget>

class QComboBox;
class QLabel;
class QSlider;
class QToolButton;

class ReplayControls : public QWidget {
    Q_OBJECT

public:
    explicit ReplayControls(QWidget* parent = nullptr);

    // A log being opened: no span yet, and a time that says so.
    void showOpening();
    // The log's time span, in UTC microseconds; resets the position.
    void setRange(qint64 startMicros, qint64 endMicros);
    void setPosition(qint64 utcMicros);
    void setPaused(bool paused);
    void setFinished(bool finished);
    double speed() const;
    // "00:12:34 / 24:00:00", as shown.
    QString timeText() const;
    // Shows `speed` (one of the choices) without asking for it again.
    void setSpeed(double speed);

signals:
    void pauseRequested(bool paused);
    void speedRequested(double speed);
    void seekRequested(qint64 utcMicros);

private:
    void showTime(qint64 utcMicros);

    qint64 m_start = 0;
    qint64 m_end = 0;
    bool m_paused = false;
    QToolButton* m_play;
    QComboBox* m_speed;
    QSlider* m_slider;
    QLabel* m_time;
};
