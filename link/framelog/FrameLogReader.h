#pragma once

// Reads a frame log written by FrameLog (or any pcapng file of LINKTYPE_USER0
// packets on interfaces named after a transport). open() maps the file and
// indexes it in one pass over the block headers; payloads are copied only by
// recordAt(), so the console's log view can page through a day of frames.
// openLive() is for a log still being written: no mapping and no index, only
// records read one at a time where FrameLog::append() said it put them.

#include "link/framelog/FrameLog.h"

#include <QFile>
#include <QString>
#include <QVector>

#include <optional>

struct FrameIndexEntry : FrameFacts {
    qint64 offset = 0;   // of the Enhanced Packet Block in the file
    quint32 length = 0;  // frame bytes
};

class FrameLogReader {
public:
    FrameLogReader() = default;
    FrameLogReader(const FrameLogReader&) = delete;
    FrameLogReader& operator=(const FrameLogReader&) = delete;

    // Indexes every complete record. A torn last block (the writer was killed
    // mid-write) is dropped silently and sets truncatedTail(). Corrupt
    // structure before the end stops the pass: open() returns false,
    // errorString() names the byte offset and the fault, and index() keeps the
    // records before it. Big-endian sections are read as well.
    bool open(const QString& path);
    // A log another thread or process is still appending to (the console's
    // own session): checks the section header and stops there. The file is
    // read, not mapped, so memory does not grow with the session; count()
    // stays 0 and records come only from recordAt(entry).
    bool openLive(const QString& path);
    void close();

    QString errorString() const { return m_error; }
    bool truncatedTail() const { return m_truncatedTail; }
    // Packets of interfaces that are not frame-log transports (another link
    // type or interface name, e.g. after mergecap): skipped, only counted.
    int foreignPackets() const { return m_foreignPackets; }

    int count() const { return int(m_index.size()); }
    const QVector<FrameIndexEntry>& index() const { return m_index; }
    // Copies one frame out of the file; i must be in [0, count()).
    FrameRecord recordAt(int i) const;
    QVector<FrameRecord> readAll() const;
    // The record whose Enhanced Packet Block starts at entry.offset: its bytes
    // and corrections from the file, the rest from `entry`. Works after open()
    // and openLive(). Nothing, with errorString() saying why, when no packet of
    // entry.length bytes starts there (a wrong offset, another file).
    std::optional<FrameRecord> recordAt(const FrameIndexEntry& entry);

    // First record at or after utcMicros, count() if none. The wall clock may
    // step backwards mid-session, so this searches the running maximum of the
    // timestamps: the answer is the first record at which the log has reached
    // that time, and it is still a binary search.
    int indexAtOrAfter(qint64 utcMicros) const;

private:
    // What open() and openLive() both begin with: whatever was open closed,
    // the file at path opened for reading, or false with errorString() set.
    bool reopen(const QString& path);

    struct Interface {
        bool ours = false;
        FrameTransport transport = FrameTransport::Serial;
        int resolution = 6;        // if_tsresol byte, 6 = microseconds
        qint64 offsetSeconds = 0;  // if_tsoffset
    };
    struct Section {
        qint64 offset = 0;
        bool bigEndian = false;
    };

    bool indexAll();
    bool parseInterface(qint64 at, quint32 length, bool be, Interface* out);
    bool parsePacket(qint64 at, quint32 length, bool be, const QVector<Interface>& interfaces);
    bool corrupt(qint64 at, const QString& what);
    bool sectionIsBigEndian(qint64 offset) const;
    // Fills r's bytes and correctedSymbols from a validated packet block.
    static void readPacket(const uchar* block, quint32 length, bool be, quint32 captured, FrameRecord& r);

    QFile m_file;
    const uchar* m_data = nullptr;  // the mapping, or m_copy's bytes
    qint64 m_size = 0;
    QByteArray m_copy;  // when the file cannot be mapped (empty, pipe)
    QVector<FrameIndexEntry> m_index;
    QVector<qint64> m_latestSoFar;  // running max of utcMicros, for seeking
    QVector<Section> m_sections;
    QString m_error;
    QByteArray m_block;  // openLive(): the one block read last, reused
    bool m_truncatedTail = false;
    int m_foreignPackets = 0;
};
