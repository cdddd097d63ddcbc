// The console's event log: each event one line of the session's event log
// file, complete on disk as soon as it is recorded (a killed console loses
// none), read back exactly; and the Events dock's table of them, errors
// tinted, the newest in view.

#include "link/clock/VirtualClock.h"
#include "link/eventlog/ConsoleEvent.h"
#include "link/eventlog/EventLog.h"
#include "ui/eventlog/EventLogModel.h"
#include "ui/eventlog/EventLogView.h"

#include <QBrush>
#include <QDateTime>
#include <QFile>
#include <QSignalSpy>
#include <QTableView>
#include <QTemporaryDir>
#include <QTest>

#include <csignal>
#include <sys/wait.h>
#include <unistd.h>

namespace {

// 2026-11-23T17:45:20.123Z
constexpr qint64 kT0 = 1'795'455'920'123'000;

QStringList fileLines(const QString& path)
{
    QFile f(path);
    if (!f.open(QIODevice::ReadOnly))
        return {QStringLiteral("(cannot open %1)").arg(path)};
    const QByteArray all = f.readAll();
    if (!all.isEmpty() && !all.endsWith('\n'))
        return {QStringLiteral("(last line incomplete)")};
    QStringList lines = QString::fromUtf8(all).split(u'\n');
    lines.removeLast();  // after the final newline
    return lines;
}

}  // namespace

class TestEventLog : public QObject {
    Q_OBJECT

private slots:
    void lineFormat()
    {
        const ConsoleEvent event{kT0, EventSeverity::Error, EventSource::Link,
                                 QStringLiteral("udp: cannot bind\t0.0.0.0:5600\nC:\\logs")};
        QCOMPARE(QDateTime::fromMSecsSinceEpoch(kT0 / 1000, Qt::UTC).toString(Qt::ISODateWithMs),
                 QStringLiteral("2026-11-23T17:45:20.123Z"));
        QCOMPARE(eventLine(event),
                 QStringLiteral("2026-11-23T17:45:20.123Z\terror\tlink\tudp: cannot bind\\t0.0.0.0:5600\\nC:\\\\logs"));
        QCOMPARE(parseEventLine(eventLine(event)), std::optional<ConsoleEvent>(event));
        for (EventSource source :
             {EventSource::Link, EventSource::Key, EventSource::Plan, EventSource::Alarm, EventSource::Console})
            for (EventSeverity severity : {EventSeverity::Info, EventSeverity::Warning, EventSeverity::Error}) {
                const ConsoleEvent e{kT0 + 1000, severity, source, QStringLiteral("x")};
                QCOMPARE(parseEventLine(eventLine(e)), std::optional<ConsoleEvent>(e));
            }
    }

    void notALine_data()
    {
        QTest::addColumn<QString>("line");
        QTest::newRow("three fields") << QStringLiteral("2026-11-23T17:45:20.123Z\terror\tlink");
        QTest::newRow("five fields") << QStringLiteral("2026-11-23T17:45:20.123Z\terror\tlink\ta\tb");
        QTest::newRow("bad time") << QStringLiteral("yesterday\terror\tlink\ttext");
        QTest::newRow("bad severity") << QStringLiteral("2026-11-23T17:45:20.123Z\tfatal\tlink\ttext");
        QTest::newRow("bad source") << QStringLiteral("2026-11-23T17:45:20.123Z\terror\tradio\ttext");
        QTest::newRow("trailing backslash") << QStringLiteral("2026-11-23T17:45:20.123Z\terror\tlink\ttext\\");
        QTest::newRow("unknown escape") << QStringLiteral("2026-11-23T17:45:20.123Z\terror\tlink\t\\q");
    }
    void notALine()
    {
        QFETCH(QString, line);
        QCOMPARE(parseEventLine(line), std::nullopt);
    }

    void fileNameBesideTheFrameLog()
    {
        const QDateTime t(QDate(2026, 11, 22), QTime(7, 32, 0), Qt::UTC);
        QCOMPARE(EventLog::sessionFileName(t), QStringLiteral("rcm-2026-11-22T07-32-00Z.events.txt"));
    }

