#pragma once

// Push to talk: voice on the link or not, a button and a key (F12, held
// while the console's window is active) to talk, the microphone or a WAV
// file for rehearsal, and two level meters, what goes out and what comes in.
// It shows and asks; VoiceChannel does the rest.

#include <QWidget>

class QCheckBox;
class QLabel;
class QLineEdit;
class QProgressBar;
class QPushButton;
class QRadioButton;
class QTimer;
class QToolButton;
class VoiceChannel;

class PushToTalkWidget : public QWidget {
    Q_OBJECT

public:
    static constexpr Qt::Key kTalkKey = Qt::Key_F12;
    // A release of the talk key counts once no press has followed it within
    // this: X's key auto-repeat sends a release and a press every 40 ms (at
    // its default 25 a second) while the key is held, and Qt 6.4 marks only
    // the first pair as auto-repeat (QKeyEvent::isAutoRepeat).
    static constexpr int kReleaseGraceMs = 120;

    explicit PushToTalkWidget(VoiceChannel* channel, QWidget* parent = nullptr);
    ~PushToTalkWidget() override;

    // Talk from this file rather than the microphone (empty: the microphone).
    void setRehearsalFile(const QString& path);
    // For tests: the meters as shown, 0..100 (-60..0 dBFS).
    int sentMeter() const;
    int receivedMeter() const;

protected:
    // The talk key anywhere in this window; and a window left with the key
    // held stops talking, as the key's release will not come.
    bool eventFilter(QObject* watched, QEvent* event) override;

private:
    void chooseFile();
    void updateSource();
    void updateEnabled();

    VoiceChannel* m_channel;
    QCheckBox* m_voiceOn;
    QPushButton* m_talk;
    QRadioButton* m_microphone;
    QRadioButton* m_file;
    QLineEdit* m_path;
    QToolButton* m_browse;
    QProgressBar* m_sent;
    QProgressBar* m_received;
    QLabel* m_note;
    bool m_keyHeld = false;
    QTimer* m_release;  // a release of the talk key, waiting to see no press follow
};
