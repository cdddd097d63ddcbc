#pragma once

// One frame the link logged, as the link thread tells the GUI of it: what a
// row of the frame log view shows, and where its bytes are. With a frame log
// they are in the file, at entry.offset, and are not copied into the signal:
// a day of frames would otherwise be a day of bytes held twice. Without one
// (or once the log has failed), the bytes travel here, being nowhere else.

#include "link/framelog/FrameLog.h"
#include "link/framelog/FrameLogReader.h"

#include <QByteArray>
#include <QList>
#include <QMetaType>

#include <optional>

struct LoggedFrame {
    // As FrameLogReader would index the record; offset -1: in no file.
    FrameIndexEntry entry;
    // Bytes Reed-Solomon corrected per codeword, -1 beyond correction; empty
    // for our own sends, which nothing corrected.
    QList<int> correctedSymbols;
    // ID_msg when the link knows it (frames sent, good frames received), so
    // that the view need not decode, nor can misread a secure link's ciphertext.
    std::optional<quint32> messageId;
    // The frame itself, only when entry.offset is -1.
    QByteArray bytes;

    bool inLog() const { return entry.offset >= 0; }
};

Q_DECLARE_METATYPE(LoggedFrame)
