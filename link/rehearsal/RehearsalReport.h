#pragma once

// What a rehearsal run found, and its two readings: report.json for
// machines and report.html for people (one file, nothing fetched: the plots
// are inline SVG). Both say the same facts; times are seconds of scenario time.

#include <QByteArray>
#include <QString>

#include <optional>
#include <vector>

struct RehearsalReport {
    struct Expectation {
        int step = 0;         // 1-based
        QString description;  // ScenarioStep::describe()
        bool held = false;
        // Seconds after "at" when it held (or, failed, nothing); for counts, the count.
        std::optional<double> measured;
        QString detail;  // why it failed, or what was seen
    };
    struct TimelineEntry {
        double time = 0;
        QString kind;  // "step", "fault", "alarm", "event", "expectation"
        QString text;
    };
    // Link quality over the last 10 s: good frames received / frames sent, per direction.
    struct QualitySample {
        double time = 0;
        double up = 1;
        double down = 1;
    };
    // A command set, and how long until the console saw the aircraft report it.
    struct Latency {
        int step = 0;
        QString control;
        std::optional<double> seconds;  // nothing: never reported
    };
    struct Frames {
        qint64 sentUp = 0;
        qint64 sentDown = 0;
        qint64 receivedUp = 0;  // good frames the aircraft received
        qint64 receivedDown = 0;
        qint64 inOutage = 0;
        qint64 damaged = 0;  // delivered with a byte changed by a fault
        qint64 lost = 0;     // carried (not in an outage) and not received good
        qint64 wrong = 0;    // received good, yet not what was sent
    };

    QString scenarioName;
    QString scenarioPath;
    double duration = 0;
    QString transport;
    std::vector<Expectation> expectations;
    std::vector<TimelineEntry> timeline;
    std::vector<QualitySample> quality;
    std::vector<Latency> latencies;
    Frames frames;

    bool passed() const;
    QByteArray toJson() const;
    QString toHtml() const;
    // report.json and report.html in `directory` (created when missing).
    bool write(const QString& directory, QString* error = nullptr) const;
};
