#pragma once

// The Events dock's content: every event of the session, newest at the
// bottom and kept in view, errors and warnings tinted, with the path of the
// file that keeps them.

#include "ui/table/TablePane.h"

class EventLogModel;
class QLabel;

class EventLogView : public TablePane {
    Q_OBJECT

public:
    explicit EventLogView(EventLogModel* model, QWidget* parent = nullptr);

    // Where the events are kept; "not kept in a file" when empty.
    void setFilePath(const QString& path);
    QString fileText() const;
    // "12 events, 1 error, 2 warnings"
    QString countsText() const;

    // A replay: the live session's events so far are hidden (they are not
    // the log's), and a note above the table says so; only what happens
    // from now on shows. endReplay() shows them all again.
    void beginReplay();
    void endReplay();
    bool isReplaying() const { return m_replaying; }
    // The note shown during a replay; empty when none.
    QString replayNoteText() const;
    // Rows hidden for the replay.
    int hiddenRows() const { return m_hidden; }

private:
    void updateCounts();

    EventLogModel* m_model;
    QLabel* m_counts;
    QLabel* m_file;
    QLabel* m_replayNote;
    bool m_replaying = false;
    int m_hidden = 0;
};
