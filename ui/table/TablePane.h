#pragma once

// A pane whose body is a table of records: the fleet, the frame log, the
// session's events. The pane makes the table; each kind of pane gives it its
// model and columns and sets what goes around it.

#include <QWidget>

class QTableView;

class TablePane : public QWidget {
    Q_OBJECT

public:
    QTableView* table() const { return m_table; }

protected:
    explicit TablePane(QWidget* parent);

    QTableView* const m_table;
};
