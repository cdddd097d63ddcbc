#include "ui/window/Theme.h"

#include <QApplication>
#include <QStyle>
#include <QStyleFactory>

#include <cmath>

namespace {

QPalette nightPalette()
{
    const QColor window(0x20, 0x21, 0x24);
    const QColor base(0x14, 0x15, 0x17);
    const QColor text(0xe6, 0xe6, 0xe6);
    // Dimmer than the text, still 4.5:1 on the buttons: a disabled control's value is still read.
    const QColor disabledText(0x9a, 0x9a, 0x9a);
    QPalette p;
    p.setColor(QPalette::Window, window);
    p.setColor(QPalette::WindowText, text);
    p.setColor(QPalette::Base, base);
    p.setColor(QPalette::AlternateBase, QColor(0x1c, 0x1d, 0x20));
    p.setColor(QPalette::Text, text);
    p.setColor(QPalette::PlaceholderText, QColor(0xa0, 0xa0, 0xa0));
    p.setColor(QPalette::Button, QColor(0x2c, 0x2d, 0x31));
    p.setColor(QPalette::ButtonText, text);
    p.setColor(QPalette::BrightText, QColor(0xff, 0x80, 0x80));
    p.setColor(QPalette::Light, QColor(0x3c, 0x3d, 0x42));
    p.setColor(QPalette::Midlight, QColor(0x32, 0x33, 0x37));
    p.setColor(QPalette::Mid, QColor(0x8c, 0x8c, 0x8c));  // also the notes some panes write in palette(mid)
    p.setColor(QPalette::Dark, QColor(0x0e, 0x0f, 0x10));
    p.setColor(QPalette::Shadow, Qt::black);
    p.setColor(QPalette::Highlight, QColor(0x2f, 0x5a, 0x96));
    p.setColor(QPalette::HighlightedText, Qt::white);
    p.setColor(QPalette::Link, QColor(0x8a, 0xb4, 0xf8));
    p.setColor(QPalette::LinkVisited, QColor(0xc5, 0x8a, 0xf8));
    p.setColor(QPalette::ToolTipBase, QColor(0x2c, 0x2d, 0x31));
    p.setColor(QPalette::ToolTipText, text);
    for (QPalette::ColorRole role : {QPalette::WindowText, QPalette::Text, QPalette::ButtonText})
        p.setColor(QPalette::Disabled, role, disabledText);
    p.setColor(QPalette::Disabled, QPalette::Base, window);
    p.setColor(QPalette::Disabled, QPalette::Highlight, QColor(0x3c, 0x3d, 0x42));
    return p;
}

double luminance(const QColor& c)
{
    auto channel = [](double v) { return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4); };
    return 0.2126 * channel(c.redF()) + 0.7152 * channel(c.greenF()) + 0.0722 * channel(c.blueF());
}

}  // namespace

QPalette Theme::palette(Kind kind)
{
    if (kind == Kind::Night)
        return nightPalette();
    QStyle* fusion = QStyleFactory::create(QStringLiteral("Fusion"));
    QPalette day = fusion ? fusion->standardPalette() : QPalette();
    delete fusion;
    // Fusion greys disabled text to about 1.6:1, and the replay's read-only
    // panels and a disabled Upload are still read: a grey at 4.5:1 or more,
    // plainly lighter than the black of enabled text.
    const QColor disabledText(0x6a, 0x6a, 0x6a);
    for (QPalette::ColorRole role : {QPalette::WindowText, QPalette::Text, QPalette::ButtonText})
        day.setColor(QPalette::Disabled, role, disabledText);
    // Fusion's selection blue (white on it 3.7:1), its half-transparent
    // placeholder (4:1) and its magenta visited link (3.1:1), each at 4.5:1 or more.
    day.setColor(QPalette::Highlight, QColor(0x1f, 0x6f, 0xb2));
    day.setColor(QPalette::Disabled, QPalette::Highlight, QColor(0x6e, 0x6e, 0x6e));
    day.setColor(QPalette::PlaceholderText, QColor(0x6a, 0x6a, 0x6a));
    day.setColor(QPalette::LinkVisited, QColor(0x7b, 0x1f, 0xa2));
    return day;
}

void Theme::apply(QApplication& app, Kind kind)
{
    if (app.style()->name().compare(QStringLiteral("fusion"), Qt::CaseInsensitive) != 0)
        app.setStyle(QStyleFactory::create(QStringLiteral("Fusion")));
    app.setPalette(palette(kind));
}

QString Theme::name(Kind kind)
{
    return kind == Kind::Night ? QStringLiteral("night") : QStringLiteral("day");
}

std::optional<Theme::Kind> Theme::fromName(const QString& name)
{
    if (name == QStringLiteral("night"))
        return Kind::Night;
    if (name == QStringLiteral("day"))
        return Kind::Day;
    return std::nullopt;
}

double Theme::contrast(const QColor& a, const QColor& b)
{
    const double la = luminance(a);
    const double lb = luminance(b);
    return (std::max(la, lb) + 0.05) / (std::min(la, lb) + 0.05);
}