    // Each event is a whole line in the file the moment record() returns,
    // and a reopened log goes on after what it held.
    void recordsAsItHappens()
    {
        QTemporaryDir dir;
        const QString path = dir.filePath(QStringLiteral("logs/rcm-2026-11-23T17-45-20Z.events.txt"));
        const auto clock = std::make_shared<VirtualClock>(kT0);
        EventLog log;
        log.setClock(clock);
        QSignalSpy recorded(&log, &EventLog::recorded);
        QVERIFY(log.openFile(path));
        QCOMPARE(log.filePath(), path);

        log.info(EventSource::Link, QStringLiteral("Connected: UDP 127.0.0.1:5600"));
        QCOMPARE(fileLines(path),
                 QStringList{QStringLiteral("2026-11-23T17:45:20.123Z\tinfo\tlink\tConnected: UDP 127.0.0.1:5600")});
        clock->advance(std::chrono::microseconds(2'500'000));
        log.error(EventSource::Key, QStringLiteral("the key file is refused: /k: mode 644, run: chmod 600 /k"));
        QCOMPARE(fileLines(path).size(), 2);
        QCOMPARE(fileLines(path).at(1), QStringLiteral("2026-11-23T17:45:22.623Z\terror\tkey\tthe key file is "
                                                       "refused: /k: mode 644, run: chmod 600 /k"));
        QCOMPARE(recorded.size(), 2);
        QCOMPARE(recorded.at(1).at(0).value<ConsoleEvent>(),
                 (ConsoleEvent{kT0 + 2'500'000, EventSeverity::Error, EventSource::Key,
                               QStringLiteral("the key file is refused: /k: mode 644, run: chmod 600 /k")}));

        EventLog again;
        again.setClock(clock);
        QVERIFY(again.openFile(path));
        again.warning(EventSource::Plan, QStringLiteral("plan: no reply"));
        QCOMPARE(fileLines(path).size(), 3);
        QCOMPARE(fileLines(path).at(2), QStringLiteral("2026-11-23T17:45:22.623Z\twarning\tplan\tplan: no reply"));
    }

    // A console killed outright (SIGKILL, no destructor, no flush) leaves
    // every event it recorded, each a complete line.
    void survivesBeingKilled()
    {
        QTemporaryDir dir;
        const QString path = dir.filePath(QStringLiteral("killed.events.txt"));
        const pid_t child = fork();
        QVERIFY(child >= 0);
        if (child == 0) {
            EventLog log;
            log.setClock(std::make_shared<VirtualClock>(kT0));
            if (!log.openFile(path))
                _exit(2);
            for (int i = 1; i <= 3; ++i)
                log.error(EventSource::Alarm, QStringLiteral("event %1").arg(i));
            raise(SIGKILL);
            _exit(3);  // never reached
        }
        int status = 0;
        QCOMPARE(waitpid(child, &status, 0), child);
        QVERIFY(WIFSIGNALED(status));
        QCOMPARE(WTERMSIG(status), SIGKILL);
        QCOMPARE(fileLines(path), (QStringList{QStringLiteral("2026-11-23T17:45:20.123Z\terror\talarm\tevent 1"),
                                               QStringLiteral("2026-11-23T17:45:20.123Z\terror\talarm\tevent 2"),
                                               QStringLiteral("2026-11-23T17:45:20.123Z\terror\talarm\tevent 3")}));
    }

    void fileRefused()
    {
        QTemporaryDir dir;
        QFile plain(dir.filePath(QStringLiteral("plain")));
        QVERIFY(plain.open(QIODevice::WriteOnly));
        plain.close();
        EventLog log;
        QString error;
        QVERIFY(!log.openFile(dir.filePath(QStringLiteral("plain/sub/x.events.txt")), &error));
        QCOMPARE(error, QStringLiteral("cannot create directory %1").arg(dir.filePath(QStringLiteral("plain/sub"))));
        QVERIFY(!log.isFileOpen());
        QSignalSpy recorded(&log, &EventLog::recorded);
        log.info(EventSource::Link, QStringLiteral("still shown"));
        QCOMPARE(recorded.size(), 1);
    }

    // A disk that fills up: the event is still shown, then one error says
    // the file is given up, and nothing more is tried.
    void writeFailsOnce()
    {
        if (!QFile::exists(QStringLiteral("/dev/full")))
            QSKIP("no /dev/full here");
        EventLog log;
        log.setClock(std::make_shared<VirtualClock>(kT0));
        QVERIFY(log.openFile(QStringLiteral("/dev/full")));
        QSignalSpy recorded(&log, &EventLog::recorded);
        log.info(EventSource::Link, QStringLiteral("first"));
        QCOMPARE(recorded.size(), 2);
        QCOMPARE(recorded.at(0).at(0).value<ConsoleEvent>().text, QStringLiteral("first"));
        const auto failure = recorded.at(1).at(0).value<ConsoleEvent>();
        QCOMPARE(failure.severity, EventSeverity::Error);
        QCOMPARE(failure.source, EventSource::Console);
        QCOMPARE(failure.text, QStringLiteral("the event log /dev/full cannot be written: No space left on device; "
                                              "events are only shown from now on"));
        QVERIFY(!log.isFileOpen());
        log.info(EventSource::Link, QStringLiteral("second"));
        QCOMPARE(recorded.size(), 3);
    }

