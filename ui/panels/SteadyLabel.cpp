#include "ui/panels/SteadyLabel.h"

#include <QEvent>

SteadyLabel::SteadyLabel(QWidget* parent) : QLabel(parent) {}

SteadyLabel::SteadyLabel(const QString& text, QWidget* parent) : QLabel(text, parent) {}

void SteadyLabel::showEvent(QShowEvent* event)
{
    QLabel::showEvent(event);
    if (!m_fitted)
        queueFit();
}

void SteadyLabel::paintEvent(QPaintEvent* event)
{
    // A new text is first seen here: QLabel::setText is not virtual. The size
    // is changed after the paint, never inside it.
    if (!m_fitted || text() != m_fittedText)
        queueFit();
    QLabel::paintEvent(event);
}

void SteadyLabel::queueFit()
{
    if (m_fitQueued)
        return;
    m_fitQueued = true;
    QMetaObject::invokeMethod(this, &SteadyLabel::fit, Qt::QueuedConnection);
}

void SteadyLabel::changeEvent(QEvent* event)
{
    QLabel::changeEvent(event);
    if (event->type() == QEvent::FontChange || event->type() == QEvent::StyleChange) {
        m_fitted = false;
        update();
    }
}

void SteadyLabel::fit()
{
    m_fitQueued = false;
    if (!m_least.isValid())
        m_least = minimumSize();
    // QLabel's hints follow its text and style, whatever size it is fixed at.
    QSize wanted = sizeHint().expandedTo(minimumSizeHint()).expandedTo(m_least);
    if (m_fitted)
        wanted = wanted.expandedTo(minimumSize());
    m_fitted = true;
    m_fittedText = text();
    if (minimumSize() != wanted || maximumSize() != wanted)
        setFixedSize(wanted);
}
