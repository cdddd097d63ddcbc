// The one send path: a commanded message, the sender's ID_msg and an instant
// -> the exact bytes on the wire, a 600-byte serial frame or a 510-byte
// datagram, plain or keyed (PROFILE.md, docs/security.md). The link worker
// sends what it builds, `rcm encode` writes it, and the console's command
// preview shows it, so the three cannot disagree about a byte.
//
// Plain C++20, no Qt.
#pragma once

#include "codec/message/Diagnostic.h"
#include "codec/message/Message.h"
#include "codec/message/MessageEncoder.h"

#include <chrono>
#include <cstdint>
#include <vector>

namespace rcm {

namespace secure {
class SecureCodec;
}

// What the sender fills in for every frame.
struct SendStamp {
    std::uint32_t messageId = 0;  // ID_msg, 0 .. 2^24-1
    std::int64_t utcMicros = 0;   // time_UTC hhmmss and date_UTC yymmdd of this instant
};

// How the bytes go: the serial frame (with its preamble) or the UDP datagram,
// enciphered with `cipher` (the sending direction's codec) when keyed.
struct SendFormat {
    bool datagram = false;
    const secure::SecureCodec* cipher = nullptr;  // not owned; null: the plain link

    // What the encoder must keep free: the keyed link's checked padding.
    EncodeOptions encodeOptions() const;
};

// Sets ID_msg, time_UTC and date_UTC of `message` to `stamp`.
void stampMessage(Message& message, const SendStamp& stamp);

// The UTC instant of the next frame of a sender that sends on each multiple
// of `interval` after `utcMicros`: what its stamp's time and date will say.
std::int64_t nextSendMicros(std::int64_t utcMicros, std::chrono::microseconds interval);

// Why `command` cannot be sent in `format`, whatever it will be stamped
// with; empty when it can.
Diagnostics validateCommand(const Message& command, const SendFormat& format);

// The wire bytes of `message` as it stands (stamped already), or none, with
// the reasons in `errors`.
std::vector<std::uint8_t> buildFrame(const Message& message, const SendFormat& format, Diagnostics& errors);
// `command` stamped with `stamp`, then as above.
std::vector<std::uint8_t> buildFrame(const Message& command, const SendStamp& stamp, const SendFormat& format,
                                     Diagnostics& errors);

}  // namespace rcm
