#include "codec/cli/Decode.h"

#include "codec/cli/InputFile.h"
#include "codec/cli/PcapngFrames.h"
#include "codec/message/TextFormat.h"
#include "codec/receive/FrameReceiver.h"
#include "codec/receive/LoggedFrameReading.h"
#include "codec/secure/SecureCodec.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

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

// What --key, --direction and --replay-state give the receiver: a codec for
// each direction a frame may have been sent in, and the replay state.
struct Keys {
    std::vector<std::unique_ptr<rcm::secure::SecureCodec>> codecs;
    std::unique_ptr<rcm::secure::ReplayGuard> guard;
};

// False, with the reason on standard error, when the key cannot be used.
bool loadKeys(const Options& o, Keys& keys)
{
    using namespace rcm::secure;
    std::string error;
    const std::optional<SecretKey> psk = readKeyFile(o.key, error);
    if (!psk) {
        std::fprintf(stderr, "rcm: %s\n", error.c_str());
        return false;
    }
    for (const Direction d : {Direction::GcsToUa, Direction::UaToGcs})
        if (!o.direction || *o.direction == d)
            keys.codecs.push_back(std::make_unique<SecureCodec>(*psk, d));
    if (o.replayState.empty())
        return true;
    ReplayGuard::Options g;
    g.stateFile = o.replayState;
    g.keyFingerprint = fingerprint(*psk);
    g.windowSeconds = o.window.value_or(kDefaultWindowSeconds);
    try {
        keys.guard = std::make_unique<ReplayGuard>(g);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "rcm: %s\n", e.what());
        return false;
    }
    if (!keys.guard->notice().empty())
        std::fprintf(stderr, "rcm: %s\n", keys.guard->notice().c_str());
    return true;
}

// A recording is judged by its own frames' continuity; with --replay-state
// decode is the live receiver, this machine's clock included.
rcm::FrameReceiver::Options receiverOptions(const Options& o, const Keys& keys)
{
    rcm::FrameReceiver::Options r;
    r.mode = keys.guard ? rcm::FrameReceiver::Mode::Live : rcm::FrameReceiver::Mode::Recording;
    r.clockWindowSeconds = o.window.value_or(rcm::secure::kDefaultWindowSeconds);
    for (const auto& codec : keys.codecs)
        r.keys.codecs.push_back(codec.get());
    r.keys.guard = keys.guard.get();
    return r;
}

// "frame 3 at byte offset 1200"; a stream that began inside the frame's
// preamble puts its start before the stream's.
std::string frameAt(std::uint64_t frameNumber, std::int64_t offset)
{
    std::string s = "frame " + std::to_string(frameNumber) + " at byte offset " + std::to_string(offset);
    if (offset < 0)
        s += " (" + std::to_string(-offset) + " bytes before the start of the stream)";
    return s;
}

void printMessage(Output& out, std::uint64_t frameNumber, const rcm::ReceivedFrame& f)
{
    std::string& s = out.buffer();
    s += "# " + frameAt(frameNumber, f.offset) + "\n";
    s += "# block1 corrected " + std::to_string(f.decoded.corrected.block1) + "\n";
    s += "# block2 corrected " + std::to_string(f.decoded.corrected.block2) + "\n";
    if (f.direction)
        s += "# secure " + std::string(rcm::secure::directionName(*f.direction)) + ", authenticated\n";
    s += rcm::formatMessage(f.decoded.message);
    s += "\n";
    out.maybeFlush();
}

// Prints what decode saw of each frame: the message on standard output, a
// refusal and its reason on standard error.
class Report {
public:
    Report(const Options& o, Output& out) : m_options(o), m_out(out) {}

    void operator()(const rcm::ReceivedFrame& f)
    {
        ++m_frames;
        if (!f.warning.empty() && !m_warned) {
            std::fprintf(stderr, "rcm: warning: %s\n", f.warning.c_str());
            m_warned = true;
        }
        if (!f.delivered()) {
            std::fprintf(stderr, "rcm: %s: refused as %s: %s\n", frameAt(m_frames, f.offset).c_str(),
                         std::string(rcm::refusalName(*f.refusal)).c_str(), f.detail.c_str());
            return;
        }
        m_corrected1 += static_cast<std::uint64_t>(f.decoded.corrected.block1);
        m_corrected2 += static_cast<std::uint64_t>(f.decoded.corrected.block2);
        if (!m_options.summary)
            printMessage(m_out, m_frames, f);
    }

