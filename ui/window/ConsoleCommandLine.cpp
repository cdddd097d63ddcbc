#include "ui/window/ConsoleCommandLine.h"

#include "link/airframe/AirframeLoader.h"
#include "link/transport/ModemProfile.h"
#include "ui/window/LinkSettingsWidget.h"
#include "ui/window/StationCommandLine.h"

namespace {

QString describe()
{
    return QStringLiteral(
        "The operator console of the RCM ground control station: commands an unmanned aircraft with\n"
        "a Remote Control Message once a second over a serial modem or UDP, and shows what it reports.\n"
        "\n"
        "Examples:\n"
        "  gcs --rehearsal                  rehearse against the simulated aircraft (uasim)\n"
        "  gcs --udp-remote 10.0.0.2:5600   connect over UDP\n"
        "  gcs --serial /dev/ttyUSB0        connect through the radio modem\n"
        "  gcs --serial /dev/ttyUSB0 --dial 881612345678   dial the aircraft's satellite phone\n"
        "  gcs --observe mqtt://127.0.0.1:1883/GB_133    watch an aircraft read-only");
}

}  // namespace

ConsoleCommandLine::ConsoleCommandLine(QCommandLineParser& parser)
    : m_parser(parser),
      m_rehearsal(QStringLiteral("rehearsal"), QStringLiteral("Start the simulated aircraft (uasim, beside gcs) on a "
                                                              "free loopback UDP port and connect to it.")),
      m_udpRemote(QStringLiteral("udp-remote"), QStringLiteral("Connect over UDP to the aircraft at <host:port>."),
                  QStringLiteral("host:port")),
      m_serial(QStringLiteral("serial"), QStringLiteral("Connect through a serial port."), QStringLiteral("device")),
      m_baud(QStringLiteral("baud"), QStringLiteral("Serial bit rate (default 9600)."), QStringLiteral("n"),
             QStringLiteral("9600")),
      m_dial(QStringLiteral("dial"),
             QStringLiteral("The serial port is a satellite phone's modem: dial this number, redial a dropped call, "
                            "hang up on quit (docs/modem.md)."),
             QStringLiteral("number")),
      m_profile(QStringLiteral("modem-profile"),
                QStringLiteral("With --dial: the phone (docs/modem.md), one of %1; default generic.")
                    .arg(modem::profileNames().join(", ")),
                QStringLiteral("name")),
      m_replay(QStringLiteral("replay"), QStringLiteral("Replay a frame log."), QStringLiteral("log.pcapng")),
      m_airframe(QStringLiteral("airframe"),
                 QStringLiteral("The aircraft's units, as a JSON airframe file (default: the one used last, or the "
                                "well-equipped aircraft)."),
                 QStringLiteral("file")),
      m_key(QStringLiteral("key"),
            QStringLiteral("The secure link (docs/security.md): the aircraft's key file, 64 hex digits, mode 0600. "
                           "With --rehearsal, uasim uses it too; with --replay, it reads a keyed session's log; with "
                           "--observe (once per station), it opens the sealed sessions on the broker. Kept in the "
                           "link settings."),
            QStringLiteral("file")),
      m_screenshot(QStringLiteral("screenshot"),
                   QStringLiteral("Lay the window out with the default settings, save a picture of it and exit "
                                  "(works offscreen)."),
                   QStringLiteral("file.png")),
      m_size(QStringLiteral("size"), QStringLiteral("Window size for --screenshot."), QStringLiteral("WxH"),
             QStringLiteral("1600x1000")),
      m_after(QStringLiteral("screenshot-after"),
              QStringLiteral("Seconds the link runs before the picture (default 0)."), QStringLiteral("s"),
              QStringLiteral("0")),
      m_night(QStringLiteral("night"), QStringLiteral("The night theme.")),
      m_page(QStringLiteral("page"),
             QStringLiteral("The tab shown, 1 to 10 (Alt+1 .. Alt+9, Alt+0): 1 the overview, 10 the flight plan."),
             QStringLiteral("n"),
             QStringLiteral("1"))
{
    parser.setApplicationDescription(describe());
    parser.addHelpOption();
    parser.addOptions({m_rehearsal, m_udpRemote, m_serial, m_baud, m_dial, m_profile, m_replay, m_airframe, m_key,
                       m_screenshot, m_size, m_after, m_night, m_page});
}

