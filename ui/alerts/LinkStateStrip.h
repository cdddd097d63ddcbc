#pragma once

// The link's state and its alarm in a line, for a window other than the main
// one (a floating dock): a plain "Link: Connected" while all is well, and the
// alarm's solid red "LINK LOST - no frame from the aircraft for 12 s" with
// its Silence button while the link is lost, so that a dock floated over the
// main window (a maximised flight plan) never hides the alarm.

#include "link/session/LinkStatistics.h"

#include <QFrame>
#include <QTimer>

class LinkAlarm;
class QLabel;
class QPushButton;

class LinkStateStrip : public QFrame {
    Q_OBJECT

public:
    explicit LinkStateStrip(LinkAlarm* alarm, QWidget* parent = nullptr);

    QString text() const;
    bool isAlarm() const { return m_alarmShown; }
    QPushButton* silenceButton() const { return m_silence; }

public slots:
    void setStatistics(const LinkStatistics& statistics);
    void setReplay(bool replay);
    void refresh();

private:
    LinkAlarm* m_alarm;
    LinkState m_state = LinkState::Closed;
    bool m_replay = false;
    bool m_alarmShown = false;
    QLabel* m_text;
    QPushButton* m_silence;
    QTimer m_timer;
};
