#pragma once

// What a rehearsal run found, and its two readings: report.json for
// machines and report.html for people (one file, nothing fetched: the plots
// are inline SVG). Both say the same facts; times are seconds of scenario time.

#include <QByteArray>
#include <QString>
#include <QStringList>

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
    // An alarm the console raised or cleared, and the step that expected it
    // (0: none did). A raised alarm (link-lost) no step expected fails the
    // run: the operator would have been alarmed, and the scenario did not
    // say so. Its clearing (link-regained) needs no expectation.
    struct Alarm {
        double time = 0;
        QString name;  // "link-lost", "link-regained"
        int expectedBy = 0;
        bool raised() const { return name == QLatin1String("link-lost"); }
        bool unexpected() const { return raised() && expectedBy == 0; }
    };
    // When a fault acted on the link: from its step until it ended (an
    // outage's seconds, a clear, a fault of its kind replacing it, the run's end).
    struct FaultPeriod {
        double start = 0;
        double end = 0;
        QString text;  // "fault ber 0.002", "fault outage 15 down", "drop the call"
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
    std::vector<Alarm> alarms;
    std::vector<FaultPeriod> faults;
    std::vector<QualitySample> quality;
    std::vector<Latency> latencies;
    Frames frames;

    // Every expectation held and no alarm was raised that no step expected.
    bool passed() const;
    // "every expectation held (5)"; failed: "2 of 3 expectations failed; 1
    // alarm no step expected".
    QString verdict() const;
    // What failed, one line each: "step 2 at 0 s: expect ... (not seen by
    // 10 s)", "link-lost alarm at 1718.0 s, which no step expected".
    QStringList failures() const;
    QByteArray toJson() const;
    QString toHtml() const;
    // report.json and report.html in `directory` (created when missing).
    bool write(const QString& directory, QString* error = nullptr) const;
};
