// What puts a problem in front of the operator: the error banner (stays until
// dismissed, wraps, counts, never widens the window), failed opens of real
// serial ports and UDP sockets reaching both the event log and the banner
// with their reason, and the link-loss alarm (sounds until silenced or the
// link is back, stays on screen until then, loss and recovery with their
// durations in the event log, nothing in a replay). Time is a virtual clock;
// the sound card is a fake that records what it was asked.

#include "link/clock/VirtualClock.h"
#include "link/eventlog/EventLog.h"
#include "link/session/LinkController.h"
#include "link/transport/SerialLink.h"
#include "link/transport/UdpLink.h"
#include "ui/alerts/AlarmSound.h"
#include "ui/alerts/ConsoleAlerts.h"
#include "ui/alerts/ErrorBanner.h"
#include "ui/alerts/LinkAlarm.h"
#include "ui/alerts/LinkAlarmBanner.h"
#include "ui/alerts/LinkStateStrip.h"
#include "ui/alerts/RefusalDigest.h"
#include "ui/alerts/ToneAlarmSound.h"
#include "ui/eventlog/EventLogModel.h"
#include "ui/eventlog/EventLogView.h"
#include "ui/window/StatusBarWidget.h"

#include <QDir>
#include <QFile>
#include <QTemporaryDir>
#include <QLabel>
#include <QPushButton>
#include <QSignalSpy>
#include <QTest>
#include <QTextDocumentFragment>
#include <QUdpSocket>
#include <QVBoxLayout>

namespace {

constexpr qint64 kT0 = 1'795'455'920'000'000;  // 2026-11-23T17:45:20Z
constexpr qint64 kSecond = 1'000'000;

struct FakeSound : AlarmSound {
    void start() override
    {
        ++starts;
        playing = true;
    }
    void stop() override
    {
        ++stops;
        playing = false;
    }
    int starts = 0;
    int stops = 0;
    bool playing = false;
};

LinkStatistics stats(LinkState state, quint64 frames, qint64 lastGood)
{
    LinkStatistics s;
    s.state = state;
    s.framesReceived = frames;
    s.lastGoodFrameUtcMicros = lastGood;
    return s;
}

// An alarm with its event log, the Events table and a fake sound card, on a
// virtual clock.
// Moves `clock` on to `utcMicros`.
void moveTo(VirtualClock& clock, qint64 utcMicros)
{
    clock.advance(std::chrono::microseconds(utcMicros - clock.utcMicros()));
}

struct AlarmBench {
    AlarmBench() { log.setClock(clock); }
    std::shared_ptr<VirtualClock> clock = std::make_shared<VirtualClock>(kT0);
    EventLog log;
    EventLogModel model{&log};
    FakeSound sound;
    LinkAlarm alarm{&sound, &log};
};

QStringList texts(const EventLogModel& model)
{
    QStringList out;
    for (int row = 0; row < model.rowCount(); ++row)
        out << eventSeverityName(model.event(row).severity) + QStringLiteral(" ") +
                   eventSourceName(model.event(row).source) + QStringLiteral(": ") + model.event(row).text;
    return out;
}

}  // namespace

