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
    : QFrame(parent),
      m_alarm(alarm),
      m_text(new QLabel),
      m_silenced(new QLabel(tr("Alarm silenced"))),
      m_silence(new QPushButton(tr("&Silence alarm")))
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
    m_silence->setAutoDefault(false);
    // Never the focus: a Space meant for another control must not silence it.
    m_silence->setFocusPolicy(Qt::NoFocus);
    connect(m_silence, &QPushButton::clicked, alarm, &LinkAlarm::acknowledge);

    auto* layout = new QHBoxLayout(this);
    layout->setContentsMargins(14, 10, 14, 10);
    layout->addWidget(m_text, 1);
    layout->addWidget(m_silenced);
    layout->addWidget(m_silence);

    m_timer.setInterval(1000);
    connect(&m_timer, &QTimer::timeout, this, &LinkAlarmBanner::refresh);
    connect(alarm, &LinkAlarm::changed, this, &LinkAlarmBanner::refresh);
    refresh();
}

QString LinkAlarmBanner::text() const
{
    return m_text->text();
}

QString LinkAlarmBanner::alarmText(qint64 silentMicros)
{
    return tr("LINK LOST \u2014 no frame from the aircraft for %1").arg(LinkAlarm::durationText(silentMicros));
}

void LinkAlarmBanner::refresh()
{
    const bool active = m_alarm->isActive();
    setVisible(active);
    if (!active) {
        m_timer.stop();
        m_text->clear();
        return;
    }
    if (!m_timer.isActive())
        m_timer.start();
    m_text->setText(alarmText(m_alarm->silentMicros()));
    m_silence->setVisible(!m_alarm->isAcknowledged());
    m_silenced->setVisible(m_alarm->isAcknowledged());
}
