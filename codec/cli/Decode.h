// rcm decode: frames found in a byte stream (or one datagram) to the text
// format, with what was corrected and what was refused.
#pragma once

#include "codec/cli/Options.h"

namespace rcm::cli {

// Reads o.file, prints each message (or with o.summary the counts) on
// standard output and each refused frame on standard error. Returns the
// exit status.
int decode(const Options& o);

}  // namespace rcm::cli
