#include "link/framelog/FrameLogReader.h"

#include <QtEndian>

#include <algorithm>
#include <limits>

namespace {

// A torn tail block can only be as long as something a writer produces; a
// longer claim past the end of the file is corruption, not truncation.
constexpr quint32 kMaxTornBlock = 16 * 1024 * 1024;

quint16 rd16(const uchar* p, bool be)
{
    return be ? qFromBigEndian<quint16>(p) : qFromLittleEndian<quint16>(p);
}

quint32 rd32(const uchar* p, bool be)
{
    return be ? qFromBigEndian<quint32>(p) : qFromLittleEndian<quint32>(p);
}

quint64 rd64(const uchar* p, bool be)
{
    return be ? qFromBigEndian<quint64>(p) : qFromLittleEndian<quint64>(p);
}

qint64 padded4(qint64 n)
{
    return (n + 3) & ~qint64(3);
}

QString hex32(quint32 v)
{
    return QStringLiteral("0x%1").arg(v, 8, 16, QLatin1Char('0'));
}

// Calls f(code, value) for each option in [begin, end); false if an option
// runs past end.
template <typename F>
bool forEachOption(const uchar* begin, const uchar* end, bool be, F&& f)
{
    const uchar* o = begin;
    while (end - o >= 4) {
        const quint16 code = rd16(o, be);
        const quint16 length = rd16(o + 2, be);
        if (code == pcapng::kOptEnd)
            return true;
        if (end - o - 4 < padded4(length))
            return false;
        f(code, QByteArrayView(reinterpret_cast<const char*>(o + 4), length));
        o += 4 + padded4(length);
    }
    return true;
}

qint64 pow10(int n)
{
    qint64 v = 1;
    while (n-- > 0)
        v *= 10;
    return v;
}

qint64 toMicros(quint64 ts, int resolution, qint64 offsetSeconds)
{
    qint64 us = 0;
    if (resolution & 0x80) {
        int bits = resolution & 0x7f;
        const quint64 whole = ts >> bits;
        quint64 fraction = bits ? ts & ((quint64(1) << bits) - 1) : 0;
        // fraction * 10^6 has to fit in 64 bits; 40 bits is far below a
        // microsecond anyway.
        if (bits > 40) {
            fraction >>= bits - 40;
            bits = 40;
        }
        us = qint64(whole * 1000000 + ((fraction * 1000000) >> bits));
    } else if (resolution == 6) {
        us = qint64(ts);  // keeps our own pre-1970 timestamps exact
    } else if (resolution < 6) {
        us = qint64(ts * quint64(pow10(6 - resolution)));
    } else {
        us = qint64(ts / quint64(pow10(resolution - 6)));
    }
    // Unsigned so that a hostile if_tsoffset wraps instead of being undefined.
    return qint64(quint64(us) + quint64(offsetSeconds) * 1000000u);
}

}  // namespace

bool FrameLogReader::reopen(const QString& path)
{
    close();
    m_file.setFileName(path);
    if (!m_file.open(QIODevice::ReadOnly)) {
        m_error = QStringLiteral("cannot open frame log %1: %2").arg(path, m_file.errorString());
        return false;
    }
    return true;
}

bool FrameLogReader::open(const QString& path)
{
    if (!reopen(path))
        return false;
    m_size = m_file.size();
    if (m_size > 0) {
        m_data = m_file.map(0, m_size);
        if (!m_data) {
            m_copy = m_file.readAll();
            m_data = reinterpret_cast<const uchar*>(m_copy.constData());
            m_size = m_copy.size();
        }
    }
    // Created, then killed before the section header got out.
    if (m_size == 0)
        m_truncatedTail = true;
    m_index.reserve(m_size / 600 + 1);  // a guess: serial frames dominate
    const bool ok = indexAll();
    m_latestSoFar.resize(m_index.size());
    qint64 latest = std::numeric_limits<qint64>::min();
    for (qsizetype i = 0; i < m_index.size(); ++i) {
        latest = std::max(latest, m_index[i].utcMicros);
        m_latestSoFar[i] = latest;
    }
    return ok;
}

