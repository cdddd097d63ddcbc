// The built `uasim`, run as a user runs it, collecting what it says on
// standard error: with one link, `uasim --udp PORT --verbose` plus the
// test's options; or with two stations (kTwoStations), GB_30226 in control
// and GB_41251 its backup, each on a free loopback port and under its key
// file when given: `uasim --station GB_30226,PORT[,KEY] --station
// GB_41251,PORT[,KEY] --verbose` plus the test's options.
#pragma once

#include <QByteArray>
#include <QProcess>
#include <QStringList>
#include <QUdpSocket>

#include <array>
#include <csignal>

namespace rcm::test {

struct TwoStations {};
inline constexpr TwoStations kTwoStations;

class UasimProcess {
public:
    explicit UasimProcess(const QStringList& extraArguments = {}) : m_port(freePort())
    {
        prepare({QStringLiteral("--udp"), QString::number(m_port)}, extraArguments);
    }
    UasimProcess(TwoStations, const QStringList& extraArguments = {}, const QStringList& keys = {})
        : ports(twoFreePorts())
    {
        QStringList stations;
        const char* ids[] = {"GB_30226", "GB_41251"};
        for (int i = 0; i < 2; ++i) {
            QString value = QStringLiteral("%1,%2").arg(QLatin1String(ids[i])).arg(ports[i]);
            if (!keys.value(i).isEmpty())
                value += QLatin1Char(',') + keys[i];
            stations << QStringLiteral("--station") << value;
        }
        prepare(stations, extraArguments);
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
    // uasim says so once its sockets are bound: the first command can go.
    // With stations, the line that names their roles comes last, after each
    // channel's "on udp" (uasim --verbose); the whole line, not its start: a
    // read can end inside it, and the suites check what the rest of it says.
    bool listening() const { return saidLine(ports[0] ? "stations: " : "on udp"); }
    // SIGTERM: uasim stops, printing its counts, and exits; true when it
    // did, of its own accord, with status 0.
    bool stop(int timeoutMs)
    {
        ::kill(static_cast<pid_t>(m_process.processId()), SIGTERM);
        const bool done = m_process.waitForFinished(timeoutMs);
        m_stderr += m_process.readAllStandardError();
        return done && m_process.exitStatus() == QProcess::NormalExit && m_process.exitCode() == 0;
    }
    // The one link's port (none with stations).
    quint16 port() const { return m_port; }
    QProcess& process() { return m_process; }
    const QByteArray& stderrText() const { return m_stderr; }
    bool said(const char* text) const { return m_stderr.contains(text); }
    // A line holding text has been said to its end.
    bool saidLine(const char* text) const
    {
        const qsizetype at = m_stderr.indexOf(text);
        return at >= 0 && m_stderr.indexOf('\n', at) >= 0;
    }

    // With kTwoStations: GB_30226's channel, then GB_41251's.
    std::array<quint16, 2> ports{};

private:
    static quint16 freePort()
    {
        QUdpSocket probe;
        probe.bind(QHostAddress::LocalHost, 0);
        return probe.localPort();
    }
    // Both bound at once: one after the other, the second could be given the
    // port the first has just let go of, and uasim's second station would
    // then find its port taken.
    static std::array<quint16, 2> twoFreePorts()
    {
        QUdpSocket first, second;
        first.bind(QHostAddress::LocalHost, 0);
        second.bind(QHostAddress::LocalHost, 0);
        return {first.localPort(), second.localPort()};
    }
    void prepare(const QStringList& link, const QStringList& extraArguments)
    {
        m_process.setProgram(QStringLiteral(RCM_BIN_DIR "/uasim"));
        m_process.setArguments(link + QStringList{QStringLiteral("--verbose")} + extraArguments);
        QObject::connect(&m_process, &QProcess::readyReadStandardError,
                         [this] { m_stderr += m_process.readAllStandardError(); });
    }

    quint16 m_port = 0;
    QProcess m_process;
    QByteArray m_stderr;
};

}  // namespace rcm::test
