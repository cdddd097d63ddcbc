#include "ui/alerts/ErrorBanner.h"

#include "link/eventlog/EventLog.h"

#include <QHBoxLayout>
#include <QLabel>
#include <QPushButton>
#include <QStyle>
#include <QVBoxLayout>

#include <algorithm>

namespace {

// Dark red text on a pale red band with a red rule: 9:1 contrast, and clearly
// not the solid red of the link-loss alarm.
const QString kStyle = QStringLiteral(
    "ErrorBanner { background-color: #ffd6d6; border: 2px solid #b71c1c; border-radius: 3px; }"
    "ErrorBanner QLabel { color: #5c0000; background: transparent; }");

}  // namespace

ErrorBanner::ErrorBanner(QWidget* parent)
    : QFrame(parent),
      m_icon(new QLabel),
      m_message(new QLabel),
      m_count(new QLabel),
      m_dismiss(new QPushButton(tr("Dismiss"))),
      m_dismissAll(new QPushButton(tr("Dismiss all")))
{
    setObjectName(QStringLiteral("errorBanner"));
    setStyleSheet(kStyle);
    setAccessibleName(tr("Errors"));
    const int iconSize = style()->pixelMetric(QStyle::PM_SmallIconSize);
    m_icon->setPixmap(style()->standardIcon(QStyle::SP_MessageBoxCritical).pixmap(iconSize, iconSize));
    m_icon->setAlignment(Qt::AlignTop);
    m_message->setObjectName(QStringLiteral("errorMessage"));
    m_message->setWordWrap(true);
    m_message->setTextFormat(Qt::PlainText);
    m_message->setTextInteractionFlags(Qt::TextSelectableByMouse);
    // Ignored: the window's width decides the banner's, never the message's length.
    QSizePolicy policy(QSizePolicy::Ignored, QSizePolicy::Preferred);
    policy.setHeightForWidth(true);  // grows as many lines as the message needs
    m_message->setSizePolicy(policy);
    QFont bold = m_message->font();
    bold.setBold(true);
    m_message->setFont(bold);
    m_count->setObjectName(QStringLiteral("errorCount"));
    m_dismiss->setToolTip(tr("Dismiss this error; the one before it comes up. All are kept in the Events dock."));
    m_dismissAll->setToolTip(tr("Dismiss every error shown here. All are kept in the Events dock."));
    for (QPushButton* b : {m_dismiss, m_dismissAll}) {
        b->setAutoDefault(false);
        b->setFocusPolicy(Qt::TabFocus);  // a click here leaves the operator's focus where it was
    }
    connect(m_dismiss, &QPushButton::clicked, this, &ErrorBanner::dismiss);
    connect(m_dismissAll, &QPushButton::clicked, this, &ErrorBanner::dismissAll);

    auto* text = new QVBoxLayout;
    text->setSpacing(2);
    text->addWidget(m_message);
    text->addWidget(m_count);
    auto* layout = new QHBoxLayout(this);
    layout->setContentsMargins(8, 6, 8, 6);
    layout->addWidget(m_icon, 0, Qt::AlignTop);
    layout->addLayout(text, 1);
    layout->addWidget(m_dismiss, 0, Qt::AlignTop);
    layout->addWidget(m_dismissAll, 0, Qt::AlignTop);
    refresh();
}

void ErrorBanner::follow(EventLog* log)
{
    connect(log, &EventLog::recorded, this, [this](const ConsoleEvent& event) {
        // The link-loss alarm has its own banner, which goes when the link is back.
        if (event.severity == EventSeverity::Error && event.source != EventSource::Alarm)
            showError(event.text);
    });
}

QString ErrorBanner::currentText() const
{
    return m_errors.isEmpty() ? QString() : m_errors.last().message;
}

QString ErrorBanner::countText() const
{
    return m_count->text();
}

void ErrorBanner::showError(const QString& message)
{
    for (qsizetype i = 0; i < m_errors.size(); ++i) {
        if (m_errors[i].message == message) {
            // Again: counted, and brought to the front as the newest.
            Error again = m_errors.takeAt(i);
            ++again.times;
            m_errors.append(again);
            refresh();
            return;
        }
    }
    m_errors.append({message, 1});
    refresh();
    emit countChanged(count());
}

void ErrorBanner::dismiss()
{
    dismissNewest(1);
}

void ErrorBanner::dismissAll()
{
    dismissNewest(m_errors.size());
}

void ErrorBanner::dismissNewest(qsizetype n)
{
    n = std::min(n, m_errors.size());
    if (n == 0)
        return;
    m_errors.remove(m_errors.size() - n, n);
    refresh();
    emit countChanged(count());
}

bool ErrorBanner::withdraw(const QString& message)
{
    const qsizetype removed = m_errors.removeIf([&](const Error& e) { return e.message == message; });
    if (!removed)
        return false;
    refresh();
    emit countChanged(count());
    return true;
}

void ErrorBanner::refresh()
{
    setVisible(!m_errors.isEmpty());
    if (m_errors.isEmpty()) {
        m_message->clear();
        m_count->clear();
        return;
    }
    const Error& shown = m_errors.last();
    m_message->setText(shown.message);
    QStringList parts;
    if (m_errors.size() > 1)
        parts << tr("Newest of %1 errors").arg(m_errors.size());
    if (shown.times > 1)
        parts << tr("this one %1 times").arg(shown.times);
    m_count->setText(parts.join(QStringLiteral("; ")));
    m_count->setVisible(!parts.isEmpty());
    m_dismissAll->setVisible(m_errors.size() > 1);
}