bool FrameLogReader::openLive(const QString& path)
{
    if (!reopen(path))
        return false;
    // FrameLog writes its section header before anything else, in one write.
    uchar header[12];
    if (m_file.read(reinterpret_cast<char*>(header), sizeof header) != qint64(sizeof header) ||
        qFromLittleEndian<quint32>(header) != pcapng::kSectionHeader) {
        m_error = QStringLiteral("frame log %1 does not start with a section header block").arg(path);
        m_file.close();
        return false;
    }
    const quint32 magic = qFromLittleEndian<quint32>(header + 8);
    if (magic != pcapng::kByteOrderMagic && magic != qbswap(pcapng::kByteOrderMagic)) {
        m_error = QStringLiteral("frame log %1: section header has byte-order magic %2").arg(path, hex32(magic));
        m_file.close();
        return false;
    }
    m_sections.append({0, magic != pcapng::kByteOrderMagic});
    return true;
}

void FrameLogReader::close()
{
    if (m_file.isOpen())
        m_file.close();  // also unmaps
    m_data = nullptr;
    m_size = 0;
    m_copy.clear();
    m_block.clear();
    m_index.clear();
    m_latestSoFar.clear();
    m_sections.clear();
    m_error.clear();
    m_truncatedTail = false;
    m_foreignPackets = 0;
}

bool FrameLogReader::corrupt(qint64 at, const QString& what)
{
    m_error = QStringLiteral("frame log %1: corrupt at byte offset %2: %3").arg(m_file.fileName()).arg(at).arg(what);
    return false;
}

bool FrameLogReader::indexAll()
{
    static constexpr uchar kShbType[4] = {0x0A, 0x0D, 0x0D, 0x0A};
    QVector<Interface> interfaces;
    bool inSection = false;
    bool be = false;
    qint64 at = 0;
    while (at < m_size) {
        const uchar* p = m_data + at;
        const qint64 left = m_size - at;
        if (!inSection && !std::equal(p, p + std::min<qint64>(left, 4), kShbType)) {
            return corrupt(at, QStringLiteral("not a pcapng file: it does not start with a "
                                              "section header block"));
        }
        if (left < 12) {  // too short for any block: the writer died in its header
            m_truncatedTail = true;
            return true;
        }
        const quint32 type = rd32(p, be);  // the section header's type reads the same both ways
        if (type == pcapng::kSectionHeader) {
            const quint32 magic = qFromLittleEndian<quint32>(p + 8);
            if (magic == pcapng::kByteOrderMagic) {
                be = false;
            } else if (magic == qbswap(pcapng::kByteOrderMagic)) {
                be = true;
            } else {
                return corrupt(at, QStringLiteral("section header has byte-order magic %1, "
                                                  "expected 0x1a2b3c4d either way round")
                                       .arg(hex32(magic)));
            }
        }
        const quint32 length = rd32(p + 4, be);
        if (length < 12 || length % 4 != 0) {
            return corrupt(at,
                           QStringLiteral("block type %1 has invalid total length %2").arg(hex32(type)).arg(length));
        }
        if (length > left) {
            const bool packetFits =
                type != pcapng::kEnhancedPacket || left < 24 || 32 + padded4(rd32(p + 20, be)) <= qint64(length);
            if (length <= kMaxTornBlock && packetFits) {
                m_truncatedTail = true;
                return true;
            }
            return corrupt(at, QStringLiteral("block type %1 claims total length %2 but only %3 "
                                              "bytes are left in the file")
                                   .arg(hex32(type))
                                   .arg(length)
                                   .arg(left));
        }
        const quint32 trailer = rd32(p + length - 4, be);
        if (trailer != length) {
            return corrupt(at, QStringLiteral("block type %1 has total length %2 at its start "
                                              "but %3 at its end")
                                   .arg(hex32(type))
                                   .arg(length)
                                   .arg(trailer));
        }

        switch (type) {
            case pcapng::kSectionHeader: {
                if (length < 28)
                    return corrupt(at, QStringLiteral("section header too short"));
                const quint16 major = rd16(p + 12, be);
                if (major != 1) {
                    return corrupt(at, QStringLiteral("unsupported pcapng version %1").arg(major));
                }
                inSection = true;
                interfaces.clear();  // interface ids restart in each section
                m_sections.append({at, be});
                break;
            }
            case pcapng::kInterfaceDescription: {
                Interface ifc;
                if (!parseInterface(at, length, be, &ifc))
                    return false;
                interfaces.append(ifc);
                break;
            }
            case pcapng::kEnhancedPacket:
                if (!parsePacket(at, length, be, interfaces))
                    return false;
                break;
            default:  // statistics, name resolution, custom blocks: not ours to read
                break;
        }
        at += length;
    }
    return true;
}

