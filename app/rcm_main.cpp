// rcm: Remote Control Messages between the text format and bytes.
//   rcm encode [FILE] [--datagram]          text -> one 600-byte frame (or 510-byte datagram)
//   rcm decode [FILE] [--datagram] [--summary]   bytes -> text
//   rcm dissector                            the Wireshark dissector, from the item table
//   rcm keygen FILE                          a new 256-bit key for the secure link
// encode and decode take --key FILE for the secure link (codec/secure/SecureCodec.h).
// Plain C++ over the codec, so it runs wherever the codec does.
#include "codec/message/DigitPairs.h"
#include "codec/message/MessageDecoder.h"
#include "codec/message/MessageEncoder.h"
#include "codec/secure/SecureCodec.h"
#include "codec/frame/StreamSync.h"
#include "codec/message/TextFormat.h"
#include "codec/dissector/WiresharkDissector.h"

#include <unistd.h>

#include <array>
#include <charconv>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace {

constexpr int kExitOk = 0;
constexpr int kExitFailed = 1;
constexpr int kExitMisuse = 2;

const char* const kHelp = R"(Usage:
  rcm encode [FILE] [--datagram] [--key KEYFILE [--direction DIR]]
  rcm decode [FILE] [--datagram] [--summary]
             [--key KEYFILE [--direction DIR] [--replay-state STATE [--window SECONDS]]]
  rcm keygen KEYFILE
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
        "# secure" line). A frame that does not authenticate is not printed;
        standard error says why: forged (not sent with this key and
        direction), plaintext (an unencrypted frame), and with --replay-state
        also replayed or stale time. Without --replay-state no replay or time
        check is made: a recording is decoded as it is.
--replay-state STATE  decode as the receiver does: STATE holds the last
        accepted ID_msg (created when absent, updated as frames are accepted);
        a frame must be ahead of it and within --window SECONDS (default 30)
        of this machine's UTC clock. Needs --direction.

keygen  writes a new random key to KEYFILE with mode 0600 (never over an
        existing file) and prints its fingerprint, which names the key
        without revealing it; give the same file to the console and to the
        aircraft.

dissector  prints the Wireshark Lua dissector generated from the item table
        (the copy in resources/wireshark/rcm.lua is this output):
          tshark -X lua_script:resources/wireshark/rcm.lua -r session.pcapng -V

Exit status: 0 when everything decoded (or encoded), 1 when a frame was
uncorrectable or rejected, none was found, or the text or key had errors,
2 for misuse.

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
    std::string key;                     // --key: the secure link
    std::optional<rcm::secure::Direction> direction;
    std::string replayState;
    std::optional<std::int64_t> window;  // seconds
};

// The keyed side of encode and decode: a codec for each direction used (one
// for encode and for --direction, both otherwise), and the receiver's replay
// guard with --replay-state.
struct Keyed {
    std::vector<std::unique_ptr<rcm::secure::SecureCodec>> codecs;
    std::unique_ptr<rcm::secure::ReplayGuard> guard;
    std::array<std::uint64_t, rcm::secure::kRejectionCount> rejected{};
    bool persistWarned = false;
};

// Nothing, with the reason on standard error, when the key cannot be used.
std::unique_ptr<Keyed> loadKeyed(const Options& o, bool decoding)
{
    using namespace rcm::secure;
    std::string error;
    const std::optional<SecretKey> psk = readKeyFile(o.key, error);
    if (!psk) {
        std::fprintf(stderr, "rcm: %s\n", error.c_str());
        return nullptr;
    }
    auto k = std::make_unique<Keyed>();
    if (o.direction || !decoding) {
        k->codecs.push_back(std::make_unique<SecureCodec>(*psk, o.direction.value_or(Direction::GcsToUa)));
    } else {
        k->codecs.push_back(std::make_unique<SecureCodec>(*psk, Direction::GcsToUa));
        k->codecs.push_back(std::make_unique<SecureCodec>(*psk, Direction::UaToGcs));
    }
    if (!o.replayState.empty()) {
        ReplayGuard::Options g;
        g.stateFile = o.replayState;
        g.keyFingerprint = fingerprint(*psk);
        g.windowSeconds = o.window.value_or(kDefaultWindowSeconds);
        try {
            k->guard = std::make_unique<ReplayGuard>(g);
        } catch (const std::exception& e) {
            std::fprintf(stderr, "rcm: %s\n", e.what());
            return nullptr;
        }
        if (!k->guard->notice().empty())
            std::fprintf(stderr, "rcm: %s\n", k->guard->notice().c_str());
    }
    return k;
}

// A keyed frame: the authenticated message and its direction, or the reason
// it was refused.
struct KeyedResult {
    bool accepted = false;
    rcm::DecodeResult decoded;
    rcm::secure::Direction direction = rcm::secure::Direction::GcsToUa;
    rcm::secure::Rejection rejection = rcm::secure::Rejection::Forged;
    std::string detail;
};

