#pragma once

// Session log of every Remote Control Message frame sent or received, as a
// pcapng file that Wireshark/tshark open directly and FrameLogReader indexes.
//
// Layout: one Section Header Block, then one Interface Description Block per
// transport the session actually used (written just before that transport's
// first frame, so the interface id says the transport), then one Enhanced
// Packet Block per frame. Link type 147 (LINKTYPE_USER0), microsecond
// timestamps (if_tsresol = 6), direction in epb_flags, decode status in an
// opt_comment such as "rcm corrected symbols=3/0", ending in " enciphered"
// for a keyed link's frame.

#include "link/framelog/FrameFacts.h"

#include <QByteArray>
#include <QDateTime>
#include <QFile>
#include <QList>
#include <QString>

#include <array>
#include <functional>

// The pcapng numbers both the writer and the reader depend on.
namespace pcapng {
constexpr quint32 kSectionHeader = 0x0A0D0D0A;
constexpr quint32 kInterfaceDescription = 1;
constexpr quint32 kEnhancedPacket = 6;
constexpr quint32 kByteOrderMagic = 0x1A2B3C4D;
constexpr quint16 kLinkTypeUser0 = 147;
constexpr quint16 kOptEnd = 0;
constexpr quint16 kOptComment = 1;
constexpr quint16 kOptShbUserAppl = 4;
constexpr quint16 kOptIfName = 2;
constexpr quint16 kOptIfDescription = 3;
constexpr quint16 kOptIfTsResol = 9;
constexpr quint16 kOptIfTsOffset = 14;
constexpr quint16 kOptEpbFlags = 2;
constexpr quint32 kEpbInbound = 1;  // epb_flags bits 0-1
constexpr quint32 kEpbOutbound = 2;
}  // namespace pcapng

struct FrameRecord : FrameFacts {
    QByteArray bytes;             // the whole frame: 600 serial or 510 UDP bytes
    QList<int> correctedSymbols;  // per codeword; empty when not known

    friend bool operator==(const FrameRecord&, const FrameRecord&) = default;
};

// Text names shared by the writer, the reader and the console.
QString frameTransportName(FrameTransport t);  // "serial", "udp", ...
QString frameStatusName(FrameStatus s);        // "decoded", "not-checked", ...

// The opt_comment carrying status and corrections, and its exact inverse.
QByteArray frameStatusComment(FrameStatus status, const QList<int>& correctedSymbols, bool enciphered = false);
bool parseFrameStatusComment(QByteArrayView comment, FrameStatus* status, QList<int>* correctedSymbols,
                             bool* enciphered = nullptr);

class FrameLog {
public:
    // The snaplen the interface blocks declare; real frames are 600 bytes.
    static constexpr int kMaxFrameBytes = 65535;

    FrameLog() = default;
    ~FrameLog();
    FrameLog(const FrameLog&) = delete;
    FrameLog& operator=(const FrameLog&) = delete;

    // AppDataLocation + "/framelogs"; not created until open() needs it.
    static QString defaultDirectory();
    // "rcm-2026-11-22T07-32-00Z.pcapng" for that instant (converted to UTC);
    // attempt 2 and on: "rcm-2026-11-22T07-32-00Z-2.pcapng", for a second session that second.
    static QString sessionFileName(const QDateTime& utc, int attempt = 1);

    // Creates missing directories. Refuses to overwrite an existing file: a
    // name clash means another session's log, not a stale one.
    bool open(const QString& path, QString* error = nullptr);
    // One write per record, so a killed process loses at most that record.
    // Returns false if the record was not logged. After a write failure the
    // log stays failed (a torn block must stay the last one in the file) and
    // the error handler is called once, not for every following frame.
    // `offset`, when given, receives where the record's Enhanced Packet Block
    // starts in the file (FrameIndexEntry::offset), so that whoever shows the
    // frame can read it back from there rather than keep a copy.
    bool append(const FrameRecord& record, qint64* offset = nullptr);
    void close();

    bool isOpen() const { return m_file.isOpen(); }
    bool hasFailed() const { return m_failed; }
    QString errorString() const { return m_error; }
    qint64 recordsWritten() const { return m_records; }
    qint64 bytesWritten() const { return m_written; }
    QString fileName() const { return m_file.fileName(); }

    // Off by default: the records already reach the kernel with each write,
    // and the page cache survives a killed or crashed process; fsync only adds
    // protection against power loss or a kernel crash, at a disk flush per
    // frame.
    void setSyncEveryRecord(bool on) { m_sync = on; }
    // Called once, on the first write failure; the default logs a qWarning.
    void setErrorHandler(std::function<void(const QString&)> handler);

private:
    bool writeBlocks(const QByteArray& blocks);
    void fail(const QString& message);

    QFile m_file;
    QByteArray m_buffer;                               // reused so a frame costs no allocation
    std::array<int, 4> m_interfaceOf{-1, -1, -1, -1};  // by FrameTransport
    int m_interfaces = 0;
    qint64 m_records = 0;
    qint64 m_written = 0;  // the file's size: what every complete write added
    bool m_failed = false;
    bool m_sync = false;
    QString m_error;
    std::function<void(const QString&)> m_onError;
};
