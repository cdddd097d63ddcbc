// The overview page: link quality per minute counted exactly from the link's
// statistics (corrected bytes, frames beyond correction, silences), the link's
// health in figures, every unit's commanded and reported values side by side
// from the item table, the plot drawing what the history holds, and a replay
// that says so. Time is a virtual clock.

#include "codec/message/Airframe.h"
#include "link/airframe/AirframeLoader.h"
#include "ui/overview/LinkQualityHistory.h"
#include "ui/overview/LinkQualityPlot.h"
#include "ui/overview/OverviewPage.h"
#include "ui/panels/CommandState.h"
#include "ui/panels/ItemText.h"
#include "ui/panels/ReportedLabel.h"
#include "ui/panels/ReportedState.h"

#include <QGroupBox>
#include <QImage>
#include <QLabel>
#include <QLocale>
#include <QScrollArea>
#include <QScrollBar>
#include <QTest>

#include <chrono>
#include <map>

using namespace rcm;

namespace {

constexpr qint64 kT0 = 1'795'455'900'000'000;  // 2026-11-23T17:45:00Z, a minute's start
constexpr qint64 kSecond = 1'000'000;
constexpr qint64 kMinute = 60 * kSecond;

// A link whose aircraft sends a frame at 0.1 s past every second, and the
// console sampling its statistics at 0.5 s past.
struct FakeLink {
    LinkStatistics s;
    void frame(int second, quint64 corrected = 0)
    {
        s.state = LinkState::Connected;
        ++s.framesReceived;
        s.correctedBytesBlock1 += corrected;
        s.lastGoodFrameUtcMicros = kT0 + second * kSecond + kSecond / 10;
    }
};

int pixelsOf(const QImage& image, const QColor& colour)
{
    int n = 0;
    for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x)
            n += image.pixelColor(x, y) == colour;
    return n;
}

}  // namespace

class TestOverview : public QObject {
    Q_OBJECT

private slots:
    void initTestCase() { QLocale::setDefault(QLocale(QLocale::English, QLocale::UnitedStates)); }

    // Two clean minutes; then five frames beyond correction, a 30-second
    // silence, and the link back: each lost frame counted in the minute it
    // is found missing, half a second after it was due.
    void perMinuteCounts()
    {
        LinkQualityHistory history;
        FakeLink link;
        link.s.state = LinkState::Waiting;
        for (int second = 0; second < 240; ++second) {
            const bool beyond = second >= 125 && second < 130;
            const bool silent = second >= 150 && second < 180;
            if (beyond)
                ++link.s.refused[std::size_t(rcm::Refusal::Uncorrectable)];
            else if (!silent)
                link.frame(second, second % 10 == 0 ? 2 : 0);
            if (second == 153)
                link.s.state = LinkState::Lost;
            history.sample(kT0 + second * kSecond + kSecond / 2, link.s);
        }
        using M = LinkQualityHistory::Minute;
        const std::deque<M> expected{
            {kT0, 12, 0, 60},
            {kT0 + kMinute, 12, 0, 60},
            {kT0 + 2 * kMinute, 6, 34, 25},
            {kT0 + 3 * kMinute, 12, 1, 60},  // frame 179 is half a second late only in this minute
        };
        QCOMPARE(history.minutes(), expected);
    }

    // A silence counts while it lasts: a frame is lost once half a second late.
    void silenceCountsAsItGoes()
    {
        LinkQualityHistory history;
        FakeLink link;
        for (int second = 0; second < 10; ++second) {
            link.frame(second);
            history.sample(kT0 + second * kSecond + kSecond / 2, link.s);
        }
        QCOMPARE(history.lostSinceFirstFrame(kT0 + 10 * kSecond + kSecond / 2, link.s), 0u);  // due 10.1 s: 0.4 s late
        QCOMPARE(history.lostSinceFirstFrame(kT0 + 10 * kSecond + 7 * kSecond / 10, link.s), 1u);
        history.sample(kT0 + 20 * kSecond + kSecond / 2, link.s);  // 10.1 .. 19.1 s due: 10 frames
        QCOMPARE(history.minutes().back().lostFrames, 10u);
    }

