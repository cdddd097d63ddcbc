#include "ui/control/StationControlWidget.h"

#include "codec/message/TextFormat.h"
#include "link/session/StationControl.h"
#include "ui/alerts/Confirmation.h"

#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QPushButton>
#include <QVBoxLayout>

namespace {

QString stationName(std::optional<rcm::StationId> station)
{
    return station ? QString::fromStdString(rcm::formatStation(*station)) : StationControlWidget::tr("no station");
}

// Role colours with dark text, readable in the day and the night theme.
QString roleStyle(StationControl::Role role)
{
    using Role = StationControl::Role;
    switch (role) {
        case Role::InControl:
            return QStringLiteral("background:#bfe8c0; color:#0b2e0c;");
        case Role::Offered:
        case Role::HandingOver:
            return QStringLiteral("background:#ffd27f; color:#3a2600;");
        case Role::Backup:
            return QStringLiteral("background:#bcd6f5; color:#0a2340;");
        case Role::Observing:
        case Role::Unknown:
            break;
    }
    return QString();
}

}  // namespace

StationControlWidget::StationControlWidget(StationControl* control, QWidget* parent)
    : QWidget(parent),
      m_control(control),
      m_station(new QLineEdit),
      m_role(new QLabel),
      m_handOver(new QPushButton(tr("Hand over to backup"))),
      m_takeControl(new QPushButton(tr("Take control")))
{
    m_station->setPlaceholderText(tr("e.g. GB_30226; empty: one station"));
    m_station->setToolTip(
        tr("This console's station ID, as the aircraft knows it. With one, the console follows which station the "
           "aircraft says is in control, and names itself in its frames only when it is."));
    m_role->setWordWrap(true);
    m_role->setMargin(4);
    m_role->setTextInteractionFlags(Qt::TextSelectableByMouse);
    m_handOver->setToolTip(tr("Ask the aircraft to give control to the backup station it reports"));
    m_takeControl->setToolTip(tr("Command the aircraft from this console: it gave this station control"));
    // As Connect and Disconnect: never the focus, so a stray Space or Enter cannot press one.
    for (QPushButton* b : {m_handOver, m_takeControl})
        b->setFocusPolicy(Qt::NoFocus);

    auto* form = new QFormLayout;
    form->setContentsMargins(0, 0, 0, 0);
    form->addRow(tr("This station"), m_station);
    auto* buttons = new QHBoxLayout;
    buttons->addWidget(m_handOver);
    buttons->addWidget(m_takeControl);
    auto* layout = new QVBoxLayout(this);
    layout->setContentsMargins(0, 0, 0, 0);
    layout->addLayout(form);
    layout->addWidget(m_role);
    layout->addLayout(buttons);

    // Applied on Enter only, as every field that changes what the frames
    // name: a station half typed (GB_30 of GB_30226) and left is not taken.
    connect(m_station, &QLineEdit::returnPressed, this, &StationControlWidget::readStation);
    connect(m_station, &QLineEdit::editingFinished, this, [this] {
        if (m_station->hasFocus())
            return;  // Enter, handled above
        const QString applied =
            m_control->station() ? QString::fromStdString(rcm::formatStation(*m_control->station())) : QString();
        if (stationText() == applied)
            return;
        const QString typed = stationText();
        m_station->setText(applied);
        m_station->setStyleSheet(QString());
        m_station->setToolTip(tr("Not applied: '%1' was left without Enter; this station stays %2")
                                  .arg(typed, applied.isEmpty() ? tr("none") : applied));
    });
    connect(m_handOver, &QPushButton::clicked, this, &StationControlWidget::requestHandOver);
    connect(m_takeControl, &QPushButton::clicked, this, [this] {
        if (m_control->canTakeControl())
            emit takeControlRequested();
    });
    connect(m_control, &StationControl::roleChanged, this, &StationControlWidget::refresh);
    connect(m_control, &StationControl::headerChanged, this, &StationControlWidget::refresh);
    refresh();
}

QString StationControlWidget::stationText() const
{
    return m_station->text().trimmed();
}

void StationControlWidget::setStationText(const QString& text)
{
    m_station->setText(text);
    readStation();
}

void StationControlWidget::setStationEditable(bool editable)
{
    m_station->setEnabled(editable);
}

void StationControlWidget::readStation()
{
    const QString text = stationText();
    if (text.isEmpty()) {
        m_station->setStyleSheet(QString());
        m_control->setStation(std::nullopt);
        return;
    }
    std::string error;
    const std::optional<rcm::StationId> station = rcm::parseStation(text.toStdString(), &error);
    if (!station) {
        // Kept as typed, marked, and said; the station stays what it was.
        m_station->setStyleSheet(QStringLiteral("background:#f6c1c1; color:#3d0000;"));
        emit stationRefused(tr("This station: %1").arg(QString::fromStdString(error)));
        return;
    }
    m_station->setStyleSheet(QString());
    m_control->setStation(station);
}

void StationControlWidget::requestHandOver()
{
    if (!m_control->canHandOver())
        return;
    const QString backup = stationName(m_control->reportedBackup());
    Confirmation ask;
    ask.title = tr("Hand over");
    ask.text = tr("Hand control of the aircraft to %1?").arg(backup);
    ask.informativeText =
        tr("The aircraft stops acting on this console's commands. It acts on %1's once that station takes control; "
           "until then it keeps what it has. If %1 does not take control within the aircraft's failover time, "
           "control comes back here and must be taken again.")
            .arg(backup);
    ask.action = tr("Hand over");
    if (ask.ask(this))
        m_control->handOver();
}

void StationControlWidget::refresh()
{
    const QString description = m_control->describe();
    m_role->setVisible(!description.isEmpty());
    m_role->setText(description);
    m_role->setStyleSheet(roleStyle(m_control->role()));
    m_handOver->setEnabled(m_control->canHandOver());
    m_handOver->setToolTip(
        m_control->canHandOver()
            ? tr("Ask the aircraft to give control to %1").arg(stationName(m_control->reportedBackup()))
            : tr("Only the station in control can hand over, and only to the backup the aircraft "
                 "reports"));
    m_takeControl->setEnabled(m_control->canTakeControl());
}
