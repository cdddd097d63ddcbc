#include "ui/fleet/FleetView.h"

#include "ui/fleet/FleetModel.h"
#include "ui/table/RecordTable.h"

#include <QCheckBox>
#include <QDateTime>
#include <QHBoxLayout>
#include <QLabel>
#include <QTimeZone>
#include <QSortFilterProxyModel>
#include <QTableView>
#include <QVBoxLayout>

namespace {

// Sorted by the model's SortRole; unverified rows only when asked for.
class FleetRows : public QSortFilterProxyModel {
public:
    FleetRows(FleetModel* model, QObject* parent) : QSortFilterProxyModel(parent)
    {
        setSourceModel(model);
        setSortRole(FleetModel::SortRole);
        setDynamicSortFilter(true);
    }

    void setShowUnverified(bool show)
    {
        m_showUnverified = show;
        invalidateFilter();
    }

protected:
    bool filterAcceptsRow(int row, const QModelIndex& parent) const override
    {
        return m_showUnverified || sourceModel()->index(row, 0, parent).data(FleetModel::VerifiedRole).toBool();
    }

private:
    bool m_showUnverified = false;
};

}  // namespace

FleetView::FleetView(FleetModel* model, QWidget* parent)
    : TablePane(parent),
      m_model(model),
      m_sorted(new FleetRows(model, this)),
      m_summary(new QLabel),
      m_showUnverified(new QCheckBox(tr("Show unverified")))
{
    m_showUnverified->setToolTip(
        tr("Also list aircraft that no station whose key is trusted reports: anyone on the "
           "broker may have published them"));
    connect(m_showUnverified, &QCheckBox::toggled, this, [this](bool show) {
        static_cast<FleetRows*>(m_sorted)->setShowUnverified(show);
        updateSummary();
    });

    m_table->setModel(m_sorted);
    m_table->setToolTip(tr("Double-click an aircraft, or press Enter, to observe it read-only"));
    setUpRecordTable(m_table, {{FleetModel::AircraftColumn, 12},
                               {FleetModel::LinkColumn, 14},
                               {FleetModel::InControlColumn, 12},
                               {FleetModel::BackupColumn, 12},
                               {FleetModel::StationsColumn, 14},
                               {FleetModel::LastFrameColumn, 12}});
    m_table->setSortingEnabled(true);
    m_table->sortByColumn(FleetModel::AircraftColumn, Qt::AscendingOrder);

    auto* layout = new QVBoxLayout(this);
    layout->setContentsMargins(6, 6, 6, 6);
    auto* top = new QHBoxLayout;
    m_summary->setWordWrap(true);
    top->addWidget(m_summary, 1);
    top->addWidget(m_showUnverified);
    layout->addLayout(top);
    layout->addWidget(m_table, 1);

    // activated() is Enter on the current row and, in every style the
    // console uses, a double-click.
    connect(m_table, &QAbstractItemView::activated, this, [this](const QModelIndex& index) {
        if (index.isValid())
            emit observeRequested(index.data(FleetModel::AircraftRole).toString());
    });
    m_ageTimer.setInterval(1000);
    // The summary follows: refreshAges() tells the rows' changes (dataChanged).
    connect(&m_ageTimer, &QTimer::timeout, m_model, &FleetModel::refreshAges);
    connect(m_model, &QAbstractItemModel::rowsInserted, this, &FleetView::updateSummary);
    connect(m_model, &QAbstractItemModel::dataChanged, this, &FleetView::updateSummary);
    connect(m_model, &QAbstractItemModel::modelReset, this, &FleetView::updateSummary);
    connect(m_model, &QAbstractItemModel::rowsRemoved, this, &FleetView::updateSummary);
    updateSummary();
}

void FleetView::setBroker(const QString& broker)
{
    m_broker = broker;
    updateSummary();
}

void FleetView::setBrokerConnected(bool connected, qint64 sinceUtcMicros)
{
    if (connected == m_connected && (connected || m_lostUtcMicros))
        return;
    m_connected = connected;
    if (connected) {
        m_everConnected = true;
        m_lostUtcMicros = 0;
    } else if (m_everConnected) {
        m_lostUtcMicros = sinceUtcMicros ? sinceUtcMicros : QDateTime::currentMSecsSinceEpoch() * 1000;
    }
    updateSummary();
}

void FleetView::setRefusedMessages(quint64 count)
{
    // updateSummary() sets the text only when it changes.
    m_refused = count;
    updateSummary();
}

QString FleetView::summaryText() const
{
    QString state;
    if (m_connected)
        state = tr("connected");
    else if (m_lostUtcMicros)
        state = tr("unreachable since %1 UTC")
                    .arg(QDateTime::fromMSecsSinceEpoch(m_lostUtcMicros / 1000, QTimeZone::utc())
                             .toString(QStringLiteral("hh:mm:ss")));
    else
        state = tr("not connected");
    const QString broker = m_broker.isEmpty() ? tr("No broker") : tr("Broker %1, %2").arg(m_broker, state);
    using S = FleetModel::RowState;
    const int unverified = m_model->rowsIn(S::Unverified);
    QString text = tr("%1: %n aircraft", nullptr, m_model->rowCount() - unverified).arg(broker);
    if (const int unknown = m_model->rowsIn(S::Unknown))
        text += tr(", %1 unknown").arg(unknown);
    if (const int sealed = m_model->rowsIn(S::Sealed))
        text += tr(", %1 sealed").arg(sealed);
    if (const int stale = m_model->rowsIn(S::Stale))
        text += tr(", %1 stale").arg(stale);
    if (const int offline = m_model->rowsIn(S::Offline))
        text += tr(", %1 offline").arg(offline);
    if (unverified)
        text += m_showUnverified->isChecked() ? tr("; %1 unverified").arg(unverified)
                                              : tr("; %1 unverified hidden").arg(unverified);
    if (m_refused)
        text += m_refused == 1 ? tr("; 1 message refused") : tr("; %1 messages refused").arg(m_refused);
    return text;
}

void FleetView::updateSummary()
{
    const QString text = summaryText();
    if (text != m_summary->text())
        m_summary->setText(text);
}

// Ages are refreshed while someone can see them; on showing, at once.
void FleetView::showEvent(QShowEvent* event)
{
    TablePane::showEvent(event);
    m_model->refreshAges();
    m_ageTimer.start();
}

void FleetView::hideEvent(QHideEvent* event)
{
    TablePane::hideEvent(event);
    m_ageTimer.stop();
}