    void newLinkClosedAndOldMinutes()
    {
        LinkQualityHistory history;
        FakeLink link;
        for (int second = 0; second < 5; ++second) {
            link.frame(second, 1);
            history.sample(kT0 + second * kSecond + kSecond / 2, link.s);
        }
        // Closed: nothing is counted, however long.
        LinkStatistics closed;
        history.sample(kT0 + 50 * kSecond, closed);
        // A new link's counters start at zero again: not negative minutes.
        FakeLink second;
        second.frame(70, 3);
        history.sample(kT0 + 70 * kSecond + kSecond / 2, second.s);
        QCOMPARE(history.minutes().size(), std::size_t(2));
        QCOMPARE(history.minutes()[0], (LinkQualityHistory::Minute{kT0, 5, 0, 5}));
        QCOMPARE(history.minutes()[1], (LinkQualityHistory::Minute{kT0 + kMinute, 3, 0, 1}));

        // An hour on, only the last hour is kept.
        for (int minute = 2; minute < 70; ++minute) {
            second.frame(minute * 60);
            history.sample(kT0 + minute * kMinute + kSecond / 2, second.s);
        }
        QCOMPARE(history.minutes().size(), std::size_t(LinkQualityHistory::kMinutes));
        QCOMPARE(history.minutes().front().startUtcMicros, kT0 + 10 * kMinute);
    }

    void plotDrawsWhatItHolds()
    {
        LinkQualityHistory history;
        LinkQualityPlot plot(&history);
        plot.resize(600, plot.sizeHint().height());
        FakeLink link;
        for (int second = 0; second < 60; ++second) {
            link.frame(second, 4);
            history.sample(kT0 + second * kSecond + kSecond / 2, link.s);
        }
        plot.setNow(kT0 + 59 * kSecond);
        QImage clean = plot.grab().toImage();
        QVERIFY(pixelsOf(clean, LinkQualityPlot::kCorrectedColour) > 0);
        QCOMPARE(pixelsOf(clean, LinkQualityPlot::kLostColour), 0);
        history.sample(kT0 + 70 * kSecond, link.s);  // ten seconds silent
        plot.setNow(kT0 + 70 * kSecond);
        QVERIFY(pixelsOf(plot.grab().toImage(), LinkQualityPlot::kLostColour) > 0);
    }

    void healthFigures()
    {
        CommandState command;
        ReportedState reported(&command);
        OverviewPage page(&command, &reported);
        qint64 now = kT0;
        page.setClock([&now] { return now; });
        QCOMPARE(page.figure(QStringLiteral("state")), QStringLiteral("Not connected"));
        QCOMPARE(page.figure(QStringLiteral("age")), QStringLiteral("\u2014"));
        LinkStatistics s;
        s.state = LinkState::Connected;
        s.framesSent = 1234;
        s.framesReceived = 1230;
        s.correctedBytesBlock1 = 40;
        s.correctedBytesBlock2 = 2;
        s.refused[std::size_t(rcm::Refusal::Uncorrectable)] = 3;
        s.refused[std::size_t(rcm::Refusal::Forged)] = 1;
        s.refused[std::size_t(rcm::Refusal::WrongSize)] = 2;
        s.lastGoodFrameUtcMicros = kT0 - 2'500'000;
        page.setStatistics(s);
        QCOMPARE(page.figure(QStringLiteral("state")), QStringLiteral("Connected"));
        QCOMPARE(page.figure(QStringLiteral("sent")), QStringLiteral("1,234"));
        QCOMPARE(page.figure(QStringLiteral("received")), QStringLiteral("1,230"));
        QCOMPARE(page.figure(QStringLiteral("corrected")), QStringLiteral("42"));
        QCOMPARE(page.figure(QStringLiteral("uncorrectable")), QStringLiteral("3"));
        QCOMPARE(page.figure(QStringLiteral("refused")), QStringLiteral("3"));
        QCOMPARE(page.figure(QStringLiteral("age")), QStringLiteral("2.5 s ago"));
        now += 10 * kSecond;
        page.tick();
        QCOMPARE(page.figure(QStringLiteral("age")), QStringLiteral("12.5 s ago"));
        QCOMPARE(page.history().minutes().size(), std::size_t(1));
        s.state = LinkState::Lost;
        page.setStatistics(s);
        QCOMPARE(page.figure(QStringLiteral("state")), QStringLiteral("LINK LOST"));
        auto* state = page.findChild<QLabel*>(QStringLiteral("figure:state"));
        QCOMPARE(state->palette().color(QPalette::WindowText), QColor(0xb7, 0x1c, 0x1c));
        // At night: a light red that reads on the dark window.
        QPalette night = page.palette();
        night.setColor(QPalette::Window, QColor(0x20, 0x20, 0x20));
        night.setColor(QPalette::WindowText, QColor(0xe0, 0xe0, 0xe0));
        page.setPalette(night);
        QCOMPARE(state->palette().color(QPalette::WindowText), QColor(0xef, 0x9a, 0x9a));
        // Closed: the page's own colour again.
        s.state = LinkState::Closed;
        page.setStatistics(s);
        QCOMPARE(state->palette().color(QPalette::WindowText), QColor(0xe0, 0xe0, 0xe0));
    }

