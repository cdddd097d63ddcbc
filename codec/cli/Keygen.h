// rcm keygen: a new key for the secure link.
#pragma once

#include "codec/cli/Options.h"

namespace rcm::cli {

// Writes a new random key to o.file (mode 0600, never over an existing file)
// and prints its fingerprint. Returns the exit status.
int keygen(const Options& o);

}  // namespace rcm::cli
