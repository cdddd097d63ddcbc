#include "ui/framelog/FrameLogView.h"

#include "codec/frame/Frame.h"
#include "codec/message/TextFormat.h"
#include "codec/receive/LoggedFrameReading.h"
#include "ui/framelog/FrameLogDelegate.h"
#include "ui/framelog/FrameLogFilterModel.h"
#include "ui/framelog/FrameLogModel.h"
#include "ui/framelog/HexDump.h"
#include "ui/framelog/SteadyScrollBar.h"
#include "ui/table/RecordTable.h"

#include <QCheckBox>
#include <QComboBox>
#include <QDateTime>
#include <QFontDatabase>
#include <QHBoxLayout>
#include <QLabel>
#include <QLocale>
#include <QPlainTextEdit>
#include <QSplitter>
#include <QTableView>
#include <QTimeZone>
#include <QVBoxLayout>

#include <span>

namespace {

QPlainTextEdit* makeDetailPane(const QString& placeholder)
{
    auto* pane = new QPlainTextEdit;
    pane->setReadOnly(true);
    pane->setLineWrapMode(QPlainTextEdit::NoWrap);
    pane->setFont(QFontDatabase::systemFont(QFontDatabase::FixedFont));
    pane->setPlaceholderText(placeholder);
    return pane;
}

// The selected frame for people: what it was, then what the receive path
// makes of it on its own (LoggedFrameReading), then its items.
QString describeFrame(int number, const FrameRecord& record, std::optional<quint32> messageId, const rcm::LogKey* key)
{
    const QDateTime time = QDateTime::fromMSecsSinceEpoch(record.utcMicros / 1000, QTimeZone::utc());
    QString text =
        QStringLiteral("# Frame %1: %2 %3 UTC, %4, %5 bytes, %6%7\n")
            .arg(number)
            .arg(record.direction == FrameDirection::Sent ? QStringLiteral("sent") : QStringLiteral("received"))
            .arg(time.toString(QStringLiteral("yyyy-MM-dd hh:mm:ss.zzz")))
            .arg(frameTransportName(record.transport))
            .arg(record.bytes.size())
            .arg(frameStatusName(record.status), record.enciphered ? QStringLiteral(", keyed link") : QString());
    if (record.bytes.isEmpty()) {
        text += QStringLiteral("# No bytes for this frame: this session keeps no frame log, or the log lacks it.\n");
        if (messageId)
            text += QStringLiteral("# ID_msg %1\n").arg(*messageId);
        return text;
    }
    const rcm::LoggedFrameReading reading = rcm::readLoggedFrame(
        std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(record.bytes.constData()),
                                      std::size_t(record.bytes.size())),
        record.enciphered, key);
    using O = rcm::LoggedFrameReading::Outcome;
    if (reading.outcome == O::NotAFrame)
        return text + QStringLiteral("# Neither a 600-byte frame nor a 510-byte datagram: not decoded.\n");
    const auto corrected = [](int c) { return c < 0 ? QStringLiteral("beyond correction") : QString::number(c); };
    text += QStringLiteral("# Reed-Solomon: BLOCK 1 %1, BLOCK 2 %2 bytes corrected\n")
                .arg(corrected(reading.blocks.corrected.block1), corrected(reading.blocks.corrected.block2));
    switch (reading.outcome) {
    case O::Enciphered:
        return text + QStringLiteral("# Enciphered: sent over a keyed link. Without its key the bytes say nothing; "
                                     "open the log with the key to read the items.\n");
    case O::Refused:
        text += QStringLiteral("# Refused as %1: %2\n")
                    .arg(QString::fromLatin1(rcm::refusalName(*reading.refusal).data(),
                                             qsizetype(rcm::refusalName(*reading.refusal).size())),
                         QString::fromStdString(reading.detail));
        if (reading.decoded.message.header.items().empty())
            return text;
        text += QStringLiteral("# Not delivered. What could be read, for inspection only:\n");
        break;
    case O::Read:
        if (reading.direction)
        {
            const std::string_view way = rcm::secure::directionName(*reading.direction);
            text += QStringLiteral("# Deciphered and authenticated (%1)\n")
                        .arg(QString::fromLatin1(way.data(), qsizetype(way.size())));
        }
        break;
    case O::NotAFrame:
        break;
    }
    for (const rcm::Diagnostic& d : reading.decoded.diagnostics)
        text += QStringLiteral("# ! %1\n").arg(QString::fromStdString(d.toString()));
    return text + QString::fromStdString(rcm::formatMessage(reading.decoded.message));
}

}  // namespace

FrameLogView::FrameLogView(FrameLogModel* model, QWidget* parent)
    : TablePane(parent),
      m_model(model),
      m_filter(new FrameLogFilterModel(this)),
      m_direction(new QComboBox),
      m_status(new QComboBox),
      m_follow(new QCheckBox(tr("Follow newest"))),
      m_count(new QLabel),
      m_detail(makeDetailPane(tr("Select a frame to see its items"))),
      m_hex(makeDetailPane(tr("Select a frame to see its bytes")))
{
    m_filter->setSourceModel(model);
    QLayout* bar = filterBar();
    setUpTable();
    auto* details = new QSplitter(Qt::Horizontal);
    details->addWidget(m_detail);
    details->addWidget(m_hex);
    details->setStretchFactor(0, 1);
    details->setStretchFactor(1, 1);
    auto* split = new QSplitter(Qt::Vertical);
    split->addWidget(m_table);
    split->addWidget(details);
    split->setStretchFactor(0, 3);
    split->setStretchFactor(1, 2);
    split->setChildrenCollapsible(false);

    auto* layout = new QVBoxLayout(this);
    layout->setContentsMargins(6, 6, 6, 6);
    layout->addLayout(bar);
    layout->addWidget(split, 1);

    connect(m_direction, &QComboBox::currentIndexChanged, this, &FrameLogView::applyFilter);
    connect(m_status, &QComboBox::currentIndexChanged, this, &FrameLogView::applyFilter);
    connect(m_table->selectionModel(), &QItemSelectionModel::currentRowChanged, this, &FrameLogView::showSelected);
    connect(m_filter, &QAbstractItemModel::rowsInserted, this, [this] {
        updateCount();
        if (m_follow->isChecked())
            m_table->scrollToBottom();
    });
    connect(m_model, &QAbstractItemModel::rowsInserted, this, &FrameLogView::updateCount);
    connect(m_model, &FrameLogModel::logKeyChanged, this, &FrameLogView::showSelected);
    connect(m_filter, &QAbstractItemModel::modelReset, this, [this] {
        updateCount();
        showSelected();
    });
    updateCount();
}

