// gcs: the operator console.
//
//   gcs                           the console, as it was left last time
//   gcs --rehearsal               start uasim on loopback and connect to it
//   gcs --udp-remote HOST:PORT    connect over UDP at once
//   gcs --serial DEV [--baud N]   connect over a serial port at once
//   gcs --replay LOG.pcapng       replay a frame log
//   gcs ... --key FILE            the secure link with the aircraft's key file
//                                 (with --rehearsal, uasim gets it too)
//   gcs --screenshot FILE.png     lay the window out, save a picture of it, exit
//
// Hidden, for docs/performance.md (each prints its figures and exits):
//   gcs --measure-startup         time from process start to the window's first paint
//   gcs --measure-memory MODE [N] resident memory before and after N frames (default
//                                 172,800: a day) reach the frame log view; MODE is
//                                 live, records or file (see reportMemory)
//   gcs --measure-stall [N]       the GUI thread's longest stall while a synthetic
//                                 log of N frames (default 1,200) replays at 10x
#include "codec/message/Airframe.h"
#include "codec/message/MessageEncoder.h"
#include "link/framelog/FrameLog.h"
#include "link/simulation/AirframeLoader.h"
#include "ui/framelog/FrameLogModel.h"
#include "ui/window/LinkSettings.h"
#include "ui/window/LinkSettingsWidget.h"
#include "ui/window/MainWindow.h"

#include <QApplication>
#include <QCommandLineParser>
#include <QElapsedTimer>
#include <QFile>
#include <QPixmap>
#include <QTemporaryDir>
#include <QTimer>

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <vector>

