// The fleet view over an MQTT broker: FleetFeed reading every aircraft's
// station reports and statistics into one summary each, believing only
// what a trusted station signed; FleetModel
// telling a burst of updates once per pass of the event loop (one
// dataChanged(), one rowsInserted()), its cells exact against a fake clock,
// rows stale or offline as time passes; FleetView sorted by aircraft and
// asking to observe one on Enter or double-click; and the whole path through
// a real mosquitto, two consoles publishing for two aircraft.

#include "codec/secure/StationSigningKey.h"
#include "link/broker/BrokerSettings.h"
#include "link/broker/BrokerTopics.h"
#include "link/broker/BrokerTrust.h"
#include "link/broker/EnvelopeWriter.h"
#include "link/broker/FleetFeed.h"
#include "link/broker/MqttClient.h"
#include "link/clock/VirtualClock.h"
#include "ui/fleet/FleetModel.h"
#include "ui/fleet/FleetView.h"

#include "MosquittoProcess.h"

#include <QApplication>
#include <QBrush>
#include <QCheckBox>
#include <QHeaderView>
#include <QLabel>
#include <QSignalSpy>
#include <QSortFilterProxyModel>
#include <QTableView>
#include <QTest>
#include <QTimer>

#include <memory>

namespace {

// 2026-11-23T17:45:20.123Z
constexpr qint64 kT0 = 1'795'455'920'123'000;
constexpr qint64 kSecond = 1'000'000;

AircraftSummary aircraft(const QString& name, quint64 framesUp = 0)
{
    AircraftSummary s;
    s.aircraft = name;
    s.inControl = QStringLiteral("GB_1");
    s.backup = QStringLiteral("GB_2");
    s.link = LinkState::Connected;
    s.stations = 2;
    s.stationsOnline = 2;
    s.lastFrameUtcMicros = kT0;
    s.framesUp = framesUp;
    s.framesDown = framesUp;
    return s;
}

QString name(int i)
{
    return QStringLiteral("GB_%1").arg(i, 4, 10, QLatin1Char('0'));
}

QString cell(const QAbstractItemModel& model, int row, int column, int role = Qt::DisplayRole)
{
    return model.data(model.index(row, column), role).toString();
}

QStringList rowTexts(const QAbstractItemModel& model, int row)
{
    QStringList texts;
    for (int c = 0; c < model.columnCount(); ++c)
        texts << cell(model, row, c);
    return texts;
}

StationReport station(const QString& id, bool online, LinkState link, qint64 utcMicros, qint64 lastFrame,
                      const QString& destination = {}, const QString& backup = {})
{
    StationReport r;
    r.station = id;
    r.role = destination == id ? QStringLiteral("control") : QStringLiteral("backup");
    r.link = link;
    r.description = QStringLiteral("UDP 127.0.0.1:5600");
    r.online = online;
    r.utcMicros = utcMicros;
    r.lastFrameUtcMicros = lastFrame;
    r.destination = destination;
    r.backup = backup;
    return r;
}

// Each station's signing key and envelopes, made once a run.
std::shared_ptr<const rcm::secure::StationSigningKey> keyOf(const QString& station)
{
    static QHash<QString, std::shared_ptr<const rcm::secure::StationSigningKey>> keys;
    auto& key = keys[station];
    if (!key)
        key = std::make_shared<const rcm::secure::StationSigningKey>(rcm::secure::StationSigningKey::generate());
    return key;
}

EnvelopeWriter& writerOf(const QString& station)
{
    static QHash<QString, std::shared_ptr<EnvelopeWriter>> writers;
    auto& writer = writers[station];
    if (!writer)
        writer = std::make_shared<EnvelopeWriter>(station, keyOf(station));
    return *writer;
}

std::shared_ptr<const BrokerTrust> trusting(const QStringList& stations)
{
    auto trust = std::make_shared<BrokerTrust>();
    for (const QString& station : stations)
        trust->trustStation(station, keyOf(station)->publicKey());
    return trust;
}

// `body` as the station named by `topic` publishes it there: signed.
QByteArray signedOn(const QString& topic, const QByteArray& body)
{
    return writerOf(BrokerTopics::parseTopic(topic)->station).wrap(topic, body);
}

}  // namespace

class TestFleet : public QObject {
    Q_OBJECT

private slots:
    void initTestCase()
    {
        QLocale::setDefault(QLocale(QLocale::English, QLocale::UnitedStates));
        qRegisterMetaType<AircraftSummary>();
        qRegisterMetaType<StatsReport>();
    }

