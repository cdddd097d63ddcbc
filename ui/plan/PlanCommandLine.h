#pragma once

// gcs --plan FILE --mbtiles FILE --tile-url TEMPLATE --tile-attribution TEXT:
// a flight plan shown at start-up and the map tiles under it. Here rather
// than in gcs_main so that the program stays a thin list of options.

#include <QCommandLineOption>
#include <QCommandLineParser>

class FlightPlanWidget;

class PlanCommandLine {
public:
    // Adds its options to `parser`, which must outlive it.
    explicit PlanCommandLine(QCommandLineParser& parser);

    // After parser.process() and after the window restored its settings:
    // the tiles given replace the saved ones, and the plan is loaded. False,
    // with the reason, when the plan cannot be read.
    bool apply(FlightPlanWidget& widget, QString* error) const;

private:
    QCommandLineParser& m_parser;
    QCommandLineOption m_plan;
    QCommandLineOption m_mbtiles;
    QCommandLineOption m_tileUrl;
    QCommandLineOption m_attribution;
};
