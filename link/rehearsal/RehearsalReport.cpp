#include "link/rehearsal/RehearsalReport.h"

#include <QDir>
#include <QFile>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>

#include <algorithm>
#include <cmath>

namespace {

QString seconds(double s)
{
    return QString::number(s, 'f', 1);
}

QJsonValue optionalNumber(const std::optional<double>& value)
{
    return value ? QJsonValue(*value) : QJsonValue(QJsonValue::Null);
}

QString plural(qsizetype n, const QString& one, const QString& many)
{
    return QStringLiteral("%1 %2").arg(n).arg(n == 1 ? one : many);
}

// Seconds between the time axis' ticks: no more than ten of them, on
// round seconds or whole minutes.
double tickStep(double duration)
{
    static constexpr double kSteps[] = {1, 2, 5, 10, 15, 30, 60, 120, 300, 600, 900, 1200, 1800, 3600, 7200, 14400};
    for (double step : kSteps) {
        if (duration / step <= 10)
            return step;
    }
    return std::ceil(duration / 10 / 3600) * 3600;
}

QString tickLabel(double t, double step)
{
    if (t == 0)
        return QStringLiteral("0");
    if (step < 60)
        return QStringLiteral("%1 s").arg(t);
    return QStringLiteral("%1 min").arg(t / 60);
}

// Link quality for each direction, 0-100 % against scenario time: a time
// axis with ticks, the faults' periods shaded (and named, one row each,
// under the axis), the link-loss alarms marked (red when no step expected
// them).
QString qualityPlot(const RehearsalReport& report)
{
    constexpr int width = 800, left = 40, right = 30, top = 10, plotHeight = 170, faultRow = 16;
    const double plotBottom = top + plotHeight;
    const double faultsTop = plotBottom + 44;
    const int height = int(faultsTop) + faultRow * int(report.faults.size()) + 4;
    const double duration = std::max(report.duration, 1.0);
    const auto x = [&](double t) { return left + (width - left - right) * std::clamp(t, 0.0, duration) / duration; };
    const auto y = [&](double q) { return top + plotHeight * (1.0 - q); };
    // SVG lengths to a tenth of a pixel.
    const auto px = [](double v) { return QString::number(v, 'f', 1); };
    const auto n = [](int v) { return QString::number(v); };
    QString svg = QStringLiteral(
                      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%1\" height=\"%2\" "
                      "role=\"img\" aria-label=\"link quality against scenario time\">\n")
                      .arg(n(width), n(height));
    for (std::size_t i = 0; i < report.faults.size(); ++i) {
        const RehearsalReport::FaultPeriod& f = report.faults[i];
        const QString title =
            QStringLiteral("%1 (%2 s to %3 s)").arg(f.text.toHtmlEscaped(), seconds(f.start), seconds(f.end));
        const double span = std::max(1.0, x(f.end) - x(f.start));
        svg += QStringLiteral(
                   "<rect class=\"fault\" x=\"%1\" y=\"%2\" width=\"%3\" height=\"%4\" fill=\"#f0a030\" "
                   "fill-opacity=\"0.25\"><title>%5</title></rect>\n")
                   .arg(px(x(f.start)), n(top), px(span), n(plotHeight), title);
        const double rowTop = faultsTop + faultRow * double(i);
        svg += QStringLiteral(
                   "<rect x=\"%1\" y=\"%2\" width=\"%3\" height=\"%4\" fill=\"#f0a030\" fill-opacity=\"0.6\"/>"
                   "<text x=\"%5\" y=\"%6\" font-size=\"11\">%7</text>\n")
                   .arg(px(x(f.start)), px(rowTop + 2), px(span), n(faultRow - 4), px(x(f.start) + 3), px(rowTop + 11),
                        title);
    }
    for (int percent : {0, 50, 100})
        svg += QStringLiteral(
                   "<line x1=\"%1\" x2=\"%2\" y1=\"%3\" y2=\"%3\" stroke=\"#ccc\"/>"
                   "<text x=\"2\" y=\"%4\" font-size=\"11\">%5%</text>\n")
                   .arg(n(left), n(width - right), px(y(percent / 100.0)), px(y(percent / 100.0) + 4), n(percent));
    const double step = tickStep(duration);
    for (double t = 0; t <= duration + 1e-9; t += step)
        svg += QStringLiteral(
                   "<line class=\"tick\" x1=\"%1\" x2=\"%1\" y1=\"%2\" y2=\"%3\" stroke=\"#888\"/>"
                   "<text x=\"%1\" y=\"%4\" font-size=\"11\" text-anchor=\"middle\">%5</text>\n")
                   .arg(px(x(t)), px(plotBottom), px(plotBottom + 5), px(plotBottom + 18), tickLabel(t, step));
    svg += QStringLiteral(
               "<line x1=\"%1\" x2=\"%2\" y1=\"%3\" y2=\"%3\" stroke=\"#888\"/>"
               "<text x=\"%4\" y=\"%5\" font-size=\"11\" text-anchor=\"middle\">scenario time</text>\n")
               .arg(n(left), n(width - right), px(plotBottom), n((left + width - right) / 2), px(plotBottom + 34));
    const auto line = [&](auto member, const char* colour, const char* name) {
        QString points;
        for (const auto& s : report.quality)
            points += QStringLiteral("%1,%2 ").arg(px(x(s.time)), px(y(s.*member)));
        return QStringLiteral(
                   "<polyline fill=\"none\" stroke=\"%1\" stroke-width=\"1.5\" points=\"%2\">"
                   "<title>%3</title></polyline>\n")
            .arg(QLatin1String(colour), points.trimmed(), QLatin1String(name));
    };
    svg += line(&RehearsalReport::QualitySample::up, "#1f77b4", "up (to the aircraft)");
    svg += line(&RehearsalReport::QualitySample::down, "#d62728", "down (to the console)");
    for (const RehearsalReport::Alarm& a : report.alarms) {
        if (!a.raised())
            continue;
        svg += QStringLiteral(
                   "<line class=\"alarm\" x1=\"%1\" x2=\"%1\" y1=\"%2\" y2=\"%3\" stroke=\"%4\" "
                   "stroke-width=\"2\" stroke-dasharray=\"4 3\"><title>%5 at %6 s%7</title></line>\n")
                   .arg(px(x(a.time)), n(top), px(plotBottom),
                        a.unexpected() ? QStringLiteral("#b00") : QStringLiteral("#555"), a.name, seconds(a.time),
                        a.unexpected() ? QStringLiteral(", which no step expected")
                                       : QStringLiteral(", expected by step %1").arg(a.expectedBy));
    }
    return svg + QStringLiteral("</svg>\n");
}

// One bar per control set: seconds until it was reported.
QString latencyPlot(const std::vector<RehearsalReport::Latency>& latencies)
{
    if (latencies.empty())
        return QStringLiteral("<p>No command was set.</p>\n");
    double longest = 1;
    for (const auto& l : latencies)
        longest = std::max(longest, l.seconds.value_or(0));
    constexpr int row = 22, labelWidth = 360, barWidth = 380;
    QString svg = QStringLiteral(
                      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%1\" height=\"%2\" role=\"img\" "
                      "aria-label=\"command to report latency\">\n")
                      .arg(labelWidth + barWidth + 80)
                      .arg(row * int(latencies.size()) + 4);
    for (std::size_t i = 0; i < latencies.size(); ++i) {
        const auto& l = latencies[i];
        const int top = int(i) * row + 2;
        // A long line ("land_wheels LHS=... TAIL=...") would run under its
        // bar: cut to what the label column holds, whole in its tool tip.
        constexpr qsizetype kLabelChars = 46;
        const QString label =
            l.control.size() > kLabelChars ? l.control.left(kLabelChars - 1) + QChar(0x2026) : l.control;
        svg += QStringLiteral("<text x=\"0\" y=\"%1\" font-size=\"12\"><title>%2</title>%3</text>")
                   .arg(top + 15)
                   .arg(l.control.toHtmlEscaped(), label.toHtmlEscaped());
        if (l.seconds)
            svg += QStringLiteral(
                       "<rect x=\"%1\" y=\"%2\" width=\"%3\" height=\"16\" fill=\"#1f77b4\"/>"
                       "<text x=\"%4\" y=\"%5\" font-size=\"12\">%6 s</text>\n")
                       .arg(labelWidth)
                       .arg(top)
                       .arg(std::max(1.0, barWidth * *l.seconds / longest), 0, 'f', 1)
                       .arg(labelWidth + barWidth * *l.seconds / longest + 6, 0, 'f', 1)
                       .arg(top + 13)
                       .arg(seconds(*l.seconds));
        else
            svg += QStringLiteral("<text x=\"%1\" y=\"%2\" font-size=\"12\" fill=\"#b00\">never reported</text>\n")
                       .arg(labelWidth)
                       .arg(top + 13);
    }
    return svg + QStringLiteral("</svg>\n");
}

}  // namespace