KeyedResult openKeyed(Keyed& k, const rcm::DecodedBlocks& blocks)
{
    using namespace rcm::secure;
    KeyedResult r;
    if (k.guard) {
        Opened o = openFrame(*k.codecs.front(), k.guard.get(), blocks);
        r.direction = k.codecs.front()->direction();
        if (!o.persistError.empty() && !k.persistWarned) {
            std::fprintf(stderr, "rcm: warning: %s\n", o.persistError.c_str());
            k.persistWarned = true;
        }
        r.accepted = o.accepted;
        r.decoded = std::move(o.decoded);
        r.rejection = o.rejection.value_or(Rejection::Forged);
        r.detail = std::move(o.detail);
        return r;
    }
    // A frame authenticates in at most one direction (the other deciphers
    // it to random bytes), so trying both names the one it was sent in.
    for (const auto& codec : k.codecs) {
        Authenticated a = codec->decryptBlocks(blocks);
        if (a.authentic) {
            r.accepted = true;
            r.decoded = std::move(a.decoded);
            r.direction = codec->direction();
            return r;
        }
        if (a.rejection == Rejection::Plaintext)
            r.rejection = Rejection::Plaintext;
        r.detail = k.codecs.size() == 1 ? a.detail : "sent neither GCS->UA nor UA->GCS with this key";
    }
    if (r.rejection == Rejection::Plaintext)
        r.detail = "an unencrypted message on a keyed link";
    return r;
}

