#include "ui/framelog/FrameLogModel.h"

#include "codec/frame/Frame.h"
#include "codec/receive/LoggedFrameReading.h"
#include "link/common/NameTable.h"

#include <QBrush>
#include <QColor>
#include <QDateTime>
#include <QFont>
#include <QTimeZone>

#include <algorithm>
#include <span>

namespace {

constexpr auto kColumns = std::to_array<FlatTableModel::Column>({
    {QT_TRANSLATE_NOOP("FrameLogModel", "No."), nullptr, Qt::AlignRight},
    {QT_TRANSLATE_NOOP("FrameLogModel", "Time (UTC)")},
    {QT_TRANSLATE_NOOP("FrameLogModel", "Direction")},
    {QT_TRANSLATE_NOOP("FrameLogModel", "Message ID"),
     QT_TRANSLATE_NOOP("FrameLogModel", "ID_msg of the frame, decoded when the row is shown"), Qt::AlignRight},
    {QT_TRANSLATE_NOOP("FrameLogModel", "Corrected bytes"),
     QT_TRANSLATE_NOOP("FrameLogModel",
                       "Bytes Reed-Solomon corrected in BLOCK 1 + BLOCK 2; \"beyond\" when a codeword could not "
                       "be corrected"),
     Qt::AlignRight},
    {QT_TRANSLATE_NOOP("FrameLogModel", "Status")},
});
static_assert(kColumns.size() == FrameLogModel::kColumnCount);

constexpr auto kStatusTexts = std::to_array<Named<FrameStatus>>({
    {FrameStatus::Decoded, QT_TRANSLATE_NOOP("FrameLogModel", "decoded")},
    {FrameStatus::Corrected, QT_TRANSLATE_NOOP("FrameLogModel", "corrected")},
    {FrameStatus::Uncorrectable, QT_TRANSLATE_NOOP("FrameLogModel", "uncorrectable")},
    {FrameStatus::Rejected, QT_TRANSLATE_NOOP("FrameLogModel", "refused")},
    {FrameStatus::NotChecked, QT_TRANSLATE_NOOP("FrameLogModel", "not checked")},
});

// "07:32:00.123": the time of day is what an operator compares; the date and
// the microseconds are in the tooltip.
QString timeOfDay(qint64 utcMicros)
{
    constexpr qint64 kMicrosPerDay = 86'400'000'000;
    qint64 inDay = utcMicros % kMicrosPerDay;
    if (inDay < 0)
        inDay += kMicrosPerDay;
    const qint64 ms = inDay / 1000;
    return QStringLiteral("%1:%2:%3.%4")
        .arg(ms / 3'600'000, 2, 10, QLatin1Char('0'))
        .arg(ms / 60'000 % 60, 2, 10, QLatin1Char('0'))
        .arg(ms / 1000 % 60, 2, 10, QLatin1Char('0'))
        .arg(ms % 1000, 3, 10, QLatin1Char('0'));
}

QString isoTime(qint64 utcMicros)
{
    const QDateTime t = QDateTime::fromMSecsSinceEpoch(utcMicros / 1000, QTimeZone::utc());
    return t.toString(QStringLiteral("yyyy-MM-dd hh:mm:ss.zzz")) +
           QStringLiteral("%1 UTC").arg(utcMicros % 1000, 3, 10, QLatin1Char('0'));
}

qint8 clampCorrected(int n)
{
    return qint8(std::clamp(n, -1, 127));
}

}  // namespace

FrameLogModel::FrameLogModel(QObject* parent) : FlatTableModel(kColumns, parent) {}

FrameLogModel::~FrameLogModel() = default;

QVariant FrameLogModel::cellData(const QModelIndex& index, int role) const
{
    const Row& r = m_rows[std::size_t(index.row())];
    switch (role) {
        case Qt::DisplayRole:
            return cellText(index.row(), r, index.column());
        case Qt::ToolTipRole:
            if (index.column() == TimeColumn)
                return isoTime(r.utcMicros);
            if (index.column() == StatusColumn)
                return tr("%1 bytes over %2").arg(r.length).arg(frameTransportName(r.transport));
            if (index.column() == CorrectedColumn && r.corrected1 >= 0 && r.corrected2 >= 0)
                return tr("%1 in the first codeword, %2 in the second").arg(r.corrected1).arg(r.corrected2);
            return {};
        case Qt::ForegroundRole:
            if (m_played >= 0 && index.row() >= m_played)
                return QBrush(QColor(0x9a, 0x9a, 0x9a));
            if (index.column() == StatusColumn || index.column() == CorrectedColumn) {
                if (r.status == FrameStatus::Uncorrectable || r.status == FrameStatus::Rejected)
                    return QBrush(QColor(0xb0, 0x1c, 0x1c));
                if (r.status == FrameStatus::Corrected)
                    return QBrush(QColor(0x9a, 0x5b, 0x00));
            }
            return {};
        case Qt::FontRole:
            if (index.row() == m_played - 1) {
                QFont bold;
                bold.setBold(true);
                return bold;
            }
            return {};
    }
    return {};
}

QString FrameLogModel::statusText(FrameStatus status)
{
    return tr(nameOf(kStatusTexts, status));
}

QString FrameLogModel::cellText(int row, const Row& r, int column) const
{
    switch (column) {
        case NumberColumn:
            return QString::number(row + 1);
        case TimeColumn:
            return timeOfDay(r.utcMicros);
        case DirectionColumn:
            return r.direction == FrameDirection::Sent ? tr("\u2192 sent") : tr("\u2190 received");
        case MessageIdColumn:
            decodeRow(r);
            return r.hasMessageId ? QString::number(r.messageId) : QStringLiteral("\u2014");
        case CorrectedColumn:
            decodeRow(r);
            if (r.corrected1 == kNotKnown || r.corrected2 == kNotKnown)
                return QStringLiteral("\u2014");
            if (r.corrected1 < 0 || r.corrected2 < 0)
                return tr("beyond");
            // The total; the tool tip tells the two codewords apart.
            return r.corrected1 + r.corrected2 == 0 ? tr("none") : QString::number(r.corrected1 + r.corrected2);
        case StatusColumn:
            return statusText(r.status);
    }
    return {};
}

QByteArray FrameLogModel::bytesOf(const Row& row) const
{
    switch (row.from) {
        case Source::OpenedLog:
            return m_reader ? m_reader->recordAt(int(row.source)).bytes : QByteArray();
        case Source::SessionLog:
            if (std::optional<FrameRecord> logged = fromSessionLog(row))
                return logged->bytes;
            return {};
        case Source::Memory:
            return m_liveBytes[std::size_t(row.source)];
        case Source::None:
            break;
    }
    return {};
}

// The one place a row's frame is read: once per row, when a view first shows
// its ID or corrections. Our own sends are not decoded for corrections: they
// were never damaged.
void FrameLogModel::decodeRow(const Row& row) const
{
    if (row.decoded)
        return;
    row.decoded = true;
    ++m_decodedRows;
    QByteArray bytes;
    if (row.from == Source::OpenedLog) {
        const FrameRecord record = m_reader->recordAt(int(row.source));
        if (record.correctedSymbols.size() == 2) {
            row.corrected1 = clampCorrected(record.correctedSymbols[0]);
            row.corrected2 = clampCorrected(record.correctedSymbols[1]);
        }
        bytes = record.bytes;
    } else {
        bytes = bytesOf(row);
    }
    if (row.hasMessageId || bytes.isEmpty())
        return;
    const rcm::LoggedFrameReading reading = rcm::readLoggedFrame(
        std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(bytes.constData()),
                                      std::size_t(bytes.size())),
        row.enciphered, m_logKey.get());
    if (reading.outcome == rcm::LoggedFrameReading::Outcome::NotAFrame)
        return;
    if (row.direction == FrameDirection::Received && row.corrected1 == kNotKnown) {
        row.corrected1 = clampCorrected(reading.blocks.corrected.block1);
        row.corrected2 = clampCorrected(reading.blocks.corrected.block2);
    }
    // The ID of a frame read, or of a plain one refused for what it says:
    // never one read from ciphertext as if it were plain.
    const rcm::Message& m = reading.decoded.message;
    if (reading.blocks.corrected.block1 >= 0 && m.header.has(rcm::ItemId::ID_msg)) {
        row.messageId = quint32(m.header.number(rcm::ItemId::ID_msg));
        row.hasMessageId = true;
    }
}

