#pragma once

// The link-loss alarm on screen: a solid red band across the top of the
// command panels, in large white letters, "LINK LOST - no frame for 42 s",
// with the button that silences the tone. It stays, counting, until the link
// comes back or is closed; once silenced it says so instead of the button.

#include "ui/alerts/LinkAlarmDisplay.h"

class LinkAlarmBanner : public LinkAlarmDisplay {
    Q_OBJECT

public:
    explicit LinkAlarmBanner(LinkAlarm* alarm, QWidget* parent = nullptr);

    // "LINK LOST \u2014 no frame from the aircraft for 12 s"
    static QString alarmText(qint64 silentMicros);

public slots:
    // Redraws the time without a frame; a timer calls it every second.
    void refresh() override;

private:
    QLabel* m_silenced;
};
