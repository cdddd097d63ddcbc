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

// `status` as the aircraft reports it once `command` has taken effect: every
// item the command sets, in the units the status has, takes the commanded
// value (repeated units matched by their key item: eng_ID, system_ID,
// cam_ID), and the header items the aircraft echoes (all but ID_msg,
// ID_UA_source, time_UTC and date_UTC) too. Units of the command the status
// lacks are left out; BLOCK 2 is the status's. The changes this makes are
// counted in Message::forEachUnit order, item by item; bit i of `changeMask`
// makes the i-th (the first 64), clear bits leave that item as the status
// has it (a part still moving, say).
Message withCommanded(const Message& status, const Message& command, std::uint64_t changeMask = ~std::uint64_t{0});

// How many items withCommanded would change in `status`.
int commandedChanges(const Message& status, const Message& command);

// hhmmss and yymmdd (20yy) advanced by `seconds`; false, leaving them as
// they were, when they are not a valid time and date.
bool advanceTimeAndDate(std::uint32_t& timeUtc, std::uint32_t& dateUtc, std::uint32_t seconds);

}  // namespace rcm
