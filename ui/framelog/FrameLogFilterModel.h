#pragma once

// Shows the rows of a FrameLogModel whose direction and status are chosen,
// without copying them: the filter keeps one vector of the source rows that
// pass (4 bytes a row), rebuilt when the choice changes and extended when the
// source appends. The source only ever appends or resets, which keeps every
// mapping a binary search. When every direction and status is chosen (as it
// is unless the operator chose otherwise) there is no vector: a row is its
// source row, and a log opened for replay is shown without going through its
// rows on the GUI thread.

#include "link/framelog/FrameLog.h"

#include <QAbstractProxyModel>

#include <vector>

class FrameLogModel;

class FrameLogFilterModel : public QAbstractProxyModel {
    Q_OBJECT

public:
    // Bit masks over FrameDirection and FrameStatus values.
    static constexpr unsigned kAllDirections = 0x3;
    static constexpr unsigned kAllStatuses = 0x1F;
    static constexpr unsigned bit(FrameDirection d) { return 1u << unsigned(d); }
    static constexpr unsigned bit(FrameStatus s) { return 1u << unsigned(s); }

    explicit FrameLogFilterModel(QObject* parent = nullptr);

    // Must be a FrameLogModel; other models are refused.
    void setSourceModel(QAbstractItemModel* model) override;
    FrameLogModel* frameLog() const { return m_source; }

    // Both at once: the rows are rebuilt once.
    void setFilter(unsigned directions, unsigned statuses);
    void setDirections(unsigned mask) { setFilter(mask, m_statuses); }
    void setStatuses(unsigned mask) { setFilter(m_directions, mask); }
    unsigned directions() const { return m_directions; }
    unsigned statuses() const { return m_statuses; }

    QModelIndex index(int row, int column, const QModelIndex& parent = {}) const override;
    QModelIndex parent(const QModelIndex& child) const override;
    int rowCount(const QModelIndex& parent = {}) const override;
    int columnCount(const QModelIndex& parent = {}) const override;
    QModelIndex mapToSource(const QModelIndex& proxyIndex) const override;
    QModelIndex mapFromSource(const QModelIndex& sourceIndex) const override;

    // The source row of a proxy row.
    int sourceRow(int row) const { return m_showsAll ? row : m_rows[std::size_t(row)]; }
    // The proxy row showing source row `sourceRow`, or the first one after
    // it when it is filtered out; rowCount() when there is none.
    int rowAtOrAfter(int sourceRow) const;

private:
    bool accepts(int sourceRow) const;
    void rebuild();
    void sourceRowsInserted(const QModelIndex& parent, int first, int last);
    void sourceDataChanged(const QModelIndex& topLeft, const QModelIndex& bottomRight, const QList<int>& roles);

    FrameLogModel* m_source = nullptr;
    std::vector<int> m_rows;  // source rows shown, ascending; empty when all are
    bool m_showsAll = true;   // every direction and status chosen
    int m_shown = 0;          // rows shown
    unsigned m_directions = kAllDirections;
    unsigned m_statuses = kAllStatuses;
};
