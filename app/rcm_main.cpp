// rcm: Remote Control Messages between the text format and bytes.
//   rcm encode [FILE] [--datagram]          text -> one 600-byte frame (or 510-byte datagram)
//   rcm decode [FILE] [--datagram] [--summary]   bytes -> text
//   rcm dissector                            the Wireshark dissector, from the item table
// Plain C++ over the codec, so it runs wherever the codec does.
#include "codec/MessageDecoder.h"
#include "codec/MessageEncoder.h"
#include "codec/StreamSync.h"
#include "codec/TextFormat.h"
#include "codec/WiresharkDissector.h"

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <string>
#include <string_view>
#include <vector>

namespace {

constexpr int kExitOk = 0;
constexpr int kExitFailed = 1;
constexpr int kExitMisuse = 2;

const char* const kHelp = R"(Usage:
  rcm encode [FILE] [--datagram]
  rcm decode [FILE] [--datagram] [--summary]
  rcm dissector
  rcm --help

encode  reads one Remote Control Message in the text format from FILE (standard
        input when FILE is absent or -) and writes one 600-byte frame to standard
        output: the 90-byte preamble and the two RS(255,223) codewords.
        --datagram writes the 510-byte UDP form (the two codewords only).
        Items given in the text are never changed. An item absent from the text
        is absent from the frame, except ID_msg (0 when not given), time_UTC and
        date_UTC (the UTC clock when not given).
        Errors name the line and column; nothing is written then.

decode  reads bytes from FILE (standard input when absent or -): any number of
        frames amid other bytes, found by their preamble even with bit errors in
        it. Each decoded message is printed in the text format, preceded by
          # frame N at byte offset X
          # block1 corrected N
          # block2 corrected N
        and a "# warning:" line for anything inside that was not acted on.
        A frame beyond correction is reported on standard error, not printed.
        --datagram reads exactly one 510-byte datagram instead.
        --summary prints only the counts.

dissector  prints the Wireshark Lua dissector generated from the item table
        (the copy in resources/wireshark/rcm.lua is this output):
          tshark -X lua_script:resources/wireshark/rcm.lua -r session.pcapng -V

Exit status: 0 when everything decoded (or encoded), 1 when a frame was
uncorrectable, none was found, or the text had errors, 2 for misuse.

Example:
  printf 'ID_msg 133\nID_UA_source GB_133\nSA_zoom_FWD_cam 105\n' > cmd.txt
  rcm encode cmd.txt > cmd.bin
  rcm decode cmd.bin
)";

int misuse(const std::string& what)
{
    std::fprintf(stderr, "rcm: %s\nTry 'rcm --help'.\n", what.c_str());
    return kExitMisuse;
}

// Reads a whole file (or standard input for "" and "-") into `out`.
bool readAll(const std::string& path, std::vector<std::uint8_t>& out, std::string& error)
{
    std::FILE* f = path.empty() || path == "-" ? stdin : std::fopen(path.c_str(), "rb");
    if (!f) {
        error = "cannot open " + path + ": " + std::strerror(errno);
        return false;
    }
    std::uint8_t buf[1 << 16];
    std::size_t n;
    while ((n = std::fread(buf, 1, sizeof buf, f)) > 0)
        out.insert(out.end(), buf, buf + n);
    const bool failed = std::ferror(f);
    if (f != stdin)
        std::fclose(f);
    if (failed) {
        error = "cannot read " + (path.empty() ? std::string("standard input") : path);
        return false;
    }
    return true;
}

struct Options {
    std::string command;
    std::string file;
    bool datagram = false;
    bool summary = false;
};

// Fills ID_msg, time_UTC and date_UTC where the text did not give them.
void fillHeaderDefaults(rcm::Message& m)
{
    using rcm::ItemId;
    if (!m.header.has(ItemId::ID_msg))
        m.header.set(ItemId::ID_msg, 0);
    const std::time_t now = std::time(nullptr);
    std::tm utc{};
    gmtime_r(&now, &utc);
    if (!m.header.has(ItemId::time_UTC))
        m.header.set(ItemId::time_UTC, utc.tm_hour * 10000 + utc.tm_min * 100 + std::min(utc.tm_sec, 59));
    if (!m.header.has(ItemId::date_UTC))
        m.header.set(ItemId::date_UTC, (utc.tm_year % 100) * 10000 + (utc.tm_mon + 1) * 100 + utc.tm_mday);
}

