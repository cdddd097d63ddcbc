#include "ui/fleet/FleetView.h"

#include "ui/fleet/FleetModel.h"

#include <QHeaderView>
#include <QLabel>
#include <QSortFilterProxyModel>
#include <QTableView>
#include <QTimer>
#include <QVBoxLayout>

FleetView::FleetView(FleetModel* model, QWidget* parent)
    : QWidget(parent),
      m_model(model),
      m_sorted(new QSortFilterProxyModel(this)),
      m_table(new QTableView),
      m_summary(new QLabel),
      m_ageTimer(new QTimer(this))
{
    m_sorted->setSourceModel(model);
    m_sorted->setSortRole(FleetModel::SortRole);
    m_sorted->setDynamicSortFilter(true);

    m_table->setModel(m_sorted);
    m_table->setSelectionBehavior(QAbstractItemView::SelectRows);
    m_table->setSelectionMode(QAbstractItemView::SingleSelection);
    m_table->setWordWrap(false);
    m_table->setShowGrid(false);
    m_table->setEditTriggers(QAbstractItemView::NoEditTriggers);
    m_table->setToolTip(tr("Double-click an aircraft, or press Enter, to observe it read-only"));
    m_table->verticalHeader()->hide();
    // Fixed row heights and column widths: a view that measured its rows
    // would ask for the text of every one of them on each change.
    m_table->verticalHeader()->setSectionResizeMode(QHeaderView::Fixed);
    m_table->verticalHeader()->setDefaultSectionSize(m_table->fontMetrics().height() + 6);
    QHeaderView* columns = m_table->horizontalHeader();
    columns->setSectionResizeMode(QHeaderView::Interactive);
    columns->setStretchLastSection(true);
    columns->setHighlightSections(false);
    const int digit = m_table->fontMetrics().horizontalAdvance(QLatin1Char('0'));
    m_table->setColumnWidth(FleetModel::AircraftColumn, digit * 12);
    m_table->setColumnWidth(FleetModel::LinkColumn, digit * 14);
    m_table->setColumnWidth(FleetModel::InControlColumn, digit * 12);
    m_table->setColumnWidth(FleetModel::BackupColumn, digit * 12);
    m_table->setColumnWidth(FleetModel::StationsColumn, digit * 14);
    m_table->setColumnWidth(FleetModel::LastFrameColumn, digit * 12);
    m_table->setSortingEnabled(true);
    m_table->sortByColumn(FleetModel::AircraftColumn, Qt::AscendingOrder);

    auto* layout = new QVBoxLayout(this);
    layout->setContentsMargins(6, 6, 6, 6);
    layout->addWidget(m_summary);
    layout->addWidget(m_table, 1);

    // activated() is Enter on the current row and, in every style the
    // console uses, a double-click.
    connect(m_table, &QAbstractItemView::activated, this, [this](const QModelIndex& index) {
        if (index.isValid())
            emit observeRequested(index.data(FleetModel::AircraftRole).toString());
    });
    m_ageTimer->setInterval(1000);
    connect(m_ageTimer, &QTimer::timeout, this, &FleetView::tick);
    connect(m_model, &QAbstractItemModel::rowsInserted, this, &FleetView::updateSummary);
    connect(m_model, &QAbstractItemModel::dataChanged, this, &FleetView::updateSummary);
    connect(m_model, &QAbstractItemModel::modelReset, this, &FleetView::updateSummary);
    updateSummary();
}

void FleetView::setBroker(const QString& broker)
{
    m_broker = broker;
    updateSummary();
}

void FleetView::setBrokerConnected(bool connected)
{
    m_connected = connected;
    updateSummary();
}

QString FleetView::summaryText() const
{
    const QString broker = m_broker.isEmpty()
                               ? tr("No broker")
                               : tr("Broker %1, %2").arg(m_broker, m_connected ? tr("connected") : tr("not connected"));
    using S = FleetModel::RowState;
    QString text = tr("%1: %n aircraft", nullptr, m_model->rowCount()).arg(broker);
    if (const int stale = m_model->rowsIn(S::Stale))
        text += tr(", %1 stale").arg(stale);
    if (const int offline = m_model->rowsIn(S::Offline))
        text += tr(", %1 offline").arg(offline);
    return text;
}

void FleetView::updateSummary()
{
    const QString text = summaryText();
    if (text != m_summary->text())
        m_summary->setText(text);
}

void FleetView::tick()
{
    m_model->refreshAges();
    updateSummary();
}

// Ages are refreshed while someone can see them; on showing, at once.
void FleetView::showEvent(QShowEvent* event)
{
    QWidget::showEvent(event);
    tick();
    m_ageTimer->start();
}

void FleetView::hideEvent(QHideEvent* event)
{
    QWidget::hideEvent(event);
    m_ageTimer->stop();
}
