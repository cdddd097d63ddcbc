#include "ui/voice/PushToTalkWidget.h"

#include "ui/voice/VoiceChannel.h"

#include <QApplication>
#include <QCheckBox>
#include <QFileDialog>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QKeyEvent>
#include <QLabel>
#include <QAudioDevice>
#include <QMediaDevices>
#include <QLineEdit>
#include <QProgressBar>
#include <QPushButton>
#include <QRadioButton>
#include <QTimer>
#include <QToolButton>
#include <QVBoxLayout>

#include <cmath>

namespace {

// Peak 0..1 as 0..100 over -60..0 dBFS: speech spans tens of dB.
int meterValue(float peak)
{
    if (peak <= 0.001f)
        return 0;
    return int(std::lround(std::clamp(100.0 + 100.0 / 60.0 * 20.0 * std::log10(double(peak)), 0.0, 100.0)));
}

// A peak meter: up at once, down by 3 dB a reading (60 dB a second), so a
// short sound stays in sight.
void showPeak(QProgressBar* meter, float peak)
{
    meter->setValue(std::max(meterValue(peak), meter->value() - 5));
}

QProgressBar* meter(const QString& what)
{
    auto* m = new QProgressBar;
    m->setRange(0, 100);
    m->setTextVisible(false);
    m->setMaximumHeight(12);
    m->setAccessibleName(what);
    return m;
}

}  // namespace

PushToTalkWidget::PushToTalkWidget(VoiceChannel* channel, QWidget* parent)
    : QWidget(parent),
      m_channel(channel),
      m_voiceOn(new QCheckBox(tr("Voice on the link"))),
      m_talk(new QPushButton(tr("Push to talk (F12)"))),
      m_microphone(new QRadioButton(tr("Microphone"))),
      m_file(new QRadioButton(tr("WAV file"))),
      m_path(new QLineEdit),
      m_browse(new QToolButton),
      m_sent(meter(tr("Level sent"))),
      m_received(meter(tr("Level received"))),
      m_note(new QLabel),
      m_release(new QTimer(this))
{
    m_release->setSingleShot(true);
    m_release->setInterval(kReleaseGraceMs);
    connect(m_release, &QTimer::timeout, this, [this] {
        m_keyHeld = false;
        m_channel->stopTalking();
    });
    m_voiceOn->setObjectName(QStringLiteral("voiceOn"));
    m_talk->setObjectName(QStringLiteral("pushToTalk"));
    m_voiceOn->setToolTip(
        tr("Commands and voice share the link (9,600 bps: 4,800 each). The aircraft must be in "
           "voice mode too. Takes effect when the link next starts."));
    m_talk->setToolTip(tr("Hold to talk; or hold F12 anywhere in this window"));
    m_talk->setMinimumHeight(36);
    m_microphone->setChecked(true);
    m_path->setReadOnly(true);
    m_path->setPlaceholderText(tr("a WAV file to say, for rehearsal"));
    m_browse->setText(QStringLiteral("\u2026"));
    m_browse->setToolTip(tr("Choose a WAV file (16-bit PCM, any rate)"));
    m_note->setWordWrap(true);

    auto* file = new QHBoxLayout;
    file->addWidget(m_file);
    file->addWidget(m_path, 1);
    file->addWidget(m_browse);
    auto* levels = new QFormLayout;
    levels->addRow(tr("Out"), m_sent);
    levels->addRow(tr("In"), m_received);
    auto* layout = new QVBoxLayout(this);
    layout->addWidget(m_voiceOn);
    layout->addWidget(m_talk);
    layout->addWidget(m_microphone);
    layout->addLayout(file);
    layout->addLayout(levels);
    layout->addWidget(m_note);
    // Beside the link's settings, which need the room more.
    setSizePolicy(QSizePolicy::Preferred, QSizePolicy::Maximum);

    connect(m_voiceOn, &QCheckBox::toggled, m_channel, &VoiceChannel::setEnabled);
    connect(m_channel, &VoiceChannel::enabledChanged, this, [this](bool on) {
        m_voiceOn->setChecked(on);
        updateEnabled();
    });
    connect(m_talk, &QPushButton::pressed, m_channel, &VoiceChannel::startTalking);
    connect(m_talk, &QPushButton::released, m_channel, &VoiceChannel::stopTalking);
    connect(m_channel, &VoiceChannel::talkingChanged, this, [this](bool talking) {
        // Nothing to talk into: say so on the button held, not "Talking".
        const bool mute = m_microphone->isChecked() && QMediaDevices::defaultAudioInput().isNull();
        m_talk->setText(!talking ? tr("Push to talk (F12)")
                        : mute   ? tr("No microphone: choose a WAV file")
                                 : tr("Talking\u2026"));
    });
    connect(m_microphone, &QRadioButton::toggled, this, &PushToTalkWidget::updateSource);
    connect(m_browse, &QToolButton::clicked, this, &PushToTalkWidget::chooseFile);
    connect(m_channel, &VoiceChannel::sentLevel, this, [this](float level) { showPeak(m_sent, level); });
    connect(m_channel, &VoiceChannel::receivedLevel, this, [this](float level) { showPeak(m_received, level); });
    connect(m_channel, &VoiceChannel::errorOccurred, m_note, &QLabel::setText);
    connect(m_channel, &VoiceChannel::voiceRefused, this, [this](quint64 forged, quint64 replayed) {
        m_note->setText(tr("Voice refused, never played: %1 forged, %2 replayed").arg(forged).arg(replayed));
    });

    qApp->installEventFilter(this);
    updateEnabled();
}

