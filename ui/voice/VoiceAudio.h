#pragma once

// The console's sound card: the microphone into the voice encoder while the
// operator talks, received voice out of the speaker. Lives in a thread of
// its own (VoiceChannel puts it there), so that no audio call ever waits in
// the GUI thread. The codec's format is 8 kHz 16-bit mono; a card that
// offers something else is converted to and from it here.

#include <QAudioFormat>
#include <QIODevice>
#include <QObject>

#include <cstdint>
#include <memory>
#include <vector>

class PcmFifo;
class QAudioSink;
class QAudioSource;
class VoiceEncoderSource;

class VoiceAudio : public QObject {
    Q_OBJECT

public:
    VoiceAudio(std::shared_ptr<VoiceEncoderSource> source, std::shared_ptr<PcmFifo> playback);
    ~VoiceAudio() override;

public slots:
    // The default microphone into the source until stopCapture(), which
    // ends the talk.
    void startCapture();
    void stopCapture();
    // A WAV file instead (rehearsal): all of it goes to the source, which
    // sends it at the line's pace.
    void speakFile(const QString& path);
    // The default speaker plays what the link's thread pushes to the FIFO.
    void startPlayback();
    void stopPlayback();

signals:
    void errorOccurred(const QString& message);

private:
    void readMicrophone();

    std::shared_ptr<VoiceEncoderSource> m_source;
    std::shared_ptr<PcmFifo> m_playback;
    std::unique_ptr<QAudioSource> m_input;
    QIODevice* m_inputDevice = nullptr;  // owned by m_input
    QAudioFormat m_inputFormat;
    double m_inputPhase = 0;  // decimation to 8 kHz: where the next output sample is due
    double m_inputSum = 0;
    int m_inputCount = 0;
    std::int16_t m_inputLast = 0;
    std::vector<std::int16_t> m_captured;
    std::unique_ptr<QIODevice> m_outputDevice;
    std::unique_ptr<QAudioSink> m_output;
};