class TestAlerts : public QObject {
    Q_OBJECT

private slots:
    // A frame refused every second for two minutes, of two reasons: the
    // first of each whole, then one line a minute per reason with how many
    // more and the last of them; the rest when the link stops.
    void refusalsDigestedByTheMinute()
    {
        AlarmBench b;
        RefusalDigest digest(&b.log);
        for (int s = 0; s < 130; ++s) {
            moveTo(*b.clock, kT0 + s * kSecond);
            digest.refused(QStringLiteral("uncorrectable: codeword 1 beyond correction (ID_msg %1)").arg(s));
            if (s % 10 == 0)
                digest.refused(QStringLiteral("forged: authentication failed (offset %1)").arg(s));
            digest.tick();
        }
        QCOMPARE(texts(b.model),
                 (QStringList{
                     QStringLiteral("warning link: A frame was refused: uncorrectable: codeword 1 beyond correction (ID_msg 0)"),
                     QStringLiteral("warning link: A frame was refused: forged: authentication failed (offset 0)"),
                     QStringLiteral("warning link: 59 more frames refused as uncorrectable in the last 60 s; the last: "
                                    "uncorrectable: codeword 1 beyond correction (ID_msg 59)"),
                     QStringLiteral("warning link: 5 more frames refused as forged in the last 60 s; the last: "
                                    "forged: authentication failed (offset 50)"),
                     QStringLiteral("warning link: 60 more frames refused as uncorrectable in the last 60 s; the last: "
                                    "uncorrectable: codeword 1 beyond correction (ID_msg 119)"),
                     QStringLiteral("warning link: 6 more frames refused as forged in the last 60 s; the last: "
                                    "forged: authentication failed (offset 110)"),
                 }));
        b.clock->advance(std::chrono::microseconds(kSecond));
        digest.flush();
        QCOMPARE(b.model.rowCount(), 8);
        QCOMPARE(texts(b.model).at(6),
                 QStringLiteral("warning link: 1 more frame refused as forged in the last 10 s; the last: "
                                "forged: authentication failed (offset 120)"));
        QCOMPARE(texts(b.model).at(7),
                 QStringLiteral("warning link: 10 more frames refused as uncorrectable in the last 10 s; the last: "
                                "uncorrectable: codeword 1 beyond correction (ID_msg 129)"));
        // Quiet for a minute, then one: recorded whole again.
        b.clock->advance(std::chrono::microseconds(61 * kSecond));
        digest.refused(QStringLiteral("forged: authentication failed (offset 999)"));
        QCOMPARE(texts(b.model).last(),
                 QStringLiteral("warning link: A frame was refused: forged: authentication failed (offset 999)"));
    }

    void bannerQueuesAndCounts()
    {
        QWidget window;
        auto* layout = new QVBoxLayout(&window);
        auto* banner = new ErrorBanner;
        layout->addWidget(banner);
        layout->addStretch(1);
        window.show();
        QVERIFY(QTest::qWaitForWindowExposed(&window));
        QVERIFY(!banner->isVisible());
        QSignalSpy counted(banner, &ErrorBanner::countChanged);

        banner->showError(QStringLiteral("udp: cannot bind 0.0.0.0:5600: The bound address is already in use"));
        QVERIFY(banner->isVisible());
        QCOMPARE(banner->count(), 1);
        QCOMPARE(banner->countText(), QString());
        banner->showError(QStringLiteral("The frame log is not pcapng"));
        QCOMPARE(banner->currentText(), QStringLiteral("The frame log is not pcapng"));
        QCOMPARE(banner->countText(), QStringLiteral("Newest of 2 errors"));
        // The same again: counted, not queued.
        banner->showError(QStringLiteral("udp: cannot bind 0.0.0.0:5600: The bound address is already in use"));
        QCOMPARE(banner->count(), 2);
        QCOMPARE(banner->currentText(),
                 QStringLiteral("udp: cannot bind 0.0.0.0:5600: The bound address is already in use"));
        QCOMPARE(banner->countText(), QStringLiteral("Newest of 2 errors; this one 2 times"));
        QCOMPARE(counted.size(), 2);

        // Dismissing shows the one before; the last dismissal hides the banner.
        auto* dismiss = banner->findChild<QPushButton*>(QString(), Qt::FindDirectChildrenOnly);
        QVERIFY(dismiss);
        QCOMPARE(dismiss->text(), QStringLiteral("Dismiss"));
        QTest::mouseClick(dismiss, Qt::LeftButton);
        QCOMPARE(banner->currentText(), QStringLiteral("The frame log is not pcapng"));
        QVERIFY(banner->isVisible());
        QTest::mouseClick(dismiss, Qt::LeftButton);
        QCOMPARE(banner->count(), 0);
        QVERIFY(!banner->isVisible());

        for (int i = 0; i < 3; ++i)
            banner->showError(QStringLiteral("error %1").arg(i));
        banner->dismissAll();
        QCOMPARE(banner->count(), 0);
        QVERIFY(!banner->isVisible());
    }