namespace {

constexpr int kUsageError = 2;

void say(const QString& line)
{
    std::fprintf(stderr, "gcs: %s\n", qPrintable(line));
}

// Milliseconds since the kernel started this process (Linux, 10 ms steps):
// includes loading the program and its libraries, which no timer in main() sees.
double millisSinceProcessStart()
{
    QFile stat(QStringLiteral("/proc/self/stat")), uptime(QStringLiteral("/proc/uptime"));
    if (!stat.open(QIODevice::ReadOnly) || !uptime.open(QIODevice::ReadOnly))
        return -1;
    const QByteArray s = stat.readAll();
    // Field 22 (starttime), counted after the parenthesised command name.
    const QList<QByteArray> fields = s.mid(s.lastIndexOf(')') + 2).split(' ');
    const double startTicks = fields.value(19).toDouble();
    const double upSeconds = uptime.readAll().split(' ').value(0).toDouble();
    return (upSeconds - startTicks / double(sysconf(_SC_CLK_TCK))) * 1000.0;
}

// Resident memory from /proc, in MiB: the whole, and the part that is the
// process's own (anonymous) rather than mapped files (libraries, a mapped
// frame log), which the kernel can drop and read again.
QString memory()
{
    QFile status(QStringLiteral("/proc/self/status"));
    if (!status.open(QIODevice::ReadOnly))
        return QStringLiteral("?");
    QString rss, anon, file;
    for (const QByteArray& line : status.readAll().split('\n')) {
        const auto mib = [&] {
            return QString::number(line.simplified().split(' ').value(1).toDouble() / 1024, 'f', 1);
        };
        if (line.startsWith("VmRSS:"))
            rss = mib();
        if (line.startsWith("RssAnon:"))
            anon = mib();
        if (line.startsWith("RssFile:"))
            file = mib();
    }
    return QStringLiteral("resident %1 MiB (own %2 MiB, mapped files %3 MiB)").arg(rss, anon, file);
}

// A session as a link would log it: a command and a status frame a second,
// real datagrams of the default airframe with the gear and flaps moving so
// that the panels have something to redraw.
FrameRecord syntheticFrame(int i, qint64 t0)
{
    static const rcm::Message resting = rcm::restingCommand(rcm::Airframe::wellEquipped());
    rcm::Message m = resting;
    m.header.set(rcm::ItemId::ID_msg, i / 2);
    m.flaps.set(rcm::ItemId::F_elev_set, (i / 2) % 41 - 20);
    m.settings.set(rcm::ItemId::land_wheels, (i / 20) % 2 ? 0xAA : 0x55);
    rcm::Diagnostics errors;
    const auto datagram = rcm::encodeDatagram(m, errors);
    FrameRecord r;
    r.bytes = QByteArray(reinterpret_cast<const char*>(datagram->data()), qsizetype(datagram->size()));
    r.utcMicros = t0 + qint64(i) * 500'000;
    r.transport = FrameTransport::Udp;
    r.direction = i % 2 ? FrameDirection::Received : FrameDirection::Sent;
    r.status = i % 2 ? FrameStatus::Decoded : FrameStatus::NotChecked;
    if (i % 2)
        r.correctedSymbols = {0, 0};
    return r;
}

bool writeSyntheticLog(const QString& path, int frames)
{
    FrameLog log;
    QString error;
    if (!log.open(path, &error)) {
        say(error);
        return false;
    }
    const qint64 t0 = QDateTime::currentMSecsSinceEpoch() * 1000;
    for (int i = 0; i < frames; ++i)
        if (!log.append(syntheticFrame(i, t0)))
            return false;
    return true;
}

// One way a day of frames can reach the log view, in a fresh process each
// so that one's freed memory does not hide in the next one's figure:
//   live     as a live link feeds it (LinkWorker::frameLogged): each frame is
//            written to the session's log and its row holds the offset; the
//            last rows are then shown, reading their frames back from the file
//   records  frames that are in no log file, their bytes kept in memory
//   file     a log file opened for replay: its index, the frames read when shown
// ("signals", the name of live before frames carried their offset, still works.)
int reportMemory(MainWindow& window, QString mode, int frames)
{
    if (mode == QLatin1String("signals"))
        mode = QStringLiteral("live");
    say(QStringLiteral("window shown: %1").arg(memory()));
    QElapsedTimer timer;
    FrameLogModel* model = window.frameLog();
    const qint64 t0 = QDateTime::currentMSecsSinceEpoch() * 1000;
    QTemporaryDir dir;
    const QString path = dir.filePath(QStringLiteral("day.pcapng"));
    if (mode == QLatin1String("file")) {
        if (!writeSyntheticLog(path, frames))
            return 1;
        say(QStringLiteral("log written: %1").arg(memory()));
        timer.start();
        if (!model->openLog(path))
            return 1;
    } else if (mode == QLatin1String("live")) {
        FrameLog log;
        QString error;
        if (!log.open(path, &error)) {
            say(error);
            return 1;
        }
        model->setSessionLog(path);
        timer.start();
        for (int i = 0; i < frames; ++i) {
            const FrameRecord r = syntheticFrame(i, t0);
            LoggedFrame logged;
            if (!log.append(r, &logged.entry.offset))
                return 1;
            logged.entry.utcMicros = r.utcMicros;
            logged.entry.length = quint32(r.bytes.size());
            logged.entry.direction = r.direction;
            logged.entry.transport = r.transport;
            logged.entry.status = r.status;
            logged.correctedSymbols = r.correctedSymbols;
            logged.messageId = quint32(i / 2);
            model->appendLogged(logged);
            if (i % 1000 == 999)
                QCoreApplication::processEvents();  // a burst a second at most, live
        }
        QCoreApplication::processEvents();
        // What the operator looks at: the newest frames, their bytes read back.
        for (int row = std::max(0, model->rowCount() - 100); row < model->rowCount(); ++row) {
            if (model->record(row).bytes.size() != syntheticFrame(row, t0).bytes.size()) {
                say(QStringLiteral("row %1: the frame could not be read back from the log").arg(row));
                return 1;
            }
        }
    } else if (mode == QLatin1String("records")) {
        timer.start();
        for (int i = 0; i < frames; ++i) {
            model->appendRecord(syntheticFrame(i, t0), quint32(i / 2));
            if (i % 1000 == 999)
                QCoreApplication::processEvents();
        }
    } else {
        say(QStringLiteral("--measure-memory wants live, records or file"));
        return kUsageError;
    }
    QCoreApplication::processEvents();
    say(QStringLiteral("%1 frames in the log view (%2) after %3 ms, %4 with their bytes in memory: %5")
            .arg(model->rowCount())
            .arg(mode)
            .arg(timer.elapsed())
            .arg(model->rowsWithBytesInMemory())
            .arg(memory()));
    return 0;
}

// Ticks a 1 ms timer on the GUI thread and records the gaps between ticks: a
// gap is as long as the longest thing the GUI thread did in between.
class StallProbe : public QObject {
public:
    StallProbe()
    {
        m_timer.setTimerType(Qt::PreciseTimer);
        m_timer.setInterval(1);
        connect(&m_timer, &QTimer::timeout, this, [this] {
            const qint64 now = m_clock.nsecsElapsed();
            if (m_last >= 0) {
                m_gaps.push_back(now - m_last);
                if (now - m_last > m_longest) {
                    m_longest = now - m_last;
                    m_longestAt = m_last;
                }
            }
            m_last = now;
        });
        m_clock.start();
        m_timer.start();
    }
    QString report()
    {
        if (m_gaps.empty())
            return QStringLiteral("no ticks");
        std::sort(m_gaps.begin(), m_gaps.end());
        const auto ms = [](qint64 ns) { return QString::number(double(ns) / 1e6, 'f', 2); };
        const auto over = std::count_if(m_gaps.begin(), m_gaps.end(), [](qint64 g) { return g > 16'000'000; });
        return QStringLiteral(
                   "%1 ticks; gap median %2 ms, 99.9th percentile %3 ms, longest %4 ms (%5 s after the "
                   "replay started); %6 gaps over 16 ms")
            .arg(m_gaps.size())
            .arg(ms(m_gaps[m_gaps.size() / 2]), ms(m_gaps[m_gaps.size() * 999 / 1000]), ms(m_gaps.back()))
            .arg(double(m_longestAt) / 1e9, 0, 'f', 2)
            .arg(over);
    }

private:
    QTimer m_timer;
    QElapsedTimer m_clock;
    qint64 m_last = -1;
    qint64 m_longest = 0;
    qint64 m_longestAt = 0;
    std::vector<qint64> m_gaps;
};

}  // namespace

