#pragma once

// The rehearsal-fault options of a command line (--ber, --burst, --drop,
// --delay, --outage, --silent, --seed), read into FaultSettings, and what
// the faults did, said in one line.

#include "link/aircraft/FaultInjector.h"

#include <QCommandLineOption>
#include <QString>

#include <optional>

class QCommandLineParser;

class FaultOptions {
public:
    FaultOptions();

    void addTo(QCommandLineParser& parser) const;
    // The settings the parsed command line asks for; null when an option's
    // value is wrong, with *error saying which and what it wants.
    std::optional<FaultSettings> read(const QCommandLineParser& parser, QString* error) const;

    // "faults: 12 frames offered, 11 sent (...)".
    static QString countersText(const FaultInjector::Counters& counters);

private:
    QCommandLineOption m_ber;
    QCommandLineOption m_burst;
    QCommandLineOption m_drop;
    QCommandLineOption m_delay;
    QCommandLineOption m_outage;
    QCommandLineOption m_silent;
    QCommandLineOption m_seed;
};

// "A:B" with both numbers not negative, into *a and *b; false when not.
bool parseNumberPair(const QString& text, double* a, double* b);
