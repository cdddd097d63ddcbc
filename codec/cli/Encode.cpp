#include "codec/cli/Encode.h"

#include "codec/message/DigitPairs.h"

#include "codec/cli/InputFile.h"
#include "codec/message/TextFormat.h"
#include "codec/secure/SecureCodec.h"
#include "codec/send/FrameBuilder.h"

#include <chrono>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <ctime>

namespace rcm::cli {

void fillHeaderDefaults(rcm::Message& m)
{
    static_assert(kHeaderDefaults.size() == 3, "the items filled in below");
    using rcm::ItemId;
    if (!m.header.has(ItemId::ID_msg))
        m.header.set(ItemId::ID_msg, 0);
    const auto now = std::chrono::system_clock::now();
    if (!m.header.has(ItemId::time_UTC))
        m.header.set(ItemId::time_UTC, rcm::DigitPairs::timeOf(now).packed());
    if (!m.header.has(ItemId::date_UTC))
        m.header.set(ItemId::date_UTC, rcm::DigitPairs::dateOf(now).packed());
}

int encode(const Options& o)
{
    std::vector<std::uint8_t> input;
    std::string error;
    if (!readAll(o.file, input, error)) {
        std::fprintf(stderr, "rcm: %s\n", error.c_str());
        return kExitFailed;
    }
    const std::string_view text(reinterpret_cast<const char*>(input.data()), input.size());
    const std::string name = inputName(o.file);
    rcm::ParseResult parsed =
        rcm::parseMessage(text, o.key.empty() ? rcm::EncodeOptions{} : rcm::secure::encodeOptions(), kHeaderDefaults);
    if (!parsed.ok()) {
        // file:line:column: as compilers write it, so editors can jump there.
        for (const rcm::Diagnostic& d : parsed.errors)
            std::fprintf(stderr, "%s:%d:%d: %s%s%s\n", name.c_str(), d.line, d.column, d.where.c_str(),
                         d.where.empty() ? "" : ": ", d.message.c_str());
        if (parsed.unlistedErrors > 0)
            std::fprintf(stderr, "%s: %zu more errors not listed\n", name.c_str(), parsed.unlistedErrors);
        return kExitFailed;
    }
    fillHeaderDefaults(parsed.message);
    std::optional<rcm::secure::SecretKey> key;
    if (!o.key.empty()) {
        key = rcm::secure::readKeyFile(o.key, error);
        if (!key) {
            std::fprintf(stderr, "rcm: %s\n", error.c_str());
            return kExitFailed;
        }
    }
    std::optional<rcm::secure::SecureCodec> cipher;
    if (key)
        cipher.emplace(*key, o.direction.value_or(rcm::secure::Direction::GcsToUa));
    rcm::Diagnostics errors;
    const std::vector<std::uint8_t> bytes =
        rcm::buildFrame(parsed.message, rcm::SendFormat{o.datagram, cipher ? &*cipher : nullptr}, errors);
    if (bytes.empty()) {
        for (const rcm::Diagnostic& d : errors)
            std::fprintf(stderr, "%s: %s\n", name.c_str(), d.toString().c_str());
        return kExitFailed;
    }
    if (isatty(STDOUT_FILENO)) {
        std::fprintf(stderr, "rcm: not writing binary to a terminal; redirect standard output (> frame.bin)\n");
        return kExitMisuse;
    }
    if (std::fwrite(bytes.data(), 1, bytes.size(), stdout) != bytes.size() || std::fflush(stdout) != 0) {
        std::fprintf(stderr, "rcm: cannot write standard output: %s\n", std::strerror(errno));
        return kExitFailed;
    }
    return kExitOk;
}

}  // namespace rcm::cli