// Fills ID_msg, time_UTC and date_UTC where the text did not give them.
void fillHeaderDefaults(rcm::Message& m)
{
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
    if (!o.key.empty()) {
        const std::unique_ptr<Keyed> k = loadKeyed(o, false);
        if (!k)
            return kExitFailed;
        if (const auto b = k->codecs.front()->encode(parsed.message, errors)) {
            if (o.datagram) {
                const rcm::DatagramBytes d = rcm::makeDatagram(b->block1, b->block2);
                bytes.assign(d.begin(), d.end());
            } else {
                const rcm::FrameBytes f = rcm::makeFrame(b->block1, b->block2);
                bytes.assign(f.begin(), f.end());
            }
        }
    } else if (o.datagram) {
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

void printMessage(Output& out, std::uint64_t frameNumber, std::uint64_t offset, const rcm::DecodeResult& r,
                  std::string_view direction = {})
{
    std::string& s = out.buffer();
    s += "# frame " + std::to_string(frameNumber) + " at byte offset " + std::to_string(offset) + "\n";
    s += "# block1 corrected " + std::to_string(r.corrected1) + "\n";
    s += "# block2 corrected " + std::to_string(r.corrected2) + "\n";
    if (!direction.empty())
        s += "# secure " + std::string(direction) + ", authenticated\n";
    for (const rcm::Diagnostic& d : r.diagnostics)
        s += "# warning: " + d.toString() + "\n";
    s += rcm::formatMessage(r.message);
    s += "\n";
    out.maybeFlush();
}

// Decodes a good frame on a keyed link: prints it, or reports why it was
// refused. False when refused.
bool decodeKeyed(Keyed& k, const Options& o, Output& out, std::uint64_t frameNumber, std::int64_t offset,
                 const rcm::DecodedBlocks& blocks, const char* what)
{
    KeyedResult r = openKeyed(k, blocks);
    if (!r.accepted) {
        ++k.rejected[static_cast<int>(r.rejection)];
        std::fprintf(stderr, "rcm: %s: rejected as %s: %s\n", what,
                     std::string(rcm::secure::rejectionName(r.rejection)).c_str(), r.detail.c_str());
        return false;
    }
    if (!o.summary)
        printMessage(out, frameNumber, static_cast<std::uint64_t>(offset), r.decoded,
                     rcm::secure::directionName(r.direction));
    return true;
}

void printRejectedCounts(const Keyed& k, std::string& s)
{
    for (int i = 0; i < rcm::secure::kRejectionCount; ++i)
        s += "rejected " + std::string(rcm::secure::rejectionName(static_cast<rcm::secure::Rejection>(i))) + " " +
             std::to_string(k.rejected[static_cast<std::size_t>(i)]) + "\n";
}

std::uint64_t totalRejected(const Keyed* k)
{
    std::uint64_t n = 0;
    if (k)
        for (std::uint64_t r : k->rejected)
            n += r;
    return n;
}

int decodeDatagram(const Options& o, const std::vector<std::uint8_t>& input)
{
    if (input.size() != rcm::kDatagramSize) {
        std::fprintf(stderr, "rcm: a datagram is %zu bytes; read %zu\n", rcm::kDatagramSize, input.size());
        return kExitFailed;
    }
    if (!o.key.empty()) {
        const std::unique_ptr<Keyed> k = loadKeyed(o, true);
        if (!k)
            return kExitFailed;
        const rcm::DecodedBlocks blocks =
            rcm::decodeCodewords(std::span<const std::uint8_t, rcm::kDatagramSize>(input.data(), rcm::kDatagramSize));
        Output out;
        bool ok = blocks.ok();
        if (!ok)
            std::fprintf(stderr, "rcm: datagram: uncorrectable (block 1 %s, block 2 %s)\n",
                         blocks.corrected1 < 0 ? "beyond correction" : "good",
                         blocks.corrected2 < 0 ? "beyond correction" : "good");
        else
            ok = decodeKeyed(*k, o, out, 1, 0, blocks, "datagram");
        if (o.summary) {
            std::string& s = out.buffer();
            s += "frames 1\ndecoded " + std::string(ok ? "1" : "0") + "\nuncorrectable " +
                 (blocks.ok() ? "0" : "1") + "\n";
            if (ok)
                s += "corrected block1 " + std::to_string(blocks.corrected1) + "\ncorrected block2 " +
                     std::to_string(blocks.corrected2) + "\n";
            printRejectedCounts(*k, s);
        }
        return ok ? kExitOk : kExitFailed;
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
    std::unique_ptr<Keyed> keyed;
    if (!o.key.empty()) {
        keyed = loadKeyed(o, true);
        if (!keyed) {
            if (f != stdin)
                std::fclose(f);
            return kExitFailed;
        }
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
        if (keyed) {
            const std::string what = "frame " + std::to_string(frameNumber) + " at byte offset " +
                                     std::to_string(frame.offset);
            if (!decodeKeyed(*keyed, o, out, frameNumber, frame.offset, frame.blocks, what.c_str()))
                return;
        }
        ++counts.decoded;
        counts.corrected1 += static_cast<std::uint64_t>(frame.blocks.corrected1);
        counts.corrected2 += static_cast<std::uint64_t>(frame.blocks.corrected2);
        if (o.summary || keyed)
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
        s += "frames " + std::to_string(counts.decoded + counts.uncorrectable + totalRejected(keyed.get())) + "\n";
        s += "decoded " + std::to_string(counts.decoded) + "\n";
        s += "uncorrectable " + std::to_string(counts.uncorrectable) + "\n";
        s += "corrected block1 " + std::to_string(counts.corrected1) + "\n";
        s += "corrected block2 " + std::to_string(counts.corrected2) + "\n";
        s += "bytes read " + std::to_string(st.bytesIn) + "\n";
        s += "bytes skipped " + std::to_string(st.bytesSkipped) + "\n";
        if (keyed)
            printRejectedCounts(*keyed, s);
    }
    out.flush();
    const std::uint64_t rejected = totalRejected(keyed.get());
    if (counts.decoded + counts.uncorrectable + rejected == 0) {
        std::fprintf(stderr, "rcm: no frame found\n");
        return kExitFailed;
    }
    return counts.uncorrectable || rejected ? kExitFailed : kExitOk;
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
        if (a == "--datagram") {
            o.datagram = true;
        } else if (a == "--summary") {
            o.summary = true;
        } else if (a == "--key" || a == "--direction" || a == "--replay-state" || a == "--window") {
            if (i + 1 >= argc)
                return misuse(std::string(a) + " needs a value");
            const std::string v = argv[++i];
            if (a == "--key") {
                o.key = v;
            } else if (a == "--replay-state") {
                o.replayState = v;
            } else if (a == "--direction") {
                if (v == "gcs-to-ua")
                    o.direction = rcm::secure::Direction::GcsToUa;
                else if (v == "ua-to-gcs")
                    o.direction = rcm::secure::Direction::UaToGcs;
                else
                    return misuse("--direction is gcs-to-ua or ua-to-gcs, not " + v);
            } else {
                std::int64_t seconds = -1;
                const auto [end, ec] = std::from_chars(v.data(), v.data() + v.size(), seconds);
                if (ec != std::errc() || end != v.data() + v.size() || seconds < 0)
                    return misuse("--window takes a number of seconds, not " + v);
                o.window = seconds;
            }
        } else if (a.size() > 1 && a.front() == '-') {
            return misuse("unknown option " + std::string(a));
        } else {
            positional.emplace_back(a);
        }
    }
    if (positional.empty())
        return misuse("no command given");
    o.command = positional[0];
    if (positional.size() > 2)
        return misuse("too many arguments: " + positional[2]);
    if (positional.size() == 2)
        o.file = positional[1];
    const bool secureOptions = o.direction || !o.replayState.empty() || o.window;
    if (secureOptions && o.key.empty())
        return misuse("--direction, --replay-state and --window need --key");
    if (o.window && o.replayState.empty())
        return misuse("--window applies with --replay-state only");
    if (!o.replayState.empty() && !o.direction)
        return misuse("--replay-state needs --direction: the state is kept per direction");
    if (!o.key.empty() && o.command != "encode" && o.command != "decode")
        return misuse("--key applies to encode and decode");
    if (o.command == "encode" && !o.replayState.empty())
        return misuse("--replay-state applies to decode only");
    if (o.command == "keygen") {
        if (o.file.empty() || o.datagram || o.summary)
            return misuse("keygen takes one argument, the key file to create");
        std::string error;
        const rcm::secure::SecretKey key = rcm::secure::generateKey();
        if (!rcm::secure::writeKeyFile(o.file, key, error)) {
            std::fprintf(stderr, "rcm: %s\n", error.c_str());
            return kExitFailed;
        }
        std::printf("fingerprint %s\n", rcm::secure::fingerprint(key).c_str());
        return kExitOk;
    }
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
