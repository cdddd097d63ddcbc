#pragma once

// The link-loss tone (resources/sounds/link-lost.wav, a two-tone beep once a
// second) on the default sound card, looped until stopped. Without a sound
// card it stays silent and says so once, in the event log's words through
// unavailable(); the visible alarm does not depend on it.

#include "ui/alerts/AlarmSound.h"

#include <QObject>

class QSoundEffect;

class ToneAlarmSound : public QObject, public AlarmSound {
    Q_OBJECT

public:
    explicit ToneAlarmSound(QObject* parent = nullptr);
    ~ToneAlarmSound() override;

    void start() override;
    void stop() override;
    bool isPlaying() const;
    // Whether the system offers any audio output at all.
    static bool hasSoundCard();

signals:
    // The tone cannot be played (no sound card, no decoder); once.
    void unavailable(const QString& reason);

private:
    QSoundEffect* m_effect;
    bool m_reported = false;
};