    // A thousand updates of a hundred aircraft in one pass are one insert of
    // a hundred rows, and nothing else; the next pass's updates of rows
    // already shown and of new aircraft are one dataChanged() over the rows
    // changed and one insert after them.
    void modelBatchesOnePass()
    {
        FleetModel model;
        qint64 now = kT0;
        model.setClock([&now] { return now; });
        QSignalSpy inserted(&model, &QAbstractItemModel::rowsInserted);
        QSignalSpy changed(&model, &QAbstractItemModel::dataChanged);
        for (int round = 0; round < 10; ++round)
            for (int i = 0; i < 100; ++i)
                model.update(aircraft(name(i), quint64(round)));
        QCOMPARE(model.rowCount(), 0);  // told in the next pass, not before
        QCOMPARE(model.pendingUpdates(), 1000);
        QCOMPARE(model.rowOf(name(0)), -1);
        QTRY_COMPARE(inserted.count(), 1);
        QCOMPARE(inserted[0][1].toInt(), 0);
        QCOMPARE(inserted[0][2].toInt(), 99);
        QCOMPARE(changed.count(), 0);
        QCOMPARE(model.rowCount(), 100);
        QCOMPARE(model.pendingUpdates(), 0);
        for (int i = 0; i < 100; ++i) {
            QCOMPARE(model.rowOf(name(i)), i);
            QCOMPARE(model.summary(i), aircraft(name(i), 9));
        }

        inserted.clear();
        for (int i = 10; i <= 20; ++i)
            model.update(aircraft(name(i), 100));
        for (int i = 100; i < 105; ++i)
            model.update(aircraft(name(i), 1));
        model.update(aircraft(name(50), 100));
        model.update(aircraft(name(102), 2));
        QCOMPARE(model.rowCount(), 100);
        QTRY_COMPARE(inserted.count(), 1);
        QCOMPARE(inserted[0][1].toInt(), 100);
        QCOMPARE(inserted[0][2].toInt(), 104);
        QCOMPARE(changed.count(), 1);
        // Rows 10 to 50, from the link column: no row's state changed, and a
        // row's aircraft never does.
        QCOMPARE(changed[0][0].toModelIndex(), model.index(10, FleetModel::LinkColumn));
        QCOMPARE(changed[0][1].toModelIndex(), model.index(50, FleetModel::FramesColumn));
        QCOMPARE(cell(model, 15, FleetModel::FramesColumn), QStringLiteral("100 up, 100 down"));
        QCOMPARE(cell(model, 102, FleetModel::FramesColumn), QStringLiteral("2 up, 2 down"));
        QCOMPARE(cell(model, 104, FleetModel::FramesColumn), QStringLiteral("1 up, 1 down"));

        // An aircraft whose stations went offline: its whole row, aircraft
        // column included (its colours changed).
        inserted.clear();
        changed.clear();
        AircraftSummary gone = aircraft(name(30), 100);
        gone.stationsOnline = 0;
        gone.link = LinkState::Closed;
        model.update(gone);
        model.update(aircraft(name(31), 101));
        QTRY_COMPARE(changed.count(), 1);
        QCOMPARE(changed[0][0].toModelIndex(), model.index(30, FleetModel::AircraftColumn));
        QCOMPARE(changed[0][1].toModelIndex(), model.index(31, FleetModel::FramesColumn));
        QCOMPARE(inserted.count(), 0);
        QCOMPARE(model.rowsIn(FleetModel::RowState::Offline), 1);
        QCOMPARE(model.rowsIn(FleetModel::RowState::Live), 104);
    }

    // flushPending() tells at once what the pass would have told.
    void modelFlushesOnDemand()
    {
        FleetModel model;
        QSignalSpy inserted(&model, &QAbstractItemModel::rowsInserted);
        model.update(aircraft(QStringLiteral("GB_133")));
        model.flushPending();
        QCOMPARE(inserted.count(), 1);
        QCOMPARE(model.rowCount(), 1);
        QCoreApplication::processEvents();  // the queued flush finds nothing left
        QCOMPARE(inserted.count(), 1);
    }

