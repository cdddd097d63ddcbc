#pragma once

// gcs --station ID --broker URL --observe URL (and the broker's user,
// password file and TLS files, this station's signing key and the stations
// it trusts): which station this console is, the broker it publishes its
// sessions to, and an aircraft to watch read-only. Here rather than in
// gcs_main so that the program stays a thin list of options.

#include <QCommandLineOption>
#include <QCommandLineParser>

class MainWindow;

class StationCommandLine {
public:
    // Adds its options to `parser`, which must outlive it.
    explicit StationCommandLine(QCommandLineParser& parser);

    // Checks the options after parser.process(): false, with the reason.
    bool check(QString* error) const;
    // After the window restored its settings and before a link starts:
    // the station, the broker joined. False, with the reason, when a file
    // named cannot be read.
    bool apply(MainWindow& window, QString* error) const;
    // --observe was given: the console watches instead of connecting.
    bool observes() const { return m_parser.isSet(m_observe); }

private:
    QCommandLineParser& m_parser;
    QCommandLineOption m_station;
    QCommandLineOption m_broker;
    QCommandLineOption m_observe;
    QCommandLineOption m_user;
    QCommandLineOption m_passwordFile;
    QCommandLineOption m_caFile;
    QCommandLineOption m_signingKey;
    QCommandLineOption m_trust;
};
