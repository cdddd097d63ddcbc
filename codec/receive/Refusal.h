// Why the receive path (FrameReceiver) did not deliver a frame: apart, so
// that counters and logs can name the reasons without the receiver itself.
// Plain C++20, no Qt.
#pragma once

#include <cstdint>
#include <string_view>

namespace rcm {

// Why a frame was not delivered. Names (refusalName) are for logs and the
// status bar.
enum class Refusal : std::uint8_t {
    // the bytes
    Uncorrectable,      // a codeword beyond correction
    WrongSize,          // a datagram that is not 510 bytes
    Enciphered,         // no key, and the blocks look enciphered (no padding anywhere)
    Forged,             // keyed: does not authenticate in any direction given
    Plaintext,          // keyed: an unencrypted message
    // not exact
    MissingHeaderItem,  // no ID_msg, time_UTC or date_UTC
    BadPadding,         // BLOCK 1 not padding then items back to back; BLOCK 2 padding or End_Of_String
    InvalidField,       // a value out of range, a corrupt two-bit field, reserved bits set
    UnknownItem,        // an Item_ID the profile does not define, or an item cut off by the block's end
    NotCanonical,       // items not in the order the profile's encoder writes them
    Warning,            // any other diagnostic (orphan item, repeated item, unit without its key)
    // not plausible (from here on: FrameReceiver retries no prediction)
    Replayed,           // ID_msg not ahead of the last accepted from this sender
    MessageIdStep,      // ID_msg ahead by more than kMaxMessageIdStep
    TimeStep,           // time_UTC behind the last accepted, or further ahead than the ID step allows
    TimeWindow,         // live: time_UTC/date_UTC outside the window of the receiver's clock
    PlanSection,        // a flight plan section that neither continues the plan being sent nor starts one
};
inline constexpr int kRefusalCount = 16;
std::string_view refusalName(Refusal r);  // "uncorrectable", "not exact: bad padding", ...

}  // namespace rcm
