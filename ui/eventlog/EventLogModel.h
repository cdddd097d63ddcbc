#pragma once

// The events of the session as a table for the Events dock: time (UTC),
// severity, source and text, oldest first. Errors and warnings carry both a
// background and a text colour, so they read the same in the day and the
// night theme. Holds the newest kMaxEvents; the file keeps them all.

#include "link/eventlog/ConsoleEvent.h"

#include <QAbstractTableModel>
#include <QList>

class EventLog;

class EventLogModel : public QAbstractTableModel {
    Q_OBJECT

public:
    enum Column { TimeColumn, SeverityColumn, SourceColumn, TextColumn, ColumnCount };
    static constexpr int kMaxEvents = 5000;

    // Listens to `log`'s recorded() when given.
    explicit EventLogModel(EventLog* log = nullptr, QObject* parent = nullptr);

    int rowCount(const QModelIndex& parent = {}) const override;
    int columnCount(const QModelIndex& parent = {}) const override;
    QVariant data(const QModelIndex& index, int role = Qt::DisplayRole) const override;
    QVariant headerData(int section, Qt::Orientation orientation, int role = Qt::DisplayRole) const override;

    const ConsoleEvent& event(int row) const { return m_events.at(row); }
    int count(EventSeverity severity) const;

public slots:
    void append(const ConsoleEvent& event);

private:
    QList<ConsoleEvent> m_events;
};
