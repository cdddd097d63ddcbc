#include "ui/window/StatusBarWidget.h"

#include "codec/receive/Refusal.h"
#include "ui/look/LinkStateName.h"
#include "ui/look/SeverityColours.h"
#include "ui/panels/SteadyLabel.h"
#include "ui/window/SignalBars.h"
#include "ui/window/StatusFigure.h"

#include <QDateTime>
#include <QEvent>
#include <QGuiApplication>
#include <QHBoxLayout>
#include <QLabel>
#include <QLocale>
#include <QStringList>

#include <algorithm>
#include <array>

namespace {

QLabel* counter(const QString& toolTip)
{
    auto* label = new SteadyLabel;
    label->setToolTip(toolTip);
    label->setTextFormat(Qt::RichText);
    return label;
}

QFrame* separator()
{
    auto* line = new QFrame;
    line->setFrameShape(QFrame::VLine);
    line->setFrameShadow(QFrame::Sunken);
    return line;
}

// The names beside the figures: a grey at 4.5:1 or more on the status bar in either theme.
QString muted()
{
    return SeverityColours::isDark(QGuiApplication::palette()) ? QStringLiteral("#a8a8a8") : QStringLiteral("#6b6b6b");
}

QString field(const QString& name, const QString& value)
{
    return QStringLiteral("<span style=\"color:%1\">%2</span> <b>%3</b>").arg(muted(), name, value);
}

}  // namespace

StatusBarWidget::StatusBarWidget(QWidget* parent)
    : QWidget(parent),
      m_state(new SteadyLabel),
      m_message(new QLabel),
      m_sent(new StatusFigure(tr("Sent"), tr("Frames handed to the link since it started"))),
      m_received(new StatusFigure(tr("Received"), tr("Good frames received from the aircraft"))),
      m_corrected(new StatusFigure(tr("Corrected bytes"),
                                   tr("Bytes Reed-Solomon corrected in the frames received (BLOCK 1 + BLOCK 2)"))),
      m_uncorrectable(
          new StatusFigure(tr("Uncorrectable"), tr("Frames received with a codeword beyond correction"))),
      m_age(new StatusFigure(tr("Last frame"), tr("Time since the last good frame from the aircraft"))),
      m_security(counter(QString())),
      m_rejectedSeparator(separator()),
      m_rejected(counter(tr("Frames the receive path refused, by reason (docs/protocol.md section 8):\n"
                            "wrong size: a datagram that is not 510 bytes\n"
                            "enciphered: no key here, and the frame looks enciphered\n"
                            "not exact: not exactly as the profile's encoder writes a frame\n"
                            "implausible: does not follow the last frame accepted from its sender\n"
                            "forged: not sent with this aircraft's key (a wrong key file, or an injector)\n"
                            "replayed: authentic, but not newer than the last frame accepted\n"
                            "stale time: authentic and new, but its time is over 30 s from this computer's clock\n"
                            "plaintext: an unencrypted frame on a keyed link"))),
      m_lost(new QLabel(tr("LINK LOST"))),
      m_transportSeparator(separator()),
      m_transport(new StatusFigure(m_transportLabel, m_transportToolTip)),
      m_signal(new SignalBars)
{
    m_state->setTextFormat(Qt::RichText);
    const int stateWidth =
        fontMetrics().horizontalAdvance(QStringLiteral("\u25cf Connected  UDP 255.255.255.255:65535"));
    m_state->setMinimumWidth(stateWidth);
    // The state keeps that width, whatever its text's length (a long
    // description is elided); the message beside it takes the room left.
    // Ignored here gave the state no room in the layout at all, and the
    // message was drawn over it.
    m_state->setSizePolicy(QSizePolicy::Fixed, QSizePolicy::Preferred);
    m_state->installEventFilter(this);
    // The message takes the room the state and the figures leave; a long one
    // is cut, whole in the tool tip and the event log.
    m_message->setObjectName(QStringLiteral("statusMessage"));
    m_message->setTextFormat(Qt::PlainText);
    m_message->setSizePolicy(QSizePolicy::Ignored, QSizePolicy::Preferred);
    m_message->setMinimumWidth(fontMetrics().horizontalAdvance(QStringLiteral("Exported /home/operator/x.csv")));
    m_lost->setToolTip(tr("No good frame from the aircraft within the silence timeout"));
    m_lost->setAlignment(Qt::AlignCenter);
    m_lost->setMinimumWidth(fontMetrics().horizontalAdvance(QStringLiteral("  LINK LOST  ")) + 16);
    m_lost->hide();

    auto* layout = new QHBoxLayout(this);
    layout->setContentsMargins(6, 0, 6, 0);
    layout->setSpacing(12);
    layout->addWidget(m_state);
    layout->addWidget(m_message, 1);
    for (QWidget* figure : std::initializer_list<QWidget*>{m_sent, m_received, m_corrected, m_uncorrectable, m_age,
                                                            m_security}) {
        layout->addWidget(separator());
        layout->addWidget(figure);
    }
    layout->addWidget(m_rejectedSeparator);
    layout->addWidget(m_rejected);
    layout->addWidget(m_transportSeparator);
    layout->addWidget(m_signal);
    layout->addWidget(m_transport);
    m_transportSeparator->hide();
    m_transport->hide();
    m_signal->hide();
    layout->addWidget(m_lost);

    m_ageTimer.setInterval(250);
    connect(&m_ageTimer, &QTimer::timeout, this, &StatusBarWidget::updateAge);
    connect(&m_ageTimer, &QTimer::timeout, this, &StatusBarWidget::updateTransport);
    m_messageTimer.setSingleShot(true);
    connect(&m_messageTimer, &QTimer::timeout, this, [this] { showMessage(QString()); });
    m_blinkTimer.setInterval(500);
    connect(&m_blinkTimer, &QTimer::timeout, this, &StatusBarWidget::blink);
    setStatistics(LinkStatistics());
}

