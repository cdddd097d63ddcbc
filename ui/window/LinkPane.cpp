#include "ui/window/LinkPane.h"

#include "link/session/ConsoleSession.h"
#include "ui/control/StationControlWidget.h"
#include "ui/window/LinkSettingsWidget.h"
#include "ui/window/ReplayControls.h"

#include <QHBoxLayout>
#include <QLabel>
#include <QPushButton>
#include <QVBoxLayout>

LinkPane::LinkPane(StationControl* control, QWidget* parent)
    : QWidget(parent),
      m_settings(new LinkSettingsWidget),
      m_connect(new QPushButton(tr("Connect"))),
      m_disconnect(new QPushButton(tr("Disconnect"))),
      m_rehearsal(new QPushButton(tr("Start rehearsal"))),
      m_stationControl(new StationControlWidget(control)),
      m_note(new QLabel),
      m_replayControls(new ReplayControls)
{
    m_connect->setToolTip(tr("Open the link and start sending the command once a second (Ctrl+K)"));
    m_disconnect->setToolTip(tr("Stop sending and close the link (Ctrl+Shift+K)"));
    m_rehearsal->setToolTip(
        tr("Start the simulated aircraft (uasim) on this computer and connect to it "
           "(Ctrl+R)"));
    // Buttons that start or end a link never hold the focus, so that a
    // stray Space or Enter cannot press one (after Connect the focus would
    // move on to Start rehearsal); their shortcuts and the mouse remain.
    for (QPushButton* b : {m_connect, m_disconnect, m_rehearsal})
        b->setFocusPolicy(Qt::NoFocus);
    m_note->setWordWrap(true);
    m_note->setTextInteractionFlags(Qt::TextSelectableByMouse);
    m_replayControls->hide();

    auto* layout = new QVBoxLayout(this);
    layout->setContentsMargins(8, 8, 8, 8);
    layout->addWidget(m_settings);
    auto* buttons = new QHBoxLayout;
    buttons->addWidget(m_connect);
    buttons->addWidget(m_disconnect);
    layout->addLayout(buttons);
    layout->addWidget(m_rehearsal);
    layout->addWidget(m_stationControl);
    layout->addWidget(m_note);
    layout->addWidget(m_replayControls);
    layout->addStretch(1);
    connect(m_connect, &QPushButton::clicked, this, &LinkPane::connectRequested);
    connect(m_disconnect, &QPushButton::clicked, this, &LinkPane::disconnectRequested);
    connect(m_rehearsal, &QPushButton::clicked, this, &LinkPane::rehearsalRequested);
}

QString LinkPane::connectText() const
{
    return m_connect->text();
}

QString LinkPane::disconnectText() const
{
    return m_disconnect->text();
}

void LinkPane::update(const ConsoleSession& session)
{
    const bool running = session.isRunning();
    m_settings->setEnabled(!running);
    m_stationControl->setStationEditable(!running);
    m_connect->setEnabled(!running);
    m_disconnect->setEnabled(session.isActive());
    // A satellite phone's modem: Connect dials and Disconnect hangs up, and says so.
    const bool dials = m_settings->settings().dialsModem();
    m_connect->setText(dials ? tr("Dial") : tr("Connect"));
    const bool inCall = dials && session.kind() == ConsoleSession::Kind::Live;
    m_disconnect->setText(inCall ? tr("Hang up") : tr("Disconnect"));
}

void LinkPane::setNote(const QString& text)
{
    m_note->setText(text);
}

void LinkPane::showNotConnected()
{
    m_note->setText(
        tr("Not connected. Connect to the aircraft's link, start a rehearsal against the "
           "simulated aircraft, or open a frame log to replay it (Ctrl+O)."));
}
