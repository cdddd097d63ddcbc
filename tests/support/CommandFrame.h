// A small valid command frame with a given ID_msg, for tests and benchmarks
// that need frames to send and care only which one arrived.
#pragma once

#include "codec/message/MessageEncoder.h"

#include <QByteArray>

#include <cstdint>

namespace rcm::test {

inline QByteArray commandFrame(std::uint32_t id)
{
    Message m;
    m.header.set(ItemId::ID_msg, std::int64_t(id));
    m.header.set(ItemId::ID_UA_source, Value::pair(44, 133));
    Diagnostics errors;
    const auto frame = encodeFrame(m, errors).value();
    return QByteArray(reinterpret_cast<const char*>(frame.data()), qsizetype(frame.size()));
}

}  // namespace rcm::test
