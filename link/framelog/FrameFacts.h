#pragma once

// One frame's facts, stated once for the frame log (FrameRecord), its reader
// (FrameIndexEntry), what the link thread says of each frame (LoggedFrame)
// and the frame log view's rows: when, which way, over what, and how it
// fared.

#include <QtGlobal>

enum class FrameDirection : quint8 { Sent, Received };

enum class FrameTransport : quint8 { Serial, Udp, Replay, Simulated };

enum class FrameStatus : quint8 {
    Decoded,        // both codewords clean
    Corrected,      // Reed-Solomon repaired symbols
    Uncorrectable,  // Reed-Solomon gave up
    Rejected,       // decoded, then refused by a later check
    NotChecked,     // logged before or without decoding, e.g. our own sends
};

// The holders derive from it, so that a 16-byte FrameFacts leaves its last
// five bytes to the holder's own small members (FrameLogModel's 32-byte row).
struct FrameFacts {
    qint64 utcMicros = 0;  // microseconds since 1970-01-01T00:00:00Z
    FrameDirection direction = FrameDirection::Received;
    FrameTransport transport = FrameTransport::Serial;
    FrameStatus status = FrameStatus::NotChecked;
    // Sent or received over a keyed link: the bytes are ciphertext, and
    // without the key a reader says so rather than decode them as plain.
    bool enciphered = false;

    friend bool operator==(const FrameFacts&, const FrameFacts&) = default;
};
