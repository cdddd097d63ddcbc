#pragma once

// The link at a glance, for the main window's status bar: its state, frames
// sent and received, bytes Reed-Solomon corrected, frames beyond correction,
// how long ago the last good frame came, whether the link is encrypted and
// authenticated and, when any, the frames it rejected by reason, and the
// link-lost alarm. The alarm
// is a red, blinking "LINK LOST" that stays until a good frame arrives again
// or the operator disconnects, and a signal, alarm(bool), for whatever else
// should sound it (a tone, a light). In a replay it says "Replay" and the
// log's time instead, and never the alarm.

#include "link/session/LinkStatistics.h"

#include <QTimer>
#include <QWidget>

class QLabel;
class SignalBars;
class StatusFigure;

class StatusBarWidget : public QWidget {
    Q_OBJECT

public:
    explicit StatusBarWidget(QWidget* parent = nullptr);

    bool alarmActive() const { return m_alarm; }
    const LinkStatistics& statistics() const { return m_statistics; }
    // The texts shown, for tests and screenshots.
    QString stateText() const;
    // The state in words: "Connected", "Lost", "Replay"...
    QString stateName() const { return m_stateName; }
    QString ageText() const;
    // "encrypted and authenticated" or "not encrypted".
    QString securityText() const;
    // "forged 3, replayed 1", the reasons with a count; empty when there are none.
    QString rejectedText() const;
    // The transport's own state and how long it has been so: "dialling
    // 881612345678, 0:14"; empty when the transport has none (UDP).
    QString transportText() const;
    // "registered, signal 3 of 5"; empty when no modem said.
    QString modemServiceText() const;
    // The window's passing message (QStatusBar::showMessage), shown beside
    // the state; empty when none.
    QString messageText() const;
    const QLabel* messageLabel() const { return m_message; }
    const QLabel* stateLabel() const { return m_state; }

public slots:
    void setStatistics(const LinkStatistics& statistics);
    void setState(LinkState state);
    // What the link is, "UDP 127.0.0.1:5600"; empty when there is none.
    void setLinkDescription(const QString& description);
    // The key's fingerprint (16 hex digits) for the tooltip; empty: none.
    void setKeyFingerprint(const QString& fingerprint);
    // A replay: the state reads "Replay", the age gives way to the log's own
    // time, and a silence in the log raises no alarm.
    void setReplay(bool replay);
    void setReplayTime(qint64 utcMicros);
    // What the transport says it does (a modem's call); empty: nothing to show.
    // What the transport status is of: "Call" (a modem's), "Broker" (an observation's).
    void setTransportLabel(const QString& label, const QString& toolTip);
    void setTransportStatus(const QString& status);
    // A satellite phone's service: signal bars beside the call; bars -1 and
    // an empty text hide them (no modem).
    void setModemService(int signalBars, bool registered, const QString& text);
    // A passing message (ConsoleNotices): this widget fills the status bar,
    // whose own message QStatusBar would paint over the link's state, so the
    // message is shown here, beside it. Gone again after `shownMs` (0: kept
    // until the next).
    void showMessage(const QString& text, int shownMs = 0);

signals:
    // True when the link is lost, false when it is back or was closed.
    void alarm(bool on);

protected:
    bool eventFilter(QObject* watched, QEvent* event) override;

private:
    void renderState();
    void updateAge();
    void updateTransport();
    void updateSecurity();
    void setAlarm(bool on);
    void blink();

    LinkStatistics m_statistics;
    QString m_description;
    QString m_stateName;
    QString m_stateColour;
    QString m_fingerprint;
    QString m_transportStatus;
    QString m_transportLabel = tr("Call");
    QString m_transportToolTip = tr("The satellite phone's call: what the modem does, and for how long");
    qint64 m_transportSince = 0;  // ms since the epoch
    bool m_alarm = false;
    bool m_replay = false;
    qint64 m_replayTime = 0;
    bool m_blink = false;
    QTimer m_ageTimer;
    QTimer m_blinkTimer;
    QTimer m_messageTimer;  // clears a passing message
    QLabel* m_state;
    QLabel* m_message;
    StatusFigure* m_sent;
    StatusFigure* m_received;
    StatusFigure* m_corrected;
    StatusFigure* m_uncorrectable;
    StatusFigure* m_age;
    QLabel* m_security;
    QWidget* m_rejectedSeparator;
    QLabel* m_rejected;
    QLabel* m_lost;
    QWidget* m_transportSeparator;
    StatusFigure* m_transport;
    SignalBars* m_signal;
};