bool ConsoleCommandLine::check(const StationCommandLine& station, QString* error)
{
    const int connections = int(m_parser.isSet(m_rehearsal)) + int(m_parser.isSet(m_udpRemote)) +
                            int(m_parser.isSet(m_serial)) + int(m_parser.isSet(m_replay));
    const auto refuse = [error](const QString& reason) {
        *error = reason;
        return false;
    };
    if (connections + int(station.observes()) > 1)
        return refuse(
            QStringLiteral("give at most one of --rehearsal, --udp-remote, --serial, --replay and --observe"));
    if (!station.check(error))
        return false;
    if (!m_parser.positionalArguments().isEmpty())
        return refuse(QStringLiteral("unexpected argument %1").arg(m_parser.positionalArguments().constLast()));
    const QStringList wh = m_parser.value(m_size).split(QLatin1Char('x'));
    m_windowSize = QSize(wh.value(0).toInt(), wh.value(1).toInt());
    if (wh.size() != 2 || m_windowSize.width() < 320 || m_windowSize.height() < 240)
        return refuse(QStringLiteral("--size wants WIDTHxHEIGHT, e.g. 1600x1000"));
    if (m_parser.isSet(m_key) && connections == 0 && !station.observes())
        return refuse(QStringLiteral("--key goes with --rehearsal, --udp-remote, --serial, --replay or --observe"));
    if (!checkLink(error))
        return false;
    if (m_parser.isSet(m_airframe) && !AirframeLoader::load(m_parser.value(m_airframe), error))
        return false;
    return true;
}

bool ConsoleCommandLine::checkLink(QString* error)
{
    if (m_parser.isSet(m_udpRemote) && !(m_link = LinkSettings::udpRemote(m_parser.value(m_udpRemote), error)))
        return false;
    if (m_parser.isSet(m_serial) &&
        !(m_link = LinkSettings::serial(m_parser.value(m_serial), m_parser.value(m_baud), error))) {
        *error = QStringLiteral("--baud: %1").arg(*error);
        return false;
    }
    if (m_parser.isSet(m_dial) && !(m_link && m_link->transport == LinkSettings::Transport::Serial)) {
        *error = QStringLiteral("--dial goes with --serial DEVICE: the phone's modem is on a serial port");
        return false;
    }
    if (m_link && m_parser.isSet(m_dial))
        m_link->dialNumber = m_parser.value(m_dial);
    QString reason = QStringLiteral("it goes with --dial NUMBER");
    if (m_parser.isSet(m_profile) &&
        !(m_link && m_link->dialsModem() && m_link->setModemProfile(m_parser.value(m_profile), &reason))) {
        *error = QStringLiteral("--modem-profile: %1").arg(reason);
        return false;
    }
    return true;
}

MainWindow::Options ConsoleCommandLine::windowOptions() const
{
    MainWindow::Options options;
    // Pictures use the defaults, not the last session's layout.
    options.restoreSettings = !m_parser.isSet(m_screenshot);
    options.airframePath = m_parser.value(m_airframe);
    return options;
}

void ConsoleCommandLine::applyLook(MainWindow& window) const
{
    if (m_parser.isSet(m_night))
        window.setTheme(Theme::Kind::Night);
    window.showPanel(m_parser.value(m_page).toInt() - 1);
}

void ConsoleCommandLine::takePicture(MainWindow& window) const
{
    if (m_parser.isSet(m_screenshot))
        window.screenshotAndQuit(m_parser.value(m_screenshot), m_windowSize, m_parser.value(m_after).toInt());
}

void ConsoleCommandLine::start(MainWindow& window, bool observes) const
{
    std::optional<LinkSettings> link = m_link;
    if (m_parser.isSet(m_key) && !observes) {
        // Into the link settings, where the rehearsal takes it from and which keep its path.
        LinkSettings settings = link.value_or(window.linkSettings()->settings());
        settings.keyPath = m_parser.value(m_key);
        window.linkSettings()->setSettings(settings);
        if (link)
            link = settings;
    }
    if (m_parser.isSet(m_rehearsal))
        window.startRehearsal();
    else if (link)
        window.connectWith(*link);
    else if (m_parser.isSet(m_replay))
        window.openFrameLog(m_parser.value(m_replay), m_parser.value(m_key));
}
