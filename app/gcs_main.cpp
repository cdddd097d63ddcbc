// gcs: the operator console (`gcs --help`); start-up, memory and GUI stalls: tests/bench/bench_console.cpp.
#include "link/airframe/AirframeLoader.h"
#include "link/session/LinkSettings.h"
#include "link/transport/ModemProfile.h"
#include "ui/control/StationCommandLine.h"
#include "ui/plan/PlanCommandLine.h"
#include "ui/rehearsal/RehearsalCommandLine.h"
#include "ui/window/LinkSettingsWidget.h"
#include "ui/window/MainWindow.h"
#include "ui/window/Theme.h"

#include <QApplication>
#include <QCommandLineParser>
#include <cstdio>

static constexpr int kUsageError = 2;
static void say(const QString& line) { std::fprintf(stderr, "gcs: %s\n", qPrintable(line)); }

int main(int argc, char* argv[])
{
    QApplication app(argc, argv);
    QCoreApplication::setOrganizationName(QStringLiteral("rcm"));
    QCoreApplication::setApplicationName(QStringLiteral("gcs"));
    QGuiApplication::setDesktopFileName(QStringLiteral(RCM_APP_ID));  // its menu entry and icon (Wayland)
    QCommandLineParser parser;
    parser.setApplicationDescription(
        QStringLiteral("The operator console of the RCM ground control station: commands an unmanned aircraft with\n"
                       "a Remote Control Message once a second over a serial modem or UDP, and shows what it reports.\n"
                       "\n"
                       "Examples:\n"
                       "  gcs --rehearsal                  rehearse against the simulated aircraft (uasim)\n"
                       "  gcs --udp-remote 10.0.0.2:5600   connect over UDP\n"
                       "  gcs --serial /dev/ttyUSB0        connect through the radio modem\n"
                       "  gcs --serial /dev/ttyUSB0 --dial 881612345678   dial the aircraft's satellite phone\n"
                       "  gcs --observe mqtt://127.0.0.1:1883/GB_133    watch an aircraft read-only"));
    parser.addHelpOption();
    const QCommandLineOption rehearsal(QStringLiteral("rehearsal"),
                                       QStringLiteral("Start the simulated aircraft (uasim, beside gcs) on a free "
                                                      "loopback UDP port and connect to it."));
    const QCommandLineOption udpRemote(QStringLiteral("udp-remote"),
                                       QStringLiteral("Connect over UDP to the aircraft at <host:port>."),
                                       QStringLiteral("host:port"));
    const QCommandLineOption serial(QStringLiteral("serial"), QStringLiteral("Connect through a serial port."),
                                    QStringLiteral("device"));
    const QCommandLineOption baud(QStringLiteral("baud"), QStringLiteral("Serial bit rate (default 9600)."),
                                  QStringLiteral("n"), QStringLiteral("9600"));
    const QCommandLineOption dial(QStringLiteral("dial"),
                                  QStringLiteral("The serial port is a satellite phone's modem: dial this number, "
                                                 "redial a dropped call, hang up on quit (docs/modem.md)."),
                                  QStringLiteral("number"));
    const QCommandLineOption profile(QStringLiteral("modem-profile"), QStringLiteral("With --dial: the phone "
        "(docs/modem.md), one of %1; default generic.").arg(modem::profileNames().join(", ")), QStringLiteral("name"));
    const QCommandLineOption replay(QStringLiteral("replay"), QStringLiteral("Replay a frame log."),
                                    QStringLiteral("log.pcapng"));
    const QCommandLineOption airframe(QStringLiteral("airframe"),
                                      QStringLiteral("The aircraft's units, as a JSON airframe file (default: the "
                                                     "one used last, or the well-equipped aircraft)."),
                                      QStringLiteral("file"));
    const QCommandLineOption screenshot(QStringLiteral("screenshot"),
                                        QStringLiteral("Lay the window out with the default settings, save a "
                                                       "picture of it and exit (works offscreen)."),
                                        QStringLiteral("file.png"));
    const QCommandLineOption key(
        QStringLiteral("key"),
        QStringLiteral("The secure link (docs/security.md): the aircraft's key file, 64 hex "
                       "digits, mode 0600. With --rehearsal, uasim uses it too; with --replay, "
                       "it reads a keyed session's log; with --observe (once per station), "
                       "it opens the sealed sessions on the broker. Kept in the link settings."),
        QStringLiteral("file"));
    const QCommandLineOption size(QStringLiteral("size"), QStringLiteral("Window size for --screenshot."),
                                  QStringLiteral("WxH"), QStringLiteral("1600x1000"));
    const QCommandLineOption after(QStringLiteral("screenshot-after"),
                                   QStringLiteral("Seconds the link runs before the picture (default 0)."),
                                   QStringLiteral("s"), QStringLiteral("0"));
    const QCommandLineOption night(QStringLiteral("night"), QStringLiteral("The night theme."));
    const QCommandLineOption page(QStringLiteral("page"), QStringLiteral("The tab shown, 1 to 9 (Alt+1 ..)."),
                                  QStringLiteral("n"), QStringLiteral("1"));
    parser.addOptions(
        {rehearsal, udpRemote, serial, baud, dial, profile, replay, airframe, key, screenshot, size, after, night, page});
    const RehearsalCommandLine rehearse(parser);
    const PlanCommandLine planOptions(parser);
    const StationCommandLine stationOptions(parser);
    parser.process(app);
    if (rehearse.requested())
        return rehearse.run();
    const auto usage = [&](const QString& message) {
        say(message);
        std::fprintf(stderr, "%s", qPrintable(parser.helpText()));
        return kUsageError;
    };
    const int connections = int(parser.isSet(rehearsal)) + int(parser.isSet(udpRemote)) + int(parser.isSet(serial)) +
                            int(parser.isSet(replay));
    QString error;
    if (connections + int(stationOptions.observes()) > 1)
        return usage(QStringLiteral("give at most one of --rehearsal, --udp-remote, --serial, --replay and --observe"));
    if (!stationOptions.check(&error))
        return usage(error);
    if (!parser.positionalArguments().isEmpty())
        return usage(QStringLiteral("unexpected argument %1").arg(parser.positionalArguments().constLast()));
    const QStringList wh = parser.value(size).split(QLatin1Char('x'));
    const QSize windowSize(wh.value(0).toInt(), wh.value(1).toInt());
    if (wh.size() != 2 || windowSize.width() < 320 || windowSize.height() < 240)
        return usage(QStringLiteral("--size wants WIDTHxHEIGHT, e.g. 1600x1000"));
    if (parser.isSet(key) && connections == 0 && !stationOptions.observes())
        return usage(QStringLiteral("--key goes with --rehearsal, --udp-remote, --serial, --replay or --observe"));
    std::optional<LinkSettings> link;
    if (parser.isSet(udpRemote) && !(link = LinkSettings::udpRemote(parser.value(udpRemote), &error)))
        return usage(error);
    if (parser.isSet(serial) && !(link = LinkSettings::serial(parser.value(serial), parser.value(baud), &error)))
        return usage(QStringLiteral("--baud: %1").arg(error));
    if (parser.isSet(dial) && !(link && link->transport == LinkSettings::Transport::Serial))
        return usage(QStringLiteral("--dial goes with --serial DEVICE: the phone's modem is on a serial port"));
    if (link && parser.isSet(dial))
        link->dialNumber = parser.value(dial);
    error = QStringLiteral("it goes with --dial NUMBER");
    if (parser.isSet(profile) && !(link && link->dialsModem() && link->setModemProfile(parser.value(profile), &error)))
        return usage(QStringLiteral("--modem-profile: %1").arg(error));
    MainWindow::Options options;
    // Pictures use the defaults, not the last session's layout.
    options.restoreSettings = !parser.isSet(screenshot);
    options.airframePath = parser.value(airframe);
    if (parser.isSet(airframe) && !AirframeLoader::load(options.airframePath, &error))
        return usage(error);
    MainWindow window(options);
    if (parser.isSet(night))
        window.setTheme(Theme::Kind::Night);
    window.showPanel(parser.value(page).toInt() - 1);
    if (!planOptions.apply(*window.flightPlan(), &error))  // the file is wrong, not the options: no help
        return say(QStringLiteral("--plan: ") + error), kUsageError;
    if (!stationOptions.apply(window, &error))
        return usage(error);
    if (parser.isSet(screenshot))
        window.screenshotAndQuit(parser.value(screenshot), windowSize, parser.value(after).toInt());
    window.show();
    if (parser.isSet(key) && !stationOptions.observes()) {
        // Into the link settings, where the rehearsal takes it from and which keep its path.
        LinkSettings settings = link.value_or(window.linkSettings()->settings());
        settings.keyPath = parser.value(key);
        window.linkSettings()->setSettings(settings);
        if (link)
            link = settings;
    }
    if (parser.isSet(rehearsal))
        window.startRehearsal();
    else if (link)
        window.connectWith(*link);
    else if (parser.isSet(replay))
        window.openFrameLog(parser.value(replay), parser.value(key));
    return app.exec();
}