    // The counts of --summary.
    void summary(const rcm::FrameReceiver& receiver) const
    {
        const rcm::FrameReceiver::Stats& st = receiver.stats();
        std::string& s = m_out.buffer();
        s += "frames " + std::to_string(m_frames) + "\n";
        s += "delivered " + std::to_string(st.delivered) + "\n";
        s += "refused " + std::to_string(st.refusedTotal()) + "\n";
        s += "corrected block1 " + std::to_string(m_corrected1) + "\n";
        s += "corrected block2 " + std::to_string(m_corrected2) + "\n";
        s += "from a prediction " + std::to_string(st.fromPrediction) + "\n";
        if (!m_options.datagram) {
            s += "bytes read " + std::to_string(receiver.syncStats().bytesIn) + "\n";
            s += "bytes skipped " + std::to_string(receiver.syncStats().bytesSkipped) + "\n";
        }
        for (int i = 0; i < rcm::kRefusalCount; ++i)
            s += "refused " + std::string(rcm::refusalName(static_cast<rcm::Refusal>(i))) + " " +
                 std::to_string(st.refused[static_cast<std::size_t>(i)]) + "\n";
    }

private:
    const Options& m_options;
    Output& m_out;
    std::uint64_t m_frames = 0;
    std::uint64_t m_corrected1 = 0;  // of delivered frames
    std::uint64_t m_corrected2 = 0;
    bool m_warned = false;  // the replay state could not be written: said once
};

// Feeds o.file to the receiver: a stream, or exactly one datagram.
bool feed(const Options& o, rcm::FrameReceiver& receiver)
{
    if (o.datagram) {
        std::vector<std::uint8_t> input;
        std::string error;
        if (!readAll(o.file, input, error)) {
            std::fprintf(stderr, "rcm: %s\n", error.c_str());
            return false;
        }
        if (input.size() != rcm::kDatagramSize) {
            std::fprintf(stderr, "rcm: a datagram is %zu bytes; read %zu\n", rcm::kDatagramSize, input.size());
            return false;
        }
        receiver.receive(input);
        return true;
    }
    std::FILE* f = o.file.empty() || o.file == "-" ? stdin : std::fopen(o.file.c_str(), "rb");
    if (!f) {
        std::fprintf(stderr, "rcm: cannot open %s: %s\n", o.file.c_str(), std::strerror(errno));
        return false;
    }
    static std::uint8_t buf[1 << 16];
    std::size_t n;
    while ((n = std::fread(buf, 1, sizeof buf, f)) > 0)
        receiver.feed(std::span<const std::uint8_t>(buf, n));
    const bool failed = std::ferror(f);
    if (f != stdin)
        std::fclose(f);
    receiver.flush();
    if (failed)
        std::fprintf(stderr, "rcm: read error: %s\n", std::strerror(errno));
    return !failed;
}

const char* directionWord(LoggedPacket::Direction d)
{
    switch (d) {
    case LoggedPacket::Direction::Sent:
        return "sent";
    case LoggedPacket::Direction::Received:
        return "received";
    case LoggedPacket::Direction::Unknown:
        break;
    }
    return "direction not logged";
}

