// What a receiver expects its sender to send next, for decoding with a
// prediction (codec/frame/TrialDecode.h): a command or status frame repeats
// itself from one second to the next except for its counter and clock.
#pragma once

#include "codec/message/Message.h"

#include <cstdint>

namespace rcm {

// `last` as its sender would send it `seconds` later if nothing else
// changed: ID_msg + seconds (modulo 2^24), time_UTC + seconds with date_UTC
// rolled over at midnight (leap years counted); every other item and BLOCK 2
// unchanged. Items `last` lacks stay absent; a time_UTC or date_UTC that is
// not a valid time or date is left as it was.
Message advanceMessage(const Message& last, std::uint32_t seconds);

// hhmmss and yymmdd (20yy) advanced by `seconds`; false, leaving them as
// they were, when they are not a valid time and date.
bool advanceTimeAndDate(std::uint32_t& timeUtc, std::uint32_t& dateUtc, std::uint32_t seconds);

}  // namespace rcm