bool FrameLogModel::openLog(const QString& path, QString* error)
{
    auto reader = std::make_unique<FrameLogReader>();
    const bool complete = reader->open(path);
    if (error)
        *error = complete ? QString() : reader->errorString();
    if (!complete && reader->count() == 0)
        return false;
    showLog(std::move(reader), path);
    return true;
}

class FrameLogModel::PreparedRows {
public:
    const FrameLogReader* reader = nullptr;  // built from
    std::vector<Row> rows;
};

std::shared_ptr<FrameLogModel::PreparedRows> FrameLogModel::prepareRows(const FrameLogReader& reader)
{
    auto prepared = std::make_shared<PreparedRows>();
    prepared->reader = &reader;
    prepared->rows.reserve(std::size_t(reader.count()));
    const QVector<FrameIndexEntry>& index = reader.index();
    for (qsizetype i = 0; i < index.size(); ++i) {
        const FrameIndexEntry& e = index[i];
        Row row;
        static_cast<FrameFacts&>(row) = e;
        row.source = qint32(i);
        row.length = e.length;
        row.from = Source::OpenedLog;
        row.corrected1 = row.corrected2 = kNotKnown;
        prepared->rows.push_back(row);
    }
    return prepared;
}

void FrameLogModel::showLog(std::unique_ptr<FrameLogReader> reader, const QString& path,
                            std::shared_ptr<PreparedRows> rows)
{
    if (!rows || rows->reader != reader.get() || rows->rows.size() != std::size_t(reader->count()))
        rows = prepareRows(*reader);
    beginResetModel();
    m_pending.clear();
    m_liveBytes.clear();
    m_rows = std::move(rows->rows);
    m_reader = std::move(reader);
    m_logPath = path;
    m_sessionLogPath.clear();
    m_sessionLog.reset();
    m_played = -1;
    m_decodedRows = 0;
    endResetModel();
}

