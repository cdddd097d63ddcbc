#include "ui/table/TablePane.h"

#include <QTableView>

TablePane::TablePane(QWidget* parent) : QWidget(parent), m_table(new QTableView(this)) {}
