#pragma once

// Everything the link thread says, stated once: LinkWorker emits these in
// the link thread, and LinkController, being one too, emits the same ones in
// the GUI thread, forwarded one for one without naming them again.

#include "link/session/LinkStatistics.h"
#include "link/session/LoggedFrame.h"
#include "link/session/ReceivedMessage.h"

#include <QObject>
#include <QString>

class LinkEvents : public QObject {
    Q_OBJECT

public:
    using QObject::QObject;

signals:
    void started();
    void stopped();
    void messageReceived(const ReceivedMessage& received);
    void frameSent(quint32 messageId);
    // Every frame the worker logs, once, just after it went into the frame log:
    // sent, received good or corrected, uncorrectable, rejected (secure link,
    // wrong-size datagram). What the console's frame log view is built from.
    void frameLogged(const LoggedFrame& frame);
    void statisticsChanged(const LinkStatistics& statistics);
    void stateChanged(LinkState state);
    // Each once per outage: lost after the silence timeout or when the
    // transport went away, regained with the first good frame after that.
    void linkLost();
    void linkRegained();
    // Transport and frame log failures, once each; see Link::errorOccurred.
    void errorOccurred(const QString& message);
    // What the transport itself is doing, for the status bar and the event
    // log: a modem dialling, connected, redialling; see Link::statusChanged.
    void transportStatusChanged(const QString& status);
    // A satellite phone's service, for the status bar's signal bars; see
    // Link::serviceChanged.
    void modemServiceChanged(int signalBars, bool registered, const QString& text);
    void commandRejected(const QString& reasons);
    // Secure link: a frame that decoded was refused; "forged: ..." and so on.
    void frameRejected(const QString& reason);

};
