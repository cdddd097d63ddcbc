#pragma once

// Starts the simulated aircraft (uasim, beside the console's own binary) on
// a UDP port of the loopback interface, for a rehearsal with no aircraft.
// Nothing here waits: the process starts in the background, ready() gives the
// port to connect to, and a uasim that exits at once (its port was taken) is
// started again on another port, up to kAttempts times, until confirm() says
// frames are flowing.

#include "codec/message/Airframe.h"

#include <QObject>
#include <QProcess>
#include <QTemporaryFile>

#include <memory>

class RehearsalLauncher : public QObject {
    Q_OBJECT

public:
    static constexpr int kAttempts = 5;

    explicit RehearsalLauncher(QObject* parent = nullptr);
    // Stops uasim if it is still running.
    ~RehearsalLauncher() override;

    // uasim beside the running program.
    static QString defaultProgram();

    // Starts `program` for `airframe`; stops a uasim already running. With a
    // key file, uasim keys its end of the link with it too (uasim --key).
    void start(const rcm::Airframe& airframe, const QString& program = defaultProgram(),
               const QString& keyPath = QString());
    // Asks uasim to end (SIGTERM), killing it if it has not within a second.
    void stop();
    // Frames came back: a later exit is a failure, not a port clash to retry.
    void confirm() { m_confirmed = true; }
    bool isConfirmed() const { return m_confirmed; }
    // uasim's process id while it runs, else 0.
    qint64 processId() const { return m_process ? m_process->processId() : 0; }
    // uasim --verbose: a line on output() for each command it takes.
    void setVerbose(bool verbose) { m_verbose = verbose; }
    // uasim on this serial device (a pseudo-terminal) instead of a UDP port.
    void setSerialDevice(const QString& device) { m_serialDevice = device; }
    // uasim --modem: the serial device is a satellite modem, whose calls it answers.
    void setModem(bool modem) { m_modem = modem; }
    // uasim --voice-echo: voice beside the commands, as the console has it,
    // and what it hears said back, so that the operator hears the round trip.
    void setVoice(bool voice) { m_voice = voice; }

    bool isRunning() const { return m_process && m_process->state() != QProcess::NotRunning; }
    quint16 port() const { return m_port; }

signals:
    // uasim is starting on 127.0.0.1:port; connect a UDP link to it.
    void ready(quint16 port);
    // uasim could not be started or ended on its own; the reason for people.
    void failed(const QString& reason);
    // A line uasim wrote to its standard error.
    void output(const QString& line);

private:
    void launch();
    void finished(int exitCode, QProcess::ExitStatus status);

    QString m_program;
    QString m_keyPath;
    std::unique_ptr<QTemporaryFile> m_airframeFile;
    QProcess* m_process = nullptr;
    quint16 m_port = 0;
    int m_attempt = 0;
    bool m_confirmed = false;
    bool m_verbose = false;
    bool m_modem = false;
    bool m_voice = false;
    QString m_serialDevice;
    QByteArray m_stderr;
};