int encode(const Options& o)
{
    if (o.summary)
        return misuse("--summary applies to decode only");
    std::vector<std::uint8_t> input;
    std::string error;
    if (!readAll(o.file, input, error)) {
        std::fprintf(stderr, "rcm: %s\n", error.c_str());
        return kExitFailed;
    }
    const std::string_view text(reinterpret_cast<const char*>(input.data()), input.size());
    const std::string name = o.file.empty() || o.file == "-" ? "<stdin>" : o.file;
    rcm::ParseResult parsed = rcm::parseMessage(text);
    if (!parsed.ok()) {
        // file:line:column: as compilers write it, so editors can jump there.
        for (const rcm::Diagnostic& d : parsed.errors)
            std::fprintf(stderr, "%s:%d:%d: %s%s%s\n", name.c_str(), d.line, d.column, d.where.c_str(),
                         d.where.empty() ? "" : ": ", d.message.c_str());
        return kExitFailed;
    }
    fillHeaderDefaults(parsed.message);
    rcm::Diagnostics errors;
    std::vector<std::uint8_t> bytes;
    if (o.datagram) {
        if (auto d = rcm::encodeDatagram(parsed.message, errors))
            bytes.assign(d->begin(), d->end());
    } else if (auto f = rcm::encodeFrame(parsed.message, errors)) {
        bytes.assign(f->begin(), f->end());
    }
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

// Output in large writes: a day's recording is 86,400 messages.
class Output {
public:
    ~Output() { flush(); }
    std::string& buffer() { return m_buffer; }
    void maybeFlush()
    {
        if (m_buffer.size() > (1 << 20))
            flush();
    }
    void flush()
    {
        std::fwrite(m_buffer.data(), 1, m_buffer.size(), stdout);
        m_buffer.clear();
    }

private:
    std::string m_buffer;
};

struct DecodeCounts {
    std::uint64_t decoded = 0;
    std::uint64_t uncorrectable = 0;
    std::uint64_t corrected1 = 0;
    std::uint64_t corrected2 = 0;
    std::uint64_t warnings = 0;
};

void printMessage(Output& out, std::uint64_t frameNumber, std::uint64_t offset, const rcm::DecodeResult& r)
{
    std::string& s = out.buffer();
    s += "# frame " + std::to_string(frameNumber) + " at byte offset " + std::to_string(offset) + "\n";
    s += "# block1 corrected " + std::to_string(r.corrected1) + "\n";
    s += "# block2 corrected " + std::to_string(r.corrected2) + "\n";
    for (const rcm::Diagnostic& d : r.diagnostics)
        s += "# warning: " + d.toString() + "\n";
    s += rcm::formatMessage(r.message);
    s += "\n";
    out.maybeFlush();
}

int decodeDatagram(const Options& o, const std::vector<std::uint8_t>& input)
{
    if (input.size() != rcm::kDatagramSize) {
        std::fprintf(stderr, "rcm: a datagram is %zu bytes; read %zu\n", rcm::kDatagramSize, input.size());
        return kExitFailed;
    }
    const rcm::DecodeResult r = rcm::decodeFrame(input);
    if (!r.ok()) {
        for (const rcm::Diagnostic& d : r.diagnostics)
            if (d.kind == rcm::Diagnostic::Kind::Uncorrectable)
                std::fprintf(stderr, "rcm: datagram: %s\n", d.toString().c_str());
        if (o.summary)
            std::printf("frames 1\ndecoded 0\nuncorrectable 1\n");
        return kExitFailed;
    }
    if (o.summary) {
        std::printf("frames 1\ndecoded 1\nuncorrectable 0\ncorrected block1 %d\ncorrected block2 %d\n", r.corrected1,
                    r.corrected2);
    } else {
        Output out;
        printMessage(out, 1, 0, r);
    }
    return kExitOk;
}

int decode(const Options& o)
{
    std::string error;
    if (o.datagram) {
        std::vector<std::uint8_t> input;
        if (!readAll(o.file, input, error)) {
            std::fprintf(stderr, "rcm: %s\n", error.c_str());
            return kExitFailed;
        }
        return decodeDatagram(o, input);
    }

    std::FILE* f = o.file.empty() || o.file == "-" ? stdin : std::fopen(o.file.c_str(), "rb");
    if (!f) {
        std::fprintf(stderr, "rcm: cannot open %s: %s\n", o.file.c_str(), std::strerror(errno));
        return kExitFailed;
    }
    Output out;
    DecodeCounts counts;
    std::uint64_t frameNumber = 0;
    rcm::StreamSync sync([&](const rcm::SyncedFrame& frame) {
        ++frameNumber;
        if (!frame.ok()) {
            ++counts.uncorrectable;
            std::fprintf(stderr, "rcm: frame %llu at byte offset %llu: uncorrectable (block 1 %s, block 2 %s)\n",
                         static_cast<unsigned long long>(frameNumber), static_cast<unsigned long long>(frame.offset),
                         frame.blocks.corrected1 < 0 ? "beyond correction" : "good",
                         frame.blocks.corrected2 < 0 ? "beyond correction" : "good");
            return;
        }
        ++counts.decoded;
        counts.corrected1 += static_cast<std::uint64_t>(frame.blocks.corrected1);
        counts.corrected2 += static_cast<std::uint64_t>(frame.blocks.corrected2);
        if (o.summary)
            return;
        const rcm::DecodeResult r = rcm::decodeBlocks(frame.blocks);
        counts.warnings += r.diagnostics.size();
        printMessage(out, frameNumber, frame.offset, r);
    });

    static std::uint8_t buf[1 << 16];
    std::size_t n;
    while ((n = std::fread(buf, 1, sizeof buf, f)) > 0)
        sync.feed(std::span<const std::uint8_t>(buf, n));
    const bool failed = std::ferror(f);
    if (f != stdin)
        std::fclose(f);
    sync.flush();
    if (failed) {
        std::fprintf(stderr, "rcm: read error: %s\n", std::strerror(errno));
        return kExitFailed;
    }

    if (o.summary) {
        const auto& st = sync.stats();
        std::string& s = out.buffer();
        s += "frames " + std::to_string(counts.decoded + counts.uncorrectable) + "\n";
        s += "decoded " + std::to_string(counts.decoded) + "\n";
        s += "uncorrectable " + std::to_string(counts.uncorrectable) + "\n";
        s += "corrected block1 " + std::to_string(counts.corrected1) + "\n";
        s += "corrected block2 " + std::to_string(counts.corrected2) + "\n";
        s += "bytes read " + std::to_string(st.bytesIn) + "\n";
        s += "bytes skipped " + std::to_string(st.bytesSkipped) + "\n";
    }
    out.flush();
    if (counts.decoded + counts.uncorrectable == 0) {
        std::fprintf(stderr, "rcm: no frame found\n");
        return kExitFailed;
    }
    return counts.uncorrectable ? kExitFailed : kExitOk;
}

}  // namespace

int main(int argc, char** argv)
{
    Options o;
    std::vector<std::string> positional;
    for (int i = 1; i < argc; ++i) {
        const std::string_view a = argv[i];
        if (a == "--help" || a == "-h") {
            std::fputs(kHelp, stdout);
            return kExitOk;
        }
        if (a == "--datagram")
            o.datagram = true;
        else if (a == "--summary")
            o.summary = true;
        else if (a.size() > 1 && a.front() == '-')
            return misuse("unknown option " + std::string(a));
        else
            positional.emplace_back(a);
    }
    if (positional.empty())
        return misuse("no command given");
    o.command = positional[0];
    if (positional.size() > 2)
        return misuse("too many arguments: " + positional[2]);
    if (positional.size() == 2)
        o.file = positional[1];
    if (o.command == "encode")
        return encode(o);
    if (o.command == "decode")
        return decode(o);
    if (o.command == "dissector") {
        if (!o.file.empty() || o.datagram || o.summary)
            return misuse("dissector takes no arguments");
        std::fputs(rcm::wiresharkDissectorLua().c_str(), stdout);
        return kExitOk;
    }
    return misuse("unknown command " + o.command);
}
