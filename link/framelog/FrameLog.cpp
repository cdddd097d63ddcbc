#include "link/framelog/FrameLog.h"

#include <QDebug>
#include <QDir>
#include <QFileInfo>
#include <QStandardPaths>
#include <QtEndian>

#if defined(Q_OS_WIN)
#include <io.h>
#elif defined(Q_OS_UNIX)
#include <unistd.h>
#endif

namespace {

constexpr const char* kTransportNames[] = {"serial", "udp", "replay", "simulated"};
constexpr const char* kTransportDescriptions[] = {
    "Remote Control Message frames over the serial link",
    "Remote Control Message frames over UDP",
    "Remote Control Message frames replayed from a log",
    "Remote Control Message frames from the simulator",
};
constexpr const char* kStatusNames[] = {"decoded", "corrected", "uncorrectable", "rejected", "not-checked"};
constexpr QByteArrayView kCommentPrefix = "rcm ";
constexpr QByteArrayView kSymbolsKey = "symbols=";
constexpr QByteArrayView kEncipheredWord = "enciphered";

// Always little-endian, whatever the host, so files are byte-identical
// everywhere and the tests can compare exact bytes.
template <typename Integer>
void putLittleEndian(QByteArray& b, Integer v)
{
    char c[sizeof v];
    qToLittleEndian(v, c);
    b.append(c, sizeof c);
}

// The widths named where the fields are written.
void put16(QByteArray& b, quint16 v)
{
    putLittleEndian(b, v);
}
void put32(QByteArray& b, quint32 v)
{
    putLittleEndian(b, v);
}
void put64(QByteArray& b, quint64 v)
{
    putLittleEndian(b, v);
}

void pad4(QByteArray& b)
{
    while (b.size() % 4 != 0)
        b.append('\0');
}

void putOption(QByteArray& b, quint16 code, QByteArrayView value)
{
    put16(b, code);
    put16(b, quint16(value.size()));
    b.append(value.data(), value.size());
    pad4(b);
}

void putEndOfOptions(QByteArray& b)
{
    put16(b, pcapng::kOptEnd);
    put16(b, 0);
}

qsizetype beginBlock(QByteArray& b, quint32 type)
{
    const qsizetype start = b.size();
    put32(b, type);
    put32(b, 0);  // total length, known once the block is complete
    return start;
}

void endBlock(QByteArray& b, qsizetype start)
{
    const quint32 total = quint32(b.size() - start + 4);
    put32(b, total);
    qToLittleEndian(total, b.data() + start + 4);
}

void appendSectionHeader(QByteArray& b)
{
    const qsizetype start = beginBlock(b, pcapng::kSectionHeader);
    put32(b, pcapng::kByteOrderMagic);
    put16(b, 1);  // version 1.0
    put16(b, 0);
    put64(b, ~quint64(0));  // section length unknown: the file grows while open
    putOption(b, pcapng::kOptShbUserAppl, "rcm-gcs");
    putEndOfOptions(b);
    endBlock(b, start);
}

void appendInterface(QByteArray& b, FrameTransport transport)
{
    const int t = int(transport);
    const qsizetype start = beginBlock(b, pcapng::kInterfaceDescription);
    put16(b, pcapng::kLinkTypeUser0);
    put16(b, 0);
    put32(b, quint32(FrameLog::kMaxFrameBytes));  // snaplen
    putOption(b, pcapng::kOptIfName, kTransportNames[t]);
    putOption(b, pcapng::kOptIfDescription, kTransportDescriptions[t]);
    const char microseconds = 6;
    putOption(b, pcapng::kOptIfTsResol, QByteArrayView(&microseconds, 1));
    putEndOfOptions(b);
    endBlock(b, start);
}

void appendPacket(QByteArray& b, int interfaceId, const FrameRecord& r)
{
    const qsizetype start = beginBlock(b, pcapng::kEnhancedPacket);
    put32(b, quint32(interfaceId));
    const quint64 ts = quint64(r.utcMicros);
    put32(b, quint32(ts >> 32));
    put32(b, quint32(ts));
    put32(b, quint32(r.bytes.size()));  // captured
    put32(b, quint32(r.bytes.size()));  // original: frames are never cut
    b.append(r.bytes);
    pad4(b);
    char flags[4];
    qToLittleEndian(r.direction == FrameDirection::Sent ? pcapng::kEpbOutbound : pcapng::kEpbInbound, flags);
    putOption(b, pcapng::kOptEpbFlags, QByteArrayView(flags, 4));
    putOption(b, pcapng::kOptComment, frameStatusComment(r.status, r.correctedSymbols, r.enciphered));
    putEndOfOptions(b);
    endBlock(b, start);
}

}  // namespace

