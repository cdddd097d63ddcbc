// The console's frame log view at the size of a long session: 200,000 frames
// written with FrameLog and opened by the model; cell text and message IDs
// made only for the rows asked for; live appends inserted once per pass of
// the event loop; the direction and status filter counting exactly; and the
// rows of a real link session (UDP on loopback) matching its log file record
// for record, with no frame's bytes held in memory while the file has them.

#include "EventCounter.h"
#include "codec/message/Airframe.h"
#include "codec/message/MessageDecoder.h"
#include "codec/message/MessageEncoder.h"
#include "codec/receive/LoggedFrameReading.h"
#include "codec/secure/SecureCodec.h"
#include "link/framelog/FrameLog.h"
#include "link/framelog/FrameLogReader.h"
#include "link/session/LinkController.h"
#include "link/transport/UdpLink.h"
#include "ui/framelog/FrameLogDelegate.h"
#include "ui/framelog/FrameLogFilterModel.h"
#include "ui/framelog/FrameLogModel.h"
#include "ui/framelog/FrameLogView.h"
#include "ui/framelog/SteadyScrollBar.h"

#include <QApplication>
#include <QDateTime>
#include <QImage>
#include <QPainter>
#include <QStandardItemModel>
#include <QStyledItemDelegate>
#include <QScrollBar>
#include <QSignalSpy>
#include <QTableView>
#include <QTemporaryDir>
#include <QTest>
#include <QThreadPool>

#include <map>

using namespace std::chrono_literals;

