// The frames of a pcapng frame log, as the console and uasim write them
// (link/framelog/FrameLog.h): each Enhanced Packet Block's bytes, its
// direction (epb_flags) and whether its status comment marks it a keyed
// link's frame ("rcm ... enciphered"). Plain C++, so that `rcm decode` reads
// the console's logs without Qt. Either byte order; blocks of other types
// (Wireshark may add some) are skipped.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace rcm::cli {

struct LoggedPacket {
    std::size_t blockOffset = 0;  // of its Enhanced Packet Block in the file
    std::vector<std::uint8_t> bytes;
    enum class Direction { Unknown, Sent, Received } direction = Direction::Unknown;
    bool enciphered = false;
};

// True when `file` begins with a pcapng Section Header Block.
bool isPcapng(std::span<const std::uint8_t> file);

// The packets of `file`; false, with what and where in `error`, at the first
// block that is not well formed (the packets before it are in `out`).
bool readPcapng(std::span<const std::uint8_t> file, std::vector<LoggedPacket>& out, std::string& error);

}  // namespace rcm::cli
