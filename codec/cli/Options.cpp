#include "codec/cli/Options.h"

#include <charconv>
#include <string_view>
#include <vector>

namespace rcm::cli {
namespace {

const char* const kHelp = R"(Usage:
  rcm encode [FILE] [--datagram] [--key KEYFILE [--direction DIR]]
  rcm decode [FILE] [--datagram] [--summary]
             [--key KEYFILE [--direction DIR] [--replay-state STATE [--window SECONDS]]]
  rcm keygen KEYFILE
  rcm stationkey STATION KEYFILE
  rcm dissector
  rcm --help

encode  reads one Remote Control Message in the text format from FILE (standard
        input when FILE is absent or -) and writes one 600-byte frame to standard
        output: the 90-byte preamble and the two RS(255,223) codewords.
        --datagram writes the 510-byte UDP form (the two codewords only).
        Items given in the text are never changed. An item absent from the text
        is absent from the frame, except ID_msg (0 when not given), time_UTC and
        date_UTC (the UTC clock when not given).
        Errors name the line and column (the first 20 are listed, the rest
        counted); nothing is written then. A UTF-8 byte-order mark is skipped.

decode  reads bytes from FILE (standard input when absent or -): any number of
        frames amid other bytes, found by their preamble even with bit errors in
        it. Each frame goes through the codec's one receive path
        (codec/receive, docs/protocol.md): it is delivered only when it is
        exact (decoded with no warning, padding and header as the profile
        says) and follows the recording's earlier frames from the same sender
        (ID_msg ahead, time_UTC in step). A delivered message is printed in
        the text format, preceded by
          # frame N at byte offset X
          # block1 corrected N
          # block2 corrected N
        Any other frame is refused, never printed: standard error says
          rcm: frame N at byte offset X: refused as REASON: what and where
        (uncorrectable, enciphered when it needs a key, not exact: ...,
        replayed, implausible: ..., and the reasons under --key below).
        --datagram reads exactly one 510-byte datagram instead.
        --summary prints only the counts, refusals counted by reason.
        A FILE that is a frame log (pcapng, as gcs and uasim write them) is
        read frame by frame, both directions, each on its own:
          # frame N (sent|received) at byte offset X of the log
        and a keyed link's frame without --key is said to be enciphered.

--key KEYFILE  the secure link (docs/security.md): AES-256-HCTR2 over BLOCK 1
        and BLOCK 2 before Reed-Solomon, authenticated by the message's own
        padding and structure. KEYFILE holds 64 hex digits and must not be
        readable by anyone but its owner (chmod 600). The key is never printed.
        encode enciphers for DIR (--direction gcs-to-ua, the default, or
        ua-to-gcs). The message must then leave 16 bytes of BLOCK 1 as
        padding and carry at most 199 flight plan bytes; ID_msg, time_UTC and
        date_UTC are filled as above when absent (a receiver accepts an ID_msg
        only once, and a time within 30 s of its clock).
        decode deciphers and authenticates each frame, in DIR only or, without
        --direction, in whichever direction it was sent (named in a
        "# secure" line). A frame that does not authenticate is refused as
        forged (not sent with this key and direction) or plaintext (an
        unencrypted frame); with --replay-state also as replayed or
        stale time. Without --replay-state a recording is checked only against its
        own earlier frames, not against this machine's clock.
--replay-state STATE  decode as the receiver does: STATE holds the last
        accepted ID_msg (created when absent, updated as frames are accepted);
        a frame must be ahead of it and within --window SECONDS (default 30)
        of this machine's UTC clock. Needs --direction.

keygen  writes a new random key to KEYFILE with mode 0600 (never over an
        existing file) and prints its fingerprint, which names the key
        without revealing it; give the same file to the console and to the
        aircraft.

stationkey  writes a new Ed25519 signing key for STATION (its ID as the
        console names it, e.g. GB_30226) to KEYFILE with mode 0600, never
        over an existing file, and prints the station's trust line, its name
        and public key:
          GB_30226 3d4017c3e843895a92b70aa74d1b7ebc9c982ccf2ec4968cc0cd55f12af4660c
        The console signs what it publishes on a broker with KEYFILE
        (gcs --station GB_30226 --broker-key KEYFILE); observers and fleet
        views trust the lines gathered in a file (gcs --broker-trust FILE).
        Given a KEYFILE that exists, it prints that key's trust line and
        changes nothing. docs/security.md, "The broker".

dissector  prints the Wireshark Lua dissector generated from the item table
        (the copy in resources/wireshark/rcm.lua is this output):
          tshark -X lua_script:resources/wireshark/rcm.lua -r session.pcapng -V

Exit status: 0 when every frame was delivered (or the text encoded), 1 when
a frame was refused, none was found, or the text or key had errors, 2 for
misuse.

Example:
  printf 'ID_msg 133\nID_UA_source GB_133\nSA_zoom_FWD_cam 105\n' > cmd.txt
  rcm encode cmd.txt > cmd.bin
  rcm decode cmd.bin
)";

// What is wrong with a whole command line, or nothing.
std::string checkCombination(const Options& o)
{
    const bool secureOptions = o.direction || !o.replayState.empty() || o.window;
    if (secureOptions && o.key.empty())
        return "--direction, --replay-state and --window need --key";
    if (o.window && o.replayState.empty())
        return "--window applies with --replay-state only";
    if (!o.replayState.empty() && !o.direction)
        return "--replay-state needs --direction: the state is kept per direction";
    if (!o.key.empty() && o.command != "encode" && o.command != "decode")
        return "--key applies to encode and decode";
    if (o.command == "encode" && !o.replayState.empty())
        return "--replay-state applies to decode only";
    if (o.command == "encode" && o.summary)
        return "--summary applies to decode only";
    if (o.command == "keygen" && (o.file.empty() || o.datagram || o.summary))
        return "keygen takes one argument, the key file to create";
    if (o.command == "stationkey" && (o.file.empty() || o.station.empty() || o.datagram || o.summary))
        return "stationkey takes two arguments, the station and the key file";
    if (o.command == "dissector" && (!o.file.empty() || o.datagram || o.summary))
        return "dissector takes no arguments";
    if (o.command != "encode" && o.command != "decode" && o.command != "keygen" && o.command != "stationkey" &&
        o.command != "dissector")
        return "unknown command " + o.command;
    return {};
}

// Reads the value of an option that takes one; empty when it is fine.
std::string readValue(std::string_view option, const std::string& v, Options& o)
{
    if (option == "--key") {
        o.key = v;
    } else if (option == "--replay-state") {
        o.replayState = v;
    } else if (option == "--direction") {
        if (v == "gcs-to-ua")
            o.direction = rcm::secure::Direction::GcsToUa;
        else if (v == "ua-to-gcs")
            o.direction = rcm::secure::Direction::UaToGcs;
        else
            return "--direction is gcs-to-ua or ua-to-gcs, not " + v;
    } else {
        std::int64_t seconds = -1;
        const auto [end, ec] = std::from_chars(v.data(), v.data() + v.size(), seconds);
        if (ec != std::errc() || end != v.data() + v.size() || seconds < 0)
            return "--window takes a number of seconds, not " + v;
        o.window = seconds;
    }
    return {};
}

}  // namespace

