// rcm: Remote Control Messages between the text format and bytes.
//   rcm encode [FILE] [--datagram]          text -> one 600-byte frame (or 510-byte datagram)
//   rcm decode [FILE] [--datagram] [--summary]   bytes -> text
//   rcm dissector                            the Wireshark dissector, from the item table
//   rcm keygen FILE                          a new 256-bit key for the secure link
//   rcm stationkey STATION FILE              a station's Ed25519 key for signing on a broker
// The commands live in codec/cli (`rcm --help` says what each does); this
// file only picks one.
#include "codec/cli/Decode.h"
#include "codec/cli/Encode.h"
#include "codec/cli/Keygen.h"
#include "codec/cli/Options.h"
#include "codec/dissector/WiresharkDissector.h"

#include <cstdio>
#include <string>

int main(int argc, char** argv)
{
    using namespace rcm::cli;
    std::string misuse;
    const std::optional<Options> o = parseOptions(argc, argv, misuse);
    if (!o) {
        std::fprintf(stderr, "rcm: %s\nTry 'rcm --help'.\n", misuse.c_str());
        return kExitMisuse;
    }
    if (o->command == "help") {
        std::fputs(helpText(), stdout);
        return kExitOk;
    }
    if (o->command == "encode")
        return encode(*o);
    if (o->command == "decode")
        return decode(*o);
    if (o->command == "keygen")
        return keygen(*o);
    if (o->command == "stationkey")
        return stationkey(*o);
    std::fputs(rcm::wiresharkDissectorLua().c_str(), stdout);  // dissector: the only command left
    return kExitOk;
}