bool RehearsalReport::passed() const
{
    return std::all_of(expectations.begin(), expectations.end(), [](const Expectation& e) { return e.held; }) &&
           std::none_of(alarms.begin(), alarms.end(), [](const Alarm& a) { return a.unexpected(); });
}

QString RehearsalReport::verdict() const
{
    const auto failed = std::count_if(expectations.begin(), expectations.end(), [](const auto& e) { return !e.held; });
    const auto unexpected = std::count_if(alarms.begin(), alarms.end(), [](const auto& a) { return a.unexpected(); });
    if (failed == 0 && unexpected == 0)
        return QStringLiteral("every expectation held (%1)").arg(expectations.size());
    QStringList parts;
    if (failed > 0)
        parts << QStringLiteral("%1 of %2 failed")
                     .arg(failed)
                     .arg(plural(qsizetype(expectations.size()), QStringLiteral("expectation"),
                                 QStringLiteral("expectations")));
    if (unexpected > 0)
        parts << plural(unexpected, QStringLiteral("alarm"), QStringLiteral("alarms")) +
                     QStringLiteral(" no step expected");
    return parts.join(QStringLiteral("; "));
}

QStringList RehearsalReport::failures() const
{
    QStringList lines;
    for (const Expectation& e : expectations)
        if (!e.held)
            lines << QStringLiteral("%1 (%2)").arg(e.description, e.detail);
    for (const Alarm& a : alarms)
        if (a.unexpected())
            lines << QStringLiteral("%1 alarm at %2 s, which no step expected").arg(a.name, seconds(a.time));
    return lines;
}

