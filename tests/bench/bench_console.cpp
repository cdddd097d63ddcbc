// The operator console's start-up, memory and GUI-thread stalls, for
// docs/performance.md. Each mode prints its figures to stderr and exits; run
// offscreen (QT_QPA_PLATFORM=offscreen) or on a display.
//
//   bench_console startup          time from process start to the window's first paint
//   bench_console memory MODE [N]  resident memory before and after N frames (default
//                                  172,800: a day both ways) reach the frame log view;
//                                  MODE is live, records or file (see reportMemory)
//   bench_console stall [N] [S]    the GUI thread's longest stall while a synthetic log
//                                  of N frames (default 86,400) is opened for replay,
//                                  then while it replays at 10x for S seconds (default 60);
//                                  with BENCH_TRACE=1 in the environment it also lists, for
//                                  the opening, every GUI event over 0.5 ms and every probe
//                                  gap over 4 ms in time order, and the layout requests,
//                                  moves, resizes and paints per widget; BENCH_SPIKE_MS=N
//                                  lists what every event over N ms painted (default 8),
//                                  BENCH_PARENTS=1 names each painted widget's nearest
//                                  named ancestor, BENCH_REGION=1 the log view's painted
//                                  region
//   bench_console repaint [N]      the whole window repainted N times (default 200): the
//                                  median and longest, and the paint time per widget
#include "codec/message/Airframe.h"
#include "codec/message/DigitPairs.h"
#include "codec/message/MessageEncoder.h"
#include "link/framelog/FrameLog.h"
#include "ui/framelog/FrameLogModel.h"
#include "ui/window/MainWindow.h"

#include <QApplication>
#include <QElapsedTimer>
#include <QEventLoop>
#include <QFile>
#include <QLabel>
#include <QMap>
#include <QPaintEvent>
#include <QTemporaryDir>
#include <QThread>
#include <QTimer>

#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <vector>

namespace {

constexpr int kUsageError = 2;

void say(const QString& line)
{
    std::fprintf(stderr, "bench_console: %s\n", qPrintable(line));
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
    // Stamped as a link stamps them, so that the receive path accepts the
    // replayed status frames and the console shows them, as in a real replay.
    const qint64 utcMicros = t0 + qint64(i) * 500'000;
    const std::chrono::sys_seconds second{std::chrono::seconds(utcMicros / 1'000'000)};
    m.header.set(rcm::ItemId::ID_msg, i / 2);
    m.header.set(rcm::ItemId::time_UTC, rcm::DigitPairs::timeOf(second).packed());
    m.header.set(rcm::ItemId::date_UTC, rcm::DigitPairs::dateOf(second).packed());
    m.flaps.set(rcm::ItemId::F_elev_set, (i / 2) % 41 - 20);
    m.settings.set(rcm::ItemId::land_wheels, (i / 20) % 2 ? 0xAA : 0x55);
    rcm::Diagnostics errors;
    const auto datagram = rcm::encodeDatagram(m, errors);
    FrameRecord r;
    r.bytes = QByteArray(reinterpret_cast<const char*>(datagram->data()), qsizetype(datagram->size()));
    r.utcMicros = utcMicros;
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
int reportMemory(MainWindow& window, const QString& mode, int frames)
{
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
        say(QStringLiteral("memory wants live, records or file"));
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
                if (now - m_last > 4'000'000)
                    m_longGaps << QStringLiteral("%1 ms: probe gap of %2 ms")
                                      .arg(double(m_last) / 1e6, 0, 'f', 2)
                                      .arg(double(now - m_last) / 1e6, 0, 'f', 2);
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
        const auto over = std::count_if(m_gaps.begin(), m_gaps.end(), [](qint64 g) { return g > 8'000'000; });
        return QStringLiteral(
                   "%1 ticks in %2 s; gap median %3 ms, 99.9th percentile %4 ms, longest %5 ms (%6 s in); "
                   "%7 gaps over 8 ms")
            .arg(m_gaps.size())
            .arg(double(m_clock.nsecsElapsed()) / 1e9, 0, 'f', 2)
            .arg(ms(m_gaps[m_gaps.size() / 2]), ms(m_gaps[m_gaps.size() * 999 / 1000]), ms(m_gaps.back()))
            .arg(double(m_longestAt) / 1e9, 0, 'f', 2)
            .arg(over);
    }

    QStringList longGaps() const { return m_longGaps; }

private:
    QStringList m_longGaps;
    QTimer m_timer;
    QElapsedTimer m_clock;
    qint64 m_last = -1;
    qint64 m_longest = 0;
    qint64 m_longestAt = 0;
    std::vector<qint64> m_gaps;
};

// Every event the GUI thread handles, timed in the thread's own CPU time:
// what the GUI thread itself spent on the longest one, whatever else the
// machine was doing meanwhile (the probe's gaps include being descheduled).
class ProbedApplication : public QApplication {
public:
    using QApplication::QApplication;

