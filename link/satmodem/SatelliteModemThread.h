#pragma once

// The satellite modem model in a thread of its own, as satmodem is a process
// of its own: a modem's hang-up (ModemLink) blocks its link's thread for
// seconds, and the model must answer it meanwhile. What the model says comes
// back queued, in the owner's thread.

#include "link/satmodem/SatelliteModem.h"

#include <QObject>
#include <QThread>

class SatelliteModemThread : public QObject {
    Q_OBJECT

public:
    explicit SatelliteModemThread(SatelliteModem::Options options, QObject* parent = nullptr);
    ~SatelliteModemThread() override;

    // Each waits for the model's thread.
    bool open(QString* error);
    SatelliteModem::CallState callState() const;
    SatelliteModem::Counters counters() const;
    QByteArray dialledNumber(int side) const;
    // Set once by open().
    QString device(int side) const { return m_devices[std::size_t(side)]; }

public slots:
    // Queued: the network loses the call.
    void dropCall();
    // Queued: the signal over both phones, 0..5 (0: no service).
    void setSignalBars(int bars);

signals:
    void hungUp(int side, const QString& how);
    void commandReceived(int side, const QByteArray& command);
    void callStateChanged(SatelliteModem::CallState state);
    void userGone(int side);

private:
    QThread m_thread;
    QObject* m_inThread;             // lives in m_thread: what calls into it run on
    SatelliteModem* m_model = nullptr;  // lives in m_thread, made there with its timers
    std::array<QString, 2> m_devices;
};