    void modelCellTexts()
    {
        FleetModel model;
        qint64 now = kT0 + 12 * kSecond + 999'999;
        model.setClock([&now] { return now; });
        QCOMPARE(model.columnCount(), FleetModel::kColumnCount);
        QStringList headers;
        for (int c = 0; c < model.columnCount(); ++c)
            headers << model.headerData(c, Qt::Horizontal).toString();
        QCOMPARE(headers,
                 (QStringList{"Aircraft", "Link", "In control", "Backup", "Stations", "Last frame", "Frames"}));

        AircraftSummary a = aircraft(QStringLiteral("GB_133"), 41);
        a.framesDown = 39;
        a.stations = 3;
        AircraftSummary b;
        b.aircraft = QStringLiteral("unknown");
        b.link = LinkState::Waiting;
        b.stations = 1;
        b.stationsOnline = 1;
        model.update(a);
        model.update(b);
        model.flushPending();
        QCOMPARE(rowTexts(model, 0),
                 (QStringList{"GB_133", "Connected", "GB_1", "GB_2", "2 of 3 online", "12 s", "41 up, 39 down"}));
        QCOMPARE(rowTexts(model, 1),
                 (QStringList{"unknown", "Waiting", "\u2014", "\u2014", "1 of 1 online", "\u2014", "0 up, 0 down"}));
        QCOMPARE(cell(model, 0, FleetModel::LastFrameColumn, Qt::ToolTipRole),
                 QStringLiteral("2026-11-23 17:45:20.123 UTC"));
        QCOMPARE(cell(model, 1, FleetModel::InControlColumn, FleetModel::AircraftRole), QStringLiteral("unknown"));
        QCOMPARE(model.data(model.index(0, FleetModel::LastFrameColumn), FleetModel::SortRole).toLongLong(),
                 12 * kSecond + 999'999);

        // The age is computed when asked, against the clock.
        const std::pair<qint64, QString> ages[] = {
            {0, "0 s"},
            {-3 * kSecond, "0 s"},  // a publisher's clock ahead of ours
            {59 * kSecond + 999'999, "59 s"},
            {60 * kSecond, "1 min 00 s"},
            {65 * kSecond, "1 min 05 s"},
            {3599 * kSecond, "59 min 59 s"},
            {(2 * 3600 + 14 * 60 + 59) * kSecond, "2 h 14 min"},
            {(27 * 3600 + 5 * 60) * kSecond, "27 h 05 min"},
        };
        for (const auto& [age, text] : ages) {
            now = kT0 + age;
            QCOMPARE(cell(model, 0, FleetModel::LastFrameColumn), text);
            QCOMPARE(FleetModel::ageText(age), text);
        }
        QCOMPARE(FleetModel::linkText(LinkState::Closed), QStringLiteral("Not connected"));
        QCOMPARE(FleetModel::linkText(LinkState::Lost), QStringLiteral("Lost"));
    }

    // A row is stale once the aircraft has not been heard for the stale
    // limit (and before it ever was), offline when no station is online;
    // refreshAges() tells the ages and the rows whose state time changed.
    void modelStaleAndOffline()
    {
        FleetModel model;
        qint64 now = kT0 + 4 * kSecond;
        model.setClock([&now] { return now; });
        QCOMPARE(model.staleLimitMicros(), 5 * kSecond);
        AircraftSummary live = aircraft(QStringLiteral("GB_1"));
        AircraftSummary older = aircraft(QStringLiteral("GB_2"));
        older.lastFrameUtcMicros = kT0 - 500'000;
        AircraftSummary never = aircraft(QStringLiteral("GB_3"));
        never.lastFrameUtcMicros = 0;
        AircraftSummary offline = aircraft(QStringLiteral("GB_4"));
        offline.stationsOnline = 0;
        offline.link = LinkState::Closed;
        AircraftSummary later = aircraft(QStringLiteral("GB_5"));
        later.lastFrameUtcMicros = kT0 + 3 * kSecond;
        for (const AircraftSummary& s : {live, older, never, offline, later})
            model.update(s);
        model.flushPending();
        using S = FleetModel::RowState;
        const auto states = [&] {
            QList<S> list;
            for (int r = 0; r < model.rowCount(); ++r) {
                list << model.rowState(r);
                if (model.data(model.index(r, FleetModel::FramesColumn), FleetModel::StateRole).toInt() !=
                    int(list.last()))
                    return QList<S>{};
            }
            return list;
        };
        QCOMPARE(states(), (QList<S>{S::Live, S::Live, S::Stale, S::Offline, S::Live}));
        QCOMPARE(model.rowsIn(S::Live), 3);
        QCOMPARE(model.rowsIn(S::Stale), 1);
        QCOMPARE(model.rowsIn(S::Offline), 1);

        // Colours of the whole row: amber for stale, grey for offline, none live.
        QCOMPARE(model.data(model.index(2, FleetModel::AircraftColumn), Qt::BackgroundRole).value<QBrush>().color(),
                 QColor(0xff, 0xe5, 0x99));
        QCOMPARE(model.data(model.index(2, FleetModel::LinkColumn), Qt::ForegroundRole).value<QBrush>().color(),
                 QColor(0x3d, 0x2b, 0x00));
        QCOMPARE(model.data(model.index(3, FleetModel::FramesColumn), Qt::BackgroundRole).value<QBrush>().color(),
                 QColor(0xdc, 0xdc, 0xdc));
        QCOMPARE(model.data(model.index(3, FleetModel::FramesColumn), Qt::ForegroundRole).value<QBrush>().color(),
                 QColor(0x3a, 0x3a, 0x3a));
        QVERIFY(!model.data(model.index(0, FleetModel::AircraftColumn), Qt::BackgroundRole).isValid());
        QCOMPARE(cell(model, 2, FleetModel::AircraftColumn, Qt::ToolTipRole),
                 QStringLiteral("GB_3 has not been heard for 5 s or more"));
        QCOMPARE(cell(model, 3, FleetModel::AircraftColumn, Qt::ToolTipRole),
                 QStringLiteral("No station publishing for GB_4 is online"));

        // 5 s exactly is not yet stale; a microsecond more is. GB_2 goes
        // stale then, GB_1 and GB_5 stay live: the age column of every row,
        // and GB_2's whole row, are told.
        QSignalSpy changed(&model, &QAbstractItemModel::dataChanged);
        now = kT0 + 4'500'000;
        model.refreshAges();
        QCOMPARE(changed.count(), 1);
        QCOMPARE(changed[0][0].toModelIndex(), model.index(0, FleetModel::LastFrameColumn));
        QCOMPARE(changed[0][1].toModelIndex(), model.index(4, FleetModel::LastFrameColumn));
        QCOMPARE(states(), (QList<S>{S::Live, S::Live, S::Stale, S::Offline, S::Live}));
        now = kT0 + 4'500'001;
        changed.clear();
        model.refreshAges();
        QCOMPARE(changed.count(), 2);
        QCOMPARE(changed[1][0].toModelIndex(), model.index(1, FleetModel::AircraftColumn));
        QCOMPARE(changed[1][1].toModelIndex(), model.index(1, FleetModel::FramesColumn));
        QCOMPARE(states(), (QList<S>{S::Live, S::Stale, S::Stale, S::Offline, S::Live}));
        QCOMPARE(cell(model, 1, FleetModel::LastFrameColumn), QStringLiteral("5 s"));

        // Past kT0 + 5 s GB_1 goes stale too; GB_5, heard at kT0 + 3 s, only
        // past kT0 + 8 s.
        now = kT0 + 5 * kSecond + 1;
        changed.clear();
        model.refreshAges();
        QCOMPARE(changed.count(), 2);
        QCOMPARE(changed[1][0].toModelIndex(), model.index(0, FleetModel::AircraftColumn));
        QCOMPARE(changed[1][1].toModelIndex(), model.index(0, FleetModel::FramesColumn));
        QCOMPARE(states(), (QList<S>{S::Stale, S::Stale, S::Stale, S::Offline, S::Live}));
        now = kT0 + 8 * kSecond + 1;
        changed.clear();
        model.refreshAges();
        QCOMPARE(changed.count(), 2);
        QCOMPARE(changed[1][0].toModelIndex(), model.index(4, FleetModel::AircraftColumn));
        QCOMPARE(states(), (QList<S>{S::Stale, S::Stale, S::Stale, S::Offline, S::Stale}));
        QCOMPARE(model.rowsIn(S::Stale), 4);
        QCOMPARE(model.rowsIn(S::Live), 0);

        // A longer limit makes the heard ones live again: rows 0 and 1 are
        // neighbours, one run; row 4 another.
        changed.clear();
        model.setStaleLimitMicros(60 * kSecond);
        QCOMPARE(changed.count(), 3);
        QCOMPARE(changed[1][0].toModelIndex(), model.index(0, FleetModel::AircraftColumn));
        QCOMPARE(changed[1][1].toModelIndex(), model.index(1, FleetModel::FramesColumn));
        QCOMPARE(changed[2][0].toModelIndex(), model.index(4, FleetModel::AircraftColumn));
        QCOMPARE(changed[2][1].toModelIndex(), model.index(4, FleetModel::FramesColumn));
        QCOMPARE(changed[2][2].value<QList<int>>(),
                 (QList<int>{Qt::ForegroundRole, Qt::BackgroundRole, Qt::ToolTipRole, FleetModel::StateRole}));
        QCOMPARE(states(), (QList<S>{S::Live, S::Live, S::Stale, S::Offline, S::Live}));
        QCOMPARE(model.rowsIn(S::Live), 3);

        // A frame heard again makes the row live at once.
        model.setStaleLimitMicros(5 * kSecond);
        AircraftSummary heard = older;
        heard.lastFrameUtcMicros = now - kSecond;
        heard.framesDown = 3;
        changed.clear();
        model.update(heard);
        QTRY_COMPARE(changed.count(), 1);
        QCOMPARE(changed[0][0].toModelIndex(), model.index(1, FleetModel::AircraftColumn));
        QCOMPARE(model.rowState(1), S::Live);
        QCOMPARE(cell(model, 1, FleetModel::LastFrameColumn), QStringLiteral("1 s"));
    }

    // What the feed makes of each kind of message, exactly; nothing of a
    // payload it cannot read but the refusal.
    void feedSummarises()
    {
        FleetFeed feed(nullptr);
        feed.setTrust(trusting({QStringLiteral("GB_1"), QStringLiteral("GB_2"), QStringLiteral("GB_9")}));
        QCOMPARE(FleetFeed::patterns(), (QStringList{"rcm/+/station/+", "rcm/+/stats/+"}));
        QSignalSpy updated(&feed, &FleetFeed::aircraftUpdated);
        QSignalSpy statsSeen(&feed, &FleetFeed::statsReported);
        QSignalSpy refused(&feed, &FleetFeed::payloadRefused);
        const QString a = QStringLiteral("GB_133");
        const QString b = QStringLiteral("GB_134");
        const auto say = [&feed](const QString& topic, const QByteArray& body) {
            feed.handleMessage(topic, signedOn(topic, body));
        };
        const auto stationAt = [](const QString& aircraft, const char* id) {
            return BrokerTopics::stationTopic(aircraft, QString::fromLatin1(id));
        };
        const auto statsAt = [](const QString& aircraft, const char* id) {
            return BrokerTopics::statsTopic(aircraft, QString::fromLatin1(id));
        };

        say(stationAt(a, "GB_1"), station(QStringLiteral("GB_1"), true, LinkState::Waiting, kT0, 0).toJson());
        QCOMPARE(updated.count(), 1);
        AircraftSummary expected;
        expected.aircraft = a;
        expected.link = LinkState::Waiting;
        expected.stations = 1;
        expected.stationsOnline = 1;
        QCOMPARE(updated.last()[0].value<AircraftSummary>(), expected);

        // The second station is connected and knows who is in control.
        say(stationAt(a, "GB_2"), station(QStringLiteral("GB_2"), true, LinkState::Connected, kT0 + kSecond,
                                          kT0 + 900'000, QStringLiteral("GB_2"), QStringLiteral("GB_1"))
                                      .toJson());
        expected.link = LinkState::Connected;
        expected.stations = 2;
        expected.stationsOnline = 2;
        expected.inControl = QStringLiteral("GB_2");
        expected.backup = QStringLiteral("GB_1");
        expected.lastFrameUtcMicros = kT0 + 900'000;
        QCOMPARE(updated.last()[0].value<AircraftSummary>(), expected);

        // Both stations' statistics: their frames add up, and the newest
        // last good frame of either is the aircraft's.
        StatsReport two;
        two.framesSent = 1;
        two.framesReceived = 1;
        two.lastGoodFrameUtcMicros = kT0 + 2 * kSecond + 300'000;
        two.state = LinkState::Connected;
        say(statsAt(a, "GB_2"), two.toJson());
        StatsReport one;
        one.framesReceived = 1;
        one.lastGoodFrameUtcMicros = kT0 + 500'000;
        one.state = LinkState::Waiting;
        say(statsAt(a, "GB_1"), one.toJson());
        QCOMPARE(statsSeen.count(), 2);
        QCOMPARE(statsSeen[0][0].toString(), a);
        QCOMPARE(statsSeen[0][1].value<StatsReport>(), two);
        expected.framesUp = 1;
        expected.framesDown = 2;
        expected.lastFrameUtcMicros = kT0 + 2 * kSecond + 300'000;
        QCOMPARE(updated.count(), 4);
        QCOMPARE(updated.last()[0].value<AircraftSummary>(), expected);

        // GB_2's newer statistics replace its older ones.
        StatsReport stats;
        stats.framesSent = 10;
        stats.framesReceived = 9;
        stats.lastGoodFrameUtcMicros = kT0 + 3 * kSecond;
        stats.state = LinkState::Connected;
        say(statsAt(a, "GB_2"), stats.toJson());
        expected.framesUp = 10;
        expected.framesDown = 10;
        expected.lastFrameUtcMicros = kT0 + 3 * kSecond;
        QCOMPARE(updated.last()[0].value<AircraftSummary>(), expected);

        // The station in control goes: its will says offline. The other one
        // still stands, waiting; who is in control is still what the
        // aircraft said last (only a gone station knew it).
        say(stationAt(a, "GB_2"), station(QStringLiteral("GB_2"), false, LinkState::Connected, kT0 + 4 * kSecond,
                                          kT0 + 900'000, QStringLiteral("GB_2"), QStringLiteral("GB_1"))
                                      .toJson());
        expected.link = LinkState::Waiting;
        expected.stationsOnline = 1;
        QCOMPARE(updated.last()[0].value<AircraftSummary>(), expected);
        // An online station's older word wins over a gone one's newer word.
        say(stationAt(a, "GB_1"), station(QStringLiteral("GB_1"), true, LinkState::Lost, kT0 + 3 * kSecond,
                                          kT0 + 500'000, QStringLiteral("GB_1"), QString())
                                      .toJson());
        expected.link = LinkState::Lost;
        expected.inControl = QStringLiteral("GB_1");
        expected.backup = QString();
        QCOMPARE(updated.last()[0].value<AircraftSummary>(), expected);

        // A retained report cleared: nobody can sign that, so a verified
        // station stays (until a signed report replaces it, or it expires).
        const int before = int(updated.count());
        feed.handleMessage(stationAt(a, "GB_2"), QByteArray());
        QCOMPARE(updated.count(), before);

        // Another aircraft, statistics only.
        StatsReport nine;
        nine.framesSent = 1;
        say(statsAt(b, "GB_9"), nine.toJson());
        AircraftSummary other;
        other.aircraft = b;
        other.framesUp = 1;
        QCOMPARE(updated.last()[0].value<AircraftSummary>(), other);
        QCOMPARE(feed.aircraftCount(), 2);
        QCOMPARE(feed.summaries(), (QList<AircraftSummary>{expected, other}));
        QCOMPARE(feed.summary(a), std::optional<AircraftSummary>(expected));
        QCOMPARE(feed.summary(QStringLiteral("GB_999")), std::nullopt);

        // Refused: not JSON, a report published bare, a wrong field, a
        // topic outside the schema; what is not subscribed to (frames,
        // state, events) is ignored without a word.
        QCOMPARE(refused.count(), 0);
        const int updates = int(updated.count());
        const QString statsA = statsAt(a, "GB_1");
        feed.handleMessage(statsA, QByteArray("{not json"));
        const QByteArray bare = one.toJson();
        feed.handleMessage(statsA, bare);
        QByteArray sideways = bare;
        sideways.replace("\"waiting\"", "\"sideways\"");
        say(statsA, sideways);
        feed.handleMessage(QStringLiteral("other/GB_133/stats/GB_1"), QByteArray("{}"));
        say(BrokerTopics::stateTopic(a, QStringLiteral("GB_1")), QByteArray("{}"));
        say(BrokerTopics::framesTopic(a, QStringLiteral("GB_1")), QByteArray("{}"));
        QCOMPARE(refused.count(), 4);
        QCOMPARE(feed.refusedPayloads(), 4u);
        QVERIFY2(
            refused[0][1].toString().startsWith(QStringLiteral("malformed: rcm/GB_133/stats/GB_1: envelope: not JSON")),
            qPrintable(refused[0][1].toString()));
        QCOMPARE(refused[1][1].toString(),
                 QStringLiteral("malformed: rcm/GB_133/stats/GB_1: envelope: v is missing: not an envelope (a "
                                "report published bare is refused)"));
        QCOMPARE(refused[2][1].toString(),
                 QStringLiteral("unreadable: GB_1's statistics: stats: state must be \"closed\", \"waiting\", "
                                "\"connected\" or \"lost\", not \"sideways\""));
        QCOMPARE(refused[3][0].toString(), QStringLiteral("other/GB_133/stats/GB_1"));
        QCOMPARE(refused[3][1].toString(),
                 QStringLiteral("malformed: other/GB_133/stats/GB_1 is not a topic of the rcm schema"));
        QCOMPARE(updated.count(), updates);
        QCOMPARE(statsSeen.count(), 4);
    }

    // What nobody trusted vouches for: forged, replayed, unsigned in a
    // trusted station's name, or merely unverified. Forged and replayed
    // messages change nothing and are counted; an unverified station is
    // counted, never in control, its aircraft unverified.
    void feedBelievesOnlyTrustedKeys()
    {
        FleetFeed feed(nullptr);
        feed.setTrust(trusting({QStringLiteral("GB_1")}));
        QSignalSpy updated(&feed, &FleetFeed::aircraftUpdated);
        QSignalSpy refused(&feed, &FleetFeed::messageRefused);
        const QString a = QStringLiteral("GB_133");
        const QString topic = BrokerTopics::stationTopic(a, QStringLiteral("GB_1"));
        const QByteArray genuine = signedOn(
            topic,
            station(QStringLiteral("GB_1"), true, LinkState::Connected, kT0, kT0, QStringLiteral("GB_1")).toJson());
        feed.handleMessage(topic, genuine);
        QCOMPARE(feed.summary(a)->inControl, QStringLiteral("GB_1"));
        QVERIFY(feed.summary(a)->verified());

        // Someone else's key, in GB_1's name: forged.
        EnvelopeWriter impostor(QStringLiteral("GB_1"), std::make_shared<const rcm::secure::StationSigningKey>(
                                                            rcm::secure::StationSigningKey::generate()));
        const QByteArray body =
            station(QStringLiteral("GB_1"), true, LinkState::Connected, kT0, kT0, QStringLiteral("GB_666")).toJson();
        feed.handleMessage(topic, impostor.wrap(topic, body));
        // No signature at all, in GB_1's name: refused too.
        feed.handleMessage(topic, EnvelopeWriter(QStringLiteral("GB_1")).wrap(topic, body));
        // A genuine message moved to another topic: its signature names the first.
        const QString otherTopic = BrokerTopics::stationTopic(QStringLiteral("GB_134"), QStringLiteral("GB_1"));
        feed.handleMessage(otherTopic, genuine);
        // The genuine one again: a duplicate (a retained message sent anew),
        // dropped; an older genuine one after a newer: replayed.
        feed.handleMessage(topic, genuine);
        const QByteArray newer = signedOn(
            topic, station(QStringLiteral("GB_1"), true, LinkState::Lost, kT0 + kSecond, kT0, QStringLiteral("GB_1"))
                       .toJson());
        feed.handleMessage(topic, newer);
        feed.handleMessage(topic, genuine);
        QCOMPARE(refused.count(), 4);
        QStringList reasons;
        for (const QList<QVariant>& r : refused)
            reasons << r[0].toString().section(QStringLiteral(": "), 0, 0);
        QCOMPARE(reasons, (QStringList{"forged", "unsigned", "forged", "replayed"}));
        QCOMPARE(refused[0][0].toString(),
                 QStringLiteral("forged: GB_1's signature does not verify on rcm/GB_133/station/GB_1"));
        QCOMPARE(feed.summary(a)->inControl, QStringLiteral("GB_1"));
        QCOMPARE(feed.summary(a)->link, LinkState::Lost);
        QCOMPARE(feed.aircraftCount(), 1);

        // A station nobody here trusts, signed or not: unverified, counted,
        // its word on who is in control not taken.
        const QString gb7 = BrokerTopics::stationTopic(a, QStringLiteral("GB_7"));
        feed.handleMessage(gb7, signedOn(gb7, station(QStringLiteral("GB_7"), true, LinkState::Connected,
                                                      kT0 + 2 * kSecond, kT0, QStringLiteral("GB_7"))
                                                  .toJson()));
        QCOMPARE(feed.summary(a)->unverifiedStations, 1);
        QCOMPARE(feed.summary(a)->stations, 1);
        QCOMPARE(feed.summary(a)->inControl, QStringLiteral("GB_1"));
        // 3,000 aircraft reported by nobody trusted: all unverified.
        for (int i = 0; i < 3000; ++i) {
            const QString t = BrokerTopics::stationTopic(name(i), QStringLiteral("AD_1"));
            feed.handleMessage(t, EnvelopeWriter(QStringLiteral("AD_1"))
                                      .wrap(t, station(QStringLiteral("AD_1"), true, LinkState::Connected, kT0, kT0,
                                                       QStringLiteral("AD_1"))
                                                   .toJson()));
        }
        QCOMPARE(feed.aircraftCount(), 3001);
        const AircraftSummary fake = *feed.summary(name(7));
        QVERIFY(!fake.verified());
        QCOMPARE(fake.inControl, QString());
        QCOMPARE(fake.unverifiedStations, 1);
        QCOMPARE(refused.count(), 4);
        // An empty retained message removes an unverified station.
        feed.handleMessage(gb7, QByteArray());
        QCOMPARE(feed.summary(a)->unverifiedStations, 0);
    }

    // An aircraft not heard of for the time to live goes, by the feed's
    // clock and on its own cadence; this console's own aircraft stays, and
    // while the broker is unreachable nothing expires and only this
    // console's link is known.
    void feedExpiresAndKnowsItsOwnLink()
    {
        const auto clock = std::make_shared<VirtualClock>(kT0);
        FleetFeed feed(nullptr, nullptr, clock);
        feed.setTrust(trusting({QStringLiteral("GB_1"), QStringLiteral("GB_2")}));
        QSignalSpy removed(&feed, &FleetFeed::aircraftRemoved);
        QSignalSpy updated(&feed, &FleetFeed::aircraftUpdated);
        const QString a = QStringLiteral("GB_133");
        const QString b = QStringLiteral("GB_134");
        const QString other = BrokerTopics::stationTopic(b, QStringLiteral("GB_2"));
        feed.handleMessage(other, signedOn(other, station(QStringLiteral("GB_2"), true, LinkState::Connected, kT0, kT0,
                                                          QStringLiteral("GB_2"))
                                                      .toJson()));
        // This console flies GB_133 as GB_1, and publishes it: its own report
        // comes back from the broker too, and counts once.
        StationReport mine =
            station(QStringLiteral("GB_1"), true, LinkState::Connected, kT0, kT0, QStringLiteral("GB_1"));
        feed.setLocalStation(a, mine);
        const QString mineTopic = BrokerTopics::stationTopic(a, QStringLiteral("GB_1"));
        feed.handleMessage(mineTopic, signedOn(mineTopic, mine.toJson()));
        QCOMPARE(feed.summary(a)->stations, 1);
        QVERIFY(feed.summary(a)->local);
        // Silent for just the time to live, every expiry on the way run: still known.
        clock->advance(std::chrono::microseconds(FleetFeed::kTimeToLiveMicros));
        feed.expireStale();
        QCOMPARE(removed.count(), 0);

        // The broker dies: the other aircraft is not known now, ours is.
        feed.setBrokerReachable(false);
        const AircraftSummary ours = *feed.summary(a);
        QCOMPARE(ours.link, LinkState::Connected);
        QCOMPARE(ours.stationsOnline, 1);
        QCOMPARE(ours.brokerReachable, false);
        QCOMPARE(FleetModel::linkCellText(ours), QStringLiteral("Connected (this console)"));
        const AircraftSummary theirs = *feed.summary(b);
        QCOMPARE(theirs.stationsOnline, 0);
        QCOMPARE(FleetModel::linkCellText(theirs), QStringLiteral("Unknown: broker unreachable"));
        QCOMPARE(theirs.inControl, QStringLiteral("GB_2"));
        // Past the time to live while unreachable: nothing goes.
        clock->advance(std::chrono::microseconds(1));
        feed.expireStale();
        QCOMPARE(removed.count(), 0);

        // Back, and still silent: gone after the time to live; ours stays.
        feed.setBrokerReachable(true);
        feed.expireStale();
        QCOMPARE(removed.count(), 1);
        QCOMPARE(removed[0][0].toString(), b);
        QCOMPARE(feed.aircraftCount(), 1);
        clock->advance(std::chrono::microseconds(10 * FleetFeed::kTimeToLiveMicros));
        QCOMPARE(removed.count(), 1);
        // Gone from the model too.
        FleetModel model;
        connect(&feed, &FleetFeed::aircraftUpdated, &model, &FleetModel::update);
        connect(&feed, &FleetFeed::aircraftRemoved, &model, &FleetModel::remove);
        feed.handleMessage(other, signedOn(other, station(QStringLiteral("GB_2"), true, LinkState::Connected, kT0, kT0,
                                                          QStringLiteral("GB_2"))
                                                      .toJson()));
        feed.setLocalStation(a, mine);
        QTRY_COMPARE(model.rowCount(), 2);
        QSignalSpy rowsRemoved(&model, &QAbstractItemModel::rowsRemoved);
        clock->advance(std::chrono::microseconds(FleetFeed::kTimeToLiveMicros + 1));
        feed.expireStale();
        QCOMPARE(rowsRemoved.count(), 1);
        QCOMPARE(model.rowCount(), 1);
        QCOMPARE(model.rowOf(a), 0);
        QCOMPARE(model.rowOf(b), -1);
        QCOMPARE(model.rowsIn(FleetModel::RowState::Live) + model.rowsIn(FleetModel::RowState::Stale), 1);
    }

    void viewSortsAndAsksToObserve()
    {
        FleetModel model;
        qint64 now = kT0 + kSecond;
        model.setClock([&now] { return now; });
        FleetView view(&model);
        view.resize(900, 300);
        view.setBroker(QStringLiteral("mqtt://127.0.0.1:1883"));
        QCOMPARE(view.summaryText(), QStringLiteral("Broker mqtt://127.0.0.1:1883, not connected: 0 aircraft"));
        view.setBrokerConnected(true);
        AircraftSummary gone = aircraft(QStringLiteral("GB_150"));
        gone.stationsOnline = 0;
        for (const AircraftSummary& s : {aircraft(QStringLiteral("GB_200")), gone, aircraft(QStringLiteral("GB_100"))})
            model.update(s);
        view.show();
        QVERIFY(QTest::qWaitForWindowExposed(&view));
        // The rows as the table shows them: sorted, and filtered.
        const QAbstractItemModel* sorted = view.table()->model();
        QTRY_COMPARE(sorted->rowCount(), 3);
        QStringList order;
        for (int r = 0; r < 3; ++r)
            order << cell(*sorted, r, FleetModel::AircraftColumn);
        QCOMPARE(order, (QStringList{"GB_100", "GB_150", "GB_200"}));
        QCOMPARE(view.summaryText(), QStringLiteral("Broker mqtt://127.0.0.1:1883, connected: 3 aircraft, 1 offline"));
        QCOMPARE(view.findChild<QLabel*>()->text(), view.summaryText());
        QVERIFY(view.ageTimer().isActive());
        QCOMPARE(view.ageTimer().interval(), 1000);

        // An update does not move rows sorted by aircraft; a new one lands in its place.
        model.update(aircraft(QStringLiteral("GB_200"), 5));
        model.update(aircraft(QStringLiteral("GB_120")));
        QTRY_COMPARE(sorted->rowCount(), 4);
        order.clear();
        for (int r = 0; r < 4; ++r)
            order << cell(*sorted, r, FleetModel::AircraftColumn);
        QCOMPARE(order, (QStringList{"GB_100", "GB_120", "GB_150", "GB_200"}));
        QCOMPARE(cell(*sorted, 3, FleetModel::FramesColumn), QStringLiteral("5 up, 5 down"));

        // Ages move on with the timer; GB_100, GB_120, GB_200 go stale.
        now = kT0 + 6 * kSecond;
        QTRY_COMPARE(view.summaryText(),
                     QStringLiteral("Broker mqtt://127.0.0.1:1883, connected: 4 aircraft, 3 stale, 1 offline"));
        QCOMPARE(cell(*sorted, 0, FleetModel::LastFrameColumn), QStringLiteral("6 s"));

        QSignalSpy observe(&view, &FleetView::observeRequested);
        QTableView* table = view.table();
        table->setFocus();
        table->setCurrentIndex(sorted->index(2, FleetModel::LinkColumn));
        QTest::keyClick(table, Qt::Key_Return);
        QCOMPARE(observe.count(), 1);
        QCOMPARE(observe[0][0].toString(), QStringLiteral("GB_150"));
        const QRect cellRect = table->visualRect(sorted->index(1, FleetModel::FramesColumn));
        // As a window system delivers a double-click to a widget: press,
        // release, press, double-click, release.
        QTest::mouseClick(table->viewport(), Qt::LeftButton, {}, cellRect.center());
        QTest::mousePress(table->viewport(), Qt::LeftButton, {}, cellRect.center());
        QTest::mouseDClick(table->viewport(), Qt::LeftButton, {}, cellRect.center());
        QTest::mouseRelease(table->viewport(), Qt::LeftButton, {}, cellRect.center());
        QCOMPARE(observe.count(), 2);
        QCOMPARE(observe[1][0].toString(), QStringLiteral("GB_120"));

        // An aircraft nobody trusted reports: hidden, counted; shown when asked.
        AircraftSummary fake;
        fake.aircraft = QStringLiteral("GB_110");
        fake.unverifiedStations = 1;
        model.update(fake);
        QTRY_COMPARE(model.rowCount(), 5);
        QCOMPARE(sorted->rowCount(), 4);
        QCOMPARE(view.summaryText(), QStringLiteral("Broker mqtt://127.0.0.1:1883, connected: 4 aircraft, 3 stale, "
                                                    "1 offline; 1 unverified hidden"));
        view.showUnverified()->setChecked(true);
        QCOMPARE(sorted->rowCount(), 5);
        QCOMPARE(cell(*sorted, 0, FleetModel::AircraftColumn), QStringLiteral("GB_100"));
        QCOMPARE(rowTexts(*sorted, 1), (QStringList{"GB_110", "Unverified", "\u2014", "\u2014",
                                                           "0 of 0 online, 1 unverified", "\u2014", "0 up, 0 down"}));
        QCOMPARE(sorted
                     ->data(sorted->index(1, FleetModel::LinkColumn), Qt::BackgroundRole)
                     .value<QBrush>()
                     .color(),
                 QColor(0xf8, 0xd7, 0xd7));
        view.showUnverified()->setChecked(false);
        QCOMPARE(sorted->rowCount(), 4);

        // The broker's state apart from any link's, with when it went.
        view.setBrokerConnected(false, kT0);
        view.setRefusedMessages(12);
        QCOMPARE(view.summaryText(), QStringLiteral("Broker mqtt://127.0.0.1:1883, unreachable since 17:45:20 UTC: "
                                                    "4 aircraft, 3 stale, 1 offline; 1 unverified hidden; "
                                                    "12 messages refused"));

        view.hide();
        QVERIFY(!view.ageTimer().isActive());
    }

    // Two consoles publish, each for its aircraft, through a real mosquitto;
    // a third client's FleetFeed fills the model with exactly what they said.
    void endToEndThroughMosquitto()
    {
        rcm::test::MosquittoProcess broker;
        QVERIFY2(broker.start(), qPrintable(broker.setupError()));
        QTRY_VERIFY(broker.accepts());
        const auto settings = [&] {
            BrokerSettings s;
            s.host = QStringLiteral("127.0.0.1");
            s.port = broker.port();
            return s;
        };
        MqttClient first(settings());
        MqttClient second(settings());
        MqttClient fleet(settings());
        QSignalSpy firstUp(&first, &MqttClient::connected);
        QSignalSpy secondUp(&second, &MqttClient::connected);
        QSignalSpy fleetUp(&fleet, &MqttClient::connected);
        first.start();
        second.start();
        QTRY_COMPARE(firstUp.count(), 1);
        QTRY_COMPARE(secondUp.count(), 1);

        const QString a = QStringLiteral("GB_133");
        const QString b = QStringLiteral("GB_134");
        const auto publish = [](MqttClient& client, const QString& topic, const QByteArray& body, bool retain) {
            return client.publish(topic, signedOn(topic, body), 1, retain);
        };
        // Retained before the fleet subscribes: it sees them at once.
        QVERIFY(publish(first, BrokerTopics::stationTopic(a, QStringLiteral("GB_1")),
                        station(QStringLiteral("GB_1"), true, LinkState::Connected, kT0, kT0 - kSecond,
                                QStringLiteral("GB_1"), QStringLiteral("GB_2"))
                            .toJson(),
                        true));
        QVERIFY(publish(second, BrokerTopics::stationTopic(b, QStringLiteral("GB_7")),
                        station(QStringLiteral("GB_7"), true, LinkState::Waiting, kT0, 0).toJson(), true));
        StatsReport stats;
        stats.framesSent = 1;
        stats.state = LinkState::Lost;
        stats.lastGoodFrameUtcMicros = kT0 - 5 * kSecond;
        QVERIFY(publish(second, BrokerTopics::statsTopic(b, QStringLiteral("GB_7")), stats.toJson(), true));

        FleetModel model;
        model.setClock([] { return kT0 + 2 * kSecond; });
        FleetFeed feed(&fleet);
        feed.setTrust(trusting({QStringLiteral("GB_1"), QStringLiteral("GB_7")}));
        connect(&feed, &FleetFeed::aircraftUpdated, &model, &FleetModel::update);
        QSignalSpy updated(&feed, &FleetFeed::aircraftUpdated);
        QSignalSpy refused(&feed, &FleetFeed::payloadRefused);
        fleet.start();
        QTRY_COMPARE(fleetUp.count(), 1);
        // The two station reports and the statistics, retained: the last
        // subscription (statistics) is through.
        QTRY_COMPARE(updated.count(), 3);
        QTRY_COMPARE(model.rowCount(), 2);

        // GB_1's link counts its frames, once a second.
        const QString statsA = BrokerTopics::statsTopic(a, QStringLiteral("GB_1"));
        for (int i = 1; i <= 3; ++i) {
            StatsReport counted;
            counted.framesSent = quint64(i);
            counted.framesReceived = quint64(i);
            counted.lastGoodFrameUtcMicros = kT0 + (i - 1) * kSecond + 400'000;
            counted.state = LinkState::Connected;
            QVERIFY(publish(first, statsA, counted.toJson(), true));
        }
        // A forger publishes statistics in GB_1's name, unsigned: refused.
        StatsReport forged;
        forged.framesSent = 999;
        QVERIFY(first.publish(statsA, EnvelopeWriter(QStringLiteral("GB_1")).wrap(statsA, forged.toJson()), 1, false));
        const auto rowOf = [&](const QString& aircraft) { return rowTexts(model, model.rowOf(aircraft)); };
        QTRY_COMPARE(rowOf(a),
                     (QStringList{"GB_133", "Connected", "GB_1", "GB_2", "1 of 1 online", "0 s", "3 up, 3 down"}));
        QTRY_COMPARE(rowOf(b),
                     (QStringList{"GB_134", "Waiting", "\u2014", "\u2014", "1 of 1 online", "7 s", "1 up, 0 down"}));
        QTRY_COMPARE(refused.count(), 1);
        AircraftSummary expectedA;
        expectedA.aircraft = a;
        expectedA.inControl = QStringLiteral("GB_1");
        expectedA.backup = QStringLiteral("GB_2");
        expectedA.link = LinkState::Connected;
        expectedA.stations = 1;
        expectedA.stationsOnline = 1;
        expectedA.lastFrameUtcMicros = kT0 + 2 * kSecond + 400'000;
        expectedA.framesUp = 3;
        expectedA.framesDown = 3;
        QCOMPARE(model.summary(model.rowOf(a)), expectedA);
        QCOMPARE(model.rowState(model.rowOf(a)), FleetModel::RowState::Live);
        QCOMPARE(model.rowState(model.rowOf(b)), FleetModel::RowState::Stale);

        QCOMPARE(refused[0][1].toString(),
                 QStringLiteral("unsigned: a message in the name of GB_1, whose key is trusted, on "
                                "rcm/GB_133/stats/GB_1"));

        // The second console says it is gone: its aircraft's row is offline.
        QVERIFY(publish(second, BrokerTopics::stationTopic(b, QStringLiteral("GB_7")),
                        station(QStringLiteral("GB_7"), false, LinkState::Closed, kT0 + kSecond, 0).toJson(), true));
        QTRY_COMPARE(model.rowState(model.rowOf(b)), FleetModel::RowState::Offline);
        QCOMPARE(rowOf(b),
                 (QStringList{"GB_134", "Not connected", "\u2014", "\u2014", "0 of 1 online", "7 s", "1 up, 0 down"}));
        QCOMPARE(refused.count(), 1);
        QCOMPARE(model.rowCount(), 2);

        // Goodbyes before the broker goes with the test.
        first.stop();
        second.stop();
        fleet.stop();
    }
};

QTEST_MAIN(TestFleet)
#include "tst_fleet.moc"
