#pragma once

// The link-loss alarm on screen: a solid red band across the top of the
// command panels, in large white letters, "LINK LOST - no frame for 42 s",
// with the button that silences the tone. It stays, counting, until the link
// comes back or is closed; once silenced it says so instead of the button.

#include <QFrame>
#include <QTimer>

class LinkAlarm;
class QLabel;
class QPushButton;

class LinkAlarmBanner : public QFrame {
    Q_OBJECT

public:
    explicit LinkAlarmBanner(LinkAlarm* alarm, QWidget* parent = nullptr);

    QString text() const;
    // "LINK LOST \u2014 no frame from the aircraft for 12 s"
    static QString alarmText(qint64 silentMicros);
    QPushButton* silenceButton() const { return m_silence; }

public slots:
    // Redraws the time without a frame; a timer calls it every second.
    void refresh();

private:
    LinkAlarm* m_alarm;
    QLabel* m_text;
    QLabel* m_silenced;
    QPushButton* m_silence;
    QTimer m_timer;
};
