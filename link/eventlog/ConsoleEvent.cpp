#include "link/eventlog/ConsoleEvent.h"

#include "link/common/NameTable.h"

#include <QDateTime>
#include <QStringList>

#include <algorithm>
#include <array>

namespace {

// The file's words for them: written by eventLine(), read by parseEventLine().
constexpr auto kSeverityNames = std::to_array<Named<EventSeverity>>({
    {EventSeverity::Info, "info"},
    {EventSeverity::Warning, "warning"},
    {EventSeverity::Error, "error"},
});
constexpr auto kSourceNames = std::to_array<Named<EventSource>>({
    {EventSource::Link, "link"},
    {EventSource::Key, "key"},
    {EventSource::Plan, "plan"},
    {EventSource::Alarm, "alarm"},
    {EventSource::Console, "console"},
    {EventSource::Control, "control"},
    {EventSource::Command, "command"},
});

const QString kTimeFormat = QStringLiteral("yyyy-MM-dd'T'HH:mm:ss.zzz'Z'");

// The characters a line cannot hold as they are, each with the letter that
// stands for it after a backslash.
struct Escape {
    char16_t character;
    char16_t letter;
};
constexpr std::array<Escape, 4> kEscapes{{{u'\\', u'\\'}, {u'\t', u't'}, {u'\n', u'n'}, {u'\r', u'r'}}};

QString escaped(const QString& text)
{
    QString out;
    out.reserve(text.size());
    for (const QChar c : text) {
        const auto escape = std::ranges::find(kEscapes, c.unicode(), &Escape::character);
        if (escape == kEscapes.end()) {
            out += c;
            continue;
        }
        out += u'\\';
        out += QChar(escape->letter);
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
        const auto escape = std::ranges::find(kEscapes, text[i].unicode(), &Escape::letter);
        if (escape == kEscapes.end())
            return std::nullopt;
        out += QChar(escape->character);
    }
    return out;
}

}  // namespace

QString eventSeverityName(EventSeverity severity)
{
    return nameText(kSeverityNames, severity);
}

QString eventSourceName(EventSource source)
{
    return nameText(kSourceNames, source);
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
    const std::optional<EventSeverity> severity = valueIn(kSeverityNames, parts[1]);
    const std::optional<EventSource> source = valueIn(kSourceNames, parts[2]);
    if (!severity || !source)
        return std::nullopt;
    event.severity = *severity;
    event.source = *source;
    std::optional<QString> text = unescaped(parts[3]);
    if (!text)
        return std::nullopt;
    event.text = *text;
    return event;
}
