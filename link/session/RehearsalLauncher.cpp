#include "link/session/RehearsalLauncher.h"

#include "link/airframe/AirframeLoader.h"

#include <QCoreApplication>
#include <QDir>
#include <QFileInfo>
#include <QRandomGenerator>
#include <QTimer>

#ifdef Q_OS_LINUX
#include <csignal>
#include <sys/prctl.h>
#endif

RehearsalLauncher::RehearsalLauncher(QObject* parent) : QObject(parent) {}

RehearsalLauncher::~RehearsalLauncher()
{
    stop();
}

QString RehearsalLauncher::defaultProgram()
{
    return QDir(QCoreApplication::applicationDirPath()).filePath(QStringLiteral("uasim"));
}

void RehearsalLauncher::start(const rcm::Airframe& airframe, const QString& program, const QString& keyPath)
{
    stop();
    m_program = program;
    m_keyPath = keyPath;
    m_attempt = 0;
    m_confirmed = false;
    m_airframeFile =
        std::make_unique<QTemporaryFile>(QDir::temp().filePath(QStringLiteral("gcs-airframe-XXXXXX.json")));
    if (!m_airframeFile->open() || m_airframeFile->write(AirframeLoader::toJson(airframe)) < 0 ||
        !m_airframeFile->flush()) {
        emit failed(tr("Cannot write the airframe for uasim: %1").arg(m_airframeFile->errorString()));
        return;
    }
    if (!QFileInfo(m_program).isExecutable()) {
        emit failed(tr("The simulated aircraft %1 is not there; build the uasim target").arg(m_program));
        return;
    }
    launch();
}

void RehearsalLauncher::launch()
{
    ++m_attempt;
    // A port from the dynamic range; a clash makes uasim exit at once, and
    // finished() tries another.
    m_port = quint16(49152 + QRandomGenerator::global()->bounded(16384));
    m_stderr.clear();
    m_process = new QProcess(this);
    m_process->setProcessChannelMode(QProcess::SeparateChannels);
    m_process->setStandardOutputFile(QProcess::nullDevice());
    connect(m_process, &QProcess::readyReadStandardError, this, [this, process = m_process] {
        m_stderr += process->readAllStandardError();
        qsizetype end;
        while ((end = m_stderr.indexOf('\n')) >= 0) {
            emit output(QString::fromLocal8Bit(m_stderr.left(end)));
            m_stderr.remove(0, end + 1);
        }
    });
    connect(m_process, &QProcess::finished, this, &RehearsalLauncher::finished);
    connect(m_process, &QProcess::errorOccurred, this, [this, process = m_process](QProcess::ProcessError error) {
        if (error == QProcess::FailedToStart)
            emit failed(tr("Cannot start %1: %2").arg(m_program, process->errorString()));
    });
    QStringList arguments{QStringLiteral("--airframe"), m_airframeFile->fileName()};
    if (m_serialDevice.isEmpty())
        arguments << QStringLiteral("--udp") << QString::number(m_port);
    else
        arguments << QStringLiteral("--serial") << m_serialDevice;
    if (m_modem)
        arguments << QStringLiteral("--modem");
    if (m_voice)
        arguments << QStringLiteral("--voice-echo");
    if (!m_keyPath.isEmpty())
        arguments << QStringLiteral("--key") << m_keyPath;
    if (m_verbose)
        arguments << QStringLiteral("--verbose");
#ifdef Q_OS_LINUX
    // The simulated aircraft ends with the console, however the console ends
    // (SIGTERM, SIGKILL, a crash): a uasim left behind would hold the port
    // and answer the next console as if it were the rehearsal's.
    m_process->setChildProcessModifier([] { ::prctl(PR_SET_PDEATHSIG, SIGTERM); });
#endif
    m_process->start(m_program, arguments);
    emit ready(m_port);
}

void RehearsalLauncher::finished(int exitCode, QProcess::ExitStatus status)
{
    QProcess* process = m_process;
    m_process = nullptr;
    process->deleteLater();
    const bool clash = status == QProcess::NormalExit && exitCode == 1 && !m_confirmed;
    if (clash && m_attempt < kAttempts) {
        launch();
        return;
    }
    emit failed(status == QProcess::CrashExit ? tr("uasim crashed")
                                              : tr("uasim ended with exit code %1").arg(exitCode));
}

void RehearsalLauncher::stop()
{
    if (!m_process)
        return;
    // uasim ends on SIGTERM. The QProcess is let go rather than deleted: its
    // destructor would wait for the exit. It deletes itself once uasim has
    // ended, and kills a uasim that has not within a second.
    QProcess* process = m_process;
    m_process = nullptr;
    process->disconnect(this);
    process->setParent(nullptr);
    connect(process, &QProcess::finished, process, &QObject::deleteLater);
    QTimer::singleShot(1000, process, [process] { process->kill(); });
    process->terminate();
}
