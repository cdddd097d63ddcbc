#include "ui/eventlog/EventLogView.h"

#include "ui/eventlog/EventLogModel.h"

#include <QDir>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QStyle>
#include <QStringList>
#include <QTableView>
#include <QVBoxLayout>

#include <algorithm>

EventLogView::EventLogView(EventLogModel* model, QWidget* parent)
    : TablePane(parent), m_model(model), m_counts(new QLabel), m_file(new QLabel), m_replayNote(new QLabel)
{
    m_table->setObjectName(QStringLiteral("eventTable"));
    m_table->setModel(model);
    m_table->setSelectionBehavior(QAbstractItemView::SelectRows);
    m_table->setEditTriggers(QAbstractItemView::NoEditTriggers);
    m_table->setWordWrap(false);
    m_table->setTextElideMode(Qt::ElideRight);
    m_table->verticalHeader()->hide();
    m_table->verticalHeader()->setDefaultSectionSize(fontMetrics().height() + 6);
    QHeaderView* header = m_table->horizontalHeader();
    // Widths fitted once to the widest text a column can hold, not
    // ResizeToContents: that measures the rows again on every event added,
    // which at a busy replay was milliseconds of the GUI thread per event.
    const auto fit = [this, header](int column, const QStringList& texts) {
        int width = header->fontMetrics().horizontalAdvance(
                        m_model->headerData(column, Qt::Horizontal, Qt::DisplayRole).toString()) +
                    header->style()->pixelMetric(QStyle::PM_HeaderMargin, nullptr, header) * 4;
        for (const QString& t : texts)
            width = std::max(width, m_table->fontMetrics().horizontalAdvance(t) + 12);
        header->resizeSection(column, width);
    };
    fit(EventLogModel::TimeColumn, {QStringLiteral("00:00:00")});
    fit(EventLogModel::SeverityColumn, {eventSeverityName(EventSeverity::Info), eventSeverityName(EventSeverity::Warning),
                                        eventSeverityName(EventSeverity::Error)});
    QStringList sources;
    for (EventSource s : kEventSources)
        sources << eventSourceName(s);
    fit(EventLogModel::SourceColumn, sources);
    header->setSectionResizeMode(EventLogModel::TextColumn, QHeaderView::Stretch);
    // Long texts are elided in the row and whole in its tool tip: the dock
    // never grows wider than the window gives it.
    m_table->setHorizontalScrollBarPolicy(Qt::ScrollBarAlwaysOff);

    m_file->setTextInteractionFlags(Qt::TextSelectableByMouse);
    m_file->setSizePolicy(QSizePolicy::Ignored, QSizePolicy::Preferred);
    setFilePath(QString());

    auto* bar = new QHBoxLayout;
    bar->addWidget(m_counts);
    bar->addSpacing(12);
    bar->addWidget(m_file, 1);
    auto* layout = new QVBoxLayout(this);
    layout->setContentsMargins(4, 4, 4, 4);
    layout->addLayout(bar);
    m_replayNote->setObjectName(QStringLiteral("eventsReplayNote"));
    m_replayNote->setWordWrap(true);
    // The replay's blue, as the status bar's "Replay": white on #1565c0, 5.8:1.
    m_replayNote->setStyleSheet(
        QStringLiteral("QLabel { background-color: #1565c0; color: white; font-weight: bold; padding: 3px 6px; }"));
    m_replayNote->hide();
    layout->addWidget(m_replayNote);
    layout->addWidget(m_table, 1);

    // The newest event in view as it arrives, wherever the operator scrolled.
    connect(model, &QAbstractItemModel::rowsInserted, m_table, [this] {
        updateCounts();
        m_table->scrollToBottom();
    });
    connect(model, &QAbstractItemModel::rowsRemoved, this, &EventLogView::updateCounts);
    updateCounts();
}

void EventLogView::beginReplay()
{
    if (!m_replaying) {
        m_hidden = m_model->rowCount();
        for (int row = 0; row < m_hidden; ++row)
            m_table->setRowHidden(row, true);
    }
    m_replaying = true;
    m_replayNote->setText(tr("Replay: the live session's events are hidden until the replay ends; "
                             "these are the replay's own"));
    m_replayNote->show();
}

void EventLogView::endReplay()
{
    if (!m_replaying)
        return;
    for (int row = 0; row < m_model->rowCount(); ++row)
        m_table->setRowHidden(row, false);
    m_replaying = false;
    m_hidden = 0;
    m_replayNote->hide();
    m_replayNote->clear();
    m_table->scrollToBottom();
}

QString EventLogView::replayNoteText() const
{
    return m_replaying ? m_replayNote->text() : QString();
}

void EventLogView::setFilePath(const QString& path)
{
    m_file->setText(path.isEmpty() ? tr("not kept in a file") : tr("Kept in %1").arg(QDir::toNativeSeparators(path)));
    m_file->setToolTip(m_file->text());
}

QString EventLogView::fileText() const
{
    return m_file->text();
}

QString EventLogView::countsText() const
{
    return m_counts->text();
}

void EventLogView::updateCounts()
{
    // Spelled out per number: without a translation loaded, tr()'s %n gives "1 event(s)".
    const auto counted = [](int n, const QString& one, const QString& many) {
        return n == 1 ? one : many.arg(n);
    };
    m_counts->setText(
        QStringList{counted(m_model->rowCount(), tr("1 event"), tr("%1 events")),
                    counted(m_model->count(EventSeverity::Error), tr("1 error"), tr("%1 errors")),
                    counted(m_model->count(EventSeverity::Warning), tr("1 warning"), tr("%1 warnings"))}
            .join(QStringLiteral(", ")));
}
