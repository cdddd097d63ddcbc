#include "codec/send/FrameBuilder.h"

#include "codec/frame/Frame.h"
#include "codec/message/DigitPairs.h"
#include "codec/secure/SecureCodec.h"

namespace rcm {
namespace {

template <std::size_t N>
std::vector<std::uint8_t> toVector(const std::array<std::uint8_t, N>& bytes)
{
    return {bytes.begin(), bytes.end()};
}

}  // namespace

EncodeOptions SendFormat::encodeOptions() const
{
    return cipher ? secure::encodeOptions() : EncodeOptions{};
}

void stampMessage(Message& message, const SendStamp& stamp)
{
    const std::chrono::sys_time<std::chrono::microseconds> instant{std::chrono::microseconds{stamp.utcMicros}};
    message.header.set(ItemId::ID_msg, std::int64_t(stamp.messageId));
    message.header.set(ItemId::time_UTC, DigitPairs::timeOf(instant).packed());
    message.header.set(ItemId::date_UTC, DigitPairs::dateOf(instant).packed());
}

std::int64_t nextSendMicros(std::int64_t utcMicros, std::chrono::microseconds interval)
{
    const std::int64_t period = interval.count();
    return (utcMicros / period + 1) * period;
}

Diagnostics validateCommand(const Message& command, const SendFormat& format)
{
    // The items the sender fills in get valid placeholders, so only the
    // operator's part is judged.
    Message probe = command;
    stampMessage(probe, SendStamp{});
    return validate(probe, format.encodeOptions());
}

std::vector<std::uint8_t> buildFrame(const Message& message, const SendFormat& format, Diagnostics& errors)
{
    if (format.cipher) {
        const std::optional<EncodedBlocks> b = format.cipher->encode(message, errors);
        if (!b)
            return {};
        return format.datagram ? toVector(makeDatagram(b->block1, b->block2))
                               : toVector(makeFrame(b->block1, b->block2));
    }
    if (format.datagram) {
        if (const auto datagram = encodeDatagram(message, errors))
            return toVector(*datagram);
    } else if (const auto frame = encodeFrame(message, errors)) {
        return toVector(*frame);
    }
    return {};
}

std::vector<std::uint8_t> buildFrame(const Message& command, const SendStamp& stamp, const SendFormat& format,
                                     Diagnostics& errors)
{
    Message stamped = command;
    stampMessage(stamped, stamp);
    return buildFrame(stamped, format, errors);
}

}  // namespace rcm
