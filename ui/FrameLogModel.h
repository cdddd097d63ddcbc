#pragma once

// The frame log as a flat table, one row per frame, oldest at the top, in the
// manner of Wireshark's packet list: a row holds only what the log's index
// holds (time, direction, status, length, where the bytes are), the text of a
// cell is built when a view asks for it, and the message ID and the corrected
// bytes, which need the frame itself, are decoded for the rows a view shows
// and cached. So a day of frames costs its index, not its decodes.
//
// Rows come from a log file (openLog: indexed by FrameLogReader, the bytes
// read from the mapping when needed) and from frames appended live
// (appendRecord). Appends are collected and inserted once per pass of the
// event loop, so a burst of frames is one rowsInserted(), not one each.

#include "link/FrameLog.h"
#include "link/FrameLogReader.h"

#include <QAbstractTableModel>
#include <QByteArray>

#include <memory>
#include <optional>
#include <vector>

class FrameLogModel : public QAbstractTableModel {
    Q_OBJECT

public:
    enum Column { NumberColumn, TimeColumn, DirectionColumn, MessageIdColumn, CorrectedColumn, StatusColumn };
    static constexpr int kColumnCount = 6;

    explicit FrameLogModel(QObject* parent = nullptr);
    ~FrameLogModel() override;

    int rowCount(const QModelIndex& parent = {}) const override;
    int columnCount(const QModelIndex& parent = {}) const override;
    QVariant data(const QModelIndex& index, int role = Qt::DisplayRole) const override;
    QVariant headerData(int section, Qt::Orientation orientation, int role = Qt::DisplayRole) const override;

    // Replaces every row by the records of a pcapng frame log. On a log
    // corrupt part-way the records before the fault are shown and the
    // reader's reason is returned in `error`; false when nothing was readable.
    bool openLog(const QString& path, QString* error = nullptr);
    // Removes every row (and closes the log file, if one was open).
    void clear();
    QString logPath() const { return m_logPath; }

    // The log file a live link is writing. A frame appended without its
    // bytes is looked up there, by direction and time, when record() is
    // asked for it: the log view shows the bytes the link logged without the
    // model holding a copy of every frame. Cleared by clear() and openLog().
    void setSessionLog(const QString& path);

    // What a filter needs, without building any text.
    FrameDirection direction(int row) const { return m_rows[std::size_t(row)].direction; }
    FrameStatus status(int row) const { return m_rows[std::size_t(row)].status; }
    qint64 utcMicros(int row) const { return m_rows[std::size_t(row)].utcMicros; }

    // The whole record: its bytes are copied out of the log file, or out of
    // memory for an appended frame. Bytes are empty for a frame appended
    // without them (see appendRecord).
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

public slots:
    // A frame as it was logged. `messageId`, when given, spares a decode
    // (and is the only source of the ID for a frame appended without bytes).
    void appendRecord(const FrameRecord& record, std::optional<quint32> messageId = std::nullopt);
    // Inserts what appendRecord() collected now rather than in the next pass.
    void flushPending();

private:
    // 32 bytes a frame: 172,800 frames (a day, both ways) take 5.5 MB.
    struct Row {
        qint64 utcMicros = 0;
        qint32 source = 0;  // index in the reader, or in m_liveBytes
        quint32 length = 0;
        mutable quint32 messageId = 0;
        FrameDirection direction = FrameDirection::Received;
        FrameTransport transport = FrameTransport::Serial;
        FrameStatus status = FrameStatus::NotChecked;
        bool fromLog = false;
        mutable qint8 corrected1 = 0;  // kNotKnown until decoded
        mutable qint8 corrected2 = 0;
        mutable bool decoded = false;  // messageId and corrected* are known
        mutable bool hasMessageId = false;
    };
    static constexpr qint8 kNotKnown = -2;

    void decodeRow(const Row& row) const;
    QByteArray bytesOf(const Row& row) const;
    QString cellText(int row, const Row& r, int column) const;
    std::optional<FrameRecord> fromSessionLog(const Row& row) const;

    std::vector<Row> m_rows;
    std::vector<Row> m_pending;
    std::vector<QByteArray> m_liveBytes;  // appended frames' bytes, by Row::source
    std::unique_ptr<FrameLogReader> m_reader;
    QString m_logPath;
    QString m_sessionLogPath;
    mutable std::unique_ptr<FrameLogReader> m_sessionLog;  // indexed again when a row is newer than its end
    int m_played = -1;
    mutable int m_decodedRows = 0;
    bool m_flushQueued = false;
};
