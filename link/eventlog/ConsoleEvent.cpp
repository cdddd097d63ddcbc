#include "link/eventlog/ConsoleEvent.h"

#include <QDateTime>
#include <QStringList>

namespace {

const QString kTimeFormat = QStringLiteral("yyyy-MM-dd'T'HH:mm:ss.zzz'Z'");

QString escaped(const QString& text)
{
    QString out;
    out.reserve(text.size());
    for (const QChar c : text) {
        if (c == u'\\')
            out += QStringLiteral("\\\\");
        else if (c == u'\t')
            out += QStringLiteral("\\t");
        else if (c == u'\n')
            out += QStringLiteral("\\n");
        else if (c == u'\r')
            out += QStringLiteral("\\r");
        else
            out += c;
    }
    return out;
}

std::optional<QString> unescaped(const QString& text)
{
    QString out;
    out.reserve(text.size());
    for (qsizetype i = 0; i < text.size(); ++i) {
        if (text[i] != u'\\') {
            out += text[i];
            continue;
        }
        if (++i == text.size())
            return std::nullopt;
        switch (text[i].unicode()) {
        case u'\\':
            out += u'\\';
            break;
        case u't':
            out += u'\t';
            break;
        case u'n':
            out += u'\n';
            break;
        case u'r':
            out += u'\r';
            break;
        default:
            return std::nullopt;
        }
    }
    return out;
}

}  // namespace

QString eventSeverityName(EventSeverity severity)
{
    switch (severity) {
    case EventSeverity::Info:
        return QStringLiteral("info");
    case EventSeverity::Warning:
        return QStringLiteral("warning");
    case EventSeverity::Error:
        return QStringLiteral("error");
    }
    return {};
}

QString eventSourceName(EventSource source)
{
    switch (source) {
    case EventSource::Link:
        return QStringLiteral("link");
    case EventSource::Key:
        return QStringLiteral("key");
    case EventSource::Plan:
        return QStringLiteral("plan");
    case EventSource::Alarm:
        return QStringLiteral("alarm");
    case EventSource::Console:
        return QStringLiteral("console");
    case EventSource::Control:
        return QStringLiteral("control");
    case EventSource::Command:
        return QStringLiteral("command");
    }
    return {};
}

QString eventLine(const ConsoleEvent& event)
{
    const QDateTime time = QDateTime::fromMSecsSinceEpoch(event.utcMicros / 1000, Qt::UTC);
    return QStringList{time.toString(kTimeFormat), eventSeverityName(event.severity), eventSourceName(event.source),
                       escaped(event.text)}
        .join(u'\t');
}

std::optional<ConsoleEvent> parseEventLine(const QString& line)
{
    const QStringList parts = line.split(u'\t');
    if (parts.size() != 4)
        return std::nullopt;
    ConsoleEvent event;
    const QDateTime time = QDateTime::fromString(parts[0], kTimeFormat);
    if (!time.isValid())
        return std::nullopt;
    event.utcMicros = QDateTime(time.date(), time.time(), Qt::UTC).toMSecsSinceEpoch() * 1000;
    bool found = false;
    for (EventSeverity s : {EventSeverity::Info, EventSeverity::Warning, EventSeverity::Error})
        if (eventSeverityName(s) == parts[1]) {
            event.severity = s;
            found = true;
        }
    if (!found)
        return std::nullopt;
    found = false;
    for (EventSource s : kEventSources)
        if (eventSourceName(s) == parts[2]) {
            event.source = s;
            found = true;
        }
    if (!found)
        return std::nullopt;
    std::optional<QString> text = unescaped(parts[3]);
    if (!text)
        return std::nullopt;
    event.text = *text;
    return event;
}