    // A replay says so, shows the log's time, and feeds no link-quality minutes.
    void replay()
    {
        CommandState command;
        ReportedState reported(&command);
        OverviewPage page(&command, &reported);
        page.setClock([] { return kT0; });
        page.setReplay(true);
        LinkStatistics s;
        s.state = LinkState::Connected;
        s.framesReceived = 10;
        s.lastGoodFrameUtcMicros = kT0 - kSecond;
        page.setStatistics(s);
        QCOMPARE(page.figure(QStringLiteral("state")), QStringLiteral("Replay"));
        QCOMPARE(page.figure(QStringLiteral("age")), QStringLiteral("\u2014"));
        page.setReplayTime(kT0 - 3600 * kSecond + 20 * kSecond);
        QCOMPARE(page.figure(QStringLiteral("age")), QStringLiteral("log 16:45:20 UTC"));
        // The plot is the log's: sampled at the log's time, 16:45; the live
        // clock's tick adds nothing.
        page.tick();
        QCOMPARE(page.history().minutes().size(), std::size_t(1));
        QCOMPARE(page.history().minutes().front().startUtcMicros, kT0 - 3600 * kSecond);
        QCOMPARE(page.history().minutes().front().goodFrames, quint64(10));
        // The frames read after the log's last time step count too: the
        // statistics that follow it are sampled at the log's time.
        s.framesReceived = 12;
        page.setStatistics(s);
        QCOMPARE(page.history().minutes().size(), std::size_t(1));
        QCOMPARE(page.history().minutes().front().goodFrames, quint64(12));
        page.setReplay(false);
        QCOMPARE(page.figure(QStringLiteral("state")), QStringLiteral("Connected"));
        // Nor are the log's minutes the next link's.
        QVERIFY(page.history().minutes().empty());
    }

    // Every item the console commands, of every unit but the header, has
    // its row: the commanded value as the command holds it, the reported one
    // as the aircraft says it, a lasting disagreement highlighted.
    void everyUnitSideBySide()
    {
        CommandState command;
        ReportedState reported(&command);
        OverviewPage page(&command, &reported);
        int rows = 0;
        int units = 0;
        command.message().forEachUnit([&](const Unit& unit) {
            if (unit.kind() == UnitKind::Header || unit.items().empty())
                return;
            ++units;
            for (const ItemValue& item : unit.items()) {
                const ItemInfo& info = itemInfo(item.id);
                if (!info.key)
                    rows += info.kind == ValueKind::Fields ? int(info.fields.size()) : 1;
            }
        });
        QCOMPARE(page.rowCount(), rows);
        QCOMPARE(int(page.findChildren<QGroupBox*>().size()), units);
        QVERIFY(page.findChild<QGroupBox*>(QStringLiteral("overview:Engine 1")));
        QVERIFY(page.findChild<QGroupBox*>(QStringLiteral("overview:Flaps")));

        const UnitRef engine2{UnitKind::Engine, 1};
        QVERIFY(command.setNumber(engine2, ItemId::eng_prop_pitch, 120));
        QCOMPARE(page.commandedText(engine2, ItemId::eng_prop_pitch),
                 ItemText::value(ItemId::eng_prop_pitch, Value::of(120)));
        const UnitRef settings{UnitKind::Settings, 0};
        QCOMPARE(page.commandedText(settings, ItemId::land_wheels, 2),
                 ItemText::fieldValue(ItemId::land_wheels, 2, *command.value(settings, ItemId::land_wheels)));

        // The aircraft keeps reporting pitch 100: after three frames it is a lasting mismatch.
        Message status = command.message();
        (*status.repeated(UnitKind::Engine))[1].set(ItemId::eng_prop_pitch, Value::of(100));
        ReportedLabel* pitch = page.reportedLabel(engine2, ItemId::eng_prop_pitch);
        QVERIFY(pitch);
        for (int i = 0; i < 3; ++i)
            reported.onStatus(status);
        QCOMPARE(pitch->text(), ItemText::value(ItemId::eng_prop_pitch, Value::of(100)));
        QVERIFY(pitch->mismatch());
        QVERIFY(!page.reportedLabel({UnitKind::Engine, 0}, ItemId::eng_prop_pitch)->mismatch());

        // Another airframe: the cards follow it.
        const auto single = AirframeLoader::load(QStringLiteral(":/airframes/single-engine.json"));
        QVERIFY(single);
        QCOMPARE(single->engines.size(), std::size_t(1));
        command.setAirframe(*single);
        QVERIFY(page.findChild<QGroupBox*>(QStringLiteral("overview:Engine 1")));
        QVERIFY(!page.findChild<QGroupBox*>(QStringLiteral("overview:Engine 2")));
        QVERIFY(page.commandedText(engine2, ItemId::eng_prop_pitch).isEmpty());
    }