QString StatusBarWidget::stateText() const
{
    return m_state->text();
}

QString StatusBarWidget::messageText() const
{
    return m_message->text();
}

void StatusBarWidget::showMessage(const QString& text, int shownMs)
{
    m_message->setText(text);
    m_message->setToolTip(text);
    if (shownMs > 0)
        m_messageTimer.start(shownMs);
    else
        m_messageTimer.stop();
}

QString StatusBarWidget::ageText() const
{
    return m_age->text();
}


QString StatusBarWidget::securityText() const
{
    return m_statistics.secure ? tr("encrypted and authenticated") : tr("not encrypted");
}

QString StatusBarWidget::rejectedText() const
{
    const QLocale locale;
    QStringList parts;
    const auto add = [&](quint64 count, const QString& reason) {
        if (count)
            parts << QStringLiteral("%1 %2").arg(reason, locale.toString(count));
    };
    // Uncorrectable frames have their own counter.
    for (int r = 0; r < rcm::kRefusalCount; ++r) {
        if (rcm::Refusal(r) == rcm::Refusal::Uncorrectable)
            continue;
        const std::string_view name = rcm::refusalName(rcm::Refusal(r));
        add(m_statistics.refused[std::size_t(r)], QString::fromLatin1(name.data(), qsizetype(name.size())));
    }
    return parts.join(QStringLiteral(", "));
}

QString StatusBarWidget::transportText() const
{
    if (m_transportStatus.isEmpty())
        return QString();
    const qint64 s = std::max<qint64>(0, (QDateTime::currentMSecsSinceEpoch() - m_transportSince) / 1000);
    const QString since = s < 3600 ? QStringLiteral("%1:%2").arg(s / 60).arg(s % 60, 2, 10, QLatin1Char('0'))
                                   : QStringLiteral("%1:%2:%3")
                                         .arg(s / 3600)
                                         .arg(s % 3600 / 60, 2, 10, QLatin1Char('0'))
                                         .arg(s % 60, 2, 10, QLatin1Char('0'));
    return QStringLiteral("%1, %2").arg(m_transportStatus, since);
}

void StatusBarWidget::setTransportStatus(const QString& status)
{
    m_transportStatus = status;
    m_transportSince = QDateTime::currentMSecsSinceEpoch();
    m_transportSeparator->setVisible(!status.isEmpty() || !m_signal->text().isEmpty());
    m_transport->setVisible(!status.isEmpty());
    if (!status.isEmpty())
        m_ageTimer.start();
    updateTransport();
}

