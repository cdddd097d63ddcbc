#include "codec/message/MessageEncoder.h"

#include "codec/message/ValueCodec.h"

#include <algorithm>
#include <cstring>

namespace rcm {

std::size_t block1ItemBytes(const Message& message)
{
    std::size_t total = 0;
    message.forEachUnit([&](const Unit& unit) {
        for (const ItemValue& item : unit.items())
            total += 1 + itemInfo(item.id).size;
    });
    return total;
}

std::string block1Overflow(std::size_t itemBytes, const EncodeOptions& options)
{
    const std::size_t needed = itemBytes + options.minBlock1Padding;
    if (needed <= kBlockSize)
        return {};
    std::string what = "the items need " + std::to_string(itemBytes) + " bytes";
    if (options.minBlock1Padding)
        what += " plus " + std::to_string(options.minBlock1Padding) + " bytes of required padding";
    return what + ", " + std::to_string(needed - kBlockSize) + " more than the " + std::to_string(kBlockSize) +
           " a block holds";
}

Diagnostics validate(const Message& message, const EncodeOptions& options)
{
    Diagnostics errors;
    message.forEachUnit([&](const Unit& unit) {
        if (const auto key = unitKey(unit.kind()); key && !unit.has(*key)) {
            errors.push_back({Diagnostic::Kind::MissingKey, 1, -1, describeUnit(unit),
                              "a " + std::string(sectionName(unit.kind())) + " needs its key item " +
                                  std::string(itemInfo(*key).name) + " to be sent"});
        }
        for (const ItemValue& item : unit.items()) {
            const ItemInfo& info = itemInfo(item.id);
            std::string reason = checkValue(info, item.value);
            if (!reason.empty())
                errors.push_back({Diagnostic::Kind::OutOfRange, 1, -1, describeUnit(unit) + " " + std::string(info.name),
                                  std::move(reason)});
        }
    });

    if (std::string overflow = block1Overflow(block1ItemBytes(message), options); !overflow.empty())
        errors.push_back({Diagnostic::Kind::DoesNotFit, 1, -1, "BLOCK 1", std::move(overflow)});
    const std::size_t planBytes = message.flightPlan.data.size();
    if (planBytes > options.maxFlightPlanData) {
        errors.push_back({Diagnostic::Kind::DoesNotFit, 2, -1, "flight plan section",
                          std::to_string(planBytes) + " data bytes, " +
                              std::to_string(planBytes - options.maxFlightPlanData) + " more than the " +
                              std::to_string(options.maxFlightPlanData) + " a section carries"});
    }
    return errors;
}

std::optional<EncodedBlocks> encodeBlocks(const Message& message, Diagnostics& errors, const EncodeOptions& options)
{
    errors = validate(message, options);
    if (!errors.empty())
        return std::nullopt;

    EncodedBlocks out;
    // BLOCK 1: padding first, then the items, as the seed's BLOCK 1 table lists them.
    const std::size_t itemBytes = block1ItemBytes(message);
    std::uint8_t* p = out.block1.data();
    std::memset(p, kPad55, kBlockSize - itemBytes);
    p += kBlockSize - itemBytes;
    message.forEachUnit([&](const Unit& unit) {
        for (const ItemValue& item : unit.items()) {
            const ItemInfo& info = itemInfo(item.id);
            *p++ = static_cast<std::uint8_t>(item.id);
            packValue(info, item.value, p);
            p += info.size;
        }
    });

    // BLOCK 2: x, plan ID, section ID, data, padding, End_Of_String.
    const FlightPlanSection& plan = message.flightPlan;
    std::uint8_t* q = out.block2.data();
    const std::size_t x = plan.data.size();
    q[0] = static_cast<std::uint8_t>(x);
    q[1] = static_cast<std::uint8_t>(plan.planId >> 24);
    q[2] = static_cast<std::uint8_t>(plan.planId >> 16);
    q[3] = static_cast<std::uint8_t>(plan.planId >> 8);
    q[4] = static_cast<std::uint8_t>(plan.planId);
    q[5] = static_cast<std::uint8_t>(plan.sectionId >> 8);
    q[6] = static_cast<std::uint8_t>(plan.sectionId);
    std::copy(plan.data.begin(), plan.data.end(), q + 7);
    std::memset(q + 7 + x, kPad55, FlightPlanSection::kMaxData - x);
    q[kBlockSize - 1] = 0x00;
    return out;
}

std::optional<FrameBytes> encodeFrame(const Message& message, Diagnostics& errors, const EncodeOptions& options)
{
    const auto blocks = encodeBlocks(message, errors, options);
    if (!blocks)
        return std::nullopt;
    return makeFrame(blocks->block1, blocks->block2);
}

std::optional<DatagramBytes> encodeDatagram(const Message& message, Diagnostics& errors, const EncodeOptions& options)
{
    const auto blocks = encodeBlocks(message, errors, options);
    if (!blocks)
        return std::nullopt;
    return makeDatagram(blocks->block1, blocks->block2);
}

}  // namespace rcm
