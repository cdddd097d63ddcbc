#pragma once

// A frame log as a CSV table (RFC 4180: CRLF line ends, a field quoted when it
// holds a comma, a quote or a line break, quotes doubled), one row per frame.
//
// Columns, in this order:
//   utc                ISO 8601 with microseconds: 2026-11-22T07:32:00.000001Z
//   direction          sent, received
//   transport          serial, udp, replay, simulated (frameTransportName)
//   status             decoded, corrected, ... (frameStatusName)
//   corrected_block1   symbols Reed-Solomon corrected in each codeword, -1 when
//   corrected_block2     beyond correction; the log's own record of it, or,
//                        when the log has none (our own sends), a decode of
//                        the logged bytes
//   reading            what the receive path makes of the frame on its own
//                      (codec/receive/LoggedFrameReading.h): "read"; "refused
//                      as <reason>"; "enciphered" (a keyed link's frame and
//                      no key given); "not a frame" (neither 600 nor 510 bytes)
//   <unit>.<item>      one column per item of each unit present anywhere in
//                      the log, named by describeUnit: "HEADER.ID_msg",
//                      "engine 1.eng_prop_pitch", "radio VHF1.Rx_freq",
//                      "camera SNY 1.ID_GCS_destination"; then the flight
//                      plan's "FLIGHT_PLAN.flight_plan_ID" ... when any frame
//                      carries one
//
// Item columns follow the canonical order: units by kind as the item table
// orders them, repeated units sorted by their key (engine 2 before engine 10),
// a unit without a readable key after the keyed ones, items in canonical
// order. So a column's name and place depend only on which units the log
// holds, never on the order frames list them in. A second unit with the same
// key in one frame gets "#2" after its name ("engine 1#2.eng_ID").
//
// Values are exactly what the text format (formatMessage) prints for the
// item; a cell is empty when the frame did not carry the item or could not be
// read at all (enciphered, not a frame). A refused frame of the plain link
// shows what could be read, its reading column saying it was refused.

#include <QIODevice>
#include <QString>

namespace rcm {
class LogKey;
}

// Reads the log twice (once for the columns, once for the rows), holding one
// frame at a time, so a day-long log exports in constant memory. On a log
// whose structure is corrupt part-way, the records before the fault are
// exported and the function still returns false with the reader's reason.
// `key`, when given, reads a keyed link's frames.
bool exportFrameLogCsv(const QString& pcapngPath, QIODevice& out, QString* error = nullptr,
                       const rcm::LogKey* key = nullptr);
