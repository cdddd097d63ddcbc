#include "ui/alerts/LinkStateStrip.h"

#include "ui/alerts/LinkAlarm.h"
#include "ui/alerts/LinkAlarmBanner.h"
#include "ui/look/LinkStateName.h"

#include <QHBoxLayout>
#include <QLabel>
#include <QPushButton>

namespace {

// The alarm as LinkAlarmBanner paints it: white on dark red, 6.6:1.
const QString kAlarmStyle = QStringLiteral(
    "LinkStateStrip { background-color: #b71c1c; border: none; }"
    "LinkStateStrip QLabel { color: white; background: transparent; font-weight: bold; }"
    "LinkStateStrip QPushButton { color: black; background-color: white; border: 1px solid #ffcdd2;"
    " border-radius: 3px; padding: 2px 10px; font-weight: bold; }");

}  // namespace

LinkStateStrip::LinkStateStrip(LinkAlarm* alarm, QWidget* parent) : LinkAlarmDisplay(alarm, tr("Silence"), parent)
{
    setObjectName(QStringLiteral("linkStateStrip"));
    setAccessibleName(tr("Link state"));
    m_text->setObjectName(QStringLiteral("linkStateStripText"));
    m_text->setTextFormat(Qt::PlainText);
    // The dock's width decides, never the text's length.
    m_text->setSizePolicy(QSizePolicy::Ignored, QSizePolicy::Preferred);
    m_silence->setToolTip(tr("Stop the tone; the alarm stays until the link is back"));
    auto* layout = new QHBoxLayout(this);
    layout->setContentsMargins(8, 3, 8, 3);
    layout->addWidget(m_text, 1);
    layout->addWidget(m_silence);
    refresh();
}

void LinkStateStrip::setStatistics(const LinkStatistics& statistics)
{
    if (statistics.state == m_state)
        return;
    m_state = statistics.state;
    refresh();
}

void LinkStateStrip::setReplay(bool replay)
{
    m_replay = replay;
    refresh();
}

void LinkStateStrip::refresh()
{
    const bool alarm = m_alarm->isActive();
    if (alarm != m_alarmShown) {
        m_alarmShown = alarm;
        setStyleSheet(alarm ? kAlarmStyle : QString());
    }
    m_silence->setVisible(alarm && !m_alarm->isAcknowledged());
    tickWhile(alarm);
    if (alarm) {
        QString text = LinkAlarmBanner::alarmText(m_alarm->silentMicros());
        if (m_alarm->isAcknowledged())
            text += tr(" (silenced)");
        m_text->setText(text);
        return;
    }
    m_text->setText(m_replay && m_state != LinkState::Closed ? tr("Link: replay of a frame log, read only")
                                                             : tr("Link: %1").arg(linkStateName(m_state)));
}
