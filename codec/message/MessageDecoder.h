// The two data blocks, a frame or a datagram -> Message. Reads everything it
// can: each problem becomes a Diagnostic saying what and where, and every item
// read correctly before or after it is kept.
//
// Internal to codec/: the receive path (codec/receive) and the secure codec
// read blocks with it, and the codec's own tests. Nothing outside codec/
// includes it: a frame is read through codec/receive (FrameReceiver for a
// link, readLoggedFrame for a logged frame), which also decides whether it
// is accepted. Its result type is public, in DecodeResult.h.
#pragma once

#include "codec/message/DecodeResult.h"

#include <span>

namespace rcm {

// `looseBytes`, when given, receives the count of bytes after the first item
// that are not items (padding, BEGIN, END between or after items): 0 means
// the items run back to back to the end of the block, as an encoder writes
// them. The secure link requires that.
void decodeBlock1(const Block& block, Message& message, Diagnostics& diagnostics,
                  std::size_t* looseBytes = nullptr);
void decodeBlock2(const Block& block, FlightPlanSection& section, Diagnostics& diagnostics);

// Parses blocks already RS-decoded (and deciphered, on a secure link).
DecodeResult decodeBlocks(const DecodedBlocks& blocks);

// RS-decodes and parses. `bytes` is a 600-byte frame (preamble not checked:
// the stream synchroniser found it) or a 510-byte datagram. When a codeword is
// beyond correction its block is not parsed, and a diagnostic says so.
DecodeResult decodeFrame(std::span<const std::uint8_t> bytes);

}  // namespace rcm
