// rcm encode: one message in the text format to one frame or datagram.
#pragma once

#include "codec/cli/Options.h"
#include "codec/message/Message.h"

namespace rcm::cli {

// Fills ID_msg (0), time_UTC and date_UTC (the UTC clock) where the text did
// not give them.
void fillHeaderDefaults(rcm::Message& m);

// Reads the text from o.file and writes the bytes to standard output; errors
// go to standard error. Returns the exit status.
int encode(const Options& o);

}  // namespace rcm::cli
