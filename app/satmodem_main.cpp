// satmodem: the pair of satellite phone modems (link/satmodem/SatelliteModem.h) on two
// pseudo-terminals, for rehearsals by hand: its command line, symlinks and way to stop.
#include "link/satmodem/SatelliteModem.h"

#include <QCommandLineParser>
#include <QCoreApplication>
#include <QDir>
#include <QSocketNotifier>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <sys/signalfd.h>
#include <unistd.h>

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
        {"no-service", "No network ever: not registered, no signal, NO DIALTONE at once."},
        {"no-service-for", "No network for the first S seconds (not registered, no signal), then 4 bars.", "S"},
        {"service", "The signal as time goes, SECONDS:BARS,... (0 bars: no service; a call then drops), e.g. 0:0,10:4,60:1.", "SCRIPT"},
        {"profile", "The phones' AT dialect: " + modem::profileNames().join(", ") + " (default generic).", "NAME", "generic"},
        {"link-dir", "Make symlinks DIR/ground and DIR/aircraft to the two devices; DIR is made if missing.", "DIR"},
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
    const int noServiceFor = parser.isSet("no-service-for") ? number("no-service-for", 0) : 0;
    if (std::min({setup, delay, rate, buffer, dropMean, seed, noServiceFor}) < 0)
        return kUsageError;
    QString error;
    const std::optional<modem::Profile> profile = modem::findProfile(parser.value("profile"));
    if (!profile)
        return say("--profile: no profile is called \"" + parser.value("profile") + "\"; there are " + modem::profileNames().join(", "), kUsageError);
    auto service = SatelliteModem::parseService(parser.value("service"), &error);
    if (!service)
        return say("--service: " + error, kUsageError);
    if (parser.isSet("no-service-for") && parser.isSet("service"))
        return say("give --no-service-for or --service, not both", kUsageError);
    if (noServiceFor > 0)
        service = {{std::chrono::milliseconds(0), 0}, {std::chrono::seconds(noServiceFor), 4}};
    SatelliteModem modem({.callSetupTime = std::chrono::milliseconds(setup), .oneWayDelay = std::chrono::milliseconds(delay),
                          .airRate = rate, .bufferLimit = buffer, .meanTimeBetweenDrops = std::chrono::seconds(dropMean),
                          .seed = quint32(seed), .busy = parser.isSet("busy"), .noService = parser.isSet("no-service"),
                          .profile = *profile, .service = *service});
    if (!modem.open(&error))
        return say(error, kRunError);
    const QString linkDir = parser.value("link-dir");
    const auto linkOf = [&](int side) { return QDir(linkDir).filePath(kSides[side]); };
    if (!linkDir.isEmpty() && !QDir().mkpath(linkDir))
        return say("--link-dir: cannot make the directory " + linkDir + ": " + std::strerror(errno), kRunError);
    for (int side = 0; side < 2; ++side) {
        if (!linkDir.isEmpty())
            QFile::remove(linkOf(side));  // left by a run that was killed
        if (!linkDir.isEmpty() && ::symlink(qPrintable(modem.device(side)), qPrintable(linkOf(side))) != 0)
            return say("cannot make the symlink " + linkOf(side) + " to " + modem.device(side) + ": " + std::strerror(errno), kRunError);
        std::printf("%s: %s\n", qPrintable(kSides[side]), qPrintable(modem.device(side)));
    }
    std::fflush(stdout);
    if (parser.isSet("verbose")) {
        QObject::connect(&modem, &SatelliteModem::commandReceived, [](int side, const QByteArray& line) { say(kSides[side] + " > " + line); });
        QObject::connect(&modem, &SatelliteModem::resultSent, [](int side, modem::Result r) { say(kSides[side] + " < " + modem::resultText(r)); });
        QObject::connect(&modem, &SatelliteModem::flowControlChanged, [](int side, bool off) { say(kSides[side] + (off ? ": CTS off" : ": CTS on")); });
        QObject::connect(&modem, &SatelliteModem::hungUp, [](int side, const QString& how) { say((side < 0 ? "network" : kSides[side]) + " hung up: " + how); });
        QObject::connect(&modem, &SatelliteModem::callStateChanged, [](SatelliteModem::CallState s) { say("call " + QVariant::fromValue(s).toString()); });
        const auto saySignal = [](int bars) { say(bars ? QString("signal %1 of 5").arg(bars) : QString("no service")); };
        QObject::connect(&modem, &SatelliteModem::signalChanged, saySignal);
        saySignal(modem.signalBars());
    }
    QSocketNotifier stopped(::signalfd(-1, &stops, SFD_CLOEXEC), QSocketNotifier::Read);
    QObject::connect(&stopped, &QSocketNotifier::activated, &app, &QCoreApplication::quit);
    const int status = app.exec();
    for (int side = 0; side < 2 && !linkDir.isEmpty(); ++side)
        QFile::remove(linkOf(side));
    return status;
}
