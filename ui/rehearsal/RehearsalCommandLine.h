#pragma once

// gcs --rehearse SCENARIO --report DIR: runs a rehearsal scenario without a
// window, writes DIR/report.html, DIR/report.json and DIR/session.pcapng,
// and gives the exit status: 0 when every expectation held, 1 when one
// failed, 2 when the scenario (or the command line) is wrong. Here rather
// than in gcs_main so that the program stays a thin list of options.

#include "link/rehearsal/Scenario.h"

#include <QCommandLineOption>
#include <QCommandLineParser>

class RehearsalCommandLine {
public:
    static constexpr int kHeld = 0;
    static constexpr int kFailed = 1;
    static constexpr int kWrongScenario = 2;

    // Adds its options to `parser`, which must outlive it.
    explicit RehearsalCommandLine(QCommandLineParser& parser);

    // After parser.process(): true when --rehearse was given.
    bool requested() const;
    // Runs it to the end (needs a QCoreApplication); the exit status.
    int run() const;

    // Reads a plan file of any format PlanFile reads into the bytes uploaded.
    static Scenario::PlanLoader planLoader();

private:
    QCommandLineParser& m_parser;
    QCommandLineOption m_rehearse;
    QCommandLineOption m_report;
    QCommandLineOption m_speed;
};
