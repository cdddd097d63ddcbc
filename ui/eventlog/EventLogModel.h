#pragma once

// The events of the session as a table for the Events dock: time (UTC),
// severity, source and text, oldest first. Errors and warnings carry both a
// background and a text colour, so they read the same in the day and the
// night theme. Holds the newest kMaxEvents; the file keeps them all.

#include "link/eventlog/ConsoleEvent.h"
#include "ui/table/FlatTableModel.h"

#include <QList>

class EventLog;

class EventLogModel : public FlatTableModel {
    Q_OBJECT

public:
    enum Column { TimeColumn, SeverityColumn, SourceColumn, TextColumn, ColumnCount };
    static constexpr int kMaxEvents = 5000;

    // Listens to `log`'s recorded() when given.
    explicit EventLogModel(EventLog* log = nullptr, QObject* parent = nullptr);

    const ConsoleEvent& event(int row) const { return m_events.at(row); }
    int count(EventSeverity severity) const;

public slots:
    void append(const ConsoleEvent& event);

private:
    QVariant cellData(const QModelIndex& index, int role) const override;
    int rows() const override { return int(m_events.size()); }

    QList<ConsoleEvent> m_events;
};
