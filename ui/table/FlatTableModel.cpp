#include "ui/table/FlatTableModel.h"

#include <QCoreApplication>

FlatTableModel::FlatTableModel(std::span<const Column> columns, QObject* parent)
    : QAbstractTableModel(parent), m_columns(columns)
{
}

int FlatTableModel::rowCount(const QModelIndex& parent) const
{
    return parent.isValid() ? 0 : rows();
}

int FlatTableModel::columnCount(const QModelIndex& parent) const
{
    return parent.isValid() ? 0 : int(m_columns.size());
}

QVariant FlatTableModel::data(const QModelIndex& index, int role) const
{
    if (!index.isValid() || index.row() >= rows())
        return {};
    if (role == Qt::TextAlignmentRole)
        return QVariant::fromValue(m_columns[std::size_t(index.column())].alignment | Qt::AlignVCenter);
    return cellData(index, role);
}

QVariant FlatTableModel::headerData(int section, Qt::Orientation orientation, int role) const
{
    if (orientation != Qt::Horizontal || section < 0 || section >= int(m_columns.size()))
        return {};
    const Column& column = m_columns[std::size_t(section)];
    const char* text = role == Qt::DisplayRole ? column.header : role == Qt::ToolTipRole ? column.toolTip : nullptr;
    if (!text)
        return {};
    // The subclass's name is the context its tr() would give.
    return QCoreApplication::translate(metaObject()->className(), text);
}

void FlatTableModel::rowsChanged(int first, int last, const QList<int>& roles)
{
    emit dataChanged(index(first, 0), index(last, columnCount() - 1), roles);
}
