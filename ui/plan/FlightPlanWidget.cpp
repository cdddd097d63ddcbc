#include "ui/plan/FlightPlanWidget.h"

#include "codec/message/FlightPlanTransfer.h"
#include "link/plan/PlanFile.h"

#include <QFileDialog>
#include <QFileInfo>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QProgressBar>
#include <QPushButton>
#include <QTableWidget>
#include <QVBoxLayout>

#include <cmath>

namespace {

QString number(const std::optional<double>& value, int decimals)
{
    return value ? QString::number(*value, 'f', decimals) : QStringLiteral("\u2014");
}

QString param(double value)
{
    return std::isnan(value) ? QStringLiteral("\u2014") : QString::number(value, 'g', 7);
}

// Sections the transfer cuts a plan of `bytes` into, for the summary line.
int sectionCount(qsizetype bytes)
{
    const qsizetype stream = qsizetype(rcm::FlightPlanDescriptor::kSize) + bytes;
    const qsizetype perSection = qsizetype(rcm::FlightPlanSection::kMaxData);
    return int((stream + perSection - 1) / perSection);
}

}  // namespace

FlightPlanWidget::FlightPlanWidget(FlightPlanUpload* upload, QWidget* parent)
    : QWidget(parent),
      m_upload(upload),
      m_file(new QLabel(tr("No flight plan loaded"))),
      m_summary(new QLabel),
      m_table(new QTableWidget(0, kColumnCount)),
      m_open(new QPushButton(tr("Open .plan\u2026"))),
      m_send(new QPushButton(tr("Upload to aircraft"))),
      m_cancel(new QPushButton(tr("Cancel upload"))),
      m_progress(new QProgressBar),
      m_state(new QLabel)
{
    m_open->setToolTip(tr("Load a QGroundControl mission (.plan); only simple items can be sent"));
    m_send->setToolTip(tr("Send the plan in BLOCK 2 sections, one per frame, until the aircraft acknowledges it"));
    m_file->setTextInteractionFlags(Qt::TextSelectableByMouse);
    m_summary->setWordWrap(true);

    m_table->setHorizontalHeaderLabels({tr("#"), tr("Command"), tr("Frame"), tr("Latitude (\u00b0)"),
                                        tr("Longitude (\u00b0)"), tr("Altitude (m)"), tr("Param 1"), tr("Param 2"),
                                        tr("Param 3"), tr("Param 4")});
    m_table->verticalHeader()->hide();
    m_table->setEditTriggers(QAbstractItemView::NoEditTriggers);
    m_table->setSelectionBehavior(QAbstractItemView::SelectRows);
    m_table->setAlternatingRowColors(true);
    m_table->setShowGrid(false);
    m_table->horizontalHeader()->setStretchLastSection(true);
    m_table->horizontalHeader()->setSectionResizeMode(QHeaderView::ResizeToContents);

    m_progress->setRange(0, 1);
    m_progress->setValue(0);
    m_progress->setFormat(tr("%v of %m sections"));
    m_progress->setMinimumWidth(220);

    auto* top = new QHBoxLayout;
    top->addWidget(m_open);
    top->addWidget(m_file, 1);
    top->addWidget(m_summary);
    auto* bottom = new QHBoxLayout;
    bottom->addWidget(m_send);
    bottom->addWidget(m_cancel);
    bottom->addWidget(m_progress, 1);
    bottom->addWidget(m_state);
    auto* layout = new QVBoxLayout(this);
    layout->setContentsMargins(6, 6, 6, 6);
    layout->addLayout(top);
    layout->addWidget(m_table, 1);
    layout->addLayout(bottom);

    connect(m_open, &QPushButton::clicked, this, &FlightPlanWidget::openPlan);
    connect(m_send, &QPushButton::clicked, this, &FlightPlanWidget::uploadPlan);
    connect(m_cancel, &QPushButton::clicked, this, &FlightPlanWidget::cancelUpload);
    connect(m_upload, &FlightPlanUpload::progressChanged, this, &FlightPlanWidget::showProgress);
    showProgress(m_upload->progress());
}

bool FlightPlanWidget::loadPlan(const QString& path, QString* error)
{
    QString reason;
    std::optional<MissionPlan> plan = PlanFile::load(path, &reason);
    if (!plan) {
        m_state->setText(QStringLiteral("<span style=\"color:#b01c1c\">%1</span>").arg(reason.toHtmlEscaped()));
        emit message(reason);
        if (error)
            *error = reason;
        return false;
    }
    m_plan = std::move(plan);
    m_file->setText(QFileInfo(path).fileName());
    m_file->setToolTip(path);
    showPlan();
    return true;
}

