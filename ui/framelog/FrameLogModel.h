#pragma once

// The frame log as a flat table, one row per frame, oldest at the top, in the
// manner of Wireshark's packet list: a row holds only what the log's index
// holds (time, direction, status, length, where the bytes are), the text of a
// cell is built when a view asks for it, and the message ID and the corrected
// bytes, which need the frame itself, are decoded for the rows a view shows
// and cached. So a day of frames costs its index, not its decodes.
//
// Rows come from a log file (openLog: indexed by FrameLogReader, the bytes
// read from the mapping when needed) and from frames a live link logged
// (appendLogged, from LinkController::frameLogged): those hold the offset of
// their record in the session's log and read it back through the same reader
// when shown, so a live day costs no more than an opened one. Appends are
// collected and inserted once per pass of the event loop, so a burst of frames
// is one rowsInserted(), not one each.

#include "link/framelog/FrameLog.h"
#include "link/framelog/FrameLogReader.h"
#include "link/session/LoggedFrame.h"
#include "ui/table/FlatTableModel.h"

#include <QByteArray>

#include <memory>
#include <optional>
#include <vector>

namespace rcm {
class LogKey;
}

class FrameLogModel : public FlatTableModel {
    Q_OBJECT

public:
    enum Column { NumberColumn, TimeColumn, DirectionColumn, MessageIdColumn, CorrectedColumn, StatusColumn };
    static constexpr int kColumnCount = 6;
    // A frame's status in words for the operator; frameStatusName() is the
    // file's and the CSV's word for it.
    static QString statusText(FrameStatus status);

    explicit FrameLogModel(QObject* parent = nullptr);
    ~FrameLogModel() override;

    // Replaces every row by the records of a pcapng frame log. On a log
    // corrupt part-way the records before the fault are shown and the
    // reader's reason is returned in `error`; false when nothing was readable.
    bool openLog(const QString& path, QString* error = nullptr);
    // The same for a log another thread has indexed already (reader->open()
    // found records), so that a day's log costs the GUI thread its rows only;
    // with `rows` built from that reader by prepareRows() in that other
    // thread, not even those (86,400 rows: milliseconds, mostly the first
    // touch of their memory).
    class PreparedRows;
    static std::shared_ptr<PreparedRows> prepareRows(const FrameLogReader& reader);
    void showLog(std::unique_ptr<FrameLogReader> reader, const QString& path,
                 std::shared_ptr<PreparedRows> rows = {});
    // Removes every row (and closes the log file, if one was open).
    void clear();
    QString logPath() const { return m_logPath; }

    // The key to read a keyed link's frames with (the session's, or one given
    // for a log opened later); null: such frames show no ID and say
    // "enciphered" rather than be decoded as plain. Rows decoded already are
    // read again with it.
    void setLogKey(std::shared_ptr<const rcm::LogKey> key);
    const rcm::LogKey* logKey() const { return m_logKey.get(); }

    // The log file a live link is writing: the file the offsets of frames
    // appended with appendLogged() point into. Cleared by clear() and openLog().
    void setSessionLog(const QString& path);
    QString sessionLog() const { return m_sessionLogPath; }

    // What a filter needs, without building any text.
    FrameDirection direction(int row) const { return m_rows[std::size_t(row)].direction; }
    FrameStatus status(int row) const { return m_rows[std::size_t(row)].status; }
    qint64 utcMicros(int row) const { return m_rows[std::size_t(row)].utcMicros; }

    // The whole record: its bytes are copied out of the log file (the opened
    // one, or the session's), or out of memory for a frame that is in no file.
    // Bytes are empty when they cannot be read (the session's log was removed).
    FrameRecord record(int row) const;
    // The frame's ID_msg, decoded on first use; nothing when it cannot be
    // read (no bytes, beyond correction, no ID_msg item).
    std::optional<quint32> messageId(int row) const;

    // Rows at or after this one are drawn as "not played yet" (a replay's
    // position); -1, the default, draws every row as played.
    void setPlayedRows(int count);
    int playedRows() const { return m_played; }

    // Rows whose frame has been read for their ID and corrections: the
    // rows some view has shown, and no others.
    int decodedRows() const { return m_decodedRows; }

    // Rows appended but not inserted yet: they become rows in the next pass
    // of the event loop.
    int pendingRows() const { return int(m_pending.size()); }

    // Rows whose bytes are held in memory: frames that are in no log file.
    int rowsWithBytesInMemory() const { return int(m_liveBytes.size()); }

public slots:
    // A frame a live link logged (LinkController::frameLogged): its bytes are
    // read from the session log at its offset when needed, or kept when it
    // carries them, being in no file.
    void appendLogged(const LoggedFrame& frame);
    // A frame with its bytes, kept in memory. `messageId`, when given, spares a decode.
    void appendRecord(const FrameRecord& record, std::optional<quint32> messageId = std::nullopt);
    // Inserts what appendRecord() collected now rather than in the next pass.
    void flushPending();

signals:
    // setLogKey() gave another key: what shows a frame reads it again.
    void logKeyChanged();

private:
    // Where a row's bytes are.
    enum class Source : quint8 {
        OpenedLog,   // Row::source is the record's index in m_reader
        SessionLog,  // Row::source is the offset of its block in the session's log
        Memory,      // Row::source is the index in m_liveBytes
        None,        // no bytes anywhere
    };
    // 32 bytes a frame: 172,800 frames (a day, both ways) take 5.5 MB.
    // The small members first: they fill FrameFacts' last bytes.
    struct Row : FrameFacts {
        Source from = Source::None;
        mutable qint8 corrected1 = 0;  // kNotKnown until decoded
        mutable qint8 corrected2 = 0;
        mutable bool decoded : 1 = false;  // messageId and corrected* are known
        mutable bool hasMessageId : 1 = false;
        quint32 length = 0;
        mutable quint32 messageId = 0;
        qint64 source = 0;  // see Source
    };
    static_assert(sizeof(Row) == 32, "a day of rows is budgeted at 32 bytes each");
    static constexpr qint8 kNotKnown = -2;

    QVariant cellData(const QModelIndex& index, int role) const override;
    int rows() const override { return int(m_rows.size()); }

    void decodeRow(const Row& row) const;
    QByteArray bytesOf(const Row& row) const;
    QString cellText(int row, const Row& r, int column) const;
    std::optional<FrameRecord> fromSessionLog(const Row& row) const;
    void queueRow(const Row& row);

    std::vector<Row> m_rows;
    std::vector<Row> m_pending;
    std::vector<QByteArray> m_liveBytes;  // appended frames' bytes, by Row::source
    std::unique_ptr<FrameLogReader> m_reader;
    std::shared_ptr<const rcm::LogKey> m_logKey;
    QString m_logPath;
    QString m_sessionLogPath;
    mutable std::unique_ptr<FrameLogReader> m_sessionLog;  // opened live on first use, never indexed
    int m_played = -1;
    mutable int m_decodedRows = 0;
    bool m_flushQueued = false;
};