const char* helpText()
{
    return kHelp;
}

std::optional<Options> parseOptions(int argc, const char* const* argv, std::string& misuse)
{
    Options o;
    std::vector<std::string> positional;
    for (int i = 1; i < argc; ++i) {
        const std::string_view a = argv[i];
        if (a == "--help" || a == "-h") {
            o.command = "help";
            return o;
        }
        if (a == "--datagram") {
            o.datagram = true;
        } else if (a == "--summary") {
            o.summary = true;
        } else if (a == "--key" || a == "--direction" || a == "--replay-state" || a == "--window") {
            if (i + 1 >= argc) {
                misuse = std::string(a) + " needs a value";
                return std::nullopt;
            }
            misuse = readValue(a, argv[++i], o);
            if (!misuse.empty())
                return std::nullopt;
        } else if (a.size() > 1 && a.front() == '-') {
            misuse = "unknown option " + std::string(a);
            return std::nullopt;
        } else {
            positional.emplace_back(a);
        }
    }
    if (positional.empty()) {
        misuse = "no command given";
        return std::nullopt;
    }
    const std::size_t most = positional[0] == "stationkey" ? 3 : 2;
    if (positional.size() > most) {
        misuse = "too many arguments: " + positional[most];
        return std::nullopt;
    }
    o.command = positional[0];
    if (o.command == "stationkey" && positional.size() == 3) {
        o.station = positional[1];
        o.file = positional[2];
    } else if (positional.size() >= 2) {
        o.file = positional[1];
    }
    misuse = checkCombination(o);
    if (!misuse.empty())
        return std::nullopt;
    return o;
}

}  // namespace rcm::cli
