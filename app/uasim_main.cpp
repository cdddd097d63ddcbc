// uasim: a simulated aircraft at the far end of the link, for rehearsals and
// tests (link/aircraft/SimulatorSession.h). This is only its command line
// and its way to stop: SIGINT or SIGTERM.
#include "link/aircraft/SimulatorOptions.h"
#include "link/aircraft/SimulatorSession.h"

#include <QCommandLineParser>
#include <QCoreApplication>
#include <QSocketNotifier>

#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>

namespace {

// Exit codes.
constexpr int kUsageError = 2;
constexpr int kRunError = 1;

void say(const QString& line)
{
    std::fprintf(stderr, "uasim: %s\n", qPrintable(line));
}

// SIGINT and SIGTERM reach the event loop through this pair: a handler may
// only write to a descriptor.
int g_signalPipe[2] = {-1, -1};

void onSignal(int)
{
    const char c = 1;
    [[maybe_unused]] const ssize_t n = ::write(g_signalPipe[0], &c, 1);
}

bool catchStopSignals()
{
    if (::socketpair(AF_UNIX, SOCK_STREAM, 0, g_signalPipe) != 0) {
        say(QStringLiteral("socketpair: %1").arg(QString::fromLocal8Bit(std::strerror(errno))));
        return false;
    }
    struct sigaction action = {};
    action.sa_handler = onSignal;
    sigemptyset(&action.sa_mask);
    action.sa_flags = SA_RESTART;
    sigaction(SIGINT, &action, nullptr);
    sigaction(SIGTERM, &action, nullptr);
    return true;
}

}  // namespace

int main(int argc, char* argv[])
{
    QCoreApplication app(argc, argv);
    QCoreApplication::setApplicationName(QStringLiteral("uasim"));

    QCommandLineParser parser;
    parser.setApplicationDescription(QStringLiteral(
        "A simulated aircraft: answers Remote Control Message commands, once a second, with a status frame in\n"
        "the same format reporting the state it actually has (gear and surfaces take time to move), and\n"
        "acknowledges flight plans uploaded in BLOCK 2 sections.\n"
        "\n"
        "Examples:\n"
        "  uasim --udp 5600 --verbose\n"
        "  uasim --serial /dev/pts/3 --baud 9600 --log uasim.pcapng --ber 1e-4 --drop 0.05 --outage 60:10\n"
        "  uasim --serial /dev/pts/3 --voice-out heard.wav --voice-in reply.wav\n"
        "  uasim --station GB_30226,5601,a.key --station GB_41251,5602,b.key --failover 5"));
    parser.addHelpOption();
    const SimulatorOptions options;
    options.addTo(parser);
    parser.process(app);

    QString error;
    std::optional<SimulatorSession::Settings> settings = options.read(parser, &error);
    if (!settings) {
        say(error);
        std::fprintf(stderr, "%s", qPrintable(parser.helpText()));
        return kUsageError;
    }

    SimulatorSession session(std::move(*settings), say);
    if (!catchStopSignals())
        return kRunError;
    QSocketNotifier signalNotifier(g_signalPipe[1], QSocketNotifier::Read);
    QObject::connect(&signalNotifier, &QSocketNotifier::activated, &app, [&] {
        char c;
        [[maybe_unused]] const ssize_t n = ::read(g_signalPipe[1], &c, 1);
        session.stop();
        QCoreApplication::quit();
    });
    if (!session.start())
        return kRunError;
    return app.exec();
}
