// The built `uasim`, run as a user runs it: `uasim --udp PORT --verbose`
// plus the test's options, collecting what it says on standard error.
#pragma once

#include <QByteArray>
#include <QProcess>
#include <QStringList>
#include <QUdpSocket>

#include <csignal>

namespace rcm::test {

class UasimProcess {
public:
    explicit UasimProcess(const QStringList& extraArguments = {}) : m_port(freePort())
    {
        m_process.setProgram(QStringLiteral(RCM_BIN_DIR "/uasim"));
        m_process.setArguments(
            QStringList{QStringLiteral("--udp"), QString::number(m_port), QStringLiteral("--verbose")} +
            extraArguments);
        QObject::connect(&m_process, &QProcess::readyReadStandardError,
                         [this] { m_stderr += m_process.readAllStandardError(); });
    }
    ~UasimProcess()
    {
        if (m_process.state() != QProcess::NotRunning) {
            m_process.kill();
            m_process.waitForFinished();
        }
    }
    UasimProcess(const UasimProcess&) = delete;
    UasimProcess& operator=(const UasimProcess&) = delete;

    bool start()
    {
        m_process.start();
        return m_process.waitForStarted();
    }
    // uasim says so once its socket is bound: the first command can go.
    bool listening() const { return m_stderr.contains("on udp"); }
    // SIGTERM: uasim stops, printing its counts, and exits.
    bool stop(int timeoutMs)
    {
        ::kill(static_cast<pid_t>(m_process.processId()), SIGTERM);
        const bool done = m_process.waitForFinished(timeoutMs);
        m_stderr += m_process.readAllStandardError();
        return done;
    }
    quint16 port() const { return m_port; }
    QProcess& process() { return m_process; }
    const QByteArray& stderrText() const { return m_stderr; }

private:
    static quint16 freePort()
    {
        QUdpSocket probe;
        probe.bind(QHostAddress::LocalHost, 0);
        return probe.localPort();
    }

    quint16 m_port;
    QProcess m_process;
    QByteArray m_stderr;
};

}  // namespace rcm::test