bool FrameLogReader::parseInterface(qint64 at, quint32 length, bool be, Interface* out)
{
    const uchar* p = m_data + at;
    if (length < 20)
        return corrupt(at, QStringLiteral("interface description too short"));
    const quint16 linkType = rd16(p + 8, be);
    bool named = false;
    const bool optionsOk = forEachOption(p + 16, p + length - 4, be, [&](quint16 code, QByteArrayView value) {
        if (code == pcapng::kOptIfName) {
            for (int t = 0; t <= int(FrameTransport::Simulated); ++t) {
                if (value == frameTransportName(FrameTransport(t)).toLatin1()) {
                    out->transport = FrameTransport(t);
                    named = true;
                }
            }
        } else if (code == pcapng::kOptIfTsResol && value.size() >= 1) {
            out->resolution = uchar(value[0]);
        } else if (code == pcapng::kOptIfTsOffset && value.size() == 8) {
            out->offsetSeconds = qint64(rd64(reinterpret_cast<const uchar*>(value.data()), be));
        }
    });
    if (!optionsOk) {
        return corrupt(at, QStringLiteral("interface description option runs past the block"));
    }
    const bool binary = out->resolution & 0x80;
    if ((binary && (out->resolution & 0x7f) > 63) || (!binary && out->resolution > 18)) {
        return corrupt(at, QStringLiteral("unsupported if_tsresol %1").arg(out->resolution));
    }
    out->ours = linkType == pcapng::kLinkTypeUser0 && named;
    return true;
}

bool FrameLogReader::parsePacket(qint64 at, quint32 length, bool be, const QVector<Interface>& interfaces)
{
    const uchar* p = m_data + at;
    if (length < 32)
        return corrupt(at, QStringLiteral("enhanced packet block too short"));
    const quint32 interfaceId = rd32(p + 8, be);
    if (interfaceId >= quint32(interfaces.size())) {
        return corrupt(at, QStringLiteral("packet names interface %1 but the section describes %2")
                               .arg(interfaceId)
                               .arg(interfaces.size()));
    }
    const quint32 captured = rd32(p + 20, be);
    if (32 + padded4(captured) > qint64(length)) {
        return corrupt(at, QStringLiteral("packet of %1 bytes does not fit its block of %2").arg(captured).arg(length));
    }
    const Interface& ifc = interfaces[interfaceId];
    if (!ifc.ours) {
        ++m_foreignPackets;
        return true;
    }

    FrameIndexEntry e;
    e.offset = at;
    e.length = captured;
    e.transport = ifc.transport;
    const quint64 ts = (quint64(rd32(p + 12, be)) << 32) | rd32(p + 16, be);
    e.utcMicros = toMicros(ts, ifc.resolution, ifc.offsetSeconds);
    bool statusFound = false;
    const bool optionsOk =
        forEachOption(p + 28 + padded4(captured), p + length - 4, be, [&](quint16 code, QByteArrayView value) {
            if (code == pcapng::kOptEpbFlags && value.size() == 4) {
                const quint32 flags = rd32(reinterpret_cast<const uchar*>(value.data()), be);
                e.direction = (flags & 3) == pcapng::kEpbOutbound ? FrameDirection::Sent : FrameDirection::Received;
            } else if (code == pcapng::kOptComment && !statusFound) {
                // Someone may have added their own comments in Wireshark.
                statusFound = parseFrameStatusComment(value, &e.status, nullptr, &e.enciphered);
            }
        });
    if (!optionsOk)
        return corrupt(at, QStringLiteral("packet option runs past the block"));
    m_index.append(e);
    return true;
}

bool FrameLogReader::sectionIsBigEndian(qint64 offset) const
{
    auto it = std::upper_bound(m_sections.cbegin(), m_sections.cend(), offset,
                               [](qint64 o, const Section& s) { return o < s.offset; });
    return it != m_sections.cbegin() && std::prev(it)->bigEndian;
}

