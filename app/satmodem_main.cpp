// satmodem: the pair of satellite phone modems (link/simulation/SatelliteModem.h) on two
// pseudo-terminals, for rehearsals by hand: its command line, symlinks and way to stop.
#include "link/simulation/SatelliteModem.h"

#include <QCommandLineParser>
#include <QCoreApplication>
#include <QDir>
#include <QSocketNotifier>

#include <csignal>
#include <cstdio>
#include <sys/signalfd.h>

namespace {

enum Status { kRunError = 1, kUsageError = 2 };
const QStringList kSides{"ground", "aircraft"};

int say(const QString& line, int status = 0)
{
    std::fprintf(stderr, "satmodem: %s\n", qPrintable(line));
    return status;
}

}  // namespace

int main(int argc, char* argv[])
{
    // Blocked before any thread starts, so that only a signalfd hears them and the links go in good
    // time; not ignored, as a shell starts a background job with SIGINT ignored and it would be lost.
    sigset_t stops;
    sigemptyset(&stops);
    for (const int s : {SIGINT, SIGTERM}) {
        std::signal(s, SIG_DFL);
        sigaddset(&stops, s);
    }
    pthread_sigmask(SIG_BLOCK, &stops, nullptr);
    QCoreApplication app(argc, argv);
    QCommandLineParser parser;
    parser.setApplicationDescription("Two satellite phone modems, ground and aircraft, on two pseudo-terminals (docs/modem.md).");
    const QCommandLineOption help = parser.addHelpOption();
    const SatelliteModem::Options d;
    parser.addOptions({
        {"setup-time", "Milliseconds from ATD to the far side's first RING.", "MS", QString::number(d.callSetupTime.count())},
        {"delay", "One-way delay of each byte, milliseconds.", "MS", QString::number(d.oneWayDelay.count())},
        {"rate", "Bytes a second on the air, each way.", "BYTES", QString::number(d.airRate)},
        {"buffer", "Bytes a sender may have waiting before its CTS drops.", "BYTES", QString::number(d.bufferLimit)},
        {"drop-mean", "Mean seconds between random call drops; 0: never.", "S", "0"},
        {"seed", "Seed of the random drops.", "N", QString::number(d.seed)},
        {"busy", "The far side is busy: BUSY after the set-up time."},
        {"no-service", "No network: NO DIALTONE at once."},
        {"link-dir", "Make symlinks DIR/ground and DIR/aircraft to the two devices.", "DIR"},
        {"verbose", "Log commands, results and call states to standard error."},
    });
    if (!parser.parse(app.arguments()) || !parser.positionalArguments().isEmpty())
        return say(parser.errorText().isEmpty() ? "unexpected: " + parser.positionalArguments().join(' ') : parser.errorText(), kUsageError);
    if (parser.isSet(help))
        parser.showHelp(0);
    // `name`'s value, a whole number of at least `least`; -1, the reason said, when it is not.
    const auto number = [&parser](const QString& name, int least) {
        bool ok = false;
        const int value = parser.value(name).toInt(&ok);
        const QString why = QStringLiteral("--%1 wants a whole number of at least %2, not \"%3\"").arg(name).arg(least).arg(parser.value(name));
        return ok && value >= least ? value : say(why, -1);
    };
    const int setup = number("setup-time", 0), delay = number("delay", 0), rate = number("rate", 1);
    const int buffer = number("buffer", 1), dropMean = number("drop-mean", 0), seed = number("seed", 0);
    if (std::min({setup, delay, rate, buffer, dropMean, seed}) < 0)
        return kUsageError;
    SatelliteModem modem({.callSetupTime = std::chrono::milliseconds(setup), .oneWayDelay = std::chrono::milliseconds(delay),
                          .airRate = rate, .bufferLimit = buffer, .meanTimeBetweenDrops = std::chrono::seconds(dropMean),
                          .seed = quint32(seed), .busy = parser.isSet("busy"), .noService = parser.isSet("no-service")});
    QString error;
    if (!modem.open(&error))
        return say(error, kRunError);
    const QString linkDir = parser.value("link-dir");
    const auto linkOf = [&](int side) { return QDir(linkDir).filePath(kSides[side]); };
    for (int side = 0; side < 2; ++side) {
        if (!linkDir.isEmpty())
            QFile::remove(linkOf(side));  // left by a run that was killed
        if (!linkDir.isEmpty() && !QFile::link(modem.device(side), linkOf(side)))
            return say("cannot make the symlink " + linkOf(side), kRunError);
        std::printf("%s: %s\n", qPrintable(kSides[side]), qPrintable(modem.device(side)));
    }
    std::fflush(stdout);
    if (parser.isSet("verbose")) {
        QObject::connect(&modem, &SatelliteModem::commandReceived, [](int side, const QByteArray& line) { say(kSides[side] + " > " + line); });
        QObject::connect(&modem, &SatelliteModem::resultSent, [](int side, modem::Result r) { say(kSides[side] + " < " + modem::resultText(r)); });
        QObject::connect(&modem, &SatelliteModem::flowControlChanged, [](int side, bool off) { say(kSides[side] + (off ? ": CTS off" : ": CTS on")); });
        QObject::connect(&modem, &SatelliteModem::hungUp, [](int side, const QString& how) { say((side < 0 ? "network" : kSides[side]) + " hung up: " + how); });
        QObject::connect(&modem, &SatelliteModem::callStateChanged, [](SatelliteModem::CallState s) { say("call " + QVariant::fromValue(s).toString()); });
    }
    QSocketNotifier stopped(::signalfd(-1, &stops, SFD_CLOEXEC), QSocketNotifier::Read);
    QObject::connect(&stopped, &QSocketNotifier::activated, &app, &QCoreApplication::quit);
    const int status = app.exec();
    for (int side = 0; side < 2 && !linkDir.isEmpty(); ++side)
        QFile::remove(linkOf(side));
    return status;
}