// A frame log (pcapng): each frame read on its own (LoggedFrameReading), in
// both directions, with --key's codecs for both. A log interleaves the two
// ends' frames, so no continuity is checked between them.
int decodeLog(const Options& o, std::span<const std::uint8_t> file, const Keys& keys)
{
    std::vector<LoggedPacket> packets;
    std::string error;
    const bool whole = readPcapng(file, packets, error);
    std::vector<const rcm::secure::SecureCodec*> codecs;
    for (const auto& c : keys.codecs)
        codecs.push_back(c.get());
    Output out;
    std::uint64_t read = 0, refused = 0, enciphered = 0, corrected1 = 0, corrected2 = 0;
    for (std::size_t i = 0; i < packets.size(); ++i) {
        const LoggedPacket& p = packets[i];
        const std::string where = "frame " + std::to_string(i + 1) + " (" + directionWord(p.direction) +
                                  ") at byte offset " + std::to_string(p.blockOffset) + " of the log";
        const rcm::LoggedFrameReading r = rcm::readLoggedFrame(p.bytes, p.enciphered, codecs);
        using O = rcm::LoggedFrameReading::Outcome;
        switch (r.outcome) {
        case O::Read:
            ++read;
            corrected1 += static_cast<std::uint64_t>(r.blocks.corrected.block1);
            corrected2 += static_cast<std::uint64_t>(r.blocks.corrected.block2);
            if (!o.summary) {
                std::string& s = out.buffer();
                s += "# " + where + "\n";
                s += "# block1 corrected " + std::to_string(r.blocks.corrected.block1) + "\n";
                s += "# block2 corrected " + std::to_string(r.blocks.corrected.block2) + "\n";
                if (r.direction)
                    s += "# secure " + std::string(rcm::secure::directionName(*r.direction)) + ", authenticated\n";
                s += rcm::formatMessage(r.decoded.message) + "\n";
                out.maybeFlush();
            }
            break;
        case O::Refused:
            ++refused;
            std::fprintf(stderr, "rcm: %s: refused as %s: %s\n", where.c_str(),
                         std::string(rcm::refusalName(*r.refusal)).c_str(), r.detail.c_str());
            break;
        case O::Enciphered:
            ++enciphered;
            std::fprintf(stderr, "rcm: %s: enciphered (a keyed link's frame): give --key to read it\n", where.c_str());
            break;
        case O::NotAFrame:
            ++refused;
            std::fprintf(stderr, "rcm: %s: %zu bytes, neither a 600-byte frame nor a 510-byte datagram\n",
                         where.c_str(), p.bytes.size());
            break;
        }
    }
    if (o.summary) {
        std::string& s = out.buffer();
        s += "frames " + std::to_string(packets.size()) + "\n";
        s += "read " + std::to_string(read) + "\n";
        s += "refused " + std::to_string(refused) + "\n";
        s += "enciphered " + std::to_string(enciphered) + "\n";
        s += "corrected block1 " + std::to_string(corrected1) + "\n";
        s += "corrected block2 " + std::to_string(corrected2) + "\n";
    }
    out.flush();
    if (!whole)
        std::fprintf(stderr, "rcm: %s: %s; the frames before it were decoded\n", inputName(o.file).c_str(),
                     error.c_str());
    if (packets.empty()) {
        std::fprintf(stderr, "rcm: no frame found\n");
        return kExitFailed;
    }
    return whole && refused + enciphered == 0 ? kExitOk : kExitFailed;
}

// A named file that begins as a pcapng frame log does, read whole.
bool readLogFile(const Options& o, std::vector<std::uint8_t>& file)
{
    if (o.datagram || o.file.empty() || o.file == "-")
        return false;
    std::FILE* f = std::fopen(o.file.c_str(), "rb");
    if (!f)
        return false;
    std::uint8_t head[12];
    const bool log = std::fread(head, 1, sizeof head, f) == sizeof head && isPcapng(head);
    std::fclose(f);
    std::string error;
    return log && readAll(o.file, file, error);
}

}  // namespace

int decode(const Options& o)
{
    Keys keys;
    if (!o.key.empty() && !loadKeys(o, keys))
        return kExitFailed;
    if (std::vector<std::uint8_t> log; readLogFile(o, log))
        return decodeLog(o, log, keys);
    Output out;
    Report report(o, out);
    rcm::FrameReceiver receiver(receiverOptions(o, keys), [&](const rcm::ReceivedFrame& f) { report(f); });
    if (!feed(o, receiver))
        return kExitFailed;
    if (o.summary)
        report.summary(receiver);
    out.flush();
    const rcm::FrameReceiver::Stats& st = receiver.stats();
    if (st.delivered + st.refusedTotal() == 0) {
        std::fprintf(stderr, "rcm: no frame found\n");
        return kExitFailed;
    }
    return st.refusedTotal() > 0 ? kExitFailed : kExitOk;
}

}  // namespace rcm::cli