QString frameTransportName(FrameTransport t)
{
    return QString::fromLatin1(kTransportNames[int(t)]);
}

QString frameStatusName(FrameStatus s)
{
    return QString::fromLatin1(kStatusNames[int(s)]);
}

QByteArray frameStatusComment(FrameStatus status, const QList<int>& correctedSymbols, bool enciphered)
{
    QByteArray c = kCommentPrefix.toByteArray() + kStatusNames[int(status)];
    if (!correctedSymbols.isEmpty()) {
        c += ' ';
        c += kSymbolsKey.toByteArray();
        for (qsizetype i = 0; i < correctedSymbols.size(); ++i) {
            if (i > 0)
                c += '/';
            c += QByteArray::number(correctedSymbols[i]);
        }
    }
    if (enciphered) {
        c += ' ';
        c += kEncipheredWord.toByteArray();
    }
    return c;
}

bool parseFrameStatusComment(QByteArrayView comment, FrameStatus* status, QList<int>* correctedSymbols,
                             bool* enciphered)
{
    if (!comment.startsWith(kCommentPrefix))
        return false;
    comment = comment.sliced(kCommentPrefix.size());
    qsizetype space = comment.indexOf(' ');
    const QByteArrayView name = space < 0 ? comment : comment.first(space);
    int found = -1;
    for (int i = 0; i < int(std::size(kStatusNames)); ++i) {
        if (name == QByteArrayView(kStatusNames[i]))
            found = i;
    }
    if (found < 0)
        return false;

    QList<int> symbols;
    QByteArrayView rest = space < 0 ? QByteArrayView() : comment.sliced(space + 1);
    if (rest.startsWith(kSymbolsKey)) {
        rest = rest.sliced(kSymbolsKey.size());
        space = rest.indexOf(' ');
        QByteArrayView numbers = space < 0 ? rest : rest.first(space);
        rest = space < 0 ? QByteArrayView() : rest.sliced(space + 1);
        for (;;) {
            const qsizetype slash = numbers.indexOf('/');
            bool ok = false;
            const int n = (slash < 0 ? numbers : numbers.first(slash)).toInt(&ok);
            if (!ok)
                return false;
            // The reader's index pass only wants the status: no allocation there.
            if (correctedSymbols)
                symbols.append(n);
            if (slash < 0)
                break;
            numbers = numbers.sliced(slash + 1);
        }
    }
    const bool keyed = rest == kEncipheredWord;
    if (!rest.isEmpty() && !keyed)
        return false;
    if (status)
        *status = FrameStatus(found);
    if (correctedSymbols)
        *correctedSymbols = std::move(symbols);
    if (enciphered)
        *enciphered = keyed;
    return true;
}

FrameLog::~FrameLog()
{
    close();
}

QString FrameLog::defaultDirectory()
{
    return QStandardPaths::writableLocation(QStandardPaths::AppDataLocation) + QStringLiteral("/framelogs");
}

QString FrameLog::sessionFileName(const QDateTime& utc, int attempt)
{
    // No colons: they are illegal in Windows file names. A second session
    // started within the same second gets "-2", and so on.
    return QStringLiteral("rcm-") + utc.toUTC().toString(QStringLiteral("yyyy-MM-dd'T'HH-mm-ss'Z'")) +
           (attempt > 1 ? QStringLiteral("-%1").arg(attempt) : QString()) + QStringLiteral(".pcapng");
}

