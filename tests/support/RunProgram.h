// Runs one of the project's programs as a user would: arguments, standard
// input, and what comes back (exit status, standard output and error).
#pragma once

#include <QByteArray>
#include <QProcess>
#include <QStringList>
#include <QtGlobal>

namespace rcm::test {

struct ProgramRun {
    int exitCode = -1;  // -1 when the program crashed or did not finish
    QByteArray out;
    QByteArray err;
};

// `program` is a file name in RCM_BIN_DIR (build/bin).
inline ProgramRun runProgram(const QString& program, const QStringList& args, const QByteArray& input = {})
{
    QProcess p;
    p.start(QStringLiteral(RCM_BIN_DIR "/") + program, args);
    if (!p.waitForStarted())
        qFatal("cannot start %s", qPrintable(program));
    p.write(input);
    p.closeWriteChannel();
    p.waitForFinished(60000);
    return {p.exitStatus() == QProcess::NormalExit ? p.exitCode() : -1, p.readAllStandardOutput(),
            p.readAllStandardError()};
}

}  // namespace rcm::test
