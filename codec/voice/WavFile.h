// 16-bit PCM WAV files: the voice channel's rehearsal input and the
// simulated aircraft's record of what it would put on its VHF radio.
//
// Plain C++20, no Qt.
#pragma once

#include <cstdint>
#include <cstdio>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace rcm {

// Mono 16-bit samples at a rate.
struct PcmAudio {
    int sampleRate = 0;
    std::vector<std::int16_t> samples;
};

class WavFile {
public:
    // A 16-bit PCM WAV (WAVE_FORMAT_PCM or EXTENSIBLE with PCM) at any rate;
    // several channels are averaged into one. A data chunk whose size runs
    // past the end of the file (as from a writer that never finished) is
    // read to the end.
    static std::optional<PcmAudio> read(const std::string& path, std::string& error);
    // The whole file at once; mono.
    static bool write(const std::string& path, const PcmAudio& audio, std::string& error);

    // Writing as samples come: the header is brought up to date after every
    // append, so the file is a complete WAV whenever the writer stops, even
    // killed.
    WavFile() = default;
    ~WavFile();
    WavFile(const WavFile&) = delete;
    WavFile& operator=(const WavFile&) = delete;

    // Creates or truncates `path`: mono, 16-bit, sampleRate.
    bool create(const std::string& path, int sampleRate, std::string& error);
    // False when the disk refused: the samples, or the header, are not all there.
    bool append(std::span<const std::int16_t> samples);
    void close();
    bool isOpen() const { return m_file != nullptr; }
    std::uint64_t samplesWritten() const { return m_samples; }

private:
    bool writeHeader();

    std::FILE* m_file = nullptr;
    int m_sampleRate = 0;
    std::uint64_t m_samples = 0;
};

}  // namespace rcm