void FrameLog::setErrorHandler(std::function<void(const QString&)> handler)
{
    m_onError = std::move(handler);
}

bool FrameLog::open(const QString& path, QString* error)
{
    close();
    m_interfaceOf.fill(-1);
    m_interfaces = 0;
    m_records = 0;
    m_written = 0;
    m_failed = false;
    m_error.clear();

    auto refuse = [&](const QString& message) {
        m_error = message;
        if (error)
            *error = message;
        return false;
    };

    const QFileInfo info(path);
    if (!QDir().mkpath(info.absolutePath())) {
        return refuse(QStringLiteral("cannot create directory %1").arg(info.absolutePath()));
    }
    m_file.setFileName(path);
    // Unbuffered: each QFile::write goes straight to write(2), so a block is
    // in the kernel (and survives our process dying) as soon as append returns.
    if (!m_file.open(QIODevice::WriteOnly | QIODevice::NewOnly | QIODevice::Unbuffered)) {
        return refuse(QStringLiteral("cannot create frame log %1: %2").arg(path, m_file.errorString()));
    }
    m_buffer.resize(0);
    appendSectionHeader(m_buffer);
    if (!writeBlocks(m_buffer)) {
        const QString message = m_error;
        m_file.close();
        m_file.remove();  // holds no frame, only a torn header
        return refuse(message);
    }
    return true;
}

bool FrameLog::append(const FrameRecord& record, qint64* offset)
{
    if (!m_file.isOpen()) {
        m_error = QStringLiteral("frame log is not open");
        return false;
    }
    if (m_failed)
        return false;
    if (int(record.transport) >= int(m_interfaceOf.size())) {
        m_error = QStringLiteral("frame with unknown transport %1").arg(int(record.transport));
        return false;
    }
    if (record.bytes.size() > kMaxFrameBytes) {
        // The file is still sound, so only this frame is refused.
        m_error = QStringLiteral("frame of %1 bytes exceeds the frame log's limit of %2")
                      .arg(record.bytes.size())
                      .arg(kMaxFrameBytes);
        return false;
    }

    m_buffer.resize(0);  // keeps the capacity
    const int t = int(record.transport);
    const bool newInterface = m_interfaceOf[t] < 0;
    // The interface block goes out in the same write as its first packet, so
    // the file never holds a packet whose interface is missing.
    if (newInterface)
        appendInterface(m_buffer, record.transport);
    const qint64 packetAt = m_written + m_buffer.size();
    appendPacket(m_buffer, newInterface ? m_interfaces : m_interfaceOf[t], record);
    if (!writeBlocks(m_buffer)) {
        fail(m_error);
        return false;
    }
    if (offset)
        *offset = packetAt;
    if (newInterface)
        m_interfaceOf[t] = m_interfaces++;
    ++m_records;
    return true;
}

bool FrameLog::writeBlocks(const QByteArray& blocks)
{
    qint64 done = 0;
    // QFile reports a short write as success; looping turns the second,
    // failing write into the real reason (disk full, file too large).
    while (done < blocks.size()) {
        const qint64 n = m_file.write(blocks.constData() + done, blocks.size() - done);
        if (n <= 0) {
            m_error = QStringLiteral("cannot write frame log %1: %2").arg(m_file.fileName(), m_file.errorString());
            return false;
        }
        done += n;
        m_written += n;
    }
    if (m_sync) {
#if defined(Q_OS_WIN)
        const bool synced = ::_commit(m_file.handle()) == 0;
#elif defined(Q_OS_UNIX)
        const bool synced = ::fsync(m_file.handle()) == 0;
#else
        const bool synced = true;
#endif
        if (!synced) {
            m_error = QStringLiteral("cannot sync frame log %1").arg(m_file.fileName());
            return false;
        }
    }
    return true;
}

void FrameLog::fail(const QString& message)
{
    m_failed = true;
    if (m_onError) {
        m_onError(message);
    } else {
        qWarning().noquote() << message;
    }
}

void FrameLog::close()
{
    if (m_file.isOpen())
        m_file.close();
}
