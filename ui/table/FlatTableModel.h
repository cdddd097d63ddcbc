#pragma once

// What the console's flat tables (the fleet, the frame log, the events)
// share as models: no tree, rows the subclass holds and counts, and a fixed
// set of columns, each with its header, its alignment and, where one helps,
// a tooltip, stated once as a table. The subclass builds a cell's text in
// cellData(), when a view asks for it.

#include <QAbstractTableModel>

#include <span>

class FlatTableModel : public QAbstractTableModel {
    Q_OBJECT

public:
    // A column's header and its tooltip (none: nullptr), as literals marked
    // QT_TRANSLATE_NOOP with the subclass's name: headerData() translates
    // them as the subclass's tr() would. Numbers align right.
    struct Column {
        const char* header;
        const char* toolTip = nullptr;
        Qt::Alignment alignment = Qt::AlignLeft;
    };

    int rowCount(const QModelIndex& parent = {}) const final;
    int columnCount(const QModelIndex& parent = {}) const final;
    // Nothing outside the rows; a column's alignment; the rest from cellData().
    QVariant data(const QModelIndex& index, int role = Qt::DisplayRole) const final;
    QVariant headerData(int section, Qt::Orientation orientation, int role = Qt::DisplayRole) const override;

protected:
    // `columns` in the order of the subclass's column numbers; it outlives the model.
    FlatTableModel(std::span<const Column> columns, QObject* parent);

    // The rows the views have been told of.
    virtual int rows() const = 0;
    // What data() answers for a cell of one of those rows, but its alignment.
    virtual QVariant cellData(const QModelIndex& index, int role) const = 0;
    // dataChanged() over whole rows, first to last.
    void rowsChanged(int first, int last, const QList<int>& roles = {});

private:
    std::span<const Column> m_columns;
};
