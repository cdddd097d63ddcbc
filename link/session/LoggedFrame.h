#pragma once

// One frame the link logged, as the link thread tells the GUI of it: what a
// row of the frame log view shows, where its bytes are, and the bytes. With a
// frame log they are in the file, at entry.offset, and a view keeps only that
// (a day of frames would otherwise be a day of bytes held twice); the bytes
// travel here as well for whoever passes each frame on as it comes (the
// broker), so that nobody reads the file back on the GUI thread.

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
    // The frame itself.
    QByteArray bytes;

    bool inLog() const { return entry.offset >= 0; }
};

Q_DECLARE_METATYPE(LoggedFrame)
