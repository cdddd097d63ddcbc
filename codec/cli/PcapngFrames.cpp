#include "codec/cli/PcapngFrames.h"

#include <string_view>

namespace rcm::cli {
namespace {

constexpr std::uint32_t kSectionHeader = 0x0A0D0D0A;
constexpr std::uint32_t kEnhancedPacket = 6;
constexpr std::uint32_t kByteOrderMagic = 0x1A2B3C4D;
constexpr std::uint16_t kOptEnd = 0;
constexpr std::uint16_t kOptComment = 1;
constexpr std::uint16_t kOptEpbFlags = 2;
constexpr std::string_view kCommentPrefix = "rcm ";
constexpr std::string_view kEncipheredSuffix = " enciphered";

std::uint32_t read32(const std::uint8_t* p, bool bigEndian)
{
    return bigEndian ? std::uint32_t(p[0]) << 24 | std::uint32_t(p[1]) << 16 | std::uint32_t(p[2]) << 8 | p[3]
                     : std::uint32_t(p[3]) << 24 | std::uint32_t(p[2]) << 16 | std::uint32_t(p[1]) << 8 | p[0];
}

std::uint16_t read16(const std::uint8_t* p, bool bigEndian)
{
    return bigEndian ? std::uint16_t(p[0] << 8 | p[1]) : std::uint16_t(p[1] << 8 | p[0]);
}

std::size_t padded4(std::size_t n)
{
    return (n + 3) & ~std::size_t(3);
}

}  // namespace

bool isPcapng(std::span<const std::uint8_t> file)
{
    return file.size() >= 12 && read32(file.data(), false) == kSectionHeader;
}

bool readPcapng(std::span<const std::uint8_t> file, std::vector<LoggedPacket>& out, std::string& error)
{
    bool bigEndian = false;
    std::size_t at = 0;
    const auto fail = [&](const std::string& what) {
        error = "pcapng block at byte offset " + std::to_string(at) + ": " + what;
        return false;
    };
    while (at < file.size()) {
        if (file.size() - at < 12)
            return fail("truncated: " + std::to_string(file.size() - at) + " bytes left, a block is at least 12");
        const std::uint8_t* p = file.data() + at;
        const std::uint32_t type = read32(p, false);  // the section header's type reads the same both ways
        if (type == kSectionHeader) {
            const std::uint32_t magic = read32(p + 8, false);
            if (magic == kByteOrderMagic)
                bigEndian = false;
            else if (read32(p + 8, true) == kByteOrderMagic)
                bigEndian = true;
            else
                return fail("section header with an unknown byte-order magic");
        } else if (at == 0) {
            return fail("not a pcapng file: it does not begin with a section header");
        }
        const std::uint32_t length = read32(p + 4, bigEndian);
        if (length < 12 || length % 4 != 0 || length > file.size() - at)
            return fail("block length " + std::to_string(length) + " does not fit the file");
        if (read32(p + length - 4, bigEndian) != length)
            return fail("its trailing length differs from its leading one");
        if (read32(p, bigEndian) == kEnhancedPacket) {
            if (length < 32)
                return fail("enhanced packet block of " + std::to_string(length) + " bytes, less than 32");
            const std::uint32_t captured = read32(p + 20, bigEndian);
            if (28 + padded4(captured) + 4 > length)
                return fail("captured length " + std::to_string(captured) + " runs past the block");
            LoggedPacket packet;
            packet.blockOffset = at;
            packet.bytes.assign(p + 28, p + 28 + captured);
            for (std::size_t o = 28 + padded4(captured); o + 4 <= length - 4;) {
                const std::uint16_t code = read16(p + o, bigEndian);
                const std::uint16_t size = read16(p + o + 2, bigEndian);
                if (code == kOptEnd)
                    break;
                if (o + 4 + size > length - 4)
                    return fail("packet option runs past the block");
                const std::uint8_t* value = p + o + 4;
                if (code == kOptEpbFlags && size == 4) {
                    const std::uint32_t flags = read32(value, bigEndian) & 3;
                    packet.direction = flags == 1   ? LoggedPacket::Direction::Received
                                       : flags == 2 ? LoggedPacket::Direction::Sent
                                                    : LoggedPacket::Direction::Unknown;
                } else if (code == kOptComment) {
                    const std::string_view comment(reinterpret_cast<const char*>(value), size);
                    if (comment.starts_with(kCommentPrefix) && comment.ends_with(kEncipheredSuffix))
                        packet.enciphered = true;
                }
                o += 4 + padded4(size);
            }
            out.push_back(std::move(packet));
        }
        at += length;
    }
    return true;
}

}  // namespace rcm::cli