void FrameLogModel::clear()
{
    beginResetModel();
    m_rows.clear();
    m_rows.shrink_to_fit();
    m_pending.clear();
    m_liveBytes.clear();
    m_liveBytes.shrink_to_fit();
    m_reader.reset();
    m_logPath.clear();
    m_sessionLogPath.clear();
    m_sessionLog.reset();
    m_played = -1;
    m_decodedRows = 0;
    endResetModel();
}

FrameRecord FrameLogModel::record(int row) const
{
    const Row& r = m_rows[std::size_t(row)];
    if (r.from == Source::OpenedLog && m_reader)
        return m_reader->recordAt(int(r.source));
    if (r.from == Source::SessionLog)
        if (std::optional<FrameRecord> logged = fromSessionLog(r))
            return *logged;
    FrameRecord record;
    static_cast<FrameFacts&>(record) = r;
    record.bytes = bytesOf(r);
    decodeRow(r);
    if (r.corrected1 != kNotKnown && r.corrected2 != kNotKnown)
        record.correctedSymbols = {r.corrected1, r.corrected2};
    return record;
}

void FrameLogModel::setLogKey(std::shared_ptr<const rcm::LogKey> key)
{
    if (key == m_logKey)
        return;
    m_logKey = std::move(key);
    for (const Row& row : m_rows)
        if (row.enciphered && !row.hasMessageId)
            row.decoded = false;
    if (!m_rows.empty())
        rowsChanged(0, rows() - 1);
    emit logKeyChanged();
}

void FrameLogModel::setSessionLog(const QString& path)
{
    m_sessionLogPath = path;
    m_sessionLog.reset();
}

