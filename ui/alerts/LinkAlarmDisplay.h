#pragma once

// What the two faces of the link-loss alarm share (LinkAlarmBanner over the
// command panels, LinkStateStrip in a floating dock): the alarm they show,
// the label that says it, the button that silences it, and a tick once a
// second while the alarm is on, so that its count of silent seconds stays
// current.

#include <QFrame>
#include <QTimer>

class LinkAlarm;
class QLabel;
class QPushButton;

class LinkAlarmDisplay : public QFrame {
    Q_OBJECT

public:
    QString text() const;
    QPushButton* silenceButton() const { return m_silence; }

public slots:
    // Redraws from the alarm's state: when it changes, and each second while ticking.
    virtual void refresh() = 0;

protected:
    // `silenceText` names the button (its tool tip is the subclass's).
    LinkAlarmDisplay(LinkAlarm* alarm, const QString& silenceText, QWidget* parent);
    // Ticks once a second while `on`; refresh() calls it.
    void tickWhile(bool on);

    LinkAlarm* m_alarm;
    QLabel* m_text;
    QPushButton* m_silence;

private:
    QTimer m_tick;
};
