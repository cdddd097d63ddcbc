#include "codec/cli/Decode.h"

#include "codec/cli/InputFile.h"
#include "codec/cli/KeyedReceive.h"
#include "codec/frame/StreamSync.h"
#include "codec/message/MessageDecoder.h"
#include "codec/message/TextFormat.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <string>
#include <string_view>

namespace rcm::cli {
namespace {

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

// "frame 3 at byte offset 1200"; a stream that began inside the frame's
// preamble puts its start before the stream's.
std::string frameAt(std::uint64_t frameNumber, std::int64_t offset)
{
    std::string s = "frame " + std::to_string(frameNumber) + " at byte offset " + std::to_string(offset);
    if (offset < 0)
        s += " (" + std::to_string(-offset) + " bytes before the start of the stream)";
    return s;
}

void printMessage(Output& out, std::uint64_t frameNumber, std::int64_t offset, const rcm::DecodeResult& r,
                  std::string_view direction = {})
{
    std::string& s = out.buffer();
    s += "# " + frameAt(frameNumber, offset) + "\n";
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
        printMessage(out, frameNumber, offset, r.decoded,
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
        const std::unique_ptr<Keyed> k = loadKeyed(o);
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

}  // namespace

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
        keyed = loadKeyed(o);
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
            std::fprintf(stderr, "rcm: %s: uncorrectable (block 1 %s, block 2 %s)\n",
                         frameAt(frameNumber, frame.offset).c_str(),
                         frame.blocks.corrected1 < 0 ? "beyond correction" : "good",
                         frame.blocks.corrected2 < 0 ? "beyond correction" : "good");
            return;
        }
        if (keyed) {
            const std::string what = frameAt(frameNumber, frame.offset);
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


}  // namespace rcm::cli
