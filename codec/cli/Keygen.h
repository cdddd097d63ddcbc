// rcm keygen: a new key for the secure link; rcm stationkey: a station's
// signing key for the broker.
#pragma once

#include "codec/cli/Options.h"

namespace rcm::cli {

// Writes a new random key to o.file (mode 0600, never over an existing file)
// and prints its fingerprint. Returns the exit status.
int keygen(const Options& o);

// Writes a new Ed25519 signing key for o.station to o.file (as keygen does)
// and prints the station's trust line, "STATION PUBLICKEYHEX"; for a file
// that exists, prints its trust line and writes nothing.
int stationkey(const Options& o);

}  // namespace rcm::cli
