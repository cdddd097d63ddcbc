// Where a panel of repeated units (engines, radios, cameras) puts its cards:
// two to a row, so that a third engine sits under the first rather than
// beyond the right edge of a 1366-pixel screen.
#pragma once

#include <QGridLayout>
#include <QWidget>

namespace CardGrid {

constexpr int kColumns = 2;

inline void add(QGridLayout* grid, QWidget* card)
{
    const int n = grid->count();
    grid->addWidget(card, n / kColumns, n % kColumns, Qt::AlignTop);
}

}  // namespace CardGrid
