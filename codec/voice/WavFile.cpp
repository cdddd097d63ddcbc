#include "codec/voice/WavFile.h"

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstring>
#include <memory>

namespace rcm {
namespace {

constexpr std::uint16_t kFormatPcm = 1;
constexpr std::uint16_t kFormatExtensible = 0xFFFE;
constexpr long kHeaderSize = 44;

std::uint32_t le32(const std::uint8_t* p)
{
    return std::uint32_t(p[0]) | std::uint32_t(p[1]) << 8 | std::uint32_t(p[2]) << 16 | std::uint32_t(p[3]) << 24;
}

std::uint16_t le16(const std::uint8_t* p)
{
    return static_cast<std::uint16_t>(p[0] | p[1] << 8);
}

void put32(std::uint8_t* p, std::uint32_t v)
{
    for (int i = 0; i < 4; ++i)
        p[i] = static_cast<std::uint8_t>(v >> (8 * i));
}

void put16(std::uint8_t* p, std::uint16_t v)
{
    p[0] = static_cast<std::uint8_t>(v);
    p[1] = static_cast<std::uint8_t>(v >> 8);
}

std::array<std::uint8_t, kHeaderSize> header(int sampleRate, std::uint64_t samples)
{
    // Sizes past 4 GiB cannot be told; a WAV that long says "to the end".
    const std::uint64_t data = samples * 2;
    const auto dataSize = static_cast<std::uint32_t>(std::min<std::uint64_t>(data, 0xFFFFFFFFu - 36));
    std::array<std::uint8_t, kHeaderSize> h{};
    std::memcpy(h.data(), "RIFF", 4);
    put32(h.data() + 4, 36 + dataSize);
    std::memcpy(h.data() + 8, "WAVEfmt ", 8);
    put32(h.data() + 16, 16);
    put16(h.data() + 20, kFormatPcm);
    put16(h.data() + 22, 1);
    put32(h.data() + 24, static_cast<std::uint32_t>(sampleRate));
    put32(h.data() + 28, static_cast<std::uint32_t>(sampleRate) * 2);
    put16(h.data() + 32, 2);
    put16(h.data() + 34, 16);
    std::memcpy(h.data() + 36, "data", 4);
    put32(h.data() + 40, dataSize);
    return h;
}

std::string systemError()
{
    return std::strerror(errno);
}

struct FileCloser {
    void operator()(std::FILE* f) const { std::fclose(f); }
};

}  // namespace

std::optional<PcmAudio> WavFile::read(const std::string& path, std::string& error)
{
    std::unique_ptr<std::FILE, FileCloser> file(std::fopen(path.c_str(), "rb"));
    if (!file) {
        error = path + ": " + systemError();
        return std::nullopt;
    }
    std::vector<std::uint8_t> bytes;
    std::array<std::uint8_t, 65536> chunk;
    for (std::size_t n; (n = std::fread(chunk.data(), 1, chunk.size(), file.get())) > 0;)
        bytes.insert(bytes.end(), chunk.begin(), chunk.begin() + static_cast<std::ptrdiff_t>(n));
    if (std::ferror(file.get())) {
        error = path + ": " + systemError();
        return std::nullopt;
    }
    if (bytes.size() < 12 || std::memcmp(bytes.data(), "RIFF", 4) != 0 ||
        std::memcmp(bytes.data() + 8, "WAVE", 4) != 0) {
        error = path + ": not a WAV file (no RIFF/WAVE header)";
        return std::nullopt;
    }
    int channels = 0;
    int rate = 0;
    bool haveFormat = false;
    std::size_t at = 12;
    while (at + 8 <= bytes.size()) {
        const std::uint8_t* id = bytes.data() + at;
        const std::size_t declared = le32(id + 4);
        const std::size_t body = at + 8;
        const std::size_t size = std::min(declared, bytes.size() - body);
        if (std::memcmp(id, "fmt ", 4) == 0 && size >= 16) {
            const std::uint8_t* f = bytes.data() + body;
            std::uint16_t format = le16(f);
            if (format == kFormatExtensible && size >= 26)
                format = le16(f + 24);  // the sub-format GUID's first two bytes
            channels = le16(f + 2);
            rate = static_cast<int>(le32(f + 4));
            const int bits = le16(f + 14);
            if (format != kFormatPcm || bits != 16 || channels < 1 || rate <= 0) {
                error = path + ": only 16-bit PCM WAV is read (format " + std::to_string(format) + ", " +
                        std::to_string(bits) + " bits, " + std::to_string(channels) + " channels)";
                return std::nullopt;
            }
            haveFormat = true;
        } else if (std::memcmp(id, "data", 4) == 0) {
            if (!haveFormat) {
                error = path + ": data before the fmt chunk";
                return std::nullopt;
            }
            PcmAudio audio;
            audio.sampleRate = rate;
            const std::size_t frames = size / (2 * static_cast<std::size_t>(channels));
            audio.samples.resize(frames);
            for (std::size_t i = 0; i < frames; ++i) {
                long sum = 0;
                for (int c = 0; c < channels; ++c)
                    sum += static_cast<std::int16_t>(le16(bytes.data() + body + 2 * (i * channels + c)));
                audio.samples[i] = static_cast<std::int16_t>(sum / channels);
            }
            return audio;
        }
        at = body + declared + (declared & 1);  // chunks are padded to even sizes
    }
    error = path + ": no data chunk";
    return std::nullopt;
}

bool WavFile::write(const std::string& path, const PcmAudio& audio, std::string& error)
{
    WavFile file;
    if (!file.create(path, audio.sampleRate, error))
        return false;
    if (!file.append(audio.samples)) {
        error = path + ": " + systemError();
        return false;
    }
    file.close();
    return true;
}

WavFile::~WavFile()
{
    close();
}

bool WavFile::create(const std::string& path, int sampleRate, std::string& error)
{
    close();
    m_file = std::fopen(path.c_str(), "w+b");
    if (!m_file) {
        error = path + ": " + systemError();
        return false;
    }
    m_sampleRate = sampleRate;
    m_samples = 0;
    if (!writeHeader()) {
        error = path + ": " + systemError();
        close();
        return false;
    }
    return true;
}

bool WavFile::append(std::span<const std::int16_t> samples)
{
    if (!m_file)
        return false;
    std::vector<std::uint8_t> bytes(2 * samples.size());
    for (std::size_t i = 0; i < samples.size(); ++i)
        put16(bytes.data() + 2 * i, static_cast<std::uint16_t>(samples[i]));
    if (std::fseek(m_file, 0, SEEK_END) != 0)
        return false;
    const bool written = std::fwrite(bytes.data(), 1, bytes.size(), m_file) == bytes.size();
    m_samples += samples.size();
    return writeHeader() && written;
}

bool WavFile::writeHeader()
{
    const auto h = header(m_sampleRate, m_samples);
    return std::fseek(m_file, 0, SEEK_SET) == 0 && std::fwrite(h.data(), 1, h.size(), m_file) == h.size() &&
           std::fflush(m_file) == 0;
}

void WavFile::close()
{
    if (m_file)
        std::fclose(m_file);
    m_file = nullptr;
}

}  // namespace rcm
