#pragma once

// The fleet as a flat table, one row per aircraft a broker has heard of, in
// the manner of the frame log's model (and Wireshark's packet list): a row
// holds the aircraft's summary as FleetFeed last said it, rows are appended
// in the order aircraft appear and never move (a view sorts through a
// proxy), and the text of a cell is built when a view asks for it. Updates
// are collected and told once per pass of the event loop, at most ten times
// a second (kMinFlushIntervalMs): a broker that
// delivers a thousand aircraft's reports in one burst costs the view one
// dataChanged() over the rows that changed and one rowsInserted() for the
// aircraft that are new, not one of each per message.
//
// The age of the last frame is computed in data() against the model's clock
// (injected, so that tests are exact); refreshAges() tells the views that
// ages moved on, and FleetView calls it once a second. A row reads as stale
// when the aircraft has not been heard for the stale limit, and as offline
// when none of its stations is online (StateRole; the brushes colour it).

#include "link/broker/FleetFeed.h"
#include "ui/table/FlatTableModel.h"

#include <QElapsedTimer>
#include <QHash>

#include <array>
#include <functional>
#include <optional>
#include <vector>

class FleetModel : public FlatTableModel {
    Q_OBJECT

public:
    enum Column {
        AircraftColumn,
        LinkColumn,
        InControlColumn,
        BackupColumn,
        StationsColumn,
        LastFrameColumn,
        FramesColumn,
    };
    static constexpr int kColumnCount = 7;

    // How a row reads, worst first: reported by no station whose key is
    // trusted; nothing known now (the broker unreachable); only sealed
    // sessions; no station online; not heard for the stale limit (or never);
    // heard within it.
    enum class RowState { Unverified, Unknown, Sealed, Offline, Stale, Live };
    static constexpr int kRowStateCount = 6;
    enum Role {
        StateRole = Qt::UserRole + 1,  // RowState as int
        AircraftRole,                  // the aircraft's name, whatever the column
        SortRole,                      // what a column sorts by: names, numbers, ages
        VerifiedRole,                  // some station whose key is trusted reports it
    };

    // Microseconds since the epoch, UTC; tests pass a fake clock.
    using Clock = std::function<qint64()>;
    static constexpr qint64 kDefaultStaleLimitMicros = 5'000'000;
    // Updates are told at most this often (10 a second).
    static constexpr qint64 kMinFlushIntervalMs = 100;

    explicit FleetModel(QObject* parent = nullptr);

    void setClock(Clock clock);
    void setStaleLimitMicros(qint64 micros);
    qint64 staleLimitMicros() const { return m_staleLimitMicros; }

    // The row of an aircraft, -1 when it has none (yet: a pending one has none).
    int rowOf(const QString& aircraft) const;
    const AircraftSummary& summary(int row) const { return m_rows[std::size_t(row)].summary; }
    RowState rowState(int row) const;
    // Rows in a state as the views were last told it (at the last flush or
    // refreshAges()), for a count beside the table.
    int rowsIn(RowState state) const { return m_told[std::size_t(state)]; }

    // Updates taken but not told yet: they are told in the next pass of the event loop.
    int pendingUpdates() const { return m_pendingUpdates; }

    // "12 s", "3 min 05 s", "2 h 14 min", in whole seconds; a negative age
    // (our clock behind the publisher's) reads "0 s". The cell of an
    // aircraft never heard says "—".
    static QString ageText(qint64 ageMicros);
    static QString linkText(LinkState state);
    // The link column of a summary: its link, or why it is not known.
    static QString linkCellText(const AircraftSummary& summary);

public slots:
    // FleetFeed::aircraftUpdated: the aircraft's row is replaced, or appended
    // when the aircraft is new.
    void update(const AircraftSummary& summary);
    // FleetFeed::aircraftRemoved: its row goes (after what is pending is told).
    void remove(const QString& aircraft);
    // Tells now what update() collected rather than in the next pass.
    void flushPending();
    // The ages moved on: dataChanged() over the last-frame column, and over
    // the whole row of any aircraft whose state the passing time changed.
    void refreshAges();

private:
    QVariant cellData(const QModelIndex& index, int role) const override;
    int rows() const override { return int(m_rows.size()); }

    struct Row {
        AircraftSummary summary;
        std::optional<RowState> told;  // the state the views were last told of; none before its insert
    };

    QString cellText(const Row& row, int column) const;
    QVariant sortValue(const Row& row, int column) const;
    RowState stateOf(const AircraftSummary& summary) const;
    // Records the state the views are told of; true when it changed.
    bool tell(Row& row);
    void scheduleFlush();

    std::vector<Row> m_rows;
    std::vector<Row> m_pending;  // new aircraft, to become rows m_rows.size() on
    // Every aircraft's row, or the row it will have once its pending insert is told.
    QHash<QString, int> m_index;
    int m_changedFirst = -1;  // the rows changed since the last flush, -1: none
    int m_changedLast = -1;
    int m_pendingUpdates = 0;
    bool m_flushQueued = false;
    // Since the last flush: rows are told at most kMaxFlushRate times a second.
    QElapsedTimer m_sinceFlush;
    std::array<int, kRowStateCount> m_told{};  // rows by RowState told
    Clock m_clock;
    qint64 m_staleLimitMicros = kDefaultStaleLimitMicros;
};
