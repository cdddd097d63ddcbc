#include "ui/alerts/ToneAlarmSound.h"

#include <QAudioDevice>
#include <QMediaDevices>
#include <QSoundEffect>
#include <QUrl>

// The tone lives in rcmui, a static library: its resource is linked in only
// when called for by name.
static void initSoundResources()
{
    static const bool done = [] {
        Q_INIT_RESOURCE(sounds);
        return true;
    }();
    Q_UNUSED(done);
}

ToneAlarmSound::ToneAlarmSound(QObject* parent) : QObject(parent), m_effect(new QSoundEffect(this))
{
    initSoundResources();
    m_effect->setSource(QUrl(QStringLiteral("qrc:/sounds/link-lost.wav")));
    m_effect->setLoopCount(QSoundEffect::Infinite);
    connect(m_effect, &QSoundEffect::statusChanged, this, [this] {
        if (m_effect->status() == QSoundEffect::Error && !m_reported) {
            m_reported = true;
            emit unavailable(tr("the link-loss tone cannot be played: %1 cannot be loaded")
                                 .arg(m_effect->source().toString()));
        }
    });
}

ToneAlarmSound::~ToneAlarmSound() = default;

bool ToneAlarmSound::hasSoundCard()
{
    return !QMediaDevices::audioOutputs().isEmpty();
}

void ToneAlarmSound::start()
{
    if (!hasSoundCard()) {
        if (!m_reported) {
            m_reported = true;
            emit unavailable(tr("no sound card: the link-loss alarm is shown but not heard"));
        }
        return;
    }
    if (!m_effect->isPlaying())
        m_effect->play();
}

void ToneAlarmSound::stop()
{
    m_effect->stop();
}

bool ToneAlarmSound::isPlaying() const
{
    return m_effect->isPlaying();
}
