// Message -> the two 223-byte data blocks in PROFILE.md's canonical order,
// and on to a frame or datagram. Refuses, with reasons, what does not fit or
// is out of range: a frame is produced only from a fully valid message.
#pragma once

#include "codec/message/Diagnostic.h"
#include "codec/frame/Frame.h"
#include "codec/message/Message.h"

#include <cstddef>
#include <optional>
#include <string>

namespace rcm {

struct EncodeOptions {
    // Padding BLOCK 1 must keep (the secure link keeps 16 bytes as redundancy).
    std::size_t minBlock1Padding = 0;
    // Data bytes a flight plan section may carry (199 on the secure link).
    std::size_t maxFlightPlanData = FlightPlanSection::kMaxData;
};

// Bytes BLOCK 1 items of `message` take, Item_ID bytes included.
std::size_t block1ItemBytes(const Message& message);

// Why BLOCK 1 items of `itemBytes` do not fit ("the items need 242 bytes, 19
// more than the 223 a block holds"); empty when they fit.
std::string block1Overflow(std::size_t itemBytes, const EncodeOptions& options = {});

// Checks everything an encode would; empty when the message can be encoded.
Diagnostics validate(const Message& message, const EncodeOptions& options = {});

struct EncodedBlocks {
    Block block1{};
    Block block2{};
};

// Both blocks, or nothing with the reasons in `errors`.
std::optional<EncodedBlocks> encodeBlocks(const Message& message, Diagnostics& errors,
                                          const EncodeOptions& options = {});
std::optional<FrameBytes> encodeFrame(const Message& message, Diagnostics& errors, const EncodeOptions& options = {});
std::optional<DatagramBytes> encodeDatagram(const Message& message, Diagnostics& errors,
                                            const EncodeOptions& options = {});

}  // namespace rcm
