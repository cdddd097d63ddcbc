#include "ui/look/SeverityColours.h"

#include <QString>

namespace SeverityColours {

bool isDark(const QPalette& palette)
{
    return palette.color(QPalette::Window).lightness() < 128;
}

QColor text(Severity severity, const QPalette& palette)
{
    const bool dark = isDark(palette);
    switch (severity) {
        case Severity::Error:
            return dark ? QColor(0xff, 0x8a, 0x80) : QColor(0xb0, 0x1c, 0x1c);
        case Severity::Warning:
            return dark ? QColor(0xff, 0xb7, 0x4d) : QColor(0x8a, 0x51, 0x00);
        case Severity::Success:
            return dark ? QColor(0x81, 0xc7, 0x84) : QColor(0x1b, 0x6b, 0x2e);
    }
    return palette.color(QPalette::WindowText);
}

Row row(Severity severity, const QPalette& palette)
{
    const bool dark = isDark(palette);
    switch (severity) {
        case Severity::Error:
            return dark ? Row{QColor(0xff, 0xd6, 0xd6), QColor(0x4a, 0x15, 0x15)}
                        : Row{QColor(0x7f, 0x00, 0x00), QColor(0xff, 0xd6, 0xd6)};
        case Severity::Warning:
            return dark ? Row{QColor(0xff, 0xe5, 0x99), QColor(0x3d, 0x30, 0x00)}
                        : Row{QColor(0x3d, 0x2b, 0x00), QColor(0xff, 0xe5, 0x99)};
        case Severity::Success:
            return dark ? Row{QColor(0xc8, 0xf0, 0xc9), QColor(0x14, 0x3a, 0x18)}
                        : Row{QColor(0x0b, 0x2e, 0x0c), QColor(0xbf, 0xe8, 0xc0)};
    }
    return {palette.color(QPalette::Text), palette.color(QPalette::Base)};
}

QString span(Severity severity, const QPalette& palette, const QString& text)
{
    return QStringLiteral("<span style=\"color:%1\"><b>%2</b></span>")
        .arg(SeverityColours::text(severity, palette).name(), text.toHtmlEscaped());
}

}  // namespace SeverityColours
