// The frame log's and the fleet's tables: a read-only view of records, one a
// row, that may hold hundreds of thousands of them.
#pragma once

#include <initializer_list>
#include <utility>

class QTableView;

// Whole rows selected one at a time, no grid, no word wrap, no editing, no
// row numbers; fixed row heights and column widths (`columnDigits`: column,
// width in digits; the last column stretches), since a view that measured
// its rows would ask for the text of every one of them on each change.
void setUpRecordTable(QTableView* table, std::initializer_list<std::pair<int, int>> columnDigits);
