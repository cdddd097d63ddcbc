#pragma once

// The Link dock's content: where to connect (LinkSettingsWidget), the
// buttons that start and stop a link, this station's control, a note on
// what runs, and the replay's controls while a log plays. The buttons only
// ask (connectRequested() ...); what may be started or stopped now comes
// from the session (update()).

#include <QWidget>

class ConsoleSession;
class LinkSettingsWidget;
class QLabel;
class QPushButton;
class ReplayControls;
class StationControl;
class StationControlWidget;

class LinkPane : public QWidget {
    Q_OBJECT

public:
    explicit LinkPane(StationControl* control, QWidget* parent = nullptr);

    LinkSettingsWidget* settings() const { return m_settings; }
    StationControlWidget* stationControl() const { return m_stationControl; }
    ReplayControls* replayControls() const { return m_replayControls; }
    // "Connect" or "Dial", "Disconnect" or "Hang up": the action as the buttons name it now.
    QString connectText() const;
    QString disconnectText() const;

    // From the session's state: what can be started or stopped now, and
    // what the buttons say (a satellite phone's modem dials and hangs up).
    void update(const ConsoleSession& session);
    void setNote(const QString& text);
    void showNotConnected();

signals:
    void connectRequested();
    void disconnectRequested();
    void rehearsalRequested();

private:
    LinkSettingsWidget* m_settings;
    QPushButton* m_connect;
    QPushButton* m_disconnect;
    QPushButton* m_rehearsal;
    StationControlWidget* m_stationControl;
    QLabel* m_note;
    ReplayControls* m_replayControls;
};
