#pragma once

// The link's state and its alarm in a line, for a window other than the main
// one (a floating dock): a plain "Link: Connected" while all is well, and the
// alarm's solid red "LINK LOST - no frame from the aircraft for 12 s" with
// its Silence button while the link is lost, so that a dock floated over the
// main window (a maximised flight plan) never hides the alarm.

#include "link/session/LinkStatistics.h"
#include "ui/alerts/LinkAlarmDisplay.h"

class LinkStateStrip : public LinkAlarmDisplay {
    Q_OBJECT

public:
    explicit LinkStateStrip(LinkAlarm* alarm, QWidget* parent = nullptr);

    bool isAlarm() const { return m_alarmShown; }

public slots:
    void setStatistics(const LinkStatistics& statistics);
    void setReplay(bool replay);
    void refresh() override;

private:
    LinkState m_state = LinkState::Closed;
    bool m_replay = false;
    bool m_alarmShown = false;
};
