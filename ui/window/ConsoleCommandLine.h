#pragma once

// gcs's own options: the link to start (--rehearsal, --udp-remote, --serial
// with --baud, --dial and --modem-profile, --replay), the airframe, the key
// file, and the window's look (--night, --page) or a picture of it
// (--screenshot, --size, --screenshot-after). Here rather than in gcs_main
// so that the program stays a thin list of steps.

#include "link/session/LinkSettings.h"
#include "ui/window/MainWindow.h"

#include <QCommandLineOption>
#include <QCommandLineParser>
#include <QSize>

#include <optional>

class StationCommandLine;

class ConsoleCommandLine {
public:
    // Adds its options and gcs's description to `parser`, which must outlive it.
    explicit ConsoleCommandLine(QCommandLineParser& parser);

    // After parser.process(), with the station's options checked in their
    // turn: false, with the reason, for a usage error.
    bool check(const StationCommandLine& station, QString* error);
    MainWindow::Options windowOptions() const;
    // Once the window is made: the theme and the panel in front.
    void applyLook(MainWindow& window) const;
    // Just before the window shows: --screenshot's picture, at its size.
    void takePicture(MainWindow& window) const;
    // After it shows: the key into the link settings (which keep its path
    // and lend it to the rehearsal), then the link asked for started.
    void start(MainWindow& window, bool observes) const;

private:
    bool checkLink(QString* error);

    QCommandLineParser& m_parser;
    QCommandLineOption m_rehearsal;
    QCommandLineOption m_udpRemote;
    QCommandLineOption m_serial;
    QCommandLineOption m_baud;
    QCommandLineOption m_dial;
    QCommandLineOption m_profile;
    QCommandLineOption m_replay;
    QCommandLineOption m_airframe;
    QCommandLineOption m_key;
    QCommandLineOption m_screenshot;
    QCommandLineOption m_size;
    QCommandLineOption m_after;
    QCommandLineOption m_night;
    QCommandLineOption m_page;
    std::optional<LinkSettings> m_link;  // --udp-remote or --serial, checked
    QSize m_windowSize;
};