void FlightPlanWidget::setLinkReady(bool ready)
{
    m_linkReady = ready;
    updateButtons();
}

void FlightPlanWidget::openPlan()
{
    const QString path = QFileDialog::getOpenFileName(this, tr("Open a QGroundControl flight plan"), QString(),
                                                      tr("QGroundControl plans (*.plan);;All files (*)"));
    if (!path.isEmpty())
        loadPlan(path);
}

void FlightPlanWidget::uploadPlan()
{
    if (!m_plan)
        return;
    QString error;
    if (!m_upload->start(m_plan->toBytes(), &error)) {
        m_state->setText(error);
        emit message(error);
    }
}

void FlightPlanWidget::cancelUpload()
{
    m_upload->cancel();
}

void FlightPlanWidget::showPlan()
{
    const QList<MissionItem>& items = m_plan->items;
    m_table->setRowCount(int(items.size()));
    for (int row = 0; row < int(items.size()); ++row) {
        const MissionItem& item = items[row];
        const auto set = [&](int column, const QString& text, Qt::Alignment align = Qt::AlignRight) {
            auto* cell = new QTableWidgetItem(text);
            cell->setTextAlignment(align | Qt::AlignVCenter);
            m_table->setItem(row, column, cell);
        };
        set(SeqColumn, QString::number(item.seq));
        set(CommandColumn, item.commandName(), Qt::AlignLeft);
        m_table->item(row, CommandColumn)->setToolTip(tr("MAV_CMD %1").arg(item.command));
        set(FrameColumn, item.frameName(), Qt::AlignLeft);
        const bool positioned = item.frame != 2;
        set(LatitudeColumn, positioned ? number(item.latitude, 7) : QStringLiteral("\u2014"));
        set(LongitudeColumn, positioned ? number(item.longitude, 7) : QStringLiteral("\u2014"));
        set(AltitudeColumn, positioned ? number(item.altitude, 1) : QStringLiteral("\u2014"));
        for (int p = 0; p < 4; ++p)
            set(Param1Column + p, param(item.params[std::size_t(p)]));
    }
    const qsizetype bytes = m_plan->toBytes().size();
    // Whole words: with no translation loaded, tr()'s %n would show "item(s)".
    const int sections = sectionCount(bytes);
    m_summary->setText((items.size() == 1 ? tr("1 mission item") : tr("%1 mission items").arg(items.size())) +
                       tr(", %1 bytes, ").arg(bytes) +
                       (sections == 1 ? tr("1 BLOCK 2 section") : tr("%1 BLOCK 2 sections").arg(sections)));
    updateButtons();
}

QString FlightPlanWidget::summary() const
{
    return m_summary->text();
}

void FlightPlanWidget::showProgress(const FlightPlanUpload::Progress& progress)
{
    m_progress->setRange(0, std::max(progress.total, 1));
    m_progress->setValue(progress.state == FlightPlanUpload::State::Acknowledged ? progress.total : progress.sent);
    switch (progress.state) {
        case FlightPlanUpload::State::Idle:
            m_state->setText(tr("Not sent"));
            break;
        case FlightPlanUpload::State::Sending:
            m_state->setText(
                progress.pass == 0
                    ? tr("Plan %1: waiting for the next frame").arg(progress.planId, 8, 16, QLatin1Char('0'))
                    : tr("Pass %1 of %2: waiting for the aircraft's acknowledgement")
                          .arg(progress.pass)
                          .arg(progress.maxPasses));
            break;
        case FlightPlanUpload::State::Acknowledged:
            m_state->setText(QStringLiteral("<span style=\"color:#1d7a35\"><b>%1</b></span>")
                                 .arg(tr("Acknowledged by the aircraft")));
            emit message(tr("Flight plan acknowledged by the aircraft"));
            break;
        case FlightPlanUpload::State::GaveUp:
            m_state->setText(QStringLiteral("<span style=\"color:#b01c1c\"><b>%1</b></span>")
                                 .arg(tr("Not acknowledged after %1 passes").arg(progress.maxPasses)));
            emit message(tr("Flight plan upload gave up: no acknowledgement"));
            break;
        case FlightPlanUpload::State::Cancelled:
            m_state->setText(tr("Cancelled"));
            break;
    }
    updateButtons();
}

void FlightPlanWidget::updateButtons()
{
    const bool sending = m_upload->progress().state == FlightPlanUpload::State::Sending;
    m_send->setEnabled(m_plan.has_value() && m_linkReady && !sending);
    m_cancel->setEnabled(sending);
    m_send->setToolTip(m_linkReady ? tr("Send the plan in BLOCK 2 sections, one per frame, until the aircraft "
                                        "acknowledges it")
                                   : tr("Connect a link first"));
}
