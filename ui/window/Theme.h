// The console's two looks, for the light it is used in: Day, the Fusion
// style's own light palette (disabled text darkened), and Night, light grey
// text on near black with no large bright area, for a dim ground station or a
// night operation. Every text colour of both, disabled text included, keeps a
// contrast ratio of 4.5:1 or more against its background (WCAG AA;
// tests/tst_theme measures each pair). The warning colours the panels paint
// themselves (amber mismatch, blue "edited") carry their own dark text and
// read the same in both; the colours of errors, warnings and successes follow
// the palette (ui/look/SeverityColours.h).
#pragma once

#include <QPalette>
#include <QString>

#include <optional>

class QApplication;

namespace Theme {

enum class Kind { Day, Night };

QPalette palette(Kind kind);
// The Fusion style, whose every widget follows the palette, and the palette,
// for the whole application; open windows repaint.
void apply(QApplication& app, Kind kind);

// For settings: "day", "night".
QString name(Kind kind);
std::optional<Kind> fromName(const QString& name);

// WCAG 2 contrast ratio of two colours, 1 (none) to 21 (black on white).
double contrast(const QColor& a, const QColor& b);

}  // namespace Theme