QString StatusBarWidget::modemServiceText() const
{
    return m_signal->isVisibleTo(this) ? m_signal->text() : QString();
}

void StatusBarWidget::setModemService(int signalBars, bool registered, const QString& text)
{
    m_signal->setService(signalBars, registered, text);
    m_signal->setVisible(!text.isEmpty());
    m_transportSeparator->setVisible(!text.isEmpty() || !m_transportStatus.isEmpty());
}

void StatusBarWidget::updateTransport()
{
    m_transport->setName(m_transportLabel);
    if (m_transportStatus.isEmpty())
        return;
    // A long status (why the phone is not dialled) is the banner's and the
    // event log's to say whole: here it is elided, whole in the tool tip.
    const QString text = transportText();
    const int room = fontMetrics().horizontalAdvance(QStringLiteral("connected at 19200 bit/s after 14 s, 12:03:45"));
    m_transport->setValue(fontMetrics().elidedText(text, Qt::ElideMiddle, room));
    m_transport->setToolTip(m_transportToolTip + QStringLiteral("\n") + m_transportStatus);
}

void StatusBarWidget::setTransportLabel(const QString& label, const QString& toolTip)
{
    m_transportLabel = label;
    m_transportToolTip = toolTip;
    updateTransport();
}

void StatusBarWidget::setKeyFingerprint(const QString& fingerprint)
{
    m_fingerprint = fingerprint;
    updateSecurity();
}

void StatusBarWidget::updateSecurity()
{
    if (m_statistics.secure) {
        m_security->setText(
            SeverityColours::span(SeverityColours::Severity::Success, QGuiApplication::palette(), securityText()));
        m_security->setToolTip(
            tr("Every frame sent is enciphered with the aircraft's key and every frame received must "
               "authenticate, be newer than the last and carry the current time (docs/security.md).") +
            (m_fingerprint.isEmpty() ? QString() : tr("\nKey fingerprint: %1").arg(m_fingerprint)));
    } else {
        m_security->setText(
            QStringLiteral("<span style=\"color:%1\">%2</span>").arg(muted(), securityText().toHtmlEscaped()));
        m_security->setToolTip(
            tr("No key file: frames go in the clear and are not authenticated. Choose the aircraft's key file "
               "in the link settings for a secure link."));
    }
    const QString rejected = rejectedText();
    m_rejected->setText(
        field(tr("Refused"), QStringLiteral("<span style=\"color:%1\">%2</span>").arg(SeverityColours::text(SeverityColours::Severity::Error, QGuiApplication::palette()).name(), rejected.toHtmlEscaped())));
    m_rejected->setVisible(!rejected.isEmpty());
    m_rejectedSeparator->setVisible(!rejected.isEmpty());
}

void StatusBarWidget::setLinkDescription(const QString& description)
{
    m_description = description;
    setState(m_statistics.state);
}

void StatusBarWidget::setReplay(bool replay)
{
    m_replay = replay;
    m_replayTime = 0;
    setState(m_statistics.state);
}

void StatusBarWidget::setReplayTime(qint64 utcMicros)
{
    m_replayTime = utcMicros;
    updateAge();
}

void StatusBarWidget::setState(LinkState state)
{
    m_statistics.state = state;
    // The dot's colour, in LinkState's order: grey, amber, green, red.
    static constexpr std::array<const char*, 4> kColours{"#8a8a8a", "#c98a00", "#1d7a35", "#b01c1c"};
    QString name = linkStateName(state);
    QString colour = QLatin1String(kColours[static_cast<std::size_t>(state)]);
    if (m_replay && state != LinkState::Closed) {
        // A log's silences and ends are not the aircraft's.
        name = tr("Replay");
        colour = QStringLiteral("#1565c0");
    }
    m_stateName = name;
    m_stateColour = colour;
    m_state->setToolTip(state == LinkState::Closed ? QString() : m_description);
    renderState();
    setAlarm(state == LinkState::Lost && !m_replay);
    if (state == LinkState::Closed)
        m_ageTimer.stop();
    else if (!m_ageTimer.isActive())
        m_ageTimer.start();
    updateAge();
}

