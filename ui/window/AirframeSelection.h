#pragma once

// Which airframe the console commands: the File > Airframe menu (the
// built-in ones and a file), loading one, and the question asked first
// while a link is live. On a live link another airframe holds the command
// back until the operator resumes; the units it lacks are said in the
// event log.

#include "ui/window/ConsoleNotices.h"

#include <QObject>
#include <QString>

class CommandState;
class ConsoleSession;
class QActionGroup;
class QMenu;
class QWidget;

class AirframeSelection : public QObject {
    Q_OBJECT

public:
    // `window`: the parent of its questions and dialogs.
    AirframeSelection(CommandState* command, ConsoleSession* session, const ConsoleNotices& notices, QWidget* window);

    // The Airframe submenu of `file`: the built-in airframes, ticked when
    // loaded, and From a file.
    void addMenu(QMenu* file);
    // The file or resource loaded last.
    QString path() const { return m_path; }

    // False, with the reason (in `error`, else said as an error), when the
    // airframe file cannot be used.
    bool load(const QString& path, QString* error = nullptr);
    // Asks first while a link is live, then load().
    void request(const QString& path);
    // A file dialog, then request().
    void choose();

private:
    // The menu's tick on the airframe loaded.
    void tick();

    CommandState* m_command;
    ConsoleSession* m_session;
    ConsoleNotices m_notices;
    QWidget* m_window;
    QActionGroup* m_actions = nullptr;
    QString m_path;
};
