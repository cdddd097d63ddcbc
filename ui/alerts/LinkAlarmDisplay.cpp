#include "ui/alerts/LinkAlarmDisplay.h"

#include "ui/alerts/LinkAlarm.h"

#include <QLabel>
#include <QPushButton>

LinkAlarmDisplay::LinkAlarmDisplay(LinkAlarm* alarm, const QString& silenceText, QWidget* parent)
    : QFrame(parent), m_alarm(alarm), m_text(new QLabel), m_silence(new QPushButton(silenceText))
{
    m_silence->setAutoDefault(false);
    // Never the focus: a Space meant for another control must not silence it.
    m_silence->setFocusPolicy(Qt::NoFocus);
    connect(m_silence, &QPushButton::clicked, alarm, &LinkAlarm::acknowledge);
    m_tick.setInterval(1000);
    connect(&m_tick, &QTimer::timeout, this, &LinkAlarmDisplay::refresh);
    connect(alarm, &LinkAlarm::changed, this, &LinkAlarmDisplay::refresh);
}

QString LinkAlarmDisplay::text() const
{
    return m_text->text();
}

void LinkAlarmDisplay::tickWhile(bool on)
{
    if (!on)
        m_tick.stop();
    else if (!m_tick.isActive())
        m_tick.start();
}
