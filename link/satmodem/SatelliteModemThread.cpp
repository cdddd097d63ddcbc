#include "link/satmodem/SatelliteModemThread.h"

SatelliteModemThread::SatelliteModemThread(SatelliteModem::Options options, QObject* parent)
    : QObject(parent), m_inThread(new QObject)
{
    m_thread.setObjectName(QStringLiteral("satmodem"));
    m_inThread->moveToThread(&m_thread);
    connect(&m_thread, &QThread::finished, m_inThread, &QObject::deleteLater);
    m_thread.start();
    QMetaObject::invokeMethod(
        m_inThread, [&] { m_model = new SatelliteModem(options, m_inThread); }, Qt::BlockingQueuedConnection);
    connect(m_model, &SatelliteModem::hungUp, this, &SatelliteModemThread::hungUp);
    connect(m_model, &SatelliteModem::callStateChanged, this, &SatelliteModemThread::callStateChanged);
    connect(m_model, &SatelliteModem::commandReceived, this, &SatelliteModemThread::commandReceived);
    connect(m_model, &SatelliteModem::userGone, this, &SatelliteModemThread::userGone);
}

SatelliteModemThread::~SatelliteModemThread()
{
    m_thread.quit();
    m_thread.wait();
}

bool SatelliteModemThread::open(QString* error)
{
    bool opened = false;
    QMetaObject::invokeMethod(
        m_model,
        [&] {
            opened = m_model->open(error);
            for (int side = 0; side < 2; ++side)
                m_devices[std::size_t(side)] = m_model->device(side);
        },
        Qt::BlockingQueuedConnection);
    return opened;
}

SatelliteModem::CallState SatelliteModemThread::callState() const
{
    SatelliteModem::CallState state{};
    QMetaObject::invokeMethod(m_model, [&] { state = m_model->callState(); }, Qt::BlockingQueuedConnection);
    return state;
}

SatelliteModem::Counters SatelliteModemThread::counters() const
{
    SatelliteModem::Counters counters;
    QMetaObject::invokeMethod(m_model, [&] { counters = m_model->counters(); }, Qt::BlockingQueuedConnection);
    return counters;
}

QByteArray SatelliteModemThread::dialledNumber(int side) const
{
    QByteArray number;
    QMetaObject::invokeMethod(m_model, [&] { number = m_model->dialledNumber(side); }, Qt::BlockingQueuedConnection);
    return number;
}

void SatelliteModemThread::dropCall()
{
    QMetaObject::invokeMethod(m_model, &SatelliteModem::dropCall, Qt::QueuedConnection);
}

void SatelliteModemThread::setSignalBars(int bars)
{
    QMetaObject::invokeMethod(m_model, [model = m_model, bars] { model->setSignalBars(bars); }, Qt::QueuedConnection);
}
