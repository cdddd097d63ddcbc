#pragma once

// uasim's command line: its options, read into SimulatorSession::Settings.
// The rehearsal faults' options are FaultOptions'.

#include "link/aircraft/FaultOptions.h"
#include "link/aircraft/SimulatorSession.h"

#include <QCommandLineOption>

#include <optional>
#include <vector>

class QCommandLineParser;

class SimulatorOptions {
public:
    SimulatorOptions();

    void addTo(QCommandLineParser& parser) const;
    // The settings the parsed command line asks for, with the airframe file
    // read and the voice to speak opened; null when the command line is
    // wrong, with *error saying what is wrong.
    std::optional<SimulatorSession::Settings> read(const QCommandLineParser& parser, QString* error) const;

private:
    // The --station options, or an error.
    std::optional<std::vector<SimulatorSession::Station>> readStations(const QCommandLineParser& parser,
                                                                       QString* error) const;

    QCommandLineOption m_station;
    QCommandLineOption m_failover;
    QCommandLineOption m_udp;
    QCommandLineOption m_serial;
    QCommandLineOption m_baud;
    QCommandLineOption m_modem;
    QCommandLineOption m_log;
    QCommandLineOption m_airframe;
    QCommandLineOption m_uaId;
    FaultOptions m_faults;
    QCommandLineOption m_verbose;
    QCommandLineOption m_key;
    QCommandLineOption m_voiceOut;
    QCommandLineOption m_voiceIn;
    QCommandLineOption m_voice;
    QCommandLineOption m_voiceEcho;
};
