#include "ui/framelog/HexDump.h"

#include "codec/frame/Frame.h"

#include <algorithm>

QList<HexDumpPart> frameParts(qsizetype length)
{
    const qsizetype block = qsizetype(rcm::kBlockSize);
    const qsizetype parity = qsizetype(rcm::kCodewordSize - rcm::kBlockSize);
    qsizetype at = 0;
    QList<HexDumpPart> parts;
    if (length == qsizetype(rcm::kFrameSize)) {
        parts.append({QStringLiteral("Preamble"), 0, qsizetype(rcm::kPreambleSize)});
        at = qsizetype(rcm::kPreambleSize);
    } else if (length != qsizetype(rcm::kDatagramSize)) {
        return {{QString(), 0, length}};
    }
    parts.append({QStringLiteral("BLOCK 1 data"), at, block});
    parts.append({QStringLiteral("BLOCK 1 parity"), at + block, parity});
    at += block + parity;
    parts.append({QStringLiteral("BLOCK 2 data"), at, block});
    parts.append({QStringLiteral("BLOCK 2 parity"), at + block, parity});
    return parts;
}

QString hexDump(QByteArrayView bytes, const QList<HexDumpPart>& parts, const QList<bool>* marked)
{
    constexpr qsizetype kPerLine = 16;
    static const char kHex[] = "0123456789ABCDEF";
    const bool html = marked != nullptr;
    const auto isMarked = [&](qsizetype i) { return html && i < marked->size() && (*marked)[i]; };
    const auto escaped = [&](char c) -> QString {
        if (c < 0x20 || c > 0x7E)
            return QStringLiteral(".");
        if (!html)
            return QString(QLatin1Char(c));
        if (c == '<')
            return QStringLiteral("&lt;");
        if (c == '>')
            return QStringLiteral("&gt;");
        if (c == '&')
            return QStringLiteral("&amp;");
        return QString(QLatin1Char(c));
    };
    const QString markOn = QStringLiteral("<span style=\"background-color:#ffe08a; color:black\">");
    const QString markOff = QStringLiteral("</span>");

    QString out;
    out.reserve(bytes.size() * 5 + parts.size() * 40);
    for (const HexDumpPart& part : parts) {
        if (!part.title.isEmpty()) {
            if (!out.isEmpty())
                out += QLatin1Char('\n');
            const QString title = QStringLiteral("%1 (%2 bytes)").arg(part.title).arg(part.length);
            out += html ? QStringLiteral("<b>%1</b>\n").arg(title) : title + QLatin1Char('\n');
        }
        const qsizetype end = std::min(part.offset + part.length, bytes.size());
        for (qsizetype line = part.offset; line < end; line += kPerLine) {
            out += QStringLiteral("%1  ").arg(line, 4, 16, QLatin1Char('0')).toUpper();
            QString text;
            for (qsizetype i = line; i < line + kPerLine; ++i) {
                if (i == line + kPerLine / 2)
                    out += QLatin1Char(' ');
                if (i >= end) {
                    out += QStringLiteral("   ");
                    continue;
                }
                const auto b = static_cast<unsigned char>(bytes[i]);
                const QString hex = QString(QLatin1Char(kHex[b >> 4])) + QLatin1Char(kHex[b & 0xF]);
                if (isMarked(i)) {
                    out += markOn + hex + markOff + QLatin1Char(' ');
                    text += markOn + escaped(char(b)) + markOff;
                } else {
                    out += hex + QLatin1Char(' ');
                    text += escaped(char(b));
                }
            }
            out += QLatin1Char(' ') + text + QLatin1Char('\n');
        }
    }
    return out;
}