QByteArray RehearsalReport::toJson() const
{
    QJsonObject root;
    root.insert(QStringLiteral("scenario"), scenarioName);
    root.insert(QStringLiteral("file"), scenarioPath);
    root.insert(QStringLiteral("verdict"), passed() ? QStringLiteral("passed") : QStringLiteral("failed"));
    root.insert(QStringLiteral("duration"), duration);
    root.insert(QStringLiteral("transport"), transport);
    QJsonArray expected;
    for (const Expectation& e : expectations)
        expected.append(
            QJsonObject{{QStringLiteral("step"), e.step},
                        {QStringLiteral("expectation"), e.description},
                        {QStringLiteral("result"), e.held ? QStringLiteral("held") : QStringLiteral("failed")},
                        {QStringLiteral("measured"), optionalNumber(e.measured)},
                        {QStringLiteral("detail"), e.detail}});
    root.insert(QStringLiteral("expectations"), expected);
    root.insert(QStringLiteral("frames"), QJsonObject{{QStringLiteral("sent-up"), frames.sentUp},
                                                      {QStringLiteral("sent-down"), frames.sentDown},
                                                      {QStringLiteral("received-up"), frames.receivedUp},
                                                      {QStringLiteral("received-down"), frames.receivedDown},
                                                      {QStringLiteral("in-outage"), frames.inOutage},
                                                      {QStringLiteral("damaged"), frames.damaged},
                                                      {QStringLiteral("lost"), frames.lost},
                                                      {QStringLiteral("wrong"), frames.wrong}});
    QJsonArray alarmsJson;
    for (const Alarm& a : alarms)
        alarmsJson.append(QJsonObject{
            {QStringLiteral("time"), a.time},
            {QStringLiteral("alarm"), a.name},
            {QStringLiteral("expected-by"), a.expectedBy > 0 ? QJsonValue(a.expectedBy) : QJsonValue(QJsonValue::Null)},
            {QStringLiteral("result"), a.unexpected() ? QStringLiteral("unexpected") : QStringLiteral("expected")}});
    root.insert(QStringLiteral("alarms"), alarmsJson);
    QJsonArray faultsJson;
    for (const FaultPeriod& f : faults)
        faultsJson.append(QJsonObject{
            {QStringLiteral("start"), f.start}, {QStringLiteral("end"), f.end}, {QStringLiteral("fault"), f.text}});
    root.insert(QStringLiteral("faults"), faultsJson);
    QJsonArray timelineJson;
    for (const TimelineEntry& t : timeline)
        timelineJson.append(QJsonObject{
            {QStringLiteral("time"), t.time}, {QStringLiteral("kind"), t.kind}, {QStringLiteral("text"), t.text}});
    root.insert(QStringLiteral("timeline"), timelineJson);
    QJsonArray latencyJson;
    for (const Latency& l : latencies)
        latencyJson.append(QJsonObject{{QStringLiteral("step"), l.step},
                                       {QStringLiteral("control"), l.control},
                                       {QStringLiteral("seconds"), optionalNumber(l.seconds)}});
    root.insert(QStringLiteral("latency"), latencyJson);
    QJsonArray qualityJson;
    for (const QualitySample& q : quality)
        qualityJson.append(QJsonArray{q.time, q.up, q.down});
    root.insert(QStringLiteral("link-quality"), qualityJson);
    return QJsonDocument(root).toJson(QJsonDocument::Indented);
}