    // A message far longer than the window wraps inside it: the window keeps
    // its width, the banner grows in height.
    void bannerNeverWidensTheWindow()
    {
        QWidget window;
        auto* layout = new QVBoxLayout(&window);
        auto* banner = new ErrorBanner;
        layout->addWidget(banner);
        layout->addStretch(1);
        window.resize(600, 400);
        window.show();
        QVERIFY(QTest::qWaitForWindowExposed(&window));
        banner->showError(QStringLiteral("Cannot open the frame log: ") + QStringLiteral("/very/long/path").repeated(40) +
                          QStringLiteral(" is not pcapng: ") + QStringLiteral("its first block is not a section header ").repeated(20));
        QCoreApplication::processEvents();
        QCOMPARE(window.width(), 600);
        QVERIFY(window.minimumSizeHint().width() <= 600);
        QVERIFY(banner->width() <= 600);
        auto* message = banner->findChild<QLabel*>(QStringLiteral("errorMessage"));
        QVERIFY(message);
        // Wrapped onto several lines.
        QTRY_VERIFY(message->height() > 4 * message->fontMetrics().height());
        QCOMPARE(window.width(), 600);
    }

    void bannerFollowsErrorEvents()
    {
        EventLog log;
        QWidget window;
        auto* banner = new ErrorBanner(&window);
        banner->follow(&log);
        log.info(EventSource::Link, QStringLiteral("Connected"));
        log.warning(EventSource::Alarm, QStringLiteral("No frame yet"));
        QCOMPARE(banner->count(), 0);
        log.error(EventSource::Key, QStringLiteral("the key file is refused"));
        QCOMPARE(banner->count(), 1);
        QCOMPARE(banner->currentText(), QStringLiteral("the key file is refused"));
        // The link-loss alarm has a banner of its own.
        log.error(EventSource::Alarm, QStringLiteral("Link lost: no good frame for 3 s, after 5 frames in 4 s"));
        QCOMPARE(banner->count(), 1);
    }

    // The failures operators met, from real ports and sockets: the reason the
    // link gives lands, word for word, in the event log and the banner.
    void failedOpenReachesLogAndBanner_data()
    {
        QTest::addColumn<QString>("kind");
        QTest::newRow("serial port that does not exist") << QStringLiteral("serial");
        QTest::newRow("UDP port already in use") << QStringLiteral("udp");
    }
    void failedOpenReachesLogAndBanner()
    {
        QFETCH(QString, kind);
        QUdpSocket holder;  // holds the port the link then asks for
        std::unique_ptr<Link> link;
        QString reason;
        if (kind == QStringLiteral("serial")) {
            const QString device = QStringLiteral("/dev/rcm-no-such-port");
            QVERIFY(!QFile::exists(device));
            link = std::make_unique<SerialLink>(device, 9600);
            reason = QStringLiteral("/dev/rcm-no-such-port: cannot open: No such file or directory; retrying");
        } else {
            QVERIFY(holder.bind(QHostAddress::LocalHost, 0));
            link = std::make_unique<UdpLink>(QHostAddress::LocalHost, holder.localPort(), QHostAddress::LocalHost, 9);
            reason = QStringLiteral("udp: cannot bind 127.0.0.1:%1: The bound address is already in use")
                         .arg(holder.localPort());
        }
        FakeSound sound;
        ConsoleAlerts alerts(&sound);
        QWidget window;
        auto* layout = new QVBoxLayout(&window);
        layout->addWidget(alerts.banners());
        ErrorBanner* banner = alerts.errorBanner();
        const EventLogModel& model = *alerts.model();
        LinkController controller(std::move(link));
        alerts.follow(&controller);  // as the console follows every link it runs
        controller.start();
        QTRY_VERIFY(model.rowCount() > 0);
        QCOMPARE(texts(model), QStringList{QStringLiteral("error link: ") + reason});
        QCOMPARE(banner->currentText(), reason);
        QCOMPARE(banner->count(), 1);
    }