    // The cards flow into columns, as many as it takes to show them all
    // and as the width holds, never wider.
    void flowsIntoColumns()
    {
        CommandState command;
        ReportedState reported(&command);
        OverviewPage page(&command, &reported);
        page.resize(1300, 500);
        page.show();
        QVERIFY(QTest::qWaitForWindowExposed(&page));
        QVERIFY2(page.cardColumns() >= 3, qPrintable(QString::number(page.cardColumns())));
        page.resize(420, 700);
        QTRY_COMPARE(page.cardColumns(), 1);
        QCOMPARE(page.width(), 420);
        QVERIFY(page.minimumSizeHint().width() <= 420);
        auto* scroll = page.findChild<QScrollArea*>();
        QVERIFY(scroll);
        QVERIFY(!scroll->horizontalScrollBar()->isVisible());
    }

    // Issue 28: a compact grid of equal cards whose column count follows the
    // page's width alone: stale reports are marked by their look (the age in
    // the tool tip), so no card grows, no value leaves its card and the
    // columns do not switch. Every unit shows at the overview's size in a
    // 1366x768 window (tst_mainwindow fitsASmallScreen) without scrolling.
    void staleMarksStayInTheirCards()
    {
        CommandState command;
        auto now = std::chrono::steady_clock::time_point{} + std::chrono::hours(1);
        ReportedState reported(&command, nullptr, [&now] { return now; });
        OverviewPage page(&command, &reported);
        page.resize(1080, 440);
        page.show();
        QVERIFY(QTest::qWaitForWindowExposed(&page));
        QTRY_COMPARE(page.cardColumns(), 4);
        const auto cards = page.findChildren<QGroupBox*>();
        QCOMPARE(cards.size(), 12);
        auto* scroll = page.findChild<QScrollArea*>();
        QTRY_COMPARE(scroll->verticalScrollBar()->maximum(), 0);
        std::map<QString, QRect> before;
        for (QGroupBox* card : cards)
            before[card->objectName()] = card->geometry();
        // The column headings beside each card's name, in its first row.
        auto* engine1 = page.findChild<QGroupBox*>(QStringLiteral("overview:Engine 1"));
        QVERIFY(engine1);
        QCOMPARE(engine1->findChild<QLabel*>(QStringLiteral("title"))->text(), QStringLiteral("Engine 1"));
        QCOMPARE(engine1->findChild<QLabel*>(QStringLiteral("heading:Commanded"))->y(),
                 engine1->findChild<QLabel*>(QStringLiteral("title"))->y());

        reported.onStatus(command.message());
        now += std::chrono::seconds(125);
        reported.checkAge();
        const UnitRef radio{UnitKind::Radio, 0};
        ReportedLabel* frequency = page.reportedLabel(radio, ItemId::Rx_freq);
        QVERIFY(frequency);
        QVERIFY(frequency->stale());
        QCOMPARE(frequency->text(), ItemText::value(ItemId::Rx_freq, *command.value(radio, ItemId::Rx_freq)));
        QCOMPARE(frequency->toolTip(), QStringLiteral("Receive frequency as the aircraft reported it 125 s ago; no "
                                                      "status frame since"));
        // The labels fit themselves to the stale look a pass of the event loop later, and their cards lay out again.
        const auto inside = [&] {
            for (QGroupBox* card : cards)
                for (ReportedLabel* label : card->findChildren<ReportedLabel*>())
                    if (!card->contentsRect().contains(label->geometry()))
                        return false;
            return true;
        };
        QTRY_VERIFY(inside());
        QCOMPARE(page.cardColumns(), 4);
        for (QGroupBox* card : cards) {
            QCOMPARE(card->geometry(), before[card->objectName()]);
            for (ReportedLabel* label : card->findChildren<ReportedLabel*>())
                QVERIFY2(card->contentsRect().contains(label->geometry()),
                         qPrintable(card->objectName() + QLatin1Char(' ') + label->objectName() +
                                    QStringLiteral(" %1,%2 %3x%4 in %5x%6")
                                        .arg(label->x())
                                        .arg(label->y())
                                        .arg(label->width())
                                        .arg(label->height())
                                        .arg(card->width())
                                        .arg(card->height())));
        }
        // The size alone decides: narrower, fewer columns, and back; taller,
        // the fewest columns in which every card shows (wider cards).
        page.resize(800, 440);
        QTRY_COMPARE(page.cardColumns(), 3);
        page.resize(1080, 440);
        QTRY_COMPARE(page.cardColumns(), 4);
        page.resize(1080, 900);
        QTRY_VERIFY(page.cardColumns() < 4);
        QTRY_COMPARE(scroll->verticalScrollBar()->maximum(), 0);
    }
};

QTEST_MAIN(TestOverview)
#include "tst_overview.moc"