PushToTalkWidget::~PushToTalkWidget()
{
    qApp->removeEventFilter(this);
}

int PushToTalkWidget::sentMeter() const
{
    return m_sent->value();
}

int PushToTalkWidget::receivedMeter() const
{
    return m_received->value();
}

bool PushToTalkWidget::eventFilter(QObject* watched, QEvent* event)
{
    const QEvent::Type type = event->type();
    if (type == QEvent::KeyPress || type == QEvent::KeyRelease) {
        auto* key = static_cast<QKeyEvent*>(event);
        auto* target = qobject_cast<QWidget*>(watched);
        if (key->key() == kTalkKey && target && target->window() == window()) {
            if (key->isAutoRepeat()) {
                // Held: nothing changes.
            } else if (type == QEvent::KeyPress) {
                // A press right after a release is the key's auto-repeat:
                // the talk goes on, it does not start again.
                m_release->stop();
                if (!m_keyHeld)
                    m_channel->startTalking();
                m_keyHeld = true;
            } else if (m_keyHeld) {
                m_release->start();
            }
            return true;
        }
    } else if (type == QEvent::WindowDeactivate && watched == window() && m_keyHeld) {
        m_release->stop();
        m_keyHeld = false;
        m_channel->stopTalking();
    }
    return QWidget::eventFilter(watched, event);
}

void PushToTalkWidget::setRehearsalFile(const QString& path)
{
    m_path->setText(path);
    (path.isEmpty() ? m_microphone : m_file)->setChecked(true);
    updateSource();
}

void PushToTalkWidget::chooseFile()
{
    const QString path = QFileDialog::getOpenFileName(this, tr("WAV file to say"), m_path->text(),
                                                      tr("WAV files (*.wav);;All files (*)"));
    if (path.isEmpty())
        return;
    m_path->setText(path);
    m_file->setChecked(true);
    updateSource();
}

void PushToTalkWidget::updateSource()
{
    m_channel->setRehearsalFile(m_file->isChecked() ? m_path->text() : QString());
    m_note->clear();
}

void PushToTalkWidget::updateEnabled()
{
    const bool on = m_channel->isEnabled();
    m_talk->setEnabled(on);
    m_sent->setEnabled(on);
    m_received->setEnabled(on);
}
