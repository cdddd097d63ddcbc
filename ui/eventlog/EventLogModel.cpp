#include "ui/eventlog/EventLogModel.h"

#include "link/eventlog/EventLog.h"
#include "ui/look/SeverityColours.h"

#include <QBrush>
#include <QColor>
#include <QDateTime>
#include <QGuiApplication>

#include <algorithm>

namespace {

constexpr auto kColumns = std::to_array<FlatTableModel::Column>({
    {QT_TRANSLATE_NOOP("EventLogModel", "Time (UTC)")},
    {QT_TRANSLATE_NOOP("EventLogModel", "Severity")},
    {QT_TRANSLATE_NOOP("EventLogModel", "Source")},
    {QT_TRANSLATE_NOOP("EventLogModel", "Event")},
});
static_assert(kColumns.size() == EventLogModel::ColumnCount);

// Errors and warnings as tinted rows: dark text on a light tint by day, light
// text on a dark tint by night (SeverityColours), 7:1 or more either way.
std::optional<SeverityColours::Row> coloursOf(EventSeverity severity)
{
    const QPalette palette = QGuiApplication::palette();
    switch (severity) {
    case EventSeverity::Error:
        return SeverityColours::row(SeverityColours::Severity::Error, palette);
    case EventSeverity::Warning:
        return SeverityColours::row(SeverityColours::Severity::Warning, palette);
    case EventSeverity::Info:
        break;
    }
    return std::nullopt;
}

}  // namespace

EventLogModel::EventLogModel(EventLog* log, QObject* parent) : FlatTableModel(kColumns, parent)
{
    if (log)
        connect(log, &EventLog::recorded, this, &EventLogModel::append);
}

QVariant EventLogModel::cellData(const QModelIndex& index, int role) const
{
    const ConsoleEvent& e = m_events.at(index.row());
    switch (role) {
    case Qt::DisplayRole:
        switch (index.column()) {
        case TimeColumn:
            return QDateTime::fromMSecsSinceEpoch(e.utcMicros / 1000, Qt::UTC)
                .toString(QStringLiteral("HH:mm:ss"));
        case SeverityColumn:
            return eventSeverityName(e.severity);
        case SourceColumn:
            return eventSourceName(e.source);
        case TextColumn:
            return e.text;
        }
        break;
    case Qt::ToolTipRole:
        return QDateTime::fromMSecsSinceEpoch(e.utcMicros / 1000, Qt::UTC)
                   .toString(QStringLiteral("yyyy-MM-dd HH:mm:ss.zzz 'UTC'")) +
               QStringLiteral("\n") + e.text;
    case Qt::ForegroundRole:
        if (const auto c = coloursOf(e.severity))
            return QBrush(c->text);
        break;
    case Qt::BackgroundRole:
        if (const auto c = coloursOf(e.severity))
            return QBrush(c->background);
        break;
    }
    return {};
}

int EventLogModel::count(EventSeverity severity) const
{
    return int(std::count_if(m_events.begin(), m_events.end(),
                             [severity](const ConsoleEvent& e) { return e.severity == severity; }));
}

void EventLogModel::append(const ConsoleEvent& event)
{
    if (m_events.size() >= kMaxEvents) {
        beginRemoveRows({}, 0, 0);
        m_events.removeFirst();
        endRemoveRows();
    }
    const int row = int(m_events.size());
    beginInsertRows({}, row, row);
    m_events.append(event);
    endInsertRows();
}