QLayout* FrameLogView::filterBar()
{
    m_direction->addItem(tr("Both directions"), FrameLogFilterModel::kAllDirections);
    m_direction->addItem(tr("Sent"), FrameLogFilterModel::bit(FrameDirection::Sent));
    m_direction->addItem(tr("Received"), FrameLogFilterModel::bit(FrameDirection::Received));
    m_direction->setToolTip(tr("Show frames sent to the aircraft, received from it, or both"));
    using F = FrameLogFilterModel;
    m_status->addItem(tr("Any status"), F::kAllStatuses);
    m_status->addItem(tr("Problems (corrected, uncorrectable, refused)"), F::bit(FrameStatus::Corrected) |
                                                                              F::bit(FrameStatus::Uncorrectable) |
                                                                              F::bit(FrameStatus::Rejected));
    for (FrameStatus s : {FrameStatus::Decoded, FrameStatus::Corrected, FrameStatus::Uncorrectable,
                          FrameStatus::Rejected, FrameStatus::NotChecked})
        m_status->addItem(FrameLogModel::statusText(s), F::bit(s));
    m_status->setToolTip(tr("Show only frames with this decode status"));
    m_follow->setChecked(true);
    m_follow->setToolTip(tr("Scroll to each new frame as it arrives"));

    auto* bar = new QHBoxLayout;
    bar->setContentsMargins(0, 0, 0, 0);
    bar->addWidget(new QLabel(tr("Show:")));
    bar->addWidget(m_direction);
    bar->addWidget(m_status);
    bar->addWidget(m_follow);
    bar->addStretch(1);
    bar->addWidget(m_count);
    return bar;
}

void FrameLogView::setUpTable()
{
    m_table->setModel(m_filter);
    m_table->setItemDelegate(new FrameLogDelegate(m_table));
    // A view lays out a new model on a timer of its own; done at once, the
    // first screen of a log opened for replay is painted with the log, not
    // together with everything else that changes when the replay starts.
    connect(m_filter, &QAbstractItemModel::modelReset, m_table, &QTableView::doItemsLayout);
    m_table->setAlternatingRowColors(true);
    // Always there: a scroll bar that appears when a log fills the view (a
    // replay opened, a live session's first minute) narrows the view, and
    // the whole view and its header are painted again in that pass.
    m_table->setVerticalScrollBarPolicy(Qt::ScrollBarAlwaysOn);
    m_table->setVerticalScrollBar(new SteadyScrollBar(Qt::Vertical));
    setUpRecordTable(m_table, {{FrameLogModel::NumberColumn, 9},
                               {FrameLogModel::TimeColumn, 15},
                               {FrameLogModel::DirectionColumn, 12},
                               {FrameLogModel::MessageIdColumn, 12},
                               {FrameLogModel::CorrectedColumn, 15}});
}

void FrameLogView::setFollowing(bool on)
{
    m_follow->setChecked(on);
}

bool FrameLogView::isFollowing() const
{
    return m_follow->isChecked();
}

void FrameLogView::showSourceRow(int sourceRow)
{
    const QModelIndex index = m_filter->mapFromSource(m_model->index(sourceRow, 0));
    if (!index.isValid())
        return;
    m_table->setCurrentIndex(index);
    m_table->scrollTo(index, QAbstractItemView::PositionAtCenter);
}

void FrameLogView::scrollToSourceRow(int sourceRow)
{
    const int row = std::min(m_filter->rowAtOrAfter(sourceRow), m_filter->rowCount() - 1);
    if (row >= 0)
        m_table->scrollTo(m_filter->index(row, 0), QAbstractItemView::EnsureVisible);
}

QString FrameLogView::detailText() const
{
    return m_detail->toPlainText();
}

QString FrameLogView::hexText() const
{
    return m_hex->toPlainText();
}

void FrameLogView::applyFilter()
{
    m_filter->setFilter(m_direction->currentData().toUInt(), m_status->currentData().toUInt());
}

void FrameLogView::showSelected()
{
    const QModelIndex current = m_table->selectionModel()->currentIndex();
    if (!current.isValid()) {
        m_detail->clear();
        m_hex->clear();
        return;
    }
    const int row = m_filter->sourceRow(current.row());
    const FrameRecord record = m_model->record(row);
    m_detail->setPlainText(describeFrame(row + 1, record, m_model->messageId(row), m_model->logKey()));
    m_hex->setPlainText(hexDump(record.bytes, frameParts(record.bytes.size())));
}

void FrameLogView::updateCount()
{
    const QLocale locale;
    const int shown = m_filter->rowCount();
    const int total = m_model->rowCount();
    m_count->setText(shown == total ? tr("%1 frames").arg(locale.toString(total))
                                    : tr("%1 of %2 frames").arg(locale.toString(shown), locale.toString(total)));
}
