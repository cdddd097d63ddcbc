#pragma once

// The Events dock's content: every event of the session, newest at the
// bottom and kept in view, errors and warnings tinted, with the path of the
// file that keeps them.

#include <QWidget>

class EventLogModel;
class QLabel;
class QTableView;

class EventLogView : public QWidget {
    Q_OBJECT

public:
    explicit EventLogView(EventLogModel* model, QWidget* parent = nullptr);

    QTableView* table() const { return m_table; }
    // Where the events are kept; "not kept in a file" when empty.
    void setFilePath(const QString& path);
    QString fileText() const;
    // "12 events, 1 error, 2 warnings"
    QString countsText() const;

private:
    void updateCounts();

    EventLogModel* m_model;
    QTableView* m_table;
    QLabel* m_counts;
    QLabel* m_file;
};
