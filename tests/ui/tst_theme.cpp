// The console's two looks measured: every text colour the day and night
// themes define, against the background it is drawn on, in every colour
// group (active, inactive and disabled), has a WCAG 2 contrast ratio of
// 4.5:1 or more; so have the severity colours the console draws itself (the
// event log's rows, the plan's fence warning, errors and acknowledgements)
// in both looks. The ratio is computed here from the sRGB definition, not
// taken from Theme::contrast, and checked against known pairs first.

#include "link/eventlog/EventLog.h"
#include "ui/eventlog/EventLogModel.h"
#include "ui/look/SeverityColours.h"
#include "ui/window/Theme.h"

#include <QApplication>
#include <QBrush>
#include <QTest>

#include <cmath>

namespace {

double channel(double v)
{
    return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
}

double luminance(const QColor& c)
{
    return 0.2126 * channel(c.redF()) + 0.7152 * channel(c.greenF()) + 0.0722 * channel(c.blueF());
}

// A translucent colour as it shows over `under`.
QColor over(const QColor& c, const QColor& under)
{
    const double a = c.alphaF();
    return QColor::fromRgbF(float(c.redF() * a + under.redF() * (1 - a)),
                            float(c.greenF() * a + under.greenF() * (1 - a)),
                            float(c.blueF() * a + under.blueF() * (1 - a)));
}

double ratio(const QColor& text, const QColor& background)
{
    const double a = luminance(over(text, background));
    const double b = luminance(background);
    return (std::max(a, b) + 0.05) / (std::min(a, b) + 0.05);
}

struct Pair {
    QPalette::ColorRole text;
    QPalette::ColorRole background;
    const char* name;
};

// Every text role of a palette with the role it is drawn on.
constexpr Pair kPairs[] = {
    {QPalette::WindowText, QPalette::Window, "WindowText on Window"},
    {QPalette::Text, QPalette::Base, "Text on Base"},
    {QPalette::Text, QPalette::AlternateBase, "Text on AlternateBase"},
    {QPalette::ButtonText, QPalette::Button, "ButtonText on Button"},
    {QPalette::HighlightedText, QPalette::Highlight, "HighlightedText on Highlight"},
    {QPalette::ToolTipText, QPalette::ToolTipBase, "ToolTipText on ToolTipBase"},
    {QPalette::PlaceholderText, QPalette::Base, "PlaceholderText on Base"},
    {QPalette::Link, QPalette::Base, "Link on Base"},
    {QPalette::LinkVisited, QPalette::Base, "LinkVisited on Base"},
};

constexpr double kLeast = 4.5;  // WCAG 2 AA, normal text

}  // namespace

class TestTheme : public QObject {
    Q_OBJECT

private slots:
    // The formula against pairs whose ratios are known.
    void ratioOfKnownPairs()
    {
        QCOMPARE(qRound(ratio(Qt::black, Qt::white) * 100), 2100);
        QCOMPARE(qRound(ratio(Qt::white, Qt::white) * 100), 100);
        QCOMPARE(qRound(ratio(QColor(0x76, 0x76, 0x76), Qt::white) * 100), 454);  // the lightest AA grey on white
        QCOMPARE(qRound(Theme::contrast(QColor(0x76, 0x76, 0x76), Qt::white) * 100), 454);
        // The night theme's old fence warning: dark red on dark grey.
        QVERIFY(ratio(QColor(0xb0, 0x1c, 0x1c), QColor(0x20, 0x21, 0x24)) < 2.5);
    }

    void paletteRoles_data()
    {
        QTest::addColumn<int>("kind");
        QTest::addColumn<int>("group");
        QTest::addColumn<int>("pair");
        const struct {
            Theme::Kind kind;
            const char* name;
        } kinds[] = {{Theme::Kind::Day, "day"}, {Theme::Kind::Night, "night"}};
        const struct {
            QPalette::ColorGroup group;
            const char* name;
        } groups[] = {{QPalette::Active, "active"}, {QPalette::Inactive, "inactive"}, {QPalette::Disabled, "disabled"}};
        for (const auto& k : kinds)
            for (const auto& g : groups)
                for (int p = 0; p < int(std::size(kPairs)); ++p)
                    QTest::addRow("%s %s %s", k.name, g.name, kPairs[p].name) << int(k.kind) << int(g.group) << p;
    }

