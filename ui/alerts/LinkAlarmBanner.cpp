#include "ui/alerts/LinkAlarmBanner.h"

#include "ui/alerts/LinkAlarm.h"

#include <QHBoxLayout>
#include <QLabel>
#include <QPushButton>

namespace {

// White on dark red: 6.6:1, readable in sunlight and at night alike.
const QString kStyle = QStringLiteral(
    "LinkAlarmBanner { background-color: #b71c1c; border: none; }"
    "LinkAlarmBanner QLabel { color: white; background: transparent; }"
    "LinkAlarmBanner QPushButton { color: black; background-color: white; border: 2px solid #ffcdd2;"
    " border-radius: 3px; padding: 6px 14px; font-weight: bold; }");

}  // namespace

LinkAlarmBanner::LinkAlarmBanner(LinkAlarm* alarm, QWidget* parent)
    : LinkAlarmDisplay(alarm, tr("&Silence alarm"), parent), m_silenced(new QLabel(tr("Alarm silenced")))
{
    setObjectName(QStringLiteral("linkAlarmBanner"));
    setStyleSheet(kStyle);
    setAccessibleName(tr("Link lost"));
    m_text->setObjectName(QStringLiteral("linkAlarmText"));
    m_text->setWordWrap(true);
    QSizePolicy policy(QSizePolicy::Ignored, QSizePolicy::Preferred);
    policy.setHeightForWidth(true);
    m_text->setSizePolicy(policy);
    QFont big = m_text->font();
    big.setBold(true);
    big.setPointSizeF(big.pointSizeF() * 1.8);
    m_text->setFont(big);
    m_silence->setToolTip(tr("Stop the tone; this banner stays until the link is back"));

    auto* layout = new QHBoxLayout(this);
    layout->setContentsMargins(14, 10, 14, 10);
    layout->addWidget(m_text, 1);
    layout->addWidget(m_silenced);
    layout->addWidget(m_silence);
    refresh();
}

QString LinkAlarmBanner::alarmText(qint64 silentMicros)
{
    return tr("LINK LOST \u2014 no frame from the aircraft for %1").arg(LinkAlarm::durationText(silentMicros));
}

void LinkAlarmBanner::refresh()
{
    const bool active = m_alarm->isActive();
    setVisible(active);
    tickWhile(active);
    if (!active) {
        m_text->clear();
        return;
    }
    m_text->setText(alarmText(m_alarm->silentMicros()));
    m_silence->setVisible(!m_alarm->isAcknowledged());
    m_silenced->setVisible(m_alarm->isAcknowledged());
}
