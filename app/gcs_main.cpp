// gcs: the operator console (`gcs --help`); start-up, memory and GUI stalls: tests/bench/bench_console.cpp.
#include "ui/plan/PlanCommandLine.h"
#include "ui/rehearsal/RehearsalCommandLine.h"
#include "ui/window/ConsoleCommandLine.h"
#include "ui/window/MainWindow.h"
#include "ui/window/StationCommandLine.h"

#include <QApplication>
#include <QCommandLineParser>
#include <cstdio>

static constexpr int kUsageError = 2;
static void say(const QString& line) { std::fprintf(stderr, "gcs: %s\n", qPrintable(line)); }

int main(int argc, char* argv[])
{
    QApplication app(argc, argv);
    QCoreApplication::setOrganizationName(QStringLiteral("rcm"));
    QCoreApplication::setApplicationName(QStringLiteral("gcs"));
    QGuiApplication::setDesktopFileName(QStringLiteral(RCM_APP_ID));  // its menu entry and icon (Wayland)
    QCommandLineParser parser;
    ConsoleCommandLine console(parser);
    const RehearsalCommandLine rehearse(parser);
    const PlanCommandLine planOptions(parser);
    const StationCommandLine stationOptions(parser);
    parser.process(app);
    if (rehearse.requested())
        return rehearse.run();
    const auto usage = [&](const QString& message) {
        say(message);
        std::fprintf(stderr, "%s", qPrintable(parser.helpText()));
        return kUsageError;
    };
    QString error;
    if (!console.check(stationOptions, &error))
        return usage(error);
    MainWindow window(console.windowOptions());
    console.applyLook(window);
    if (!planOptions.apply(*window.flightPlan(), &error))  // the file is wrong, not the options: no help
        return say(QStringLiteral("--plan: ") + error), kUsageError;
    if (!stationOptions.apply(window, &error))
        return usage(error);
    console.takePicture(window);
    window.show();
    console.start(window, stationOptions.observes());
    return app.exec();
}
