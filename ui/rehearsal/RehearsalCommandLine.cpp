#include "ui/rehearsal/RehearsalCommandLine.h"

#include "link/rehearsal/ScenarioRunner.h"
#include "link/plan/PlanFile.h"
#include "link/session/DataFolder.h"

#include <QDir>
#include <QEventLoop>
#include <QFileInfo>

#include <cstdio>

namespace {

void say(const QString& line)
{
    std::fprintf(stderr, "gcs: %s\n", qPrintable(line));
}

// A name that is no file here, such as gear-outage-plan, is one of the
// scenarios that come with gcs; anything else is left to Scenario::load,
// which says what is wrong with it.
QString scenarioFile(const QString& given)
{
    if (QFileInfo::exists(given) || given.contains(QLatin1Char('/')))
        return given;
    const QString shipped = DataFolder::path(QStringLiteral("scenarios"));
    const QString name = given.endsWith(QLatin1String(".json")) ? given : given + QStringLiteral(".json");
    if (!shipped.isEmpty() && QFileInfo::exists(shipped + QLatin1Char('/') + name))
        return shipped + QLatin1Char('/') + name;
    return given;
}

}  // namespace

RehearsalCommandLine::RehearsalCommandLine(QCommandLineParser& parser)
    : m_parser(parser),
      m_rehearse(QStringLiteral("rehearse"),
                 QStringLiteral("Run a rehearsal scenario against the simulated aircraft without a window: a "
                                "file, or the name of one that comes with gcs (share/rcm-gcs/scenarios/ beside "
                                "its bin folder, e.g. gear-outage-plan). Exit 0 when every expectation held, 1 "
                                "when one failed (or an alarm came that no step expected), 2 when the scenario is "
                                "wrong."),
                 QStringLiteral("scenario.json")),
      m_report(QStringLiteral("report"),
               QStringLiteral("Where --rehearse writes report.html, report.json and session.pcapng."),
               QStringLiteral("dir")),
      m_speed(QStringLiteral("rehearse-speed"),
              QStringLiteral("Scenario seconds per second for --rehearse, instead of the scenario's speed; 0: as "
                             "fast as the machine goes."),
              QStringLiteral("n"))
{
    parser.addOptions({m_rehearse, m_report, m_speed});
}

bool RehearsalCommandLine::requested() const
{
    return m_parser.isSet(m_rehearse);
}

Scenario::PlanLoader RehearsalCommandLine::planLoader()
{
    return [](const QString& path, QString* error) -> std::optional<QByteArray> {
        const auto plan = PlanFile::load(path, error);
        return plan ? plan->encode(error) : std::nullopt;
    };
}

int RehearsalCommandLine::run() const
{
    if (!m_parser.isSet(m_report)) {
        say(QStringLiteral("--rehearse needs --report DIR"));
        return kWrongScenario;
    }
    bool speedOk = true;
    const double speed = m_parser.isSet(m_speed) ? m_parser.value(m_speed).toDouble(&speedOk) : -1;
    if (!speedOk || (m_parser.isSet(m_speed) && speed < 0)) {
        say(QStringLiteral("--rehearse-speed wants a number, 0 or more"));
        return kWrongScenario;
    }
    ScenarioError error;
    auto scenario = Scenario::load(scenarioFile(m_parser.value(m_rehearse)), planLoader(), &error);
    if (!scenario) {
        say(error.text());
        return kWrongScenario;
    }
    const QDir report(m_parser.value(m_report));
    const QString logPath = report.filePath(QStringLiteral("session.pcapng"));
    if (!QDir().mkpath(report.path()) || (QFile::exists(logPath) && !QFile::remove(logPath))) {
        say(QStringLiteral("cannot write the report in %1").arg(report.path()));
        return kWrongScenario;
    }
    ScenarioRunner runner(std::move(*scenario), logPath);
    if (!runner.frameLogError().isEmpty())
        say(QStringLiteral("no frame log: %1").arg(runner.frameLogError()));
    if (speed == 0) {
        runner.runToEnd();
    } else {
        QEventLoop loop;
        QObject::connect(&runner, &ScenarioRunner::finished, &loop, &QEventLoop::quit);
        runner.start(speed);
        if (!runner.isFinished())
            loop.exec();
    }
    QString writeError;
    if (!runner.report().write(report.path(), &writeError)) {
        say(writeError);
        return kWrongScenario;
    }
    const RehearsalReport& result = runner.report();
    say(QStringLiteral("rehearsal \"%1\": %2; report in %3")
            .arg(result.scenarioName, result.verdict(), report.filePath(QStringLiteral("report.html"))));
    for (const QString& failure : result.failures())
        say(QStringLiteral("failed: ") + failure);
    return result.passed() ? kHeld : kFailed;
}