    void modelColumnsAndColours()
    {
        EventLog log;
        log.setClock(std::make_shared<VirtualClock>(kT0));
        EventLogModel model(&log);
        log.info(EventSource::Link, QStringLiteral("Connected"));
        log.warning(EventSource::Alarm, QStringLiteral("No frame from the aircraft since the link opened"));
        log.error(EventSource::Link, QStringLiteral("udp: cannot bind"));
        QCOMPARE(model.rowCount(), 3);
        QCOMPARE(model.columnCount(), 4);
        const auto text = [&](int row, int column) { return model.index(row, column).data().toString(); };
        QCOMPARE(text(2, EventLogModel::TimeColumn), QStringLiteral("17:45:20"));
        QCOMPARE(text(2, EventLogModel::SeverityColumn), QStringLiteral("error"));
        QCOMPARE(text(2, EventLogModel::SourceColumn), QStringLiteral("link"));
        QCOMPARE(text(2, EventLogModel::TextColumn), QStringLiteral("udp: cannot bind"));
        QCOMPARE(model.headerData(0, Qt::Horizontal).toString(), QStringLiteral("Time (UTC)"));
        QCOMPARE(model.count(EventSeverity::Error), 1);

        // Both colours set, or neither: a tint on its own could be unreadable in the night theme.
        QVERIFY(!model.index(0, 3).data(Qt::BackgroundRole).isValid());
        QVERIFY(!model.index(0, 3).data(Qt::ForegroundRole).isValid());
        for (int row : {1, 2}) {
            const QColor fg = model.index(row, 3).data(Qt::ForegroundRole).value<QBrush>().color();
            const QColor bg = model.index(row, 3).data(Qt::BackgroundRole).value<QBrush>().color();
            // WCAG relative luminance contrast, at least 7:1 (AAA).
            const auto luminance = [](const QColor& c) {
                const auto channel = [](double v) {
                    return v <= 0.03928 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
                };
                return 0.2126 * channel(c.redF()) + 0.7152 * channel(c.greenF()) + 0.0722 * channel(c.blueF());
            };
            const double ratio = (luminance(bg) + 0.05) / (luminance(fg) + 0.05);
            QVERIFY2(ratio >= 7.0, qPrintable(QStringLiteral("row %1: %2").arg(row).arg(ratio)));
        }
        QCOMPARE(model.index(2, 3).data(Qt::BackgroundRole).value<QBrush>().color(), QColor(0xff, 0xd6, 0xd6));
    }

    void modelKeepsTheNewest()
    {
        EventLogModel model;
        QSignalSpy removed(&model, &QAbstractItemModel::rowsRemoved);
        for (int i = 0; i < EventLogModel::kMaxEvents + 2; ++i)
            model.append({kT0 + i, EventSeverity::Info, EventSource::Link, QString::number(i)});
        QCOMPARE(model.rowCount(), EventLogModel::kMaxEvents);
        QCOMPARE(removed.size(), 2);
        QCOMPARE(model.event(0).text, QStringLiteral("2"));
        QCOMPARE(model.event(model.rowCount() - 1).text, QString::number(EventLogModel::kMaxEvents + 1));
    }

    void viewKeepsTheNewestInView()
    {
        EventLog log;
        log.setClock(std::make_shared<VirtualClock>(kT0));
        EventLogModel model(&log);
        EventLogView view(&model);
        view.resize(500, 200);
        view.show();
        QVERIFY(QTest::qWaitForWindowExposed(&view));
        QCOMPARE(view.countsText(), QStringLiteral("0 events, 0 errors, 0 warnings"));
        QCOMPARE(view.fileText(), QStringLiteral("not kept in a file"));
        view.setFilePath(QStringLiteral("/var/log/rcm/x.events.txt"));
        QCOMPARE(view.fileText(), QStringLiteral("Kept in /var/log/rcm/x.events.txt"));

        for (int i = 0; i < 199; ++i)
            log.info(EventSource::Link, QStringLiteral("event %1").arg(i));
        // Scrolled back by the operator, and then an error comes: it is in view.
        view.table()->scrollToTop();
        log.error(EventSource::Link, QStringLiteral("serial: port lost"));
        QCOMPARE(view.countsText(), QStringLiteral("200 events, 1 error, 0 warnings"));
        QTRY_VERIFY(view.table()->viewport()->rect().contains(
            view.table()->visualRect(model.index(199, EventLogModel::TextColumn)).center()));
        QVERIFY(!view.table()->viewport()->rect().intersects(view.table()->visualRect(model.index(0, 0))));
    }
};

QTEST_MAIN(TestEventLog)
#include "tst_eventlog.moc"
