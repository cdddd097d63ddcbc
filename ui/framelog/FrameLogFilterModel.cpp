#include "ui/framelog/FrameLogFilterModel.h"

#include "ui/framelog/FrameLogModel.h"

#include <algorithm>

FrameLogFilterModel::FrameLogFilterModel(QObject* parent) : QAbstractProxyModel(parent) {}

void FrameLogFilterModel::setSourceModel(QAbstractItemModel* model)
{
    auto* frameLog = qobject_cast<FrameLogModel*>(model);
    Q_ASSERT_X(frameLog || !model, "FrameLogFilterModel", "the source must be a FrameLogModel");
    beginResetModel();
    if (m_source)
        disconnect(m_source, nullptr, this, nullptr);
    m_source = frameLog;
    QAbstractProxyModel::setSourceModel(frameLog);
    if (m_source) {
        connect(m_source, &QAbstractItemModel::modelAboutToBeReset, this, &FrameLogFilterModel::beginResetModel);
        connect(m_source, &QAbstractItemModel::modelReset, this, [this] {
            rebuild();
            endResetModel();
        });
        connect(m_source, &QAbstractItemModel::rowsInserted, this, &FrameLogFilterModel::sourceRowsInserted);
        connect(m_source, &QAbstractItemModel::dataChanged, this, &FrameLogFilterModel::sourceDataChanged);
        connect(m_source, &QAbstractItemModel::headerDataChanged, this, &FrameLogFilterModel::headerDataChanged);
    }
    rebuild();
    endResetModel();
}

void FrameLogFilterModel::setFilter(unsigned directions, unsigned statuses)
{
    if (directions == m_directions && statuses == m_statuses)
        return;
    beginResetModel();
    m_directions = directions;
    m_statuses = statuses;
    rebuild();
    endResetModel();
}

bool FrameLogFilterModel::accepts(int sourceRow) const
{
    return (m_directions & bit(m_source->direction(sourceRow))) && (m_statuses & bit(m_source->status(sourceRow)));
}

void FrameLogFilterModel::rebuild()
{
    m_rows.clear();
    m_showsAll = (m_directions & kAllDirections) == kAllDirections && (m_statuses & kAllStatuses) == kAllStatuses;
    const int n = m_source ? m_source->rowCount() : 0;
    if (m_showsAll) {
        m_rows.shrink_to_fit();
        m_shown = n;
        return;
    }
    m_rows.reserve(std::size_t(n / 2));
    for (int row = 0; row < n; ++row)
        if (accepts(row))
            m_rows.push_back(row);
    // A filter that shows little should not keep the capacity of one that showed more.
    if (m_rows.capacity() > 2 * m_rows.size() + 1024)
        m_rows.shrink_to_fit();
    m_shown = int(m_rows.size());
}

void FrameLogFilterModel::sourceRowsInserted(const QModelIndex& parent, int first, int last)
{
    if (parent.isValid())
        return;
    if (m_showsAll) {
        Q_ASSERT_X(first == m_shown, "FrameLogFilterModel", "the source only appends");
        beginInsertRows({}, first, last);
        m_shown = last + 1;
        endInsertRows();
        return;
    }
    Q_ASSERT_X(m_rows.empty() || m_rows.back() < first, "FrameLogFilterModel", "the source only appends");
    std::vector<int> added;
    for (int row = first; row <= last; ++row)
        if (accepts(row))
            added.push_back(row);
    if (added.empty())
        return;
    const int at = int(m_rows.size());
    beginInsertRows({}, at, at + int(added.size()) - 1);
    m_rows.insert(m_rows.end(), added.begin(), added.end());
    m_shown = int(m_rows.size());
    endInsertRows();
}

void FrameLogFilterModel::sourceDataChanged(const QModelIndex& topLeft, const QModelIndex& bottomRight,
                                            const QList<int>& roles)
{
    const int from = rowAtOrAfter(topLeft.row());
    const int to = m_showsAll ? std::min(bottomRight.row(), m_shown - 1)
                              : int(std::upper_bound(m_rows.begin(), m_rows.end(), bottomRight.row()) - m_rows.begin()) - 1;
    if (from > to)
        return;
    emit dataChanged(index(from, topLeft.column()), index(to, bottomRight.column()), roles);
}

int FrameLogFilterModel::rowAtOrAfter(int sourceRow) const
{
    if (m_showsAll)
        return std::clamp(sourceRow, 0, m_shown);
    return int(std::lower_bound(m_rows.begin(), m_rows.end(), sourceRow) - m_rows.begin());
}

QModelIndex FrameLogFilterModel::index(int row, int column, const QModelIndex& parent) const
{
    if (parent.isValid() || row < 0 || row >= m_shown || column < 0 || column >= columnCount())
        return {};
    return createIndex(row, column);
}

QModelIndex FrameLogFilterModel::parent(const QModelIndex&) const
{
    return {};
}

int FrameLogFilterModel::rowCount(const QModelIndex& parent) const
{
    return parent.isValid() ? 0 : m_shown;
}

int FrameLogFilterModel::columnCount(const QModelIndex& parent) const
{
    return parent.isValid() || !m_source ? 0 : m_source->columnCount();
}

QModelIndex FrameLogFilterModel::mapToSource(const QModelIndex& proxyIndex) const
{
    if (!m_source || !proxyIndex.isValid() || proxyIndex.row() >= m_shown)
        return {};
    return m_source->index(sourceRow(proxyIndex.row()), proxyIndex.column());
}

QModelIndex FrameLogFilterModel::mapFromSource(const QModelIndex& sourceIndex) const
{
    if (!m_source || !sourceIndex.isValid())
        return {};
    const int row = rowAtOrAfter(sourceIndex.row());
    if (row >= m_shown || sourceRow(row) != sourceIndex.row())
        return {};
    return createIndex(row, sourceIndex.column());
}
