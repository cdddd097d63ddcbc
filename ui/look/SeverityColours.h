// The colours that say how things stand (an error, a warning, a success),
// chosen for the palette they are drawn on: dark tones on the day theme's
// light window, light ones on the night theme's near black, so that each
// keeps a contrast ratio of 4.5:1 or more (WCAG AA) against the window and
// the views' base in both looks. The tinted rows (the event log's errors and
// warnings) are dark text on a light tint by day and light text on a dark,
// unsaturated tint by night: no bright area in a dim room. tests/tst_theme
// measures every pair.
#pragma once

#include <QColor>
#include <QPalette>

namespace SeverityColours {

enum class Severity { Error, Warning, Success };

// True for a palette whose window is dark (the night theme).
bool isDark(const QPalette& palette);

// Text in the severity's colour, on the palette's Window or Base.
QColor text(Severity severity, const QPalette& palette);

// A row marked with the severity: its text and its background.
struct Row {
    QColor text;
    QColor background;
};
Row row(Severity severity, const QPalette& palette);

// `text` HTML-escaped in a bold span of the severity's colour, for rich-text labels.
QString span(Severity severity, const QPalette& palette, const QString& text);

}  // namespace SeverityColours