// A live row's record, read where the link said it wrote it. The reader is
// opened once, live: no index and no mapping, one block read per call.
std::optional<FrameRecord> FrameLogModel::fromSessionLog(const Row& row) const
{
    if (m_sessionLogPath.isEmpty())
        return std::nullopt;
    if (!m_sessionLog) {
        auto reader = std::make_unique<FrameLogReader>();
        if (!reader->openLive(m_sessionLogPath)) {
            qWarning("%s", qPrintable(reader->errorString()));
            return std::nullopt;
        }
        m_sessionLog = std::move(reader);
    }
    FrameIndexEntry entry;
    static_cast<FrameFacts&>(entry) = row;
    entry.offset = row.source;
    entry.length = row.length;
    std::optional<FrameRecord> record = m_sessionLog->recordAt(entry);
    if (!record)
        qWarning("%s", qPrintable(m_sessionLog->errorString()));
    return record;
}

std::optional<quint32> FrameLogModel::messageId(int row) const
{
    const Row& r = m_rows[std::size_t(row)];
    decodeRow(r);
    return r.hasMessageId ? std::optional<quint32>(r.messageId) : std::nullopt;
}

void FrameLogModel::setPlayedRows(int count)
{
    if (count == m_played)
        return;
    const int before = m_played;
    m_played = count;
    if (m_rows.empty())
        return;
    // Only the rows whose look changed: between the old and the new position.
    const int last = int(m_rows.size()) - 1;
    const int from = std::clamp(before < 0 || count < 0 ? 0 : std::min(before, count) - 1, 0, last);
    const int to = before < 0 || count < 0 ? last : std::clamp(std::max(before, count), 0, last);
    rowsChanged(from, to, {Qt::ForegroundRole, Qt::FontRole});
}

void FrameLogModel::appendLogged(const LoggedFrame& frame)
{
    Row row;
    static_cast<FrameFacts&>(row) = frame.entry;
    row.length = frame.entry.length;
    row.corrected1 = row.corrected2 = kNotKnown;
    if (frame.correctedSymbols.size() == 2) {
        row.corrected1 = clampCorrected(frame.correctedSymbols[0]);
        row.corrected2 = clampCorrected(frame.correctedSymbols[1]);
    }
    if (frame.messageId) {
        row.messageId = *frame.messageId;
        row.hasMessageId = true;
    }
    if (frame.inLog()) {
        row.from = Source::SessionLog;
        row.source = frame.entry.offset;
    } else if (!frame.bytes.isEmpty()) {
        row.from = Source::Memory;
        row.source = qint64(m_liveBytes.size());
        m_liveBytes.push_back(frame.bytes);
    } else {
        row.from = Source::None;
    }
    // What the link told us is all the view needs: no read of the frame for
    // its ID (a secure link's bytes are ciphertext anyway) or corrections.
    // A rejected frame's ID is not one to show: it was refused. Frames beyond
    // correction are still read, for an ID in the codeword that did decode.
    const bool correctionsKnown = row.direction == FrameDirection::Sent || row.corrected1 != kNotKnown;
    if (row.from == Source::None || (correctionsKnown && (row.hasMessageId || row.status == FrameStatus::Rejected)))
        row.decoded = true;
    queueRow(row);
}

void FrameLogModel::appendRecord(const FrameRecord& record, std::optional<quint32> messageId)
{
    LoggedFrame frame;
    static_cast<FrameFacts&>(frame.entry) = record;
    frame.entry.offset = -1;
    frame.entry.length = quint32(record.bytes.size());
    frame.correctedSymbols = record.correctedSymbols;
    frame.messageId = messageId;
    frame.bytes = record.bytes;
    appendLogged(frame);
}

void FrameLogModel::queueRow(const Row& row)
{
    m_pending.push_back(row);
    if (!m_flushQueued) {
        m_flushQueued = true;
        QMetaObject::invokeMethod(this, &FrameLogModel::flushPending, Qt::QueuedConnection);
    }
}

void FrameLogModel::flushPending()
{
    m_flushQueued = false;
    if (m_pending.empty())
        return;
    const int first = int(m_rows.size());
    beginInsertRows({}, first, first + int(m_pending.size()) - 1);
    m_rows.insert(m_rows.end(), m_pending.begin(), m_pending.end());
    m_pending.clear();
    endInsertRows();
}