    void durations()
    {
        QCOMPARE(LinkAlarm::durationText(0), QStringLiteral("0 s"));
        QCOMPARE(LinkAlarm::durationText(14 * kSecond + 400'000), QStringLiteral("14 s"));
        QCOMPARE(LinkAlarm::durationText(14 * kSecond + 500'000), QStringLiteral("15 s"));
        QCOMPARE(LinkAlarm::durationText(60 * kSecond), QStringLiteral("1 min"));
        QCOMPARE(LinkAlarm::durationText(125 * kSecond), QStringLiteral("2 min 5 s"));
        QCOMPARE(LinkAlarm::durationText(3600 * kSecond), QStringLiteral("1 h"));
        QCOMPARE(LinkAlarm::durationText(3780 * kSecond), QStringLiteral("1 h 3 min"));
    }

    // Connected for two minutes, then silent: the alarm sounds and shows; the
    // operator silences it; the link comes back after 14 s: it ends, and the
    // event log holds all three with their durations.
    void lossSilencedAndRegained()
    {
        AlarmBench bench;
        auto& [clock, log, model, sound, alarm] = bench;
        QSignalSpy changed(&alarm, &LinkAlarm::changed);

        alarm.setStatistics(stats(LinkState::Waiting, 0, 0));
        moveTo(*clock, kT0 + kSecond);
        alarm.setStatistics(stats(LinkState::Connected, 1, kT0 + kSecond));
        moveTo(*clock, kT0 + 120 * kSecond);
        alarm.setStatistics(stats(LinkState::Connected, 120, kT0 + 120 * kSecond));
        QVERIFY(!alarm.isActive());
        QCOMPARE(sound.starts, 0);

        moveTo(*clock, kT0 + 123 * kSecond);
        alarm.setStatistics(stats(LinkState::Lost, 120, kT0 + 120 * kSecond));
        QVERIFY(alarm.isActive());
        QVERIFY(alarm.isSounding());
        QCOMPARE(sound.starts, 1);
        QVERIFY(sound.playing);
        QCOMPARE(changed.size(), 1);
        QCOMPARE(texts(model),
                 QStringList{QStringLiteral("error alarm: Link lost: no good frame for 3 s, after 120 frames in 1 min 59 s")});

        moveTo(*clock, kT0 + 125 * kSecond);
        alarm.acknowledge();
        QVERIFY(alarm.isActive());
        QVERIFY(alarm.isAcknowledged());
        QVERIFY(!sound.playing);
        QCOMPARE(alarm.silentMicros(), 5 * kSecond);
        alarm.acknowledge();  // twice is once
        QCOMPARE(model.rowCount(), 2);
        QCOMPARE(texts(model).at(1),
                 QStringLiteral("info alarm: Link-loss alarm silenced by the operator, 5 s without a frame"));

        // Still lost: more statistics change nothing.
        moveTo(*clock, kT0 + 130 * kSecond);
        alarm.setStatistics(stats(LinkState::Lost, 120, kT0 + 120 * kSecond));
        QCOMPARE(sound.starts, 1);
        QCOMPARE(model.rowCount(), 2);

        moveTo(*clock, kT0 + 134 * kSecond + 200'000);
        alarm.setStatistics(stats(LinkState::Connected, 121, kT0 + 134 * kSecond));
        QVERIFY(!alarm.isActive());
        QCOMPARE(alarm.silentMicros(), 0);
        QCOMPARE(texts(model).at(2), QStringLiteral("info alarm: Link regained after 14 s without a frame"));

        // The next loss counts the frames of the new spell only.
        moveTo(*clock, kT0 + 200 * kSecond);
        alarm.setStatistics(stats(LinkState::Connected, 180, kT0 + 197 * kSecond));
        alarm.setStatistics(stats(LinkState::Lost, 180, kT0 + 197 * kSecond));
        QCOMPARE(texts(model).at(3),
                 QStringLiteral("error alarm: Link lost: no good frame for 3 s, after 60 frames in 1 min 3 s"));
        QCOMPARE(sound.starts, 2);
        QVERIFY(sound.playing);
    }

    void regainedStopsTheSound()
    {
        AlarmBench bench;
        auto& [clock, log, model, sound, alarm] = bench;
        alarm.setStatistics(stats(LinkState::Connected, 5, kT0));
        clock->advance(std::chrono::microseconds(3 * kSecond));
        alarm.setStatistics(stats(LinkState::Lost, 5, kT0));
        QVERIFY(sound.playing);
        clock->advance(std::chrono::microseconds(10 * kSecond));
        alarm.setStatistics(stats(LinkState::Connected, 6, clock->utcMicros()));
        QVERIFY(!sound.playing);
        QVERIFY(!alarm.isActive());
    }

    // The operator's Disconnect ends the alarm without a word: nothing was lost.
    void closedEndsItQuietly()
    {
        AlarmBench bench;
        auto& [clock, log, model, sound, alarm] = bench;
        alarm.setStatistics(stats(LinkState::Connected, 5, kT0));
        alarm.setStatistics(stats(LinkState::Lost, 5, kT0));
        QVERIFY(alarm.isActive());
        alarm.setStatistics(stats(LinkState::Closed, 5, kT0));
        QVERIFY(!alarm.isActive());
        QVERIFY(!sound.playing);
        QCOMPARE(model.rowCount(), 1);
    }

    // Nothing ever arrived: a warning in the log, once; no alarm.
    void neverConnectedWarnsOnce()
    {
        AlarmBench bench;
        auto& [clock, log, model, sound, alarm] = bench;
        alarm.setStatistics(stats(LinkState::Waiting, 0, 0));
        alarm.setStatistics(stats(LinkState::Lost, 0, 0));
        QVERIFY(!alarm.isActive());
        QCOMPARE(sound.starts, 0);
        QCOMPARE(texts(model), QStringList{QStringLiteral("warning alarm: No frame from the aircraft since the link opened")});
        // A serial port that comes and goes before any frame: still once.
        alarm.setStatistics(stats(LinkState::Lost, 0, 0));
        QCOMPARE(model.rowCount(), 1);
    }

    // A replay: the log's silences are not the aircraft's.
    void disabledInReplay()
    {
        AlarmBench bench;
        auto& [clock, log, model, sound, alarm] = bench;
        alarm.setEnabled(false);
        alarm.setStatistics(stats(LinkState::Connected, 5, kT0));
        alarm.setStatistics(stats(LinkState::Lost, 5, kT0));
        QVERIFY(!alarm.isActive());
        QCOMPARE(sound.starts, 0);
        QCOMPARE(model.rowCount(), 0);

        // Turned off while it sounds (a live link replaced by a replay): silent at once.
        alarm.setEnabled(true);
        alarm.setStatistics(stats(LinkState::Connected, 6, kT0 + kSecond));
        alarm.setStatistics(stats(LinkState::Lost, 6, kT0 + kSecond));
        QVERIFY(sound.playing);
        alarm.setEnabled(false);
        QVERIFY(!alarm.isActive());
        QVERIFY(!sound.playing);
    }

    // The status bar in a replay: "Replay", the log's time, and a silence
    // or the end of the log raises no alarm.
    void statusBarInReplay()
    {
        StatusBarWidget status;
        QSignalSpy alarmed(&status, &StatusBarWidget::alarm);
        status.setLinkDescription(QStringLiteral("replay of rcm-2026-11-23T17-45-00Z.pcapng"));
        status.setReplay(true);
        status.setStatistics(stats(LinkState::Connected, 5, kT0));
        const QString state = QTextDocumentFragment::fromHtml(status.stateText()).toPlainText();
        QCOMPARE(state, QStringLiteral("\u25cf Replay replay of rcm-2026-11-23T17-45-00Z.pcapng"));
        status.setReplayTime(kT0 + 20 * kSecond);
        QCOMPARE(QTextDocumentFragment::fromHtml(status.ageText()).toPlainText(),
                 QStringLiteral("Log time 2026-11-23 17:45:40 UTC"));
        status.setStatistics(stats(LinkState::Lost, 5, kT0));
        QVERIFY(!status.alarmActive());
        QCOMPARE(alarmed.size(), 0);

        // Live again: the same silence is an alarm.
        status.setReplay(false);
        QVERIFY(status.alarmActive());
        QCOMPARE(QTextDocumentFragment::fromHtml(status.stateText()).toPlainText(),
                 QStringLiteral("\u25cf Lost replay of rcm-2026-11-23T17-45-00Z.pcapng"));
    }

    void bannerShowsUntilRegained()
    {
        AlarmBench bench;
        auto& [clock, log, model, sound, alarm] = bench;
        QWidget window;
        auto* layout = new QVBoxLayout(&window);
        auto* banner = new LinkAlarmBanner(&alarm);
        layout->addWidget(banner);
        layout->addStretch(1);
        window.resize(800, 400);
        window.show();
        QVERIFY(QTest::qWaitForWindowExposed(&window));
        QVERIFY(!banner->isVisible());
        QCOMPARE(banner->silenceButton()->focusPolicy(), Qt::NoFocus);

        alarm.setStatistics(stats(LinkState::Connected, 5, kT0));
        moveTo(*clock, kT0 + 3 * kSecond);
        alarm.setStatistics(stats(LinkState::Lost, 5, kT0));
        QVERIFY(banner->isVisible());
        QCOMPARE(banner->text(), QStringLiteral("LINK LOST \u2014 no frame from the aircraft for 3 s"));
        QVERIFY(banner->silenceButton()->isVisible());
        moveTo(*clock, kT0 + 42 * kSecond);
        banner->refresh();
        QCOMPARE(banner->text(), QStringLiteral("LINK LOST \u2014 no frame from the aircraft for 42 s"));
        // Large: at least twice the height of a line of the window's text.
        QVERIFY(banner->height() >= 2 * window.fontMetrics().height());

        QTest::mouseClick(banner->silenceButton(), Qt::LeftButton);
        QVERIFY(alarm.isAcknowledged());
        QVERIFY(!sound.playing);
        QVERIFY(banner->isVisible());
        QVERIFY(!banner->silenceButton()->isVisible());
        auto* silenced = banner->findChild<QLabel*>(QString(), Qt::FindDirectChildrenOnly);
        QVERIFY(silenced);

        alarm.setStatistics(stats(LinkState::Connected, 6, clock->utcMicros()));
        QVERIFY(!banner->isVisible());
    }

    // The console's alerts as one part: events kept in the session's
    // directory, the real tone (silent here) saying once that it cannot be
    // heard, no alarm in a replay.
    void consoleAlerts()
    {
        QTemporaryDir dir;
        ConsoleAlerts alerts;
        alerts.events()->setClock(std::make_shared<VirtualClock>(kT0 + 4 * kSecond));
        QVERIFY(alerts.keepIn(dir.filePath(QStringLiteral("framelogs"))));
        QVERIFY(alerts.events()->filePath().startsWith(dir.filePath(QStringLiteral("framelogs/rcm-"))));
        QVERIFY(alerts.events()->filePath().endsWith(QStringLiteral(".events.txt")));
        QCOMPARE(alerts.eventView()->fileText(),
                 QStringLiteral("Kept in %1").arg(QDir::toNativeSeparators(alerts.events()->filePath())));

        alerts.setReplay(true);
        alerts.setStatistics(stats(LinkState::Connected, 5, kT0));
        alerts.setStatistics(stats(LinkState::Lost, 5, kT0));
        QVERIFY(!alerts.alarm()->isActive());
        alerts.setReplay(false);
        alerts.setStatistics(stats(LinkState::Connected, 6, kT0 + kSecond));
        alerts.setStatistics(stats(LinkState::Lost, 6, kT0 + kSecond));
        QVERIFY(alerts.alarm()->isActive());
        QStringList lines;
        QFile file(alerts.events()->filePath());
        QVERIFY(file.open(QIODevice::ReadOnly));
        for (const QByteArray& line : file.readAll().split('\n'))
            if (!line.isEmpty())
                lines << QString::fromUtf8(line.mid(line.indexOf('\t') + 1));
        QStringList expected{
            QStringLiteral("error\talarm\tLink lost: no good frame for 3 s, after 1 frame in 0 s")};
        if (!ToneAlarmSound::hasSoundCard())
            expected.prepend(QStringLiteral("warning\talarm\tno sound card: the link-loss alarm is shown but not heard"));
        QCOMPARE(lines, expected);
    }

    // The tone is built in; without a sound card it says so once and the
    // rest of the alarm goes on.
    void toneWithoutASoundCard()
    {
        ToneAlarmSound tone;
        QFile wav(QStringLiteral(":/sounds/link-lost.wav"));
        QVERIFY(wav.open(QIODevice::ReadOnly));
        const QByteArray header = wav.read(44);
        QCOMPARE(header.left(4), QByteArray("RIFF"));
        QCOMPARE(header.mid(8, 8), QByteArray("WAVEfmt "));
        QCOMPARE(wav.size(), 16044);  // 8000 samples of 16 bits, and the header
        if (ToneAlarmSound::hasSoundCard())
            QSKIP("this machine has a sound card: the tone would sound");
        QSignalSpy unavailable(&tone, &ToneAlarmSound::unavailable);
        tone.start();
        tone.start();
        tone.stop();
        QCOMPARE(unavailable.size(), 1);
        QCOMPARE(unavailable.at(0).at(0).toString(),
                 QStringLiteral("no sound card: the link-loss alarm is shown but not heard"));
        QVERIFY(!tone.isPlaying());
    }

    // An error whose cause cleared leaves the banner, however many times it
    // came; the others stay in their order. The event log keeps it.
    void errorBannerWithdrawsAClearedError()
    {
        ErrorBanner banner;
        QSignalSpy counts(&banner, &ErrorBanner::countChanged);
        banner.showError(QStringLiteral("key file refused"));
        banner.showError(QStringLiteral("call dropped; redialling in 10 s"));
        banner.showError(QStringLiteral("call dropped; redialling in 10 s"));
        QCOMPARE(banner.count(), 2);
        QVERIFY(banner.withdraw(QStringLiteral("call dropped; redialling in 10 s")));
        QCOMPARE(banner.count(), 1);
        QCOMPARE(banner.currentText(), QStringLiteral("key file refused"));
        QCOMPARE(banner.countText(), QString());
        QVERIFY(!banner.withdraw(QStringLiteral("call dropped; redialling in 10 s")));
        QCOMPARE(counts.size(), 3);

        FakeSound sound;
        ConsoleAlerts alerts(&sound);
        alerts.banners();
        alerts.error(EventSource::Link, QStringLiteral("call dropped; redialling in 10 s"));
        alerts.withdraw(QStringLiteral("call dropped; redialling in 10 s"), QStringLiteral("the link was closed"));
        QCOMPARE(alerts.errorBanner()->count(), 0);
        QCOMPARE(texts(*alerts.model()),
                 (QStringList{QStringLiteral("error link: call dropped; redialling in 10 s"),
                              QStringLiteral("info console: Off the banner, the link was closed: call dropped; "
                                             "redialling in 10 s")}));
    }

    // Without a sound card: an error at start, on the banner and in the log.
    void noSoundCardIsAnErrorAtStart()
    {
        FakeSound sound;
        ConsoleAlerts alerts(&sound);
        alerts.banners();
        QVERIFY(alerts.checkSound(true));
        QCOMPARE(alerts.model()->rowCount(), 0);
        QVERIFY(!alerts.checkSound(false));
        QCOMPARE(texts(*alerts.model()),
                 QStringList{QStringLiteral("error console: No sound card: the link-loss alarm will be shown but not heard")});
        QCOMPARE(alerts.errorBanner()->currentText(),
                 QStringLiteral("No sound card: the link-loss alarm will be shown but not heard"));
    }

    // The strip of a floating dock: the state in words, the alarm in red
    // with its own Silence button, counting as the banner does.
    void linkStateStripFollowsTheAlarm()
    {
        FakeSound sound;
        ConsoleAlerts alerts(&sound);
        const auto clock = std::make_shared<VirtualClock>(kT0);
        alerts.events()->setClock(clock);
        std::unique_ptr<LinkStateStrip> strip(alerts.newLinkStrip());
        QCOMPARE(strip->text(), QStringLiteral("Link: Not connected"));
        alerts.setStatistics(stats(LinkState::Waiting, 0, 0));
        QCOMPARE(strip->text(), QStringLiteral("Link: Waiting for the aircraft"));
        alerts.setStatistics(stats(LinkState::Connected, 10, kT0));
        QCOMPARE(strip->text(), QStringLiteral("Link: Connected"));
        moveTo(*clock, kT0 + 3 * kSecond);
        alerts.setStatistics(stats(LinkState::Lost, 10, kT0));
        QVERIFY(strip->isAlarm());
        QCOMPARE(strip->text(), QStringLiteral("LINK LOST \u2014 no frame from the aircraft for 3 s"));
        moveTo(*clock, kT0 + 75 * kSecond);
        strip->refresh();  // what its timer does each second
        QCOMPARE(strip->text(), QStringLiteral("LINK LOST \u2014 no frame from the aircraft for 1 min 15 s"));
        QVERIFY(!strip->silenceButton()->isHidden());
        strip->silenceButton()->click();
        QVERIFY(!sound.playing);
        QCOMPARE(strip->text(), QStringLiteral("LINK LOST \u2014 no frame from the aircraft for 1 min 15 s (silenced)"));
        QVERIFY(strip->silenceButton()->isHidden());
        alerts.setStatistics(stats(LinkState::Closed, 10, kT0));
        QVERIFY(!strip->isAlarm());
        QCOMPARE(strip->text(), QStringLiteral("Link: Not connected"));
        alerts.setReplay(true);
        alerts.setStatistics(stats(LinkState::Connected, 10, kT0));
        QCOMPARE(strip->text(), QStringLiteral("Link: replay of a frame log, read only"));
    }
};

QTEST_MAIN(TestAlerts)
#include "tst_alerts.moc"
