#include "ui/voice/VoiceAudio.h"

#include "codec/voice/VoiceCodec.h"
#include "link/voice/VoiceEncoderSource.h"
#include "ui/voice/PcmFifo.h"

#include <QAudioDevice>
#include <QAudioSink>
#include <QAudioSource>
#include <QMediaDevices>

#include <algorithm>
#include <cmath>

namespace {

constexpr int kRate = rcm::voice::kSampleRate;

QAudioFormat codecFormat()
{
    QAudioFormat f;
    f.setSampleRate(kRate);
    f.setChannelCount(1);
    f.setSampleFormat(QAudioFormat::Int16);
    return f;
}

QAudioFormat formatFor(const QAudioDevice& device)
{
    const QAudioFormat wanted = codecFormat();
    return device.isFormatSupported(wanted) ? wanted : device.preferredFormat();
}

void writeSample(char* to, QAudioFormat::SampleFormat format, float v)
{
    v = std::clamp(v, -1.0f, 1.0f);
    switch (format) {
        case QAudioFormat::UInt8:
            *reinterpret_cast<quint8*>(to) = quint8(std::lround(v * 127.0f + 128.0f));
            break;
        case QAudioFormat::Int16:
            *reinterpret_cast<qint16*>(to) = qint16(std::lround(v * 32767.0f));
            break;
        case QAudioFormat::Int32:
            *reinterpret_cast<qint32*>(to) = qint32(std::llround(double(v) * 2147483647.0));
            break;
        case QAudioFormat::Float:
            *reinterpret_cast<float*>(to) = v;
            break;
        default:
            break;
    }
}

// What the speaker pulls: the FIFO at 8 kHz, converted to the card's
// format by linear interpolation, silence when nothing waits (so the card
// never stops and the delay stays that of its buffer).
class PlaybackDevice : public QIODevice {
public:
    PlaybackDevice(std::shared_ptr<PcmFifo> fifo, const QAudioFormat& format)
        : m_fifo(std::move(fifo)), m_format(format)
    {
        m_step = double(kRate) / format.sampleRate();
        open(QIODevice::ReadOnly);
    }

    bool isSequential() const override { return true; }
    qint64 bytesAvailable() const override { return 1 << 16; }

protected:
    qint64 readData(char* data, qint64 maxlen) override
    {
        const int frameBytes = m_format.bytesPerFrame();
        const int sampleBytes = m_format.bytesPerSample();
        const qint64 frames = maxlen / frameBytes;
        const auto needed = std::size_t(std::ceil(double(frames) * m_step)) + 1;
        m_pulled.resize(needed);
        m_fifo->pull(m_pulled);
        std::size_t next = 0;
        for (qint64 i = 0; i < frames; ++i) {
            const float v = float(m_previous + (m_current - m_previous) * m_phase) / 32768.0f;
            for (int c = 0; c < m_format.channelCount(); ++c)
                writeSample(data + i * frameBytes + c * sampleBytes, m_format.sampleFormat(), v);
            for (m_phase += m_step; m_phase >= 1.0; m_phase -= 1.0) {
                m_previous = m_current;
                m_current = next < m_pulled.size() ? m_pulled[next++] : 0;
            }
        }
        return frames * frameBytes;
    }
    qint64 writeData(const char*, qint64) override { return -1; }

private:
    std::shared_ptr<PcmFifo> m_fifo;
    QAudioFormat m_format;
    double m_step = 1;
    double m_phase = 0;
    std::int16_t m_previous = 0;
    std::int16_t m_current = 0;
    std::vector<std::int16_t> m_pulled;
};

}  // namespace

VoiceAudio::VoiceAudio(std::shared_ptr<VoiceEncoderSource> source, std::shared_ptr<PcmFifo> playback)
    : m_source(std::move(source)), m_playback(std::move(playback))
{
}

VoiceAudio::~VoiceAudio()
{
    stopCapture();
    stopPlayback();
}

void VoiceAudio::startCapture()
{
    if (m_input)
        return;
    const QAudioDevice device = QMediaDevices::defaultAudioInput();
    if (device.isNull()) {
        emit errorOccurred(tr("No microphone: choose a WAV file to talk from"));
        return;
    }
    m_inputFormat = formatFor(device);
    m_input = std::make_unique<QAudioSource>(device, m_inputFormat);
    // Small, for latency: the encoder takes 20 ms at a time.
    m_input->setBufferSize(m_inputFormat.bytesForDuration(20000));
    m_inputPhase = 0;
    m_inputSum = 0;
    m_inputCount = 0;
    m_inputDevice = m_input->start();
    if (!m_inputDevice) {
        emit errorOccurred(tr("The microphone did not start (%1)").arg(device.description()));
        m_input.reset();
        return;
    }
    connect(m_inputDevice, &QIODevice::readyRead, this, &VoiceAudio::readMicrophone);
}

void VoiceAudio::stopCapture()
{
    if (!m_input)
        return;
    readMicrophone();
    m_input->stop();
    m_input.reset();
    m_inputDevice = nullptr;
    m_source->endTalk();
}

void VoiceAudio::speakFile(const QString& path)
{
    std::string error;
    m_source->clear();
    if (!m_source->speakFile(path.toStdString(), error))
        emit errorOccurred(QString::fromStdString(error));
}

// Channels averaged, then each 8 kHz sample the mean of the card's samples
// in its 125 us: enough of a low-pass for speech on its way to Codec 2.
void VoiceAudio::readMicrophone()
{
    if (!m_inputDevice)
        return;
    const QByteArray bytes = m_inputDevice->readAll();
    const int frameBytes = m_inputFormat.bytesPerFrame();
    const int sampleBytes = m_inputFormat.bytesPerSample();
    const int channels = m_inputFormat.channelCount();
    const double rate = m_inputFormat.sampleRate();
    m_captured.clear();
    for (qsizetype at = 0; at + frameBytes <= bytes.size(); at += frameBytes) {
        float v = 0;
        for (int c = 0; c < channels; ++c)
            v += m_inputFormat.normalizedSampleValue(bytes.constData() + at + c * sampleBytes);
        m_inputSum += v / float(channels);
        ++m_inputCount;
        // A card slower than 8 kHz repeats its sample.
        for (m_inputPhase += kRate; m_inputPhase >= rate; m_inputPhase -= rate) {
            if (m_inputCount > 0) {
                m_inputLast =
                    std::int16_t(std::clamp(std::lround(m_inputSum / m_inputCount * 32767.0), -32768L, 32767L));
                m_inputSum = 0;
                m_inputCount = 0;
            }
            m_captured.push_back(m_inputLast);
        }
    }
    if (!m_captured.empty())
        m_source->pushPcm(m_captured);
}

void VoiceAudio::startPlayback()
{
    if (m_output)
        return;
    const QAudioDevice device = QMediaDevices::defaultAudioOutput();
    if (device.isNull())
        return;  // a console without a speaker still talks
    const QAudioFormat format = formatFor(device);
    m_outputDevice = std::make_unique<PlaybackDevice>(m_playback, format);
    m_output = std::make_unique<QAudioSink>(device, format);
    m_output->setBufferSize(format.bytesForDuration(60000));
    m_output->start(m_outputDevice.get());
}

void VoiceAudio::stopPlayback()
{
    if (!m_output)
        return;
    m_output->stop();
    m_output.reset();
    m_outputDevice.reset();
}
