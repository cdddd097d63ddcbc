#pragma once

// Hex dumps of frames for people: 16 bytes a line with the offset and the
// printable characters, split at the parts of the frame (preamble, each
// block's data and parity) so that a byte's place is read off, not counted.

#include <QByteArrayView>
#include <QList>
#include <QString>

struct HexDumpPart {
    QString title;  // "BLOCK 1 data"
    qsizetype offset = 0;
    qsizetype length = 0;
};

// The parts of a 600-byte frame or a 510-byte datagram; one untitled part
// for any other length.
QList<HexDumpPart> frameParts(qsizetype length);

// Plain text, offsets counted from the start of `bytes`. When `marked` is
// given (one flag a byte) the result is HTML instead, the marked bytes
// highlighted; the caller puts it in a <pre>.
QString hexDump(QByteArrayView bytes, const QList<HexDumpPart>& parts, const QList<bool>* marked = nullptr);