// The description is elided to the room the label has, so that a long port
// path and a modem's number never push the figures beside it under one
// another (at 1366 px, in a call); the whole of it is the tool tip. A label
// not shown yet has no room to speak of: it says it all.
void StatusBarWidget::renderState()
{
    QString text = QStringLiteral("<span style=\"color:%1\">\u25cf</span> <b>%2</b>").arg(m_stateColour, m_stateName);
    if (!m_description.isEmpty() && m_statistics.state != LinkState::Closed) {
        QString shown = m_description;
        if (m_state->isVisible()) {
            QFont bold = font();
            bold.setBold(true);
            const int room = m_state->width() -
                             QFontMetrics(bold).horizontalAdvance(QStringLiteral("\u25cf ") + m_stateName) -
                             fontMetrics().horizontalAdvance(QStringLiteral("   "));
            shown = fontMetrics().elidedText(m_description, Qt::ElideMiddle, std::max(room, 0));
        }
        text += QStringLiteral(" <span style=\"color:%1\">%2</span>").arg(muted(), shown.toHtmlEscaped());
    }
    if (text != m_state->text())
        m_state->setText(text);
}

bool StatusBarWidget::eventFilter(QObject* watched, QEvent* event)
{
    if (watched == m_state && (event->type() == QEvent::Resize || event->type() == QEvent::Show))
        renderState();
    return QWidget::eventFilter(watched, event);
}

void StatusBarWidget::setStatistics(const LinkStatistics& statistics)
{
    const bool stateChanged = statistics.state != m_statistics.state;
    m_statistics = statistics;
    const QLocale locale;
    m_sent->setValue(locale.toString(statistics.framesSent));
    m_received->setValue(locale.toString(statistics.framesReceived));
    m_corrected->setValue(locale.toString(statistics.correctedBytesBlock1 + statistics.correctedBytesBlock2));
    const quint64 uncorrectable = statistics.refusedFor(rcm::Refusal::Uncorrectable);
    m_uncorrectable->setValue(locale.toString(uncorrectable));
    m_uncorrectable->setValueColour(uncorrectable ? QColor(0xb0, 0x1c, 0x1c) : QColor());
    updateSecurity();
    if (stateChanged || statistics.state == LinkState::Closed)
        setState(statistics.state);
    else
        updateAge();
}

void StatusBarWidget::updateAge()
{
    if (m_replay) {
        const QString time = m_replayTime ? QDateTime::fromMSecsSinceEpoch(m_replayTime / 1000, Qt::UTC)
                                                .toString(QStringLiteral("yyyy-MM-dd HH:mm:ss 'UTC'"))
                                          : QStringLiteral("\u2014");
        m_age->setName(tr("Log time"));
        m_age->setValue(time);
        return;
    }
    const qint64 age = m_statistics.lastGoodFrameAgeMicros(QDateTime::currentDateTimeUtc().toMSecsSinceEpoch() * 1000);
    QString text;
    if (age < 0)
        text = QStringLiteral("\u2014");
    else if (age < 60'000'000)
        text = tr("%1 s ago").arg(double(std::max<qint64>(age, 0)) / 1e6, 0, 'f', 1);
    else if (age < 3'600'000'000)
        text = tr("%1 min ago").arg(age / 60'000'000);
    else
        text = tr("%1 h ago").arg(age / 3'600'000'000);
    m_age->setName(tr("Last frame"));
    m_age->setValue(text);
}

void StatusBarWidget::setAlarm(bool on)
{
    if (on == m_alarm)
        return;
    m_alarm = on;
    m_lost->setVisible(on);
    if (on) {
        m_blink = false;
        m_blinkTimer.start();
        blink();
    } else {
        m_blinkTimer.stop();
    }
    emit alarm(on);
}

// Alternates two looks rather than hiding the label: the alarm never
// disappears, it only pulses.
void StatusBarWidget::blink()
{
    m_blink = !m_blink;
    m_lost->setStyleSheet(m_blink ? QStringLiteral("background:#b01c1c; color:white; font-weight:bold; "
                                                   "border-radius:3px; padding:1px 8px;")
                                  : QStringLiteral("background:#f6d5d5; color:#b01c1c; font-weight:bold; "
                                                   "border-radius:3px; padding:1px 8px;"));
}