    void paletteRoles()
    {
        QFETCH(int, kind);
        QFETCH(int, group);
        QFETCH(int, pair);
        const QPalette palette = Theme::palette(Theme::Kind(kind));
        const Pair& p = kPairs[pair];
        const auto g = QPalette::ColorGroup(group);
        const double r = ratio(palette.color(g, p.text), palette.color(g, p.background));
        QVERIFY2(r >= kLeast, qPrintable(QStringLiteral("%1 on %2: %3:1")
                                             .arg(palette.color(g, p.text).name(QColor::HexArgb),
                                                  palette.color(g, p.background).name())
                                             .arg(r, 0, 'f', 2)));
    }

    // The colours the console draws itself, on the backgrounds they are drawn on.
    void severityColours_data()
    {
        QTest::addColumn<int>("kind");
        QTest::addRow("day") << int(Theme::Kind::Day);
        QTest::addRow("night") << int(Theme::Kind::Night);
    }

    void severityColours()
    {
        QFETCH(int, kind);
        const QPalette palette = Theme::palette(Theme::Kind(kind));
        QCOMPARE(SeverityColours::isDark(palette), Theme::Kind(kind) == Theme::Kind::Night);
        using S = SeverityColours::Severity;
        for (S s : {S::Error, S::Warning, S::Success}) {
            const QColor text = SeverityColours::text(s, palette);
            for (QPalette::ColorRole role : {QPalette::Window, QPalette::Base, QPalette::AlternateBase}) {
                const double r = ratio(text, palette.color(role));
                QVERIFY2(r >= kLeast, qPrintable(QStringLiteral("severity %1 text %2 on %3: %4:1")
                                                     .arg(int(s))
                                                     .arg(text.name(), palette.color(role).name())
                                                     .arg(r, 0, 'f', 2)));
            }
            const SeverityColours::Row row = SeverityColours::row(s, palette);
            QVERIFY2(ratio(row.text, row.background) >= kLeast,
                     qPrintable(row.text.name() + QStringLiteral(" on ") + row.background.name()));
            // A tint by night is dark: no bright row in a dim room.
            if (SeverityColours::isDark(palette))
                QVERIFY2(row.background.lightness() < 100, qPrintable(row.background.name()));
        }
        const QString span = SeverityColours::span(S::Error, palette, QStringLiteral("Fence: <1>"));
        QCOMPARE(span, QStringLiteral("<span style=\"color:%1\"><b>Fence: &lt;1&gt;</b></span>")
                           .arg(SeverityColours::text(S::Error, palette).name()));
    }

    // The event log's rows follow the application's palette: light tints by
    // day, dark ones by night, each readable.
    void eventRows()
    {
        auto* app = qobject_cast<QApplication*>(QCoreApplication::instance());
        QVERIFY(app);
        const QPalette before = QApplication::palette();
        EventLog log;
        EventLogModel model(&log);
        log.warning(EventSource::Alarm, QStringLiteral("No frame from the aircraft since the link opened"));
        log.error(EventSource::Link, QStringLiteral("udp: cannot bind"));
        log.info(EventSource::Link, QStringLiteral("Connected"));
        const auto colour = [&](int row, int role) {
            return model.index(row, EventLogModel::TextColumn).data(role).value<QBrush>().color();
        };
        for (Theme::Kind kind : {Theme::Kind::Day, Theme::Kind::Night}) {
            Theme::apply(*app, kind);
            for (int row : {0, 1}) {
                const QColor fg = colour(row, Qt::ForegroundRole);
                const QColor bg = colour(row, Qt::BackgroundRole);
                QVERIFY2(ratio(fg, bg) >= 7.0, qPrintable(fg.name() + QStringLiteral(" on ") + bg.name()));
                if (kind == Theme::Kind::Night)
                    QVERIFY2(bg.lightness() < 100, qPrintable(bg.name()));
                else
                    QVERIFY2(bg.lightness() > 180, qPrintable(bg.name()));
            }
            QVERIFY(!model.index(2, EventLogModel::TextColumn).data(Qt::BackgroundRole).isValid());
        }
        QCOMPARE(colour(1, Qt::BackgroundRole), QColor(0x4a, 0x15, 0x15));
        QCOMPARE(colour(1, Qt::ForegroundRole), QColor(0xff, 0xd6, 0xd6));
        Theme::apply(*app, Theme::Kind::Day);
        QCOMPARE(colour(1, Qt::BackgroundRole), QColor(0xff, 0xd6, 0xd6));
        QApplication::setPalette(before);
    }
};

QTEST_MAIN(TestTheme)
#include "tst_theme.moc"
