#include "codec/message/MessageDecoder.h"

#include "codec/message/ValueCodec.h"

#include <array>
#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace rcm {
namespace {

std::string hexByte(std::uint8_t b)
{
    char buf[8];
    std::snprintf(buf, sizeof buf, "0x%02X", b);
    return buf;
}

}  // namespace

void decodeBlock1(const Block& block, Message& message, Diagnostics& diagnostics, std::size_t* looseBytes)
{
    std::size_t loose = 0;
    bool itemSeen = false;
    using Kind = Diagnostic::Kind;
    // The unit that a repeated kind's items attach to: the last key seen.
    Unit* current[kUnitKindCount] = {};

    std::size_t i = 0;
    while (i < kBlockSize) {
        const std::uint8_t id = block[i];
        if (id == kPad55 || id == kPadAA || id == kEnd) {
            loose += itemSeen;
            ++i;
            continue;
        }
        if (id == kBegin) {  // BEGIN and its section byte: never sent, but harmless
            loose += itemSeen ? 2 : 0;
            i += 2;
            continue;
        }
        itemSeen = true;
        const ItemInfo* info = findItem(id);
        if (!info) {
            diagnostics.push_back({Kind::UnknownItem, 1, static_cast<int>(i), "",
                                   "unknown Item_ID " + hexByte(id) +
                                       "; the length of what follows is unknown, so the rest of the block is not read"});
            return;
        }
        if (i + 1 + info->size > kBlockSize) {
            diagnostics.push_back({Kind::Truncated, 1, static_cast<int>(i), std::string(info->name),
                                   "needs " + std::to_string(info->size) + " value bytes, only " +
                                       std::to_string(kBlockSize - i - 1) + " left in the block"});
            if (looseBytes)
                *looseBytes = loose + (kBlockSize - i);
            return;
        }
        const int offset = static_cast<int>(i);
        Value value = unpackValue(*info, &block[i + 1]);
        i += 1 + info->size;

        Unit* unit = nullptr;
        const int kindIndex = static_cast<int>(info->owner);
        if (info->key) {
            std::vector<Unit>* units = message.repeated(info->owner);
            unit = &units->emplace_back(info->owner);
            current[kindIndex] = unit;
        } else if (std::vector<Unit>* units = message.repeated(info->owner)) {
            unit = current[kindIndex];
            if (!unit) {
                diagnostics.push_back({Kind::Orphan, 1, offset, std::string(info->name),
                                       "comes before any " + std::string(itemInfo(*unitKey(info->owner)).name) +
                                           "; ignored"});
                continue;
            }
            (void)units;
        } else {
            unit = message.single(info->owner);
        }

        // Built only for a diagnostic: the clean path must stay cheap.
        auto where = [&] { return describeUnit(*unit) + " " + std::string(info->name); };
        if (info->kind == ValueKind::Fields) {
            // A corrupt field is reported and not acted on, but the item stays:
            // its other fields were read correctly. Readers check fieldCodeValid.
            std::vector<FieldProblem> problems;
            checkFields(*info, static_cast<std::uint8_t>(value.number), problems);
            for (FieldProblem& p : problems)
                diagnostics.push_back({p.field == "reserved bits" ? Kind::ReservedBits : Kind::CorruptField, 1, offset,
                                       where() + " " + p.field, p.reason + "; ignored"});
        } else if (std::string reason = checkValue(*info, value); !reason.empty()) {
            diagnostics.push_back({Kind::OutOfRange, 1, offset, where(), reason + "; ignored"});
            if (info->key)  // keep the unit so its other items attach, but without a bad key
                unit->erase(info->id);
            continue;
        }
        if (unit->set(info->id, std::move(value)))
            diagnostics.push_back({Kind::Repeated, 1, offset, where(), "given twice; the later value is kept"});
    }
    if (looseBytes)
        *looseBytes = loose;
}

void decodeBlock2(const Block& block, FlightPlanSection& section, Diagnostics& diagnostics)
{
    using Kind = Diagnostic::Kind;
    const std::size_t x = block[0];
    if (x > FlightPlanSection::kMaxData) {
        diagnostics.push_back({Kind::OutOfRange, 2, 0, "flight plan data length",
                               std::to_string(x) + " is above the maximum 215 by " + std::to_string(x - 215) +
                                   "; section ignored"});
        return;
    }
    section.planId = (std::uint32_t{block[1]} << 24) | (std::uint32_t{block[2]} << 16) |
                     (std::uint32_t{block[3]} << 8) | block[4];
    section.sectionId = static_cast<std::uint16_t>((block[5] << 8) | block[6]);
    section.data.assign(block.begin() + 7, block.begin() + 7 + static_cast<std::ptrdiff_t>(x));
    // One comparison of the whole run in the common case (every clean frame,
    // and each one the secure link authenticates, passes through here).
    static const auto kPadding = [] {
        std::array<std::uint8_t, FlightPlanSection::kMaxData> p;
        p.fill(kPad55);
        return p;
    }();
    const std::size_t padStart = 7 + x, padLength = kBlockSize - 1 - padStart;
    if (std::memcmp(&block[padStart], kPadding.data(), padLength) != 0) {
        for (std::size_t i = padStart; i < kBlockSize - 1; ++i) {
            if (block[i] != kPad55) {
                diagnostics.push_back({Kind::BadPadding, 2, static_cast<int>(i), "flight plan padding",
                                       "byte " + hexByte(block[i]) + " where padding 0x55 belongs"});
                break;
            }
        }
    }
    if (block[kBlockSize - 1] != 0x00)
        diagnostics.push_back({Kind::BadPadding, 2, static_cast<int>(kBlockSize - 1), "End_Of_String",
                               "byte " + hexByte(block[kBlockSize - 1]) + " where 0x00 belongs"});
}

DecodeResult decodeBlocks(const DecodedBlocks& blocks)
{
    DecodeResult r;
    r.corrected.block1 = blocks.corrected.block1;
    r.corrected.block2 = blocks.corrected.block2;
    if (blocks.corrected.block1 >= 0)
        decodeBlock1(blocks.block1, r.message, r.diagnostics);
    else
        r.diagnostics.push_back({Diagnostic::Kind::Uncorrectable, 1, -1, "",
                                 "more than 16 byte errors in the codeword; block not read"});
    if (blocks.corrected.block2 >= 0)
        decodeBlock2(blocks.block2, r.message.flightPlan, r.diagnostics);
    else
        r.diagnostics.push_back({Diagnostic::Kind::Uncorrectable, 2, -1, "",
                                 "more than 16 byte errors in the codeword; block not read"});
    return r;
}

DecodeResult decodeFrame(std::span<const std::uint8_t> bytes)
{
    std::size_t start = 0;
    if (bytes.size() == kFrameSize)
        start = kPreambleSize;
    else if (bytes.size() != kDatagramSize)
        throw std::invalid_argument("decodeFrame: " + std::to_string(bytes.size()) +
                                    " bytes; a frame is 600 and a datagram 510");
    return decodeBlocks(decodeCodewords(std::span<const std::uint8_t, kDatagramSize>(bytes.data() + start, kDatagramSize)));
}

}  // namespace rcm
