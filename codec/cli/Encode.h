// rcm encode: one message in the text format to one frame or datagram.
#pragma once

#include "codec/cli/Options.h"
#include "codec/message/Message.h"

#include <array>

namespace rcm::cli {

// The header items encode fills in where the text does not give them: ID_msg
// (0), time_UTC and date_UTC (the UTC clock).
inline constexpr std::array<rcm::ItemId, 3> kHeaderDefaults{rcm::ItemId::ID_msg, rcm::ItemId::time_UTC,
                                                            rcm::ItemId::date_UTC};
void fillHeaderDefaults(rcm::Message& m);

// Reads the text from o.file and writes the bytes to standard output; errors
// go to standard error. Returns the exit status.
int encode(const Options& o);

}  // namespace rcm::cli
