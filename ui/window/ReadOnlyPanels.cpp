#include "ui/window/ReadOnlyPanels.h"

#include "ui/panels/CommandState.h"
#include "ui/panels/ReportedState.h"

#include <QApplication>
#include <QEvent>
#include <QLabel>
#include <QScrollBar>
#include <QTabBar>
#include <QTabWidget>

namespace {

// Makes the widgets inside `area` read only while it is installed on the
// application: clicks and keys never reach them. Tabs and scroll bars still
// move, to look around.
class ReadOnlyArea : public QObject {
public:
    ReadOnlyArea(QWidget* area, QObject* parent) : QObject(parent), m_area(area) {}

protected:
    bool eventFilter(QObject* watched, QEvent* event) override
    {
        switch (event->type()) {
            case QEvent::MouseButtonPress:
            case QEvent::MouseButtonRelease:
            case QEvent::MouseButtonDblClick:
            case QEvent::KeyPress:
            case QEvent::KeyRelease:
                break;
            default:
                return false;
        }
        auto* widget = qobject_cast<QWidget*>(watched);
        if (!widget || !m_area->isAncestorOf(widget) || qobject_cast<QTabBar*>(widget) ||
            qobject_cast<QScrollBar*>(widget))
            return false;
        // A page that is not the log's command (the flight plan) keeps its input.
        for (QWidget* w = widget; w && w != m_area; w = w->parentWidget())
            if (w->property(ReadOnlyPanels::kKeepsInput).toBool())
                return false;
        return true;
    }

private:
    QWidget* m_area;
};

}  // namespace

ReadOnlyPanels::ReadOnlyPanels(CommandState* command, QObject* parent) : QObject(parent), m_command(command) {}

void ReadOnlyPanels::attach(ReportedState* reported, QTabWidget* panels)
{
    m_reported = reported;
    m_panels = panels;
    m_note = new QLabel(replayNote());
    m_note->setObjectName(QStringLiteral("readOnlyNote"));
    // A badge, not a caption: the panels look as editable as ever, so what
    // says they are not must catch the eye. White on the replay's blue, 5.8:1.
    m_note->setStyleSheet(QStringLiteral(
        "QLabel { background-color: #1565c0; color: white; font-weight: bold; padding: 2px 10px; border-radius: 3px; }"));
    m_note->setToolTip(tr("Clicks and keys in the panels are ignored: they show what was commanded, nothing is sent"));
    m_note->hide();
    m_panels->setCornerWidget(m_note, Qt::TopRightCorner);
}

QString ReadOnlyPanels::replayNote()
{
    return tr("Replay: the log's commands, read only");
}

std::chrono::steady_clock::time_point ReadOnlyPanels::now() const
{
    return m_ownCommand ? std::chrono::steady_clock::time_point(std::chrono::microseconds(m_micros))
                        : std::chrono::steady_clock::now();
}

void ReadOnlyPanels::announce(const QString& note)
{
    m_note->setText(note);
    m_note->show();
}

void ReadOnlyPanels::withdraw()
{
    if (!isActive())
        m_note->hide();
}

void ReadOnlyPanels::begin(qint64 startMicros, const QString& note)
{
    if (!isActive()) {
        m_ownCommand = m_command->message();
        m_filter = new ReadOnlyArea(m_panels, this);
        qApp->installEventFilter(m_filter);
    }
    m_micros = startMicros;
    m_reported->clear();
    announce(note);
}

void ReadOnlyPanels::end()
{
    if (!isActive())
        return;
    delete m_filter;  // removes itself from the application
    m_filter = nullptr;
    m_note->hide();
    m_note->setText(replayNote());
    m_reported->clear();
    m_command->replaceMessage(*m_ownCommand);
    m_ownCommand.reset();
}

void ReadOnlyPanels::show(qint64 utcMicros, const std::optional<rcm::Message>& commanded)
{
    if (!isActive())
        return;  // the replay ended meanwhile
    m_micros = utcMicros;
    if (commanded)
        m_command->replaceMessage(*commanded);
}