    bool notify(QObject* receiver, QEvent* event) override
    {
        // Events of other threads (the link's) are theirs.
        if (QThread::currentThread() != thread())
            return QApplication::notify(receiver, event);
        if (m_on && (event->type() == QEvent::LayoutRequest || event->type() == QEvent::Move || event->type() == QEvent::Paint ||
                     event->type() == QEvent::Resize))
            ++m_geometry[QStringLiteral("%1 %2").arg(event->type()).arg(describe(receiver))];
        if (m_depth++ > 0 || !m_on) {
            // Inside a repaint: which widgets it painted, and for how long.
            const bool paint = m_on && event->type() == QEvent::Paint;
            const qint64 paintStart = paint ? threadCpuNanos() : 0;
            QString painted = paint ? describe(receiver) : QString();
            if (paint && painted.contains(QStringLiteral("QTableView")) && qEnvironmentVariableIsSet("BENCH_REGION")) {
                const QRegion reg = static_cast<QPaintEvent*>(event)->region();
                painted += QStringLiteral(" [%1 rects, %2x%3]").arg(reg.rectCount()).arg(reg.boundingRect().width()).arg(reg.boundingRect().height());
            }
            const bool handled = QApplication::notify(receiver, event);
            if (paint)
                m_paints[painted] += threadCpuNanos() - paintStart;
            --m_depth;
            return handled;
        }
        m_paints.clear();
        const qint64 start = threadCpuNanos();
        const qint64 wallStart = m_trace ? m_clock.nsecsElapsed() : 0;
        const int type = event->type();  // the event may be gone afterwards
        const QString what = QStringLiteral("%1 to a %2").arg(type).arg(receiver->metaObject()->className());
        const bool handled = QApplication::notify(receiver, event);
        --m_depth;
        const qint64 spent = threadCpuNanos() - start;
        if (spent > m_longest) {
            m_longest = spent;
            m_longestWhat = what;
        }
        if (m_trace && spent > 20'000)
            m_traced << QStringLiteral("%1 ms: %2 for %3 ms (wall %4 ms)")
                            .arg(double(m_clock.nsecsElapsed()) / 1e6, 0, 'f', 2)
                            .arg(what)
                            .arg(double(spent) / 1e6, 0, 'f', 2)
                            .arg(double(m_clock.nsecsElapsed() - wallStart) / 1e6, 0, 'f', 2);
        if (spent > spikeNanos()) {
            // What a spike painted: the costliest widgets first.
            std::vector<std::pair<qint64, QString>> paints;
            for (auto it = m_paints.cbegin(); it != m_paints.cend(); ++it)
                paints.emplace_back(it.value(), it.key());
            std::sort(paints.rbegin(), paints.rend());
            QStringList parts;
            for (std::size_t i = 0; i < std::min<std::size_t>(qEnvironmentVariableIsSet("BENCH_TRACE") ? 40 : 6, paints.size()); ++i)
                parts << QStringLiteral("%1 %2 ms").arg(paints[i].second).arg(double(paints[i].first) / 1e6, 0, 'f', 2);
            m_spikes << QStringLiteral("%1 ms, %2, %3 widgets painted: %4")
                            .arg(double(spent) / 1e6, 0, 'f', 2)
                            .arg(what)
                            .arg(paints.size())
                            .arg(parts.join(QStringLiteral(", ")));
        }
        if (spent > kSlowEventNanos) {
            auto& [count, longest] = m_slow[what];
            ++count;
            longest = std::max(longest, spent);
        }
        return handled;
    }
    void restart()
    {
        m_on = true;
        m_longest = 0;
        m_longestWhat.clear();
        m_slow.clear();
        m_spikes.clear();
        m_geometry.clear();
        m_paints.clear();
    }
    QStringList geometry() const
    {
        std::vector<std::pair<int, QString>> v;
        for (auto it = m_geometry.cbegin(); it != m_geometry.cend(); ++it)
            v.emplace_back(it.value(), it.key());
        std::sort(v.rbegin(), v.rend());
        QStringList out;
        for (std::size_t i = 0; i < std::min<std::size_t>(90, v.size()); ++i)
            out << QStringLiteral("%1 x %2").arg(v[i].first).arg(v[i].second);
        return out;
    }
    // Paints sent outside the event loop (QWidget::repaint()) are timed as
    // if inside an event, adding up by widget until the next restart().
    void timePaintsOutsideEvents(bool on) { m_depth += on ? 1 : -1; }
    // Paint time by widget, the costliest first.
    QStringList paintTimes(int divisor) const
    {
        std::vector<std::pair<qint64, QString>> paints;
        for (auto it = m_paints.cbegin(); it != m_paints.cend(); ++it)
            paints.emplace_back(it.value(), it.key());
        std::sort(paints.rbegin(), paints.rend());
        QStringList out;
        for (const auto& [nanos, what] : paints)
            out << QStringLiteral("%1 ms %2").arg(double(nanos) / 1e6 / divisor, 0, 'f', 3).arg(what);
        return out;
    }
    // Every event over half a millisecond, in order, with the time it ended.
    void trace(bool on)
    {
        m_trace = on;
        m_traced.clear();
        m_clock.start();
    }
    QStringList traced() const { return m_traced; }
    // Events over spikeNanos(), with the widgets they painted.
    QStringList spikes() const { return m_spikes; }
    QString report() const
    {
        QStringList slow;
        for (auto it = m_slow.cbegin(); it != m_slow.cend(); ++it)
            slow << QStringLiteral("%1 x %2 (longest %3 ms)")
                        .arg(it->first)
                        .arg(it.key())
                        .arg(double(it->second) / 1e6, 0, 'f', 2);
        return QStringLiteral("longest event handled %1 ms of GUI-thread CPU time (event type %2); over %3 ms: %4")
            .arg(double(m_longest) / 1e6, 0, 'f', 2)
            .arg(m_longestWhat)
            .arg(double(kSlowEventNanos) / 1e6)
            .arg(slow.isEmpty() ? QStringLiteral("none") : slow.join(QStringLiteral(", ")));
    }

private:
    // A scroll area's viewport by the view it is part of.
    static QString describe(const QObject* o)
    {
        QString self = QStringLiteral("%1 %2").arg(o->metaObject()->className(), o->objectName());
        // An unnamed label by what it says.
        if (const auto* label = qobject_cast<const QLabel*>(o); label && o->objectName().isEmpty())
            self += QStringLiteral("\"%1\"").arg(label->text().left(24));
        if (qEnvironmentVariableIsSet("BENCH_PARENTS")) {
            for (const QObject* p = o->parent(); p; p = p->parent())
                if (!p->objectName().isEmpty()) { self += QStringLiteral(" in ") + p->objectName(); break; }
        }
        if (o->objectName() != QLatin1String("qt_scrollarea_viewport") || !o->parent())
            return self;
        return self + QStringLiteral(" of ") + describe(o->parent());
    }
    static qint64 threadCpuNanos()
    {
        timespec t{};
        clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
        return qint64(t.tv_sec) * 1'000'000'000 + t.tv_nsec;
    }
    static constexpr qint64 kSlowEventNanos = 4'000'000;
    static qint64 spikeNanos()
    {
        static const qint64 nanos = qint64(qEnvironmentVariable("BENCH_SPIKE_MS", QStringLiteral("8")).toDouble() * 1e6);
        return nanos;
    }
    bool m_trace = false;
    QElapsedTimer m_clock;
    QStringList m_traced;
    int m_depth = 0;
    bool m_on = false;
    qint64 m_longest = 0;
    QString m_longestWhat;
    QMap<QString, std::pair<int, qint64>> m_slow;  // events over kSlowEventNanos: how many, the longest
    QMap<QString, int> m_geometry;
    QMap<QString, qint64> m_paints;                // paint time by widget, in the event being handled
    QStringList m_spikes;
};

// Opening the log (indexing, the log view's rows) until the first record
// plays, then `seconds` of replay at 10x, each under its own probe.
int reportStalls(ProbedApplication& app, MainWindow& window, int frames, int seconds)
{
    QTemporaryDir dir;
    const QString path = dir.filePath(QStringLiteral("session.pcapng"));
    if (!writeSyntheticLog(path, frames))
        return 1;
    // The first layouts and paints are startup, not replay: a second of the
    // event loop to finish them.
    {
        QEventLoop settle;
        QTimer::singleShot(1000, &settle, &QEventLoop::quit);
        settle.exec();
    }
    ConsoleSession* session = window.session();
    std::unique_ptr<StallProbe> probe = std::make_unique<StallProbe>();
    app.restart();
    bool playing = false;
    QObject::connect(session, &ConsoleSession::failed, &app, [](const QString& reason) {
        say(reason);
        QCoreApplication::exit(1);
    });
    QObject::connect(session, &ConsoleSession::linkStarted, &app, [&] {
        QObject::connect(session->replay(), &ReplayLink::positionChanged, &app, [&](qint64, int next) {
            if (next == 0 || playing)
                return;
            playing = true;
            say(QStringLiteral("opening a %1-frame log for replay, until its first frame played: %2; %3")
                    .arg(frames)
                    .arg(probe->report(), app.report()));
            for (const QString& spike : app.spikes())
                say(QStringLiteral("  event over 8 ms: ") + spike);
            if (qEnvironmentVariableIsSet("BENCH_TRACE")) {
                for (const QString& g : app.geometry())
                    if (!g.contains(QLatin1String(" x 12 ")))
                        say(QStringLiteral("  geometry: ") + g);
                for (const QString& t : app.traced())
                    say(QStringLiteral("  event at ") + t);
                for (const QString& t : probe->longGaps())
                    say(QStringLiteral("  gap at ") + t);
            }
            probe = std::make_unique<StallProbe>();
            app.restart();
            app.trace(qEnvironmentVariableIsSet("BENCH_TRACE"));
            QTimer::singleShot(seconds * 1000, &app, [&] {
                say(QStringLiteral("%1 s of replay at 10x: %2; %3").arg(seconds).arg(probe->report(), app.report()));
                for (const QString& spike : app.spikes())
                    say(QStringLiteral("  event over 8 ms: ") + spike);
                for (const QString& g : app.geometry())
                    say(QStringLiteral("  geometry: ") + g);
                if (qEnvironmentVariableIsSet("BENCH_TRACE")) {
                    for (const QString& t : app.traced())
                        say(QStringLiteral("  event at ") + t);
                    for (const QString& t : probe->longGaps())
                        say(QStringLiteral("  gap at ") + t);
                }
                QCoreApplication::quit();
            });
        });
    });
    window.setReplaySpeed(10.0);
    app.trace(qEnvironmentVariableIsSet("BENCH_TRACE"));
    window.openFrameLog(path);
    return app.exec();
}

// The whole window painted again `times` times, as after a change that
// touches every panel (a replay starting clears every reported value): the
// longest a full repaint holds the GUI thread, and where its time goes.
int reportRepaint(ProbedApplication& app, MainWindow& window, int times)
{
    QCoreApplication::processEvents();
    std::vector<double> millis;
    app.restart();
    app.timePaintsOutsideEvents(true);
    for (int i = 0; i < times; ++i) {
        QElapsedTimer timer;
        timer.start();
        window.repaint();
        millis.push_back(double(timer.nsecsElapsed()) / 1e6);
    }
    app.timePaintsOutsideEvents(false);
    const QStringList paints = app.paintTimes(times);
    for (qsizetype i = 0; i < std::min<qsizetype>(paints.size(), 30); ++i)
        say(QStringLiteral("  a repaint: ") + paints[i]);
    say(QStringLiteral("  %1 widgets painted").arg(paints.size()));
    std::sort(millis.begin(), millis.end());
    say(QStringLiteral("whole window repainted %1 times: median %2 ms, longest %3 ms")
            .arg(times)
            .arg(millis[millis.size() / 2], 0, 'f', 2)
            .arg(millis.back(), 0, 'f', 2));
    return 0;
}

}  // namespace

int main(int argc, char* argv[])
{
    ProbedApplication app(argc, argv);
    const QStringList args = app.arguments().mid(1);
    const QString mode = args.value(0);
    if (mode != QLatin1String("startup") && mode != QLatin1String("memory") && mode != QLatin1String("stall") &&
        mode != QLatin1String("repaint")) {
        say(QStringLiteral("usage: bench_console startup | memory live|records|file [N] | stall [N] [SECONDS]"));
        return kUsageError;
    }
    MainWindow::Options options;
    options.restoreSettings = false;  // the defaults, not the last session's layout
    QTemporaryDir logs;
    options.frameLogDirectory = logs.path();
    MainWindow window(options);
    window.resize(1600, 1000);

    if (mode == QLatin1String("startup")) {
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
        window.show();
        return app.exec();
    }
    window.show();
    QCoreApplication::processEvents();
    if (mode == QLatin1String("repaint"))
        return reportRepaint(app, window, args.value(1, QStringLiteral("200")).toInt());
    if (mode == QLatin1String("memory"))
        return reportMemory(window, args.value(1), args.value(2, QStringLiteral("172800")).toInt());
    return reportStalls(app, window, args.value(1, QStringLiteral("86400")).toInt(),
                        args.value(2, QStringLiteral("60")).toInt());
}