int main(int argc, char* argv[])
{
    QApplication app(argc, argv);
    QCoreApplication::setOrganizationName(QStringLiteral("rcm"));
    QCoreApplication::setApplicationName(QStringLiteral("gcs"));

    QCommandLineParser parser;
    parser.setApplicationDescription(
        QStringLiteral("The operator console of the RCM ground control station: commands an unmanned aircraft with\n"
                       "a Remote Control Message once a second over a serial modem or UDP, and shows what it reports.\n"
                       "\n"
                       "Examples:\n"
                       "  gcs --rehearsal                  rehearse against the simulated aircraft (uasim)\n"
                       "  gcs --udp-remote 10.0.0.2:5600   connect over UDP\n"
                       "  gcs --serial /dev/ttyUSB0        connect through the radio modem"));
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
    const QCommandLineOption key(QStringLiteral("key"),
                                 QStringLiteral("The secure link (docs/security.md): the aircraft's key file, 64 hex "
                                                "digits, mode 0600. With --rehearsal, uasim uses it too. Kept in the "
                                                "link settings (the path, never the key)."),
                                 QStringLiteral("file"));
    const QCommandLineOption size(QStringLiteral("size"), QStringLiteral("Window size for --screenshot."),
                                  QStringLiteral("WxH"), QStringLiteral("1600x1000"));
    QCommandLineOption measureStartup(QStringLiteral("measure-startup"));
    QCommandLineOption measureMemory(QStringLiteral("measure-memory"));
    QCommandLineOption measureStall(QStringLiteral("measure-stall"));
    for (QCommandLineOption* hidden : {&measureStartup, &measureMemory, &measureStall})
        hidden->setFlags(QCommandLineOption::HiddenFromHelp);
    parser.addOptions({rehearsal, udpRemote, serial, baud, replay, airframe, key, screenshot, size, measureStartup,
                       measureMemory, measureStall});
    parser.process(app);

    const auto usage = [&](const QString& message) {
        say(message);
        std::fprintf(stderr, "%s", qPrintable(parser.helpText()));
        return kUsageError;
    };
    const int connections = int(parser.isSet(rehearsal)) + int(parser.isSet(udpRemote)) + int(parser.isSet(serial)) +
                            int(parser.isSet(replay));
    if (connections > 1)
        return usage(QStringLiteral("give at most one of --rehearsal, --udp-remote, --serial and --replay"));
    const bool measuring = parser.isSet(measureMemory) || parser.isSet(measureStall);
    if (parser.positionalArguments().size() > (measuring ? 2 : 0))
        return usage(QStringLiteral("unexpected argument %1").arg(parser.positionalArguments().constLast()));
    int width = 0, height = 0;
    {
        const QStringList wh = parser.value(size).split(QLatin1Char('x'));
        width = wh.value(0).toInt();
        height = wh.value(1).toInt();
        if (wh.size() != 2 || width < 320 || height < 240)
            return usage(QStringLiteral("--size wants WIDTHxHEIGHT, e.g. 1600x1000"));
    }
    std::optional<LinkSettings> link;
    if (parser.isSet(udpRemote)) {
        QString error;
        link = LinkSettings::udpRemote(parser.value(udpRemote), &error);
        if (!link)
            return usage(error);
    }
    if (parser.isSet(key) && !parser.isSet(rehearsal) && !parser.isSet(udpRemote) && !parser.isSet(serial))
        return usage(QStringLiteral("--key goes with --rehearsal, --udp-remote or --serial"));
    if (parser.isSet(serial)) {
        bool ok = false;
        link = LinkSettings();
        link->transport = LinkSettings::Transport::Serial;
        link->serialPort = parser.value(serial);
        link->baudRate = parser.value(baud).toInt(&ok);
        if (!ok || link->baudRate <= 0)
            return usage(QStringLiteral("--baud wants a bit rate, not %1").arg(parser.value(baud)));
    }

    MainWindow::Options options;
    // Pictures and measurements use the defaults, not the last session's layout.
    options.restoreSettings = !parser.isSet(screenshot) && !measuring && !parser.isSet(measureStartup);
    options.airframePath = parser.value(airframe);
    if (parser.isSet(airframe)) {
        QString error;
        if (!AirframeLoader::load(options.airframePath, &error))
            return usage(error);
    }
    MainWindow window(options);

    if (parser.isSet(screenshot)) {
        window.resize(width, height);
        window.show();
        // After the first pass of the event loop, so that docks and layouts have settled.
        QTimer::singleShot(0, &window, [&] {
            const QString path = parser.value(screenshot);
            if (!window.grab().save(path)) {
                say(QStringLiteral("cannot save %1").arg(path));
                QCoreApplication::exit(1);
                return;
            }
            QCoreApplication::quit();
        });
        return app.exec();
    }
    if (parser.isSet(measureStartup)) {
        // The first paint of the window is when the operator sees it.
        struct FirstPaint : QObject {
            bool eventFilter(QObject*, QEvent* event) override
            {
                if (event->type() == QEvent::Paint && !done) {
                    done = true;
                    say(QStringLiteral("window painted %1 ms after the process started")
                            .arg(millisSinceProcessStart(), 0, 'f', 0));
                    QTimer::singleShot(0, qApp, &QCoreApplication::quit);
                }
                return false;
            }
            bool done = false;
        } firstPaint;
        window.installEventFilter(&firstPaint);
        window.resize(width, height);
        window.show();
        return app.exec();
    }
    if (parser.isSet(measureMemory)) {
        const QString mode = parser.positionalArguments().value(0, QStringLiteral("signals"));
        const int frames = parser.positionalArguments().value(1, QStringLiteral("172800")).toInt();
        window.resize(width, height);
        window.show();
        QCoreApplication::processEvents();
        return reportMemory(window, mode, frames);
    }
    if (parser.isSet(measureStall)) {
        const int frames = parser.positionalArguments().value(0, QStringLiteral("1200")).toInt();
        QTemporaryDir dir;
        const QString path = dir.filePath(QStringLiteral("session.pcapng"));
        if (!writeSyntheticLog(path, frames))
            return 1;
        window.resize(width, height);
        window.show();
        QCoreApplication::processEvents();  // the first layout and paint are startup, not replay
        StallProbe probe;
        if (!window.openFrameLog(path))
            return 1;
        window.setReplaySpeed(10.0);
        QObject::connect(&window, &MainWindow::replayFinished, &app, [&] {
            say(QStringLiteral("replay of %1 frames at 10x: %2").arg(frames).arg(probe.report()));
            QCoreApplication::quit();
        });
        return app.exec();
    }

    window.show();
    if (parser.isSet(key)) {
        // Into the link settings, where the rehearsal takes it from and which keep its path.
        if (link) {
            link->keyPath = parser.value(key);
        } else {
            LinkSettings settings = window.linkSettings()->settings();
            settings.keyPath = parser.value(key);
            window.linkSettings()->setSettings(settings);
        }
    }
    if (parser.isSet(rehearsal))
        window.startRehearsal();
    else if (link)
        window.connectWith(*link);
    else if (parser.isSet(replay) && !window.openFrameLog(parser.value(replay)))
        return 1;
    return app.exec();
}