QString RehearsalReport::toHtml() const
{
    const bool ok = passed();
    const auto e = [](const QString& s) { return s.toHtmlEscaped(); };
    QString html = QStringLiteral(
                       "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>Rehearsal: %1</title>\n"
                       "<style>body{font-family:sans-serif;margin:2em;max-width:60em}table{border-collapse:collapse}"
                       "td,th{border:1px solid #ccc;padding:3px 8px;text-align:left}.held{color:#060}"
                       ".failed{color:#b00;font-weight:bold}.verdict{font-size:1.6em;padding:.4em;border-radius:4px}"
                       ".pass{background:#dfd}.fail{background:#fdd}</style></head><body>\n")
                       .arg(e(scenarioName));
    html += QStringLiteral("<p class=\"verdict %1\">%2: %3</p>\n")
                .arg(ok ? QStringLiteral("pass") : QStringLiteral("fail"),
                     ok ? QStringLiteral("PASSED") : QStringLiteral("FAILED"), e(verdict()));
    html += QStringLiteral("<h1>%1</h1>\n<p>%2 &middot; %3 s of scenario time &middot; %4</p>\n")
                .arg(e(scenarioName), e(scenarioPath), seconds(duration), e(transport));
    // What was seen says the measured time or count in words: one column.
    html += QStringLiteral(
        "<h2>Expectations</h2>\n<table><tr><th>Step</th><th>Expectation</th><th>Result</th>"
        "<th>What was seen</th></tr>\n");
    for (const Expectation& x : expectations)
        html += QStringLiteral("<tr><td>%1</td><td>%2</td><td class=\"%3\">%3</td><td>%4</td></tr>\n")
                    .arg(x.step)
                    .arg(e(x.description), x.held ? QStringLiteral("held") : QStringLiteral("failed"), e(x.detail));
    html += QStringLiteral("</table>\n<h2>Alarms</h2>\n");
    if (alarms.empty()) {
        html += QStringLiteral("<p>None.</p>\n");
    } else {
        html += QStringLiteral("<table><tr><th>Time (s)</th><th>Alarm</th><th>Expected</th></tr>\n");
        for (const Alarm& a : alarms)
            html +=
                QStringLiteral("<tr><td>%1</td><td>%2</td><td%3>%4</td></tr>\n")
                    .arg(seconds(a.time), e(a.name), a.unexpected() ? QStringLiteral(" class=\"failed\"") : QString(),
                         a.expectedBy > 0 ? QStringLiteral("by step %1").arg(a.expectedBy)
                         : a.raised()     ? QStringLiteral("by no step")
                                          : QStringLiteral("&mdash; (the alarm clearing)"));
        html += QStringLiteral("</table>\n");
    }
    html += QStringLiteral(
                "<h2>Frames</h2>\n<p>Up (to the aircraft): %1 sent, %2 received good. Down: %3 "
                "sent, %4 received good. %5 lost to outages, %6 damaged by faults, %7 lost, %8 wrong.</p>\n")
                .arg(frames.sentUp)
                .arg(frames.receivedUp)
                .arg(frames.sentDown)
                .arg(frames.receivedDown)
                .arg(frames.inOutage)
                .arg(frames.damaged)
                .arg(frames.lost)
                .arg(frames.wrong);
    html += QStringLiteral(
        "<h2>Link quality</h2>\n<p>Good frames received per frame sent over the last 10 s: "
        "<span style=\"color:#1f77b4\">up</span>, <span style=\"color:#d62728\">down</span>; "
        "<span style=\"background:#fbe3bd\">shaded</span> while a fault acted; dashed lines where the link-loss "
        "alarm was raised (<span style=\"color:#b00\">red</span>: no step expected it).</p>\n");
    html += qualityPlot(*this);
    html += QStringLiteral("<h2>Command to report latency</h2>\n") + latencyPlot(latencies);
    html += QStringLiteral("<h2>Timeline</h2>\n<table><tr><th>Time (s)</th><th>Kind</th><th>What</th></tr>\n");
    for (const TimelineEntry& t : timeline)
        html +=
            QStringLiteral("<tr><td>%1</td><td>%2</td><td>%3</td></tr>\n").arg(seconds(t.time), e(t.kind), e(t.text));
    return html + QStringLiteral("</table>\n</body></html>\n");
}

bool RehearsalReport::write(const QString& directory, QString* error) const
{
    if (!QDir().mkpath(directory)) {
        if (error)
            *error = QStringLiteral("cannot create %1").arg(directory);
        return false;
    }
    const auto save = [&](const QString& name, const QByteArray& bytes) {
        QFile file(QDir(directory).filePath(name));
        if (file.open(QIODevice::WriteOnly | QIODevice::Truncate) && file.write(bytes) == bytes.size())
            return true;
        if (error)
            *error = QStringLiteral("cannot write %1: %2").arg(file.fileName(), file.errorString());
        return false;
    };
    return save(QStringLiteral("report.json"), toJson()) && save(QStringLiteral("report.html"), toHtml().toUtf8());
}
