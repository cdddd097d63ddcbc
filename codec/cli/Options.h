// The rcm tool's command line: what each command was asked to do.
#pragma once

#include "codec/secure/SecureCodec.h"

#include <cstdint>
#include <optional>
#include <string>

namespace rcm::cli {

constexpr int kExitOk = 0;
constexpr int kExitFailed = 1;
constexpr int kExitMisuse = 2;

struct Options {
    std::string command;  // encode, decode, keygen, stationkey, dissector, help
    std::string file;
    std::string station;  // stationkey: the station the key signs for
    bool datagram = false;
    bool summary = false;
    std::string key;  // --key: the secure link
    std::optional<rcm::secure::Direction> direction;
    std::string replayState;
    std::optional<std::int64_t> window;  // seconds
};

// The options, or nothing with what is wrong with them in `misuse`.
std::optional<Options> parseOptions(int argc, const char* const* argv, std::string& misuse);

// The text `rcm --help` prints.
const char* helpText();

}  // namespace rcm::cli