FrameRecord FrameLogReader::recordAt(int i) const
{
    FrameRecord r;
    if (i < 0 || i >= m_index.size())
        return r;
    const FrameIndexEntry& e = m_index[i];
    const uchar* p = m_data + e.offset;
    const bool be = sectionIsBigEndian(e.offset);
    static_cast<FrameFacts&>(r) = e;
    // Validated while indexing, so the block needs no check here.
    readPacket(p, rd32(p + 4, be), be, e.length, r);
    return r;
}

void FrameLogReader::readPacket(const uchar* block, quint32 length, bool be, quint32 captured, FrameRecord& r)
{
    r.bytes = QByteArray(reinterpret_cast<const char*>(block + 28), qsizetype(captured));
    r.correctedSymbols.clear();
    bool found = false;
    forEachOption(block + 28 + padded4(captured), block + length - 4, be, [&](quint16 code, QByteArrayView value) {
        if (code == pcapng::kOptComment && !found) {
            found = parseFrameStatusComment(value, nullptr, &r.correctedSymbols, &r.enciphered);
        }
    });
}

std::optional<FrameRecord> FrameLogReader::recordAt(const FrameIndexEntry& entry)
{
    const auto refuse = [&](const QString& what) -> std::optional<FrameRecord> {
        m_error = QStringLiteral("frame log %1: no frame of %2 bytes at byte offset %3: %4")
                      .arg(m_file.fileName())
                      .arg(entry.length)
                      .arg(entry.offset)
                      .arg(what);
        return std::nullopt;
    };
    if (!m_file.isOpen())
        return refuse(QStringLiteral("the log is not open"));
    if (entry.offset < 0)
        return refuse(QStringLiteral("no such offset"));
    const bool be = sectionIsBigEndian(entry.offset);
    const uchar* block = nullptr;
    qint64 available = 0;  // bytes of the file from entry.offset on that block may use
    if (m_data && entry.offset <= m_size - 12) {
        block = m_data + entry.offset;
        available = m_size - entry.offset;
    } else {
        // Not mapped (openLive), or past the mapping: the header, then the
        // rest of the block once its length is known.
        m_block.resize(8);
        if (!m_file.seek(entry.offset) || m_file.read(m_block.data(), 8) != 8)
            return refuse(QStringLiteral("past the end of the file"));
        const quint32 length = rd32(reinterpret_cast<const uchar*>(m_block.constData()) + 4, be);
        if (length < 32 || length % 4 != 0 || length > kMaxTornBlock)
            return refuse(QStringLiteral("block length %1").arg(length));
        m_block.resize(length);
        if (m_file.read(m_block.data() + 8, length - 8) != qint64(length) - 8)
            return refuse(QStringLiteral("the block is cut short"));
        block = reinterpret_cast<const uchar*>(m_block.constData());
        available = length;
    }
    const quint32 type = rd32(block, be);
    const quint32 length = rd32(block + 4, be);
    if (type != pcapng::kEnhancedPacket)
        return refuse(QStringLiteral("block type %1 is not an enhanced packet").arg(hex32(type)));
    if (length < 32 || length % 4 != 0 || length > available)
        return refuse(QStringLiteral("block length %1").arg(length));
    if (rd32(block + length - 4, be) != length)
        return refuse(QStringLiteral("the block's trailing length differs"));
    const quint32 captured = rd32(block + 20, be);
    if (captured != entry.length || 32 + padded4(captured) > qint64(length))
        return refuse(QStringLiteral("the packet there has %1 bytes").arg(captured));
    FrameRecord r;
    static_cast<FrameFacts&>(r) = entry;
    readPacket(block, length, be, captured, r);
    return r;
}

QVector<FrameRecord> FrameLogReader::readAll() const
{
    QVector<FrameRecord> all;
    all.reserve(m_index.size());
    for (int i = 0; i < count(); ++i)
        all.append(recordAt(i));
    return all;
}

int FrameLogReader::indexAtOrAfter(qint64 utcMicros) const
{
    return int(std::lower_bound(m_latestSoFar.cbegin(), m_latestSoFar.cend(), utcMicros) - m_latestSoFar.cbegin());
}