namespace {

constexpr int kFrames = 200'000;
constexpr qint64 kT0 = 1795332720000000;  // 2026-11-22T07:32:00Z

// What frame i of the synthetic session is: every other frame one of ours,
// the aircraft's replies with a sprinkling of corrected, uncorrectable and
// rejected ones.
struct Kind {
    FrameDirection direction;
    FrameStatus status;
};

Kind kindOf(int i)
{
    if (i % 2 == 0)
        return {FrameDirection::Sent, FrameStatus::NotChecked};
    if (i % 50 == 3)
        return {FrameDirection::Received, FrameStatus::Uncorrectable};
    if (i % 100 == 7)
        return {FrameDirection::Received, FrameStatus::Rejected};
    if (i % 10 == 1)
        return {FrameDirection::Received, FrameStatus::Corrected};
    return {FrameDirection::Received, FrameStatus::Decoded};
}

// Frame i: a real datagram whose ID_msg is i, damaged as its status says,
// its time_UTC and date_UTC those of `stampUtcMicros` (0: of its row's time).
FrameRecord frame(int i, qint64 stampUtcMicros = 0)
{
    static const rcm::Message resting = rcm::restingCommand(rcm::Airframe::wellEquipped());
    rcm::Message m = resting;
    m.header.set(rcm::ItemId::ID_msg, i);
    const QDateTime stamp =
        QDateTime::fromMSecsSinceEpoch((stampUtcMicros ? stampUtcMicros : kT0 + qint64(i) * 500'000) / 1000, Qt::UTC);
    const QTime t = stamp.time();
    const QDate d = stamp.date();
    m.header.set(rcm::ItemId::time_UTC, std::int64_t(t.hour() * 10000 + t.minute() * 100 + t.second()));
    m.header.set(rcm::ItemId::date_UTC, std::int64_t((d.year() % 100) * 10000 + d.month() * 100 + d.day()));
    rcm::Diagnostics errors;
    const auto datagram = rcm::encodeDatagram(m, errors);
    Q_ASSERT(datagram);
    FrameRecord r;
    r.bytes = QByteArray(reinterpret_cast<const char*>(datagram->data()), qsizetype(datagram->size()));
    r.utcMicros = kT0 + qint64(i) * 500'000;
    r.transport = FrameTransport::Udp;
    const Kind kind = kindOf(i);
    r.direction = kind.direction;
    r.status = kind.status;
    switch (kind.status) {
        case FrameStatus::Corrected:
            r.bytes[10] = char(r.bytes[10] ^ 0x5A);
            r.bytes[300] = char(r.bytes[300] ^ 0x01);
            r.correctedSymbols = {1, 1};
            break;
        case FrameStatus::Uncorrectable:
            for (int k = 0; k < 40; ++k)
                r.bytes[k * 6] = char(r.bytes[k * 6] ^ 0xFF);
            r.correctedSymbols = {-1, 0};
            break;
        case FrameStatus::Decoded:
        case FrameStatus::Rejected:
            r.correctedSymbols = {0, 0};
            break;
        case FrameStatus::NotChecked:
            break;
    }
    return r;
}

// A session against a far end on loopback that answers with one frame of
// each kind the link logs differently: clean, corrected, beyond correction,
// and a datagram of the wrong size. Rows reach `model` from frameLogged();
// `sent` gets the datagrams the far end received, in order.
// When runSession() began: the live receive path refuses frames outside the
// window of its clock, so the far end's frames carry this time.
qint64 g_sessionStamp = 0;

void runSession(FrameLogModel& model, std::unique_ptr<FrameLog> log, QList<QByteArray>& sent)
{
    g_sessionStamp = QDateTime::currentMSecsSinceEpoch() * 1000;
    UdpLink far(QHostAddress::LocalHost, 0);
    far.setReplyToSender(true);
    far.open();
    QSignalSpy farReceived(&far, &Link::datagramReceived);
    LinkWorker::Options options;
    options.interval = 50ms;  // quick; nothing here depends on the pace
    options.statisticsInterval = 20ms;
    LinkController controller(
        std::make_unique<UdpLink>(QHostAddress::LocalHost, 0, QHostAddress::LocalHost, far.boundPort()), std::move(log),
        options);
    QObject::connect(&controller, &LinkController::frameLogged, &model, &FrameLogModel::appendLogged);
    QSignalSpy stopped(&controller, &LinkController::stopped);
    controller.setCommand(rcm::restingCommand(rcm::Airframe::wellEquipped()));
    controller.start();
    QTRY_VERIFY_WITH_TIMEOUT(farReceived.count() >= 1, 10000);
    for (int i : {5, 11, 3})  // decoded, corrected, uncorrectable: see kindOf()
        far.write(frame(i, g_sessionStamp).bytes);
    far.write(QByteArray(100, '\x55'));
    QTRY_VERIFY_WITH_TIMEOUT(controller.statistics().refusedFor(rcm::Refusal::WrongSize) == 1, 10000);
    controller.stop();
    // Every frameLogged() emitted before stopped() has arrived with it.
    QTRY_COMPARE_WITH_TIMEOUT(stopped.count(), 1, 10000);
    QTRY_COMPARE_WITH_TIMEOUT(quint64(farReceived.count()), controller.statistics().framesSent, 10000);
    for (const QList<QVariant>& arguments : farReceived)
        sent.append(arguments.at(0).toByteArray());
    model.flushPending();
}

}  // namespace

class TestFrameLogModel : public QObject {
    Q_OBJECT

private slots:
    void initTestCase();
    void opensTheWholeLog();
    void showsRowsPreparedElsewhere();
    void textIsMadeOnDemand();
    void appendsAreInsertedOncePerPass();
    void filterCountsByDirectionAndStatus();
    void filterFollowsAppends();
    void viewDecodesOnlyWhatItShows();
    void viewLaysOutALogAtOnce();
    void delegateDrawsTheModelsText();
    void scrollBarRepaintsWhenItsSliderMoves();
    void keyedRowsNeedTheKey();
    void liveRowsMatchTheSessionLog();
    void liveRowsWithoutALogKeepTheirBytes();

private:
    QTemporaryDir m_dir;
    QString m_path;
    std::map<std::pair<FrameDirection, FrameStatus>, int> m_counts;
};

void TestFrameLogModel::initTestCase()
{
    QVERIFY(m_dir.isValid());
    m_path = m_dir.filePath(QStringLiteral("day.pcapng"));
    FrameLog log;
    QString error;
    QVERIFY2(log.open(m_path, &error), qPrintable(error));
    for (int i = 0; i < kFrames; ++i) {
        const FrameRecord r = frame(i);
        QVERIFY(log.append(r));
        ++m_counts[{r.direction, r.status}];
    }
    log.close();
}

void TestFrameLogModel::opensTheWholeLog()
{
    FrameLogModel model;
    QSignalSpy reset(&model, &QAbstractItemModel::modelReset);
    QString error;
    QVERIFY2(model.openLog(m_path, &error), qPrintable(error));
    QCOMPARE(reset.count(), 1);
    QCOMPARE(model.rowCount(), kFrames);
    QCOMPARE(model.columnCount(), FrameLogModel::kColumnCount);
    QCOMPARE(model.logPath(), m_path);
    // Opening reads the index only.
    QCOMPARE(model.decodedRows(), 0);
    QCOMPARE(model.direction(0), FrameDirection::Sent);
    QCOMPARE(model.status(kFrames - 1), kindOf(kFrames - 1).status);
    QCOMPARE(model.utcMicros(kFrames - 1), kT0 + qint64(kFrames - 1) * 500'000);
}

// Rows built from an index in another thread are the rows showLog() would
// build; rows built from another index are not taken for this one's.
void TestFrameLogModel::showsRowsPreparedElsewhere()
{
    const auto indexed = [this] {
        auto reader = std::make_unique<FrameLogReader>();
        reader->open(m_path);
        return reader;
    };
    FrameLogModel built;
    built.showLog(indexed(), m_path);
    std::unique_ptr<FrameLogReader> reader = indexed();
    std::shared_ptr<FrameLogModel::PreparedRows> rows;
    QThreadPool::globalInstance()->start([&] { rows = FrameLogModel::prepareRows(*reader); });
    QVERIFY(QThreadPool::globalInstance()->waitForDone(10000));
    FrameLogModel prepared;
    prepared.showLog(std::move(reader), m_path, rows);
    QCOMPARE(prepared.rowCount(), kFrames);
    for (int row = 0; row < kFrames; ++row)
        for (int column = 0; column < FrameLogModel::kColumnCount; ++column)
            QCOMPARE(prepared.data(prepared.index(row, column)), built.data(built.index(row, column)));

    std::unique_ptr<FrameLogReader> other = indexed();
    const auto otherRows = FrameLogModel::prepareRows(*other);
    FrameLogModel mismatched;
    mismatched.showLog(indexed(), m_path, otherRows);  // built from `other`: built anew
    QCOMPARE(mismatched.rowCount(), kFrames);
    QCOMPARE(mismatched.data(mismatched.index(kFrames - 1, 1)), built.data(built.index(kFrames - 1, 1)));
}

void TestFrameLogModel::textIsMadeOnDemand()
{
    FrameLogModel model;
    QVERIFY(model.openLog(m_path));
    QCOMPARE(model.decodedRows(), 0);

    // A row far from anything displayed: its text and ID exist once asked for.
    constexpr int kRow = 150'005;  // received, decoded cleanly
    QCOMPARE(kindOf(kRow).status, FrameStatus::Decoded);
    const auto cell = [&](int row, int column) { return model.index(row, column).data().toString(); };
    QCOMPARE(cell(kRow, FrameLogModel::NumberColumn), QStringLiteral("150006"));
    QCOMPARE(cell(kRow, FrameLogModel::TimeColumn), QStringLiteral("04:22:02.500"));
    QCOMPARE(cell(kRow, FrameLogModel::DirectionColumn), QStringLiteral("\u2190 received"));
    QCOMPARE(cell(kRow, FrameLogModel::StatusColumn), QStringLiteral("decoded"));
    QCOMPARE(model.decodedRows(), 0);  // none of those needed the frame
    QCOMPARE(cell(kRow, FrameLogModel::MessageIdColumn), QStringLiteral("150005"));
    QCOMPARE(model.decodedRows(), 1);
    QCOMPARE(cell(kRow, FrameLogModel::CorrectedColumn), QStringLiteral("none"));
    QCOMPARE(model.decodedRows(), 1);  // cached: one read per row

    // The log's own record of corrections; IDs through repairable damage;
    // none beyond it.
    QCOMPARE(cell(11, FrameLogModel::CorrectedColumn), QStringLiteral("2"));
    QCOMPARE(model.index(11, FrameLogModel::CorrectedColumn).data(Qt::ToolTipRole).toString(),
             QStringLiteral("1 in the first codeword, 1 in the second"));
    QCOMPARE(model.messageId(11), std::optional<quint32>(11));
    QCOMPARE(cell(3, FrameLogModel::CorrectedColumn), QStringLiteral("beyond"));
    QCOMPARE(cell(3, FrameLogModel::MessageIdColumn), QStringLiteral("\u2014"));
    QCOMPARE(model.messageId(3), std::nullopt);
    QCOMPARE(cell(199'998, FrameLogModel::MessageIdColumn), QStringLiteral("199998"));
    QCOMPARE(cell(199'998, FrameLogModel::CorrectedColumn), QStringLiteral("\u2014"));  // our own send
    QCOMPARE(model.decodedRows(), 4);

    // The whole record comes back for the detail pane.
    const FrameRecord r = model.record(kRow);
    QCOMPARE(r, frame(kRow));
}

void TestFrameLogModel::appendsAreInsertedOncePerPass()
{
    FrameLogModel model;
    FrameLogFilterModel filter;
    filter.setSourceModel(&model);
    QSignalSpy inserted(&model, &QAbstractItemModel::rowsInserted);
    QSignalSpy filterInserted(&filter, &QAbstractItemModel::rowsInserted);

    for (int i = 0; i < 1000; ++i)
        model.appendRecord(frame(i));
    // Nothing yet: the burst is inserted when the event loop next runs.
    QCOMPARE(model.rowCount(), 0);
    QCOMPARE(model.pendingRows(), 1000);
    QCOMPARE(inserted.count(), 0);

    QTRY_COMPARE(model.rowCount(), 1000);
    QCOMPARE(inserted.count(), 1);
    QCOMPARE(inserted.at(0).at(1).toInt(), 0);
    QCOMPARE(inserted.at(0).at(2).toInt(), 999);
    QCOMPARE(filterInserted.count(), 1);
    QCOMPARE(filter.rowCount(), 1000);
    QCOMPARE(model.pendingRows(), 0);

    // A second burst lands after the first, again as one insertion.
    for (int i = 1000; i < 1500; ++i)
        model.appendRecord(frame(i), quint32(i));
    QTRY_COMPARE(model.rowCount(), 1500);
    QCOMPARE(inserted.count(), 2);
    QCOMPARE(inserted.at(1).at(1).toInt(), 1000);
    QCOMPARE(inserted.at(1).at(2).toInt(), 1499);
    QCOMPARE(model.messageId(1499), std::optional<quint32>(1499));
    QCOMPARE(model.record(1234), frame(1234));

    // A frame known only by what the link said of it has no bytes to show.
    FrameRecord summary;
    summary.direction = FrameDirection::Sent;
    summary.utcMicros = kT0;
    model.appendRecord(summary, 42);
    model.flushPending();
    QCOMPARE(model.rowCount(), 1501);
    QCOMPARE(model.index(1500, FrameLogModel::MessageIdColumn).data().toString(), QStringLiteral("42"));
    QVERIFY(model.record(1500).bytes.isEmpty());
}

void TestFrameLogModel::filterCountsByDirectionAndStatus()
{
    FrameLogModel model;
    QVERIFY(model.openLog(m_path));
    FrameLogFilterModel filter;
    filter.setSourceModel(&model);
    QCOMPARE(filter.rowCount(), kFrames);

    const auto count = [&](FrameDirection d, FrameStatus s) {
        const auto it = m_counts.find({d, s});
        return it == m_counts.end() ? 0 : it->second;
    };
    using F = FrameLogFilterModel;
    const FrameDirection R = FrameDirection::Received, S = FrameDirection::Sent;

    filter.setDirections(F::bit(S));
    QCOMPARE(filter.rowCount(), kFrames / 2);
    filter.setDirections(F::bit(R));
    QCOMPARE(filter.rowCount(), kFrames / 2);

    int received = 0;
    for (FrameStatus s : {FrameStatus::Decoded, FrameStatus::Corrected, FrameStatus::Uncorrectable,
                          FrameStatus::Rejected, FrameStatus::NotChecked}) {
        filter.setStatuses(F::bit(s));
        QCOMPARE(filter.rowCount(), count(R, s));
        received += filter.rowCount();
    }
    QCOMPARE(received, kFrames / 2);
    // The exact figures of this session, counted independently of the table above.
    QCOMPARE(count(R, FrameStatus::Uncorrectable), kFrames / 50);
    QCOMPARE(count(R, FrameStatus::Rejected), kFrames / 100);

    filter.setStatuses(F::bit(FrameStatus::Corrected) | F::bit(FrameStatus::Uncorrectable) |
                       F::bit(FrameStatus::Rejected));
    const int problems =
        count(R, FrameStatus::Corrected) + count(R, FrameStatus::Uncorrectable) + count(R, FrameStatus::Rejected);
    QCOMPARE(filter.rowCount(), problems);
    // Every row shown is one the filter asked for, and maps back to itself.
    for (int row : {0, problems / 2, problems - 1}) {
        const QModelIndex source = filter.mapToSource(filter.index(row, 0));
        QCOMPARE(model.direction(source.row()), R);
        QVERIFY(model.status(source.row()) != FrameStatus::Decoded);
        QCOMPARE(filter.mapFromSource(source).row(), row);
    }
    // A row filtered out maps nowhere.
    QVERIFY(!filter.mapFromSource(model.index(0, 0)).isValid());

    filter.setDirections(F::kAllDirections);
    filter.setStatuses(F::bit(FrameStatus::NotChecked));
    QCOMPARE(filter.rowCount(), count(S, FrameStatus::NotChecked));
    filter.setStatuses(F::kAllStatuses);
    QCOMPARE(filter.rowCount(), kFrames);
}

void TestFrameLogModel::filterFollowsAppends()
{
    FrameLogModel model;
    FrameLogFilterModel filter;
    filter.setSourceModel(&model);
    filter.setStatuses(FrameLogFilterModel::bit(FrameStatus::Uncorrectable));
    QSignalSpy inserted(&filter, &QAbstractItemModel::rowsInserted);
    int expected = 0;
    for (int i = 0; i < 500; ++i) {
        model.appendRecord(frame(i));
        expected += kindOf(i).status == FrameStatus::Uncorrectable;
    }
    QTRY_COMPARE(model.rowCount(), 500);
    QCOMPARE(filter.rowCount(), expected);
    QCOMPARE(inserted.count(), 1);
    QCOMPARE(filter.sourceRow(0), 3);

    // Everything chosen: each row is its source row, appends and changes included.
    filter.setStatuses(FrameLogFilterModel::kAllStatuses);
    QCOMPARE(filter.rowCount(), 500);
    inserted.clear();
    for (int i = 500; i < 510; ++i)
        model.appendRecord(frame(i));
    QTRY_COMPARE(filter.rowCount(), 510);
    QCOMPARE(inserted.count(), 1);
    QCOMPARE(inserted.at(0).at(1).toInt(), 500);
    QCOMPARE(inserted.at(0).at(2).toInt(), 509);
    QCOMPARE(filter.sourceRow(505), 505);
    QCOMPARE(filter.mapToSource(filter.index(505, 2)), model.index(505, 2));
    QCOMPARE(filter.mapFromSource(model.index(509, 1)), filter.index(509, 1));
    QCOMPARE(filter.rowAtOrAfter(600), 510);
    QSignalSpy changed(&filter, &QAbstractItemModel::dataChanged);
    model.setPlayedRows(0);
    model.setPlayedRows(7);
    QCOMPARE(changed.count(), 2);
    QCOMPARE(changed.at(1).at(0).toModelIndex().row(), 0);  // the old last played row is no longer bold
    QCOMPARE(changed.at(1).at(1).toModelIndex().row(), 7);
}

void TestFrameLogModel::viewDecodesOnlyWhatItShows()
{
    FrameLogModel model;
    QVERIFY(model.openLog(m_path));
    FrameLogView view(&model);
    view.resize(1000, 700);
    view.show();
    QVERIFY(QTest::qWaitForWindowExposed(&view));
    view.table()->scrollToBottom();
    QTRY_VERIFY(model.decodedRows() > 0);
    // A screenful, not the log.
    QVERIFY2(model.decodedRows() < 500, qPrintable(QString::number(model.decodedRows())));

    // Selecting a frame decodes it in full for the detail panes.
    view.showSourceRow(150'005);
    QVERIFY(view.detailText().contains(QStringLiteral("ID_msg 150005")));
    QVERIFY(view.detailText().contains(QStringLiteral("BEGIN HEADER")));
    QVERIFY(view.hexText().contains(QStringLiteral("BLOCK 1 data (223 bytes)")));
    QVERIFY(view.hexText().contains(QStringLiteral("BLOCK 2 parity (32 bytes)")));
    view.showSourceRow(3);
    QVERIFY(view.detailText().contains(QStringLiteral("beyond correction")));
}

// A log opened into a shown view is laid out in the same pass (not on the
// view's own timer, where it would be painted together with whatever comes
// next), and its scroll bar, always there, does not narrow the view.
void TestFrameLogModel::viewLaysOutALogAtOnce()
{
    FrameLogModel model;
    FrameLogView view(&model);
    view.resize(1000, 700);
    view.show();
    QVERIFY(QTest::qWaitForWindowExposed(&view));
    QCoreApplication::processEvents();
    QScrollBar* bar = view.table()->verticalScrollBar();
    QVERIFY(bar->isVisible());  // before there is anything to scroll
    const int viewportWidth = view.table()->viewport()->width();
    QCOMPARE(bar->maximum(), 0);
    QVERIFY(model.openLog(m_path));
    QVERIFY2(bar->maximum() > kFrames - 100, qPrintable(QString::number(bar->maximum())));  // no event loop yet
    QCOMPARE(view.table()->viewport()->width(), viewportWidth);
}

// A keyed link's frames: without the key a row has no ID and its detail says
// "Enciphered", not items read from ciphertext; with it, the real items,
// authenticated, in the rows and the detail pane alike.
void TestFrameLogModel::keyedRowsNeedTheKey()
{
    const rcm::secure::SecretKey psk = rcm::secure::generateKey();
    const rcm::secure::SecureCodec console(psk, rcm::secure::Direction::GcsToUa);
    const QString path = m_dir.filePath(QStringLiteral("keyed.pcapng"));
    {
        FrameLog log;
        QVERIFY(log.open(path));
        for (int i = 0; i < 6; i += 2) {  // our own sends: clean
            const FrameRecord plain = frame(i);
            const rcm::DecodeResult decoded = rcm::decodeFrame(
                std::span(reinterpret_cast<const std::uint8_t*>(plain.bytes.constData()), std::size_t(plain.bytes.size())));
            rcm::Diagnostics errors;
            const auto blocks = console.encode(decoded.message, errors);
            QVERIFY(blocks);
            const rcm::DatagramBytes datagram = rcm::makeDatagram(blocks->block1, blocks->block2);
            FrameRecord r;
            r.bytes = QByteArray(reinterpret_cast<const char*>(datagram.data()), qsizetype(datagram.size()));
            r.utcMicros = plain.utcMicros;
            r.direction = FrameDirection::Sent;
            r.transport = FrameTransport::Udp;
            r.enciphered = true;
            QVERIFY(log.append(r));
        }
    }
    FrameLogModel model;
    QVERIFY(model.openLog(path));
    FrameLogView view(&model);
    QCOMPARE(model.rowCount(), 3);
    QCOMPARE(model.messageId(1), std::nullopt);
    view.showSourceRow(1);
    QVERIFY2(view.detailText().contains(QStringLiteral("# Enciphered: sent over a keyed link.")),
             qPrintable(view.detailText()));
    QVERIFY(!view.detailText().contains(QStringLiteral("BEGIN HEADER")));

    model.setLogKey(std::make_shared<rcm::LogKey>(psk));
    QCOMPARE(model.messageId(1), std::optional<quint32>(2));
    view.showSourceRow(1);
    QVERIFY2(view.detailText().contains(QStringLiteral("# Deciphered and authenticated (GCS->UA)")),
             qPrintable(view.detailText()));
    QVERIFY(view.detailText().contains(QStringLiteral("ID_msg 2\n")));
}

void TestFrameLogModel::liveRowsMatchTheSessionLog()
{
    QTemporaryDir dir;
    const QString path = dir.filePath(QStringLiteral("session.pcapng"));
    auto log = std::make_unique<FrameLog>();
    QString error;
    QVERIFY2(log->open(path, &error), qPrintable(error));
    FrameLogModel model;
    model.setSessionLog(path);
    QList<QByteArray> farReceived;
    runSession(model, std::move(log), farReceived);
    if (QTest::currentTestFailed())
        return;
    QCOMPARE(model.rowsWithBytesInMemory(), 0);  // the log file has them

    FrameLogReader reader;
    QVERIFY2(reader.open(path), qPrintable(reader.errorString()));
    QCOMPARE(model.rowCount(), reader.count());
    std::map<FrameStatus, int> statuses;
    int sent = 0;
    for (int row = 0; row < model.rowCount(); ++row) {
        const FrameRecord logged = reader.recordAt(row);
        QCOMPARE(model.direction(row), logged.direction);
        QCOMPARE(model.status(row), logged.status);
        QCOMPARE(model.utcMicros(row), logged.utcMicros);
        QCOMPARE(model.record(row), logged);  // bytes and corrections read back at the row's offset
        ++statuses[logged.status];
        if (logged.direction == FrameDirection::Sent) {
            QCOMPARE(logged.bytes, farReceived.value(sent++));
            QVERIFY(model.messageId(row).has_value());
        }
    }
    QCOMPARE(sent, farReceived.size());
    for (FrameStatus s :
         {FrameStatus::Decoded, FrameStatus::Corrected, FrameStatus::Uncorrectable, FrameStatus::Rejected})
        QCOMPARE(statuses[s], 1);

    // The cells of the aircraft's frames, from what the link reported and the log.
    const auto rowOf = [&](FrameStatus status) {
        int row = 0;
        while (row < model.rowCount() && model.status(row) != status)
            ++row;
        return row;
    };
    const auto cell = [&](int row, int column) { return model.index(row, column).data().toString(); };
    QCOMPARE(cell(rowOf(FrameStatus::Decoded), FrameLogModel::MessageIdColumn), QStringLiteral("5"));
    QCOMPARE(cell(rowOf(FrameStatus::Corrected), FrameLogModel::CorrectedColumn), QStringLiteral("2"));
    QCOMPARE(cell(rowOf(FrameStatus::Uncorrectable), FrameLogModel::CorrectedColumn), QStringLiteral("beyond"));
    QCOMPARE(model.record(rowOf(FrameStatus::Uncorrectable)).bytes, frame(3, g_sessionStamp).bytes);
    QCOMPARE(model.record(rowOf(FrameStatus::Rejected)).bytes, QByteArray(100, '\x55'));
    QCOMPARE(cell(rowOf(FrameStatus::Rejected), FrameLogModel::MessageIdColumn), QStringLiteral("\u2014"));
}

void TestFrameLogModel::liveRowsWithoutALogKeepTheirBytes()
{
    FrameLogModel model;
    QList<QByteArray> farReceived;
    runSession(model, nullptr, farReceived);
    if (QTest::currentTestFailed())
        return;
    QCOMPARE(model.rowsWithBytesInMemory(), model.rowCount());
    int sent = 0;
    for (int row = 0; row < model.rowCount(); ++row) {
        const FrameRecord r = model.record(row);
        if (r.direction == FrameDirection::Sent)
            QCOMPARE(r.bytes, farReceived.value(sent++));
        else if (r.status == FrameStatus::Uncorrectable)
            QCOMPARE(r.bytes, frame(3, g_sessionStamp).bytes);
        else if (r.status == FrameStatus::Rejected)
            QCOMPARE(r.bytes, QByteArray(100, '\x55'));
    }
    QCOMPARE(sent, farReceived.size());
}

namespace {

// Where a cell's text was drawn: the box of the pixels not of the background.
QRect inkOf(const QImage& image, QRgb background)
{
    QRect ink;
    for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x)
            if (image.pixel(x, y) != background)
                ink |= QRect(x, y, 1, 1);
    return ink;
}

QImage paintCell(const QStyledItemDelegate& delegate, const QModelIndex& index, QSize size, QStyle::State state)
{
    QImage image(size, QImage::Format_ARGB32);
    image.fill(Qt::white);
    QStyleOptionViewItem option;
    option.rect = QRect(QPoint(0, 0), size);
    option.state = QStyle::State_Enabled | QStyle::State_Active | state;
    // As a table view sets them.
    option.displayAlignment = Qt::AlignLeft | Qt::AlignVCenter;
    option.showDecorationSelected = true;
    option.palette = QApplication::palette();
    option.palette.setColor(QPalette::Base, Qt::white);
    option.font = QApplication::font();
    option.fontMetrics = QFontMetrics(option.font);
    QPainter painter(&image);
    delegate.paint(&painter, option, index);
    painter.end();
    return image;
}

}  // namespace

// The log's own delegate draws a cell's text where Qt's would, in the
// model's colour, font and alignment, and lays each text out once.
void TestFrameLogModel::delegateDrawsTheModelsText()
{
    QStandardItemModel model(1, 3);
    model.setItem(0, 0, new QStandardItem(QStringLiteral("\u2190 received")));
    model.item(0, 0)->setForeground(QColor(0xb0, 0x1c, 0x1c));
    model.setItem(0, 1, new QStandardItem(QStringLiteral("150005")));
    model.item(0, 1)->setTextAlignment(Qt::AlignRight | Qt::AlignVCenter);
    model.setItem(0, 2, new QStandardItem(QStringLiteral("uncorrectable")));
    QFont bold = QApplication::font();
    bold.setBold(true);
    model.item(0, 2)->setFont(bold);
    FrameLogDelegate ours;
    QStyledItemDelegate qts;
    const QSize cell(160, 24);
    const QRgb white = qRgb(255, 255, 255);
    for (int column = 0; column < 3; ++column) {
        const QModelIndex index = model.index(0, column);
        const QRect drawn = inkOf(paintCell(ours, index, cell, {}), white);
        const QRect expected = inkOf(paintCell(qts, index, cell, {}), white);
        QVERIFY2(!drawn.isEmpty(), qPrintable(index.data().toString()));
        // The same place to a pixel: only how the glyphs are positioned differs.
        for (const auto& [a, b] : {std::pair{drawn.left(), expected.left()}, {drawn.right(), expected.right()},
                                   {drawn.top(), expected.top()}, {drawn.bottom(), expected.bottom()}})
            QVERIFY2(std::abs(a - b) <= 1, qPrintable(QStringLiteral("%1: drawn at %2, Qt draws at %3")
                                                          .arg(index.data().toString())
                                                          .arg(QStringLiteral("%1,%2 %3,%4")
                                                                   .arg(drawn.left())
                                                                   .arg(drawn.top())
                                                                   .arg(drawn.right())
                                                                   .arg(drawn.bottom()))
                                                          .arg(QStringLiteral("%1,%2 %3,%4")
                                                                   .arg(expected.left())
                                                                   .arg(expected.top())
                                                                   .arg(expected.right())
                                                                   .arg(expected.bottom()))));
    }
    // In the model's colour: the darkest pixel of the red text is red.
    const QImage red = paintCell(ours, model.index(0, 0), cell, {});
    int darkest = 255 * 3;
    QRgb ink = white;
    for (int y = 0; y < red.height(); ++y)
        for (int x = 0; x < red.width(); ++x)
            if (const QRgb p = red.pixel(x, y); qRed(p) + qGreen(p) + qBlue(p) < darkest) {
                darkest = qRed(p) + qGreen(p) + qBlue(p);
                ink = p;
            }
    QVERIFY2(qRed(ink) > 2 * qGreen(ink) && qRed(ink) > 2 * qBlue(ink), qPrintable(QColor(ink).name()));
    // Selected: the selection's text colour on the selection.
    const QImage selected = paintCell(ours, model.index(0, 1), cell, QStyle::State_Selected);
    QCOMPARE(selected.pixel(2, 2), QApplication::palette().color(QPalette::Active, QPalette::Highlight).rgb());
    // Each text laid out once (the bold one in its own font); painted again, nothing new.
    QCOMPARE(ours.laidOutTexts(), 3);
    paintCell(ours, model.index(0, 0), cell, {});
    paintCell(ours, model.index(0, 1), cell, {});
    paintCell(ours, model.index(0, 2), cell, {});
    QCOMPARE(ours.laidOutTexts(), 3);
    // A day's row numbers: kept up to the bound, the least recently drawn given up.
    QStandardItemModel numbers(3000, 1);
    for (int row = 0; row < 3000; ++row) {
        numbers.setItem(row, 0, new QStandardItem(QString::number(row + 1)));
        paintCell(ours, numbers.index(row, 0), cell, {});
    }
    QCOMPARE(ours.laidOutTexts(), 2048 + 1);  // and the bold one
    // Too narrow a column: elided, within the cell.
    const QRect narrow = inkOf(paintCell(ours, model.index(0, 0), QSize(40, 24), {}), white);
    QVERIFY(narrow.right() < 40);
}

// A day's log scrolled one row moves the slider by less than a pixel: the
// bar is not painted again until the slider moves or an end is reached.
void TestFrameLogModel::scrollBarRepaintsWhenItsSliderMoves()
{
    SteadyScrollBar bar(Qt::Vertical);
    bar.setRange(0, 86'400);
    bar.setPageStep(20);
    bar.resize(16, 400);
    EventCounter paints(&bar, QEvent::Paint);
    bar.show();
    QVERIFY(QTest::qWaitForWindowExposed(&bar));
    QTRY_VERIFY(paints.count() > 0);
    bar.setValue(100);  // off the top end, whose arrow is drawn apart
    QCoreApplication::processEvents();
    const int shown = paints.count();

    for (int value = 101; value <= 110; ++value) {
        bar.setValue(value);
        QCoreApplication::processEvents();
    }
    QCOMPARE(paints.count(), shown);
    bar.setValue(43'200);
    QCoreApplication::processEvents();
    QCOMPARE(paints.count(), shown + 1);
    bar.setValue(86'400);  // the end: its arrow changes
    QCoreApplication::processEvents();
    QCOMPARE(paints.count(), shown + 2);
    bar.setValue(86'399);  // and changes back, a row before it
    QCoreApplication::processEvents();
    QCOMPARE(paints.count(), shown + 3);
}

QTEST_MAIN(TestFrameLogModel)
#include "tst_framelogmodel.moc"
