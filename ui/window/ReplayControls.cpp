#include "ui/window/ReplayControls.h"

#include "ui/panels/SteadyLabel.h"

#include <QComboBox>
#include <QDateTime>
#include <QHBoxLayout>
#include <QLabel>
#include <QSignalBlocker>
#include <QSlider>
#include <QStyle>
#include <QTimeZone>
#include <QToolButton>
#include <QVBoxLayout>

namespace {

// The slider counts seconds: a day's log is 86,400 steps, well inside an int.
constexpr qint64 kMicrosPerStep = 1'000'000;

QString clock(qint64 micros)
{
    const qint64 s = std::max<qint64>(micros, 0) / 1'000'000;
    return QStringLiteral("%1:%2:%3")
        .arg(s / 3600, 2, 10, QLatin1Char('0'))
        .arg(s / 60 % 60, 2, 10, QLatin1Char('0'))
        .arg(s % 60, 2, 10, QLatin1Char('0'));
}

}  // namespace

ReplayControls::ReplayControls(QWidget* parent)
    : QWidget(parent),
      m_play(new QToolButton),
      m_speed(new QComboBox),
      m_slider(new QSlider(Qt::Horizontal)),
      m_time(new SteadyLabel)
{
    m_play->setToolTip(tr("Pause or resume the replay (Ctrl+P)"));
    for (double s : {0.25, 0.5, 1.0, 2.0, 5.0, 10.0})
        m_speed->addItem(QStringLiteral("%1\u00d7").arg(s), s);
    m_speed->setCurrentIndex(m_speed->findData(1.0));
    m_speed->setToolTip(tr("Replay speed: 0.25\u00d7 to 10\u00d7 the logged pace"));
    m_slider->setToolTip(tr("Drag to jump to a time in the log"));

    // Two rows, so that the slider has the dock's whole width however narrow it is.
    auto* buttons = new QHBoxLayout;
    buttons->addWidget(m_play);
    buttons->addWidget(m_speed);
    buttons->addStretch(1);
    buttons->addWidget(m_time);
    auto* layout = new QVBoxLayout(this);
    layout->setContentsMargins(0, 0, 0, 0);
    layout->addWidget(m_slider);
    layout->addLayout(buttons);

    connect(m_play, &QToolButton::clicked, this, [this] { emit pauseRequested(!m_paused); });
    connect(m_speed, &QComboBox::currentIndexChanged, this,
            [this] { emit speedRequested(m_speed->currentData().toDouble()); });
    // Seek when the operator lets go, not at every pixel of the drag.
    connect(m_slider, &QSlider::sliderMoved, this,
            [this](int value) { showTime(m_start + qint64(value) * kMicrosPerStep); });
    connect(m_slider, &QSlider::sliderReleased, this,
            [this] { emit seekRequested(m_start + qint64(m_slider->value()) * kMicrosPerStep); });
    connect(m_slider, &QSlider::actionTriggered, this, [this](int action) {
        if (action == QSlider::SliderPageStepAdd || action == QSlider::SliderPageStepSub ||
            action == QSlider::SliderSingleStepAdd || action == QSlider::SliderSingleStepSub)
            emit seekRequested(m_start + qint64(m_slider->sliderPosition()) * kMicrosPerStep);
    });
    setPaused(false);
    setRange(0, 0);
}

void ReplayControls::showOpening()
{
    setRange(0, 0);
    m_time->setText(tr("Opening the log\u2026"));
    m_time->setToolTip(QString());
}

QString ReplayControls::timeText() const
{
    return m_time->text();
}

void ReplayControls::setRange(qint64 startMicros, qint64 endMicros)
{
    m_start = startMicros;
    m_end = std::max(startMicros, endMicros);
    const int steps = int((m_end - m_start + kMicrosPerStep - 1) / kMicrosPerStep);
    m_slider->setRange(0, steps);
    m_slider->setPageStep(std::max(steps / 20, 1));
    m_slider->setValue(0);
    showTime(m_start);
}

void ReplayControls::setPosition(qint64 utcMicros)
{
    if (!m_slider->isSliderDown())
        m_slider->setValue(int((utcMicros - m_start) / kMicrosPerStep));
    showTime(utcMicros);
}

void ReplayControls::setPaused(bool paused)
{
    m_paused = paused;
    m_play->setIcon(style()->standardIcon(paused ? QStyle::SP_MediaPlay : QStyle::SP_MediaPause));
}

void ReplayControls::setFinished(bool finished)
{
    if (finished)
        setPosition(m_end);
}

double ReplayControls::speed() const
{
    return m_speed->currentData().toDouble();
}

void ReplayControls::setSpeed(double speed)
{
    const QSignalBlocker quiet(m_speed);
    const int index = m_speed->findData(speed);
    if (index >= 0)
        m_speed->setCurrentIndex(index);
}

void ReplayControls::showTime(qint64 utcMicros)
{
    const QString utc =
        QDateTime::fromMSecsSinceEpoch(utcMicros / 1000, QTimeZone::utc()).toString(QStringLiteral("hh:mm:ss"));
    m_time->setText(QStringLiteral("%1 / %2").arg(clock(utcMicros - m_start), clock(m_end - m_start)));
    m_time->setToolTip(tr("Position in the log / length of the log; the position is %1 UTC").arg(utc));
}
