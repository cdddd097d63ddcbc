#include "ui/plan/FlightPlanWidget.h"

#include "codec/message/FlightPlanTransfer.h"
#include "codec/plan/PlanContents.h"
#include "link/plan/MavCommand.h"
#include "link/plan/PlanFile.h"
#include "ui/alerts/Confirmation.h"
#include "ui/look/NoteLabel.h"
#include "ui/plan/PlanMapView.h"

#include <QDialog>
#include <QDialogButtonBox>
#include <QDir>
#include <QFileDialog>
#include <QFileInfo>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QLineEdit>
#include <QMessageBox>
#include <QProgressBar>
#include <QPushButton>
#include <QSplitter>
#include <QStandardPaths>
#include <QTableWidget>
#include <QVBoxLayout>

#include <cmath>
#include <utility>

namespace {

using Severity = SeverityColours::Severity;

QString number(const std::optional<double>& value, int decimals)
{
    return value ? QString::number(*value, 'f', decimals) : QStringLiteral("\u2014");
}

QString param(double value)
{
    return std::isnan(value) ? QStringLiteral("\u2014") : QString::number(value, 'g', 7);
}

// "0x5245000D": one form wherever a plan ID is shown.
QString planIdText(quint32 id)
{
    return QString::fromStdString(rcm::planIdText(id));
}

QString count(qsizetype n, const QString& one, const QString& many)
{
    // Whole words: with no translation loaded, tr()'s %n would show "item(s)".
    return QStringLiteral("%1 %2").arg(n).arg(n == 1 ? one : many);
}

// "45 s", "26 min 22 s", "2 h 12 min": what an operator plans around.
QString duration(double seconds)
{
    const qint64 s = qint64(std::ceil(std::max(seconds, 0.0)));
    if (s < 60)
        return QStringLiteral("%1 s").arg(s);
    if (s < 3600)
        return s % 60 == 0 ? QStringLiteral("%1 min").arg(s / 60)
                           : QStringLiteral("%1 min %2 s").arg(s / 60).arg(s % 60);
    const qint64 minutes = (s + 59) / 60;
    return minutes % 60 == 0 ? QStringLiteral("%1 h").arg(minutes / 60)
                             : QStringLiteral("%1 h %2 min").arg(minutes / 60).arg(minutes % 60);
}

rcm::plan::Report reportOf(const MissionPlan& plan)
{
    rcm::plan::Report r;
    r.format = std::uint8_t(plan.format());
    r.items = std::uint16_t(std::min<qsizetype>(plan.items.size(), 65535));
    r.polygons = std::uint16_t(std::min<qsizetype>(plan.fencePolygons.size(), 65535));
    qsizetype vertices = 0;
    for (const FencePolygon& p : plan.fencePolygons)
        vertices += p.vertices.size();
    r.vertices = std::uint16_t(std::min<qsizetype>(vertices, 65535));
    r.circles = std::uint16_t(std::min<qsizetype>(plan.fenceCircles.size(), 65535));
    r.rallyPoints = std::uint16_t(std::min<qsizetype>(plan.rallyPoints.size(), 65535));
    return r;
}

}  // namespace

FlightPlanWidget::FlightPlanWidget(FlightPlanUpload* upload, QWidget* parent)
    : QWidget(parent),
      m_upload(upload),
      m_tiles(new MapTiles(this)),
      m_file(new QLabel(tr("No flight plan loaded"))),
      m_summary(new NoteLabel(2)),
      m_edits(new NoteLabel(2)),
      m_mapSource(new QLabel),
      m_table(new QTableWidget(0, kColumnCount)),
      m_map(new PlanMapView),
      m_open(new QPushButton(tr("Open plan\u2026"))),
      m_save(new QPushButton(tr("Save as .plan\u2026"))),
      m_editOnMap(new QPushButton(tr("Edit plan"))),
      m_tileButton(new QPushButton(tr("Map tiles\u2026"))),
      m_send(new QPushButton(tr("Upload to aircraft"))),
      m_cancel(new QPushButton(tr("Cancel upload"))),
      m_progress(new QProgressBar),
      m_state(new NoteLabel(2))
{
    m_confirm = [this](const QString& text, const QString& action) {
        return Confirmation{QMessageBox::Question, tr("Flight plan"), text, QString(), action, QMessageBox::AcceptRole}
            .ask(this);
    };
    m_open->setToolTip(tr("Load a plan: QGroundControl .plan, Mission Planner .waypoints or KML"));
    m_save->setToolTip(tr("Write the plan shown, with its edits, as a QGroundControl .plan"));
    // As the link's Connect and Disconnect: buttons that change what the
    // aircraft gets, or what may change the plan, never hold the focus, so a
    // stray Space or Enter after a click cannot press them again.
    for (QPushButton* b : {m_editOnMap, m_send, m_cancel})
        b->setFocusPolicy(Qt::NoFocus);
    m_editOnMap->setCheckable(true);
    m_editOnMap->setToolTip(
        tr("While on: drag a waypoint to move it, double-click the map to add one after the "
           "selected item, Delete removes the selected one, double-click an altitude in the "
           "table to change it. Edits are not sent until you upload."));
    m_tileButton->setToolTip(tr("Choose an MBTiles file for offline maps, or a tile server"));
    m_file->setTextInteractionFlags(Qt::TextSelectableByMouse);
    // Long states (an acknowledgement that lists the fence, a refusal that
    // names a file) wrap in two lines of their own and are cut there, whole
    // in the tool tip: they never widen the window nor take the map's room.
    m_state->setObjectName(QStringLiteral("planState"));
    m_edits->setObjectName(QStringLiteral("planEdits"));
    m_mapSource->setWordWrap(true);
    m_mapSource->setSizePolicy(QSizePolicy::Ignored, QSizePolicy::Preferred);
    m_file->setWordWrap(true);
    m_file->setMaximumWidth(260);
    m_mapSource->setTextFormat(Qt::PlainText);
    setUpTable();
    m_map->setTiles(m_tiles);
    m_map->setEditable(false);
    setProgressRange(1);
    m_progress->setValue(0);
    m_progress->setMinimumWidth(220);
    layOut();
    connectParts();
    m_mapSource->setText(m_tiles->description());
    showProgress(m_upload->progress());
}

void FlightPlanWidget::setUpTable()
{
    m_table->setHorizontalHeaderLabels({tr("#"), tr("Command"), tr("Frame"), tr("Latitude (\u00b0)"),
                                        tr("Longitude (\u00b0)"), tr("Altitude (m)"), tr("Param 1"), tr("Param 2"),
                                        tr("Param 3"), tr("Param 4")});
    m_table->verticalHeader()->hide();
    // Only the altitude cell is editable, by a double-click or F2: a stray key
    // must not start an edit.
    m_table->setEditTriggers(QAbstractItemView::DoubleClicked | QAbstractItemView::EditKeyPressed);
    m_table->setSelectionBehavior(QAbstractItemView::SelectRows);
    m_table->setSelectionMode(QAbstractItemView::SingleSelection);
    m_table->setAlternatingRowColors(true);
    m_table->setShowGrid(false);
    m_table->horizontalHeader()->setStretchLastSection(true);
    // Widths from the first rows, once per fill: measuring every cell of a
    // 10,000-item plan on every change held the GUI thread for seconds.
    m_table->horizontalHeader()->setSectionResizeMode(QHeaderView::Interactive);
    m_table->horizontalHeader()->setResizeContentsPrecision(kRowsMeasured);
}

void FlightPlanWidget::layOut()
{
    // The map takes the page; the table beside it in a splitter (the
    // operator moves the handle), the file and the upload in a line each
    // above and below, and the notes in rooms of their own that never
    // squeeze the map.
    auto* top = new QHBoxLayout;
    top->addWidget(m_open);
    top->addWidget(m_save);
    top->addWidget(m_file);
    top->addWidget(m_summary, 1);
    auto* mapBar = new QHBoxLayout;
    mapBar->addWidget(m_editOnMap);
    mapBar->addWidget(m_edits, 3);
    mapBar->addWidget(m_mapSource, 2);
    mapBar->addWidget(m_tileButton);
    auto* mapBox = new QWidget;
    auto* mapLayout = new QVBoxLayout(mapBox);
    mapLayout->setContentsMargins(0, 0, 0, 0);
    mapLayout->addLayout(mapBar);
    mapLayout->addWidget(m_map, 1);
    m_split = new QSplitter(Qt::Horizontal);
    m_split->setObjectName(QStringLiteral("planSplitter"));
    m_split->addWidget(mapBox);
    m_split->addWidget(m_table);
    m_split->setStretchFactor(0, 3);
    m_split->setStretchFactor(1, 2);
    m_split->setChildrenCollapsible(false);
    m_table->setMinimumWidth(200);
    m_map->setMinimumSize(240, 160);
    auto* bottom = new QHBoxLayout;
    bottom->addWidget(m_send);
    bottom->addWidget(m_cancel);
    bottom->addWidget(m_progress, 1);
    bottom->addWidget(m_state, 2);
    auto* layout = new QVBoxLayout(this);
    layout->setContentsMargins(6, 6, 6, 6);
    layout->addLayout(top);
    layout->addWidget(m_split, 1);
    layout->addLayout(bottom);
}

void FlightPlanWidget::connectParts()
{
    const std::pair<QPushButton*, void (FlightPlanWidget::*)()> buttonActions[] = {
        {m_open, &FlightPlanWidget::openPlan},          {m_save, &FlightPlanWidget::savePlanAs},
        {m_tileButton, &FlightPlanWidget::chooseTiles}, {m_send, &FlightPlanWidget::uploadPlan},
        {m_cancel, &FlightPlanWidget::cancelUpload},
    };
    for (const auto& [button, action] : buttonActions)
        connect(button, &QPushButton::clicked, this, action);
    // The map and the altitude cells follow the same switch: off, no drag, key or click changes the plan.
    connect(m_editOnMap, &QPushButton::toggled, this, [this](bool editable) {
        m_map->setEditable(editable);
        if (m_plan)
            showPlan();
    });
    connect(m_upload, &FlightPlanUpload::progressChanged, this, &FlightPlanWidget::showProgress);
    connect(m_table, &QTableWidget::currentCellChanged, this, [this](int row) { m_map->setSelectedItem(row); });
    connect(m_table, &QTableWidget::cellChanged, this, &FlightPlanWidget::cellEdited);
    connect(m_map, &PlanMapView::itemSelected, this, &FlightPlanWidget::selectRow);
    connect(m_map, &PlanMapView::moveRequested, this, &FlightPlanWidget::moveItem);
    connect(m_map, &PlanMapView::addRequested, this, &FlightPlanWidget::addWaypoint);
    connect(m_map, &PlanMapView::deleteRequested, this, &FlightPlanWidget::deleteItem);
    connect(m_map, &PlanMapView::altitudeRequested, this, [this](int index) {
        selectRow(index);
        if (QTableWidgetItem* cell = m_table->item(index, AltitudeColumn); cell && (cell->flags() & Qt::ItemIsEditable))
            m_table->editItem(cell);
    });
    connect(m_tiles, &MapTiles::sourceChanged, this, [this] { m_mapSource->setText(m_tiles->description()); });
    connect(m_tiles, &MapTiles::error, this, &FlightPlanWidget::problem);
}

FlightPlanWidget::~FlightPlanWidget() = default;

bool FlightPlanWidget::loadPlan(const QString& path, QString* error)
{
    if (m_edited && !m_confirm(tr("The plan shown has edits that are neither uploaded nor saved. Open %1 and drop "
                                  "them?")
                                   .arg(QFileInfo(path).fileName()),
                               tr("Drop the edits"))) {
        if (error)
            *error = tr("kept the edited plan");
        return false;
    }
    QString reason;
    std::optional<MissionPlan> plan = PlanFile::load(path, &reason);
    if (plan) {
        // A plan the bytes cannot hold is refused now, not when the operator uploads it.
        if (!plan->encode(&reason))
            plan.reset(), reason = QStringLiteral("%1: %2").arg(QDir::toNativeSeparators(path), reason);
    }
    if (!plan) {
        m_state->setNote(reason, Severity::Error);
        emit problem(reason);
        if (error)
            *error = reason;
        return false;
    }
    m_plan = std::move(plan);
    m_edited = false;
    m_sentPlan.reset();
    // A new plan starts safe: editing is switched on for a plan, never carried over.
    m_editOnMap->setChecked(false);
    m_file->setText(QFileInfo(path).fileName());
    m_file->setToolTip(path);
    showPlan();
    m_map->setPlan(&*m_plan);
    m_map->fitToPlan();
    // An earlier refusal, or the last plan's acknowledgement, no longer stands beside the new plan.
    if (m_upload->progress().state != FlightPlanUpload::State::Sending)
        m_state->setNote(tr("Not sent"));
    emit message(tr("Flight plan opened: %1: %2").arg(QDir::toNativeSeparators(path), m_summary->note()));
    emit planOpened(path);
    return true;
}

bool FlightPlanWidget::savePlan(const QString& path, QString* error)
{
    QString reason;
    if (!m_plan || !PlanFile::save(*m_plan, path, &reason)) {
        if (!m_plan)
            reason = tr("no flight plan to save");
        emit problem(reason);
        if (error)
            *error = reason;
        return false;
    }
    m_file->setText(QFileInfo(path).fileName());
    m_file->setToolTip(path);
    emit message(tr("Flight plan saved as %1").arg(QDir::toNativeSeparators(path)));
    return true;
}

void FlightPlanWidget::setLinkReady(bool ready)
{
    m_linkReady = ready;
    updateButtons();
}

void FlightPlanWidget::setTileSettings(const TileSettings& settings)
{
    TileSettings s = settings;
    if (s.cacheDir.isEmpty())
        s.cacheDir = QStandardPaths::writableLocation(QStandardPaths::CacheLocation) + QStringLiteral("/tiles");
    m_tiles->configure(s);
}

void FlightPlanWidget::openPlan()
{
    const QString path =
        QFileDialog::getOpenFileName(this, tr("Open a flight plan"), QString(), PlanFile::openFilter());
    if (!path.isEmpty())
        loadPlan(path);
}

void FlightPlanWidget::savePlanAs()
{
    if (!m_plan)
        return;
    QString path =
        QFileDialog::getSaveFileName(this, tr("Save the flight plan"), QString(), tr("QGroundControl plans (*.plan)"));
    if (path.isEmpty())
        return;
    if (!path.endsWith(QLatin1String(".plan"), Qt::CaseInsensitive))
        path += QLatin1String(".plan");
    savePlan(path);
}

void FlightPlanWidget::chooseTiles()
{
    QDialog dialog(this);
    dialog.setWindowTitle(tr("Map tiles"));
    const TileSettings current = m_tiles->settings();
    auto* mbtiles = new QLineEdit(current.mbtilesPath);
    auto* browse = new QPushButton(tr("Browse\u2026"));
    auto* url = new QLineEdit(current.urlTemplate);
    url->setPlaceholderText(QStringLiteral("https://tile.example.org/{z}/{x}/{y}.png"));
    auto* attribution = new QLineEdit(current.attribution);
    attribution->setPlaceholderText(tr("\u00a9 the map's authors, as the provider asks"));
    auto* file = new QHBoxLayout;
    file->addWidget(mbtiles, 1);
    file->addWidget(browse);
    auto* form = new QFormLayout;
    form->addRow(tr("Offline MBTiles file"), file);
    form->addRow(tr("Tile server URL"), url);
    form->addRow(tr("Attribution"), attribution);
    auto* note =
        new QLabel(tr("The MBTiles file is used when set; tiles from a server are kept in a disk cache "
                      "for use offline. With neither, the map is a grid with coordinates."));
    note->setWordWrap(true);
    auto* buttons = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel);
    auto* layout = new QVBoxLayout(&dialog);
    layout->addLayout(form);
    layout->addWidget(note);
    layout->addWidget(buttons);
    connect(buttons, &QDialogButtonBox::accepted, &dialog, &QDialog::accept);
    connect(buttons, &QDialogButtonBox::rejected, &dialog, &QDialog::reject);
    connect(browse, &QPushButton::clicked, &dialog, [&] {
        const QString path = QFileDialog::getOpenFileName(&dialog, tr("Offline map tiles"), mbtiles->text(),
                                                          tr("MBTiles (*.mbtiles);;All files (*)"));
        if (!path.isEmpty())
            mbtiles->setText(path);
    });
    dialog.resize(560, dialog.sizeHint().height());
    if (dialog.exec() != QDialog::Accepted)
        return;
    TileSettings s = current;
    s.mbtilesPath = mbtiles->text().trimmed();
    s.urlTemplate = url->text().trimmed();
    s.attribution = attribution->text().trimmed();
    setTileSettings(s);
}

void FlightPlanWidget::uploadPlan()
{
    if (!m_plan)
        return;
    QString error;
    const std::optional<QByteArray> bytes = m_plan->encode(&error);
    if (!bytes) {
        m_state->setNote(error, Severity::Error);
        emit problem(error);
        return;
    }
    const QStringList fence = m_plan->fenceViolations();
    if (!fence.isEmpty() && !m_confirm(tr("The plan's own fence forbids where it goes: %1. Upload it anyway?")
                                           .arg(fence.join(QStringLiteral("; "))),
                                       tr("Upload anyway")))
        return;
    const int sections = sectionsFor(bytes->size());
    const FlightPlanUpload::Progress now = m_upload->progress();
    // Never less than the frame cadence: a rate measured over a burst must not hide a long upload.
    const double perSection =
        now.rateMeasured ? std::max(now.secondsPerSection, kNominalSecondsPerSection) : kNominalSecondsPerSection;
    const double pass = sections * perSection;
    if (pass > kLongUploadSeconds &&
        !m_confirm(tr("This plan is %1 BLOCK 2 sections: one pass takes about %2 at %3 s a section, and up to %4 "
                      "if frames are lost and all %5 passes are needed. Upload it?")
                       .arg(sections)
                       .arg(duration(pass))
                       .arg(perSection, 0, 'f', 1)
                       .arg(duration(pass * FlightPlanUpload::kMaxPasses))
                       .arg(FlightPlanUpload::kMaxPasses),
                   tr("Upload")))
        return;
    if (!m_upload->start(*bytes, &error)) {
        m_state->setNote(error, Severity::Error);
        emit problem(error);
        return;
    }
    m_sentPlan = m_plan;
    m_edited = false;
    emit message(tr("Uploading flight plan %1 (%2): %3")
                     .arg(planIdText(m_upload->progress().planId), m_file->text(),
                          count(sections, tr("BLOCK 2 section"), tr("BLOCK 2 sections"))));
    planEdited();
}

void FlightPlanWidget::cancelUpload()
{
    if (m_upload->progress().state != FlightPlanUpload::State::Sending)
        return;
    m_upload->cancel();
    emit message(tr("Flight plan upload cancelled: the aircraft holds the plan it last acknowledged"));
}

void FlightPlanWidget::setProgressRange(int sections)
{
    m_progress->setRange(0, sections);
    m_progress->setFormat(sections == 1 ? tr("%v of %m section") : tr("%v of %m sections"));
}

int FlightPlanWidget::sectionsFor(qsizetype bytes) const
{
    const qsizetype stream = qsizetype(rcm::FlightPlanDescriptor::kSize) + bytes;
    const qsizetype perSection = m_upload->sectionSize();
    return int((stream + perSection - 1) / perSection);
}

void FlightPlanWidget::showPlan()
{
    m_filling = true;
    m_table->setUpdatesEnabled(false);
    const int previousRows = m_table->rowCount();
    m_table->setRowCount(int(m_plan->items.size()));
    for (int row = 0; row < int(m_plan->items.size()); ++row)
        showRow(row);
    // An edit keeps the widths the operator may have set; a new plan is measured.
    if (previousRows == 0 || !m_edited)
        m_table->resizeColumnsToContents();
    m_table->setUpdatesEnabled(true);
    m_filling = false;
    showSummary();
}

void FlightPlanWidget::showRow(int row)
{
    const bool filling = m_filling;
    m_filling = true;
    const MissionItem& item = m_plan->items[row];
    const auto set = [&](int column, const QString& text, Qt::Alignment align = Qt::AlignRight) {
        auto* cell = new QTableWidgetItem(text);
        cell->setTextAlignment(align | Qt::AlignVCenter);
        cell->setFlags(cell->flags() & ~Qt::ItemIsEditable);
        m_table->setItem(row, column, cell);
    };
    // Numbered from 1, as QGroundControl and Mission Planner number them.
    set(SeqColumn, QString::number(item.seq + 1));
    set(CommandColumn, item.commandName(), Qt::AlignLeft);
    m_table->item(row, CommandColumn)->setToolTip(MavCommand::mavlinkNameOf(item.command));
    set(FrameColumn, item.frameName(), Qt::AlignLeft);
    // A field the command does not use (a RETURN_TO_LAUNCH's position, a
    // TAKEOFF's 0, 0) is a dash, not a number the aircraft would ignore.
    const bool positioned = item.hasPosition();
    const bool altitude = item.hasAltitude();
    set(LatitudeColumn, positioned ? number(item.latitude, 7) : QStringLiteral("\u2014"));
    set(LongitudeColumn, positioned ? number(item.longitude, 7) : QStringLiteral("\u2014"));
    set(AltitudeColumn, altitude ? number(item.altitude, 1) : QStringLiteral("\u2014"));
    if (altitude) {
        QTableWidgetItem* altitude = m_table->item(row, AltitudeColumn);
        if (m_editOnMap->isChecked())
            altitude->setFlags(altitude->flags() | Qt::ItemIsEditable);
        altitude->setToolTip(tr("Double-click to change the altitude (metres, %1)").arg(item.frameName()));
    }
    for (int p = 0; p < 4; ++p)
        set(Param1Column + p, param(item.params[std::size_t(p)]));
    m_filling = filling;
}

void FlightPlanWidget::showSummary()
{
    const qsizetype bytes = m_plan->toBytes().size();
    const int sections = sectionsFor(bytes);
    QStringList parts{count(m_plan->items.size(), tr("mission item"), tr("mission items"))};
    if (m_plan->format() >= 2) {
        rcm::plan::Report r = reportOf(*m_plan);
        r.items = 0;
        // "fence 1 polygon (4 vertices), 2 rally points": the report's words, without the items.
        const QString contents = QString::fromStdString(r.describe());
        parts << contents.mid(contents.indexOf(QLatin1Char(',')) + 2);
    }
    parts << tr("%1 bytes").arg(bytes) << count(sections, tr("BLOCK 2 section"), tr("BLOCK 2 sections"))
          << tr("%1 a pass").arg(duration(sections * kNominalSecondsPerSection));
    m_summary->setNote(parts.join(QStringLiteral(", ")));
    if (m_upload->progress().state != FlightPlanUpload::State::Sending) {
        setProgressRange(sections);
        m_progress->setValue(0);
    }
    planEdited();
}

void FlightPlanWidget::planEdited()
{
    if (!m_plan) {
        updateButtons();  // nothing to upload
        return;
    }
    const FlightPlanUpload::State state = m_upload->progress().state;
    const bool sending = state == FlightPlanUpload::State::Sending;
    const bool notSent = state == FlightPlanUpload::State::Cancelled || state == FlightPlanUpload::State::GaveUp;
    const QStringList fence = m_plan->fenceViolations();
    if (!fence.isEmpty())
        m_edits->setNote(tr("Fence: %1").arg(fence.join(QStringLiteral("; "))), Severity::Error);
    else if (!m_edited && notSent && m_sentPlan)
        m_edits->setNote(tr("Not on the aircraft: the upload did not finish; the aircraft holds the plan it last "
                            "acknowledged"),
                         Severity::Warning);
    else if (!m_edited)
        m_edits->clearNote();
    else if (sending)
        m_edits->setNote(tr("Edited: the upload in progress sends the plan as it was before"), Severity::Warning);
    else
        m_edits->setNote(tr("Edited: not sent until you upload"), Severity::Warning);
    updateButtons();
}

QString FlightPlanWidget::summary() const
{
    return m_summary->note();
}

QString FlightPlanWidget::uploadState() const
{
    return m_state->note();
}

void FlightPlanWidget::selectRow(int row)
{
    if (row < 0 || row >= m_table->rowCount())
        return;
    m_table->setCurrentCell(row, m_table->currentColumn() < 0 ? 0 : m_table->currentColumn());
    m_table->scrollToItem(m_table->item(row, 0));
}

void FlightPlanWidget::cellEdited(int row, int column)
{
    if (m_filling || column != AltitudeColumn || !m_plan || row >= m_plan->items.size())
        return;
    bool ok = false;
    const double metres = m_table->item(row, column)->text().trimmed().toDouble(&ok);
    if (!ok || !std::isfinite(metres) || metres < kLowestAltitude || metres > kHighestAltitude) {
        const QString reason = tr("Mission item %1: altitude \"%2\" is not a number of metres from %3 to %4; "
                                  "it stays %5 m")
                                   .arg(row + 1)
                                   .arg(m_table->item(row, column)->text())
                                   .arg(kLowestAltitude)
                                   .arg(kHighestAltitude)
                                   .arg(number(m_plan->items[row].altitude, 1));
        emit problem(reason);
        showPlan();
        return;
    }
    setItemAltitude(row, metres);
}

void FlightPlanWidget::moveItem(int index, const GeoPoint& to)
{
    if (!m_plan || index < 0 || index >= m_plan->items.size() || !m_plan->items[index].hasPosition())
        return;
    m_plan->items[index].latitude = std::clamp(to.latitude, -85.0, 85.0);
    m_plan->items[index].longitude = std::clamp(to.longitude, -180.0, 180.0);
    m_edited = true;
    showRow(index);
    showSummary();
    m_map->planChanged();
    selectRow(index);
}

void FlightPlanWidget::addWaypoint(const GeoPoint& at)
{
    if (!m_plan) {
        m_plan = MissionPlan{};
        m_map->setPlan(&*m_plan);
        m_file->setText(tr("New plan"));
    }
    if (m_plan->items.size() >= 65535)
        return;
    const int after = m_table->currentRow() >= 0 ? m_table->currentRow() : int(m_plan->items.size()) - 1;
    // The new waypoint flies at the altitude of the positioned item before it, in its frame.
    MissionItem item;
    item.command = 16;  // NAV_WAYPOINT
    item.frame = 3;     // above home
    item.params = {0, 0, 0, std::nan("")};
    item.altitude = kNewWaypointAltitude;
    for (int i = after; i >= 0; --i) {
        if (m_plan->items[i].hasPosition() && m_plan->items[i].altitude) {
            item.frame = m_plan->items[i].frame;
            item.altitude = m_plan->items[i].altitude;
            break;
        }
    }
    item.latitude = std::clamp(at.latitude, -85.0, 85.0);
    item.longitude = std::clamp(at.longitude, -180.0, 180.0);
    m_plan->items.insert(after + 1, item);
    m_plan->renumber();
    m_edited = true;
    showPlan();
    m_map->planChanged();
    selectRow(after + 1);
}

void FlightPlanWidget::deleteItem(int index)
{
    if (!m_plan || index < 0 || index >= m_plan->items.size())
        return;
    m_plan->items.removeAt(index);
    m_plan->renumber();
    m_edited = true;
    showPlan();
    m_map->planChanged();
    const int next = std::min(index, int(m_plan->items.size()) - 1);
    selectRow(next);
    // The row number may not have changed, so the table says nothing: tell the map.
    m_map->setSelectedItem(next);
}

void FlightPlanWidget::setItemAltitude(int index, double metres)
{
    if (!m_plan || index < 0 || index >= m_plan->items.size())
        return;
    m_plan->items[index].altitude = metres;
    m_edited = true;
    showRow(index);
    showSummary();
    m_map->planChanged();
    selectRow(index);
}

void FlightPlanWidget::showProgress(const FlightPlanUpload::Progress& progress)
{
    const int total = progress.total > 0 ? progress.total : (m_plan ? sectionsFor(m_plan->toBytes().size()) : 1);
    setProgressRange(std::max(total, 1));
    m_progress->setValue(progress.state == FlightPlanUpload::State::Acknowledged ? progress.total : progress.sent);
    switch (progress.state) {
        case FlightPlanUpload::State::Idle:
            m_state->setNote(tr("Not sent"));
            break;
        case FlightPlanUpload::State::Sending: {
            if (progress.pass == 0) {
                m_state->setNote(tr("Flight plan %1: waiting for the next frame").arg(planIdText(progress.planId)));
                break;
            }
            const double left = progress.secondsLeftInPass(kNominalSecondsPerSection);
            const QString rate = progress.rateMeasured ? tr("%1 s a section").arg(progress.secondsPerSection, 0, 'f', 1)
                                                       : tr("a section a frame");
            m_state->setNote(left > 0 ? tr("Pass %1 of %2: %3 of %4, %5 left in this pass (%6)")
                                            .arg(progress.pass)
                                            .arg(progress.maxPasses)
                                            .arg(progress.inPass)
                                            .arg(count(progress.total, tr("section"), tr("sections")))
                                            .arg(duration(left), rate)
                                      : tr("Pass %1 of %2 sent: waiting for the aircraft's acknowledgement")
                                            .arg(progress.pass)
                                            .arg(progress.maxPasses));
            m_progress->setValue(progress.inPass);
            break;
        }
        case FlightPlanUpload::State::Acknowledged:
            showAcknowledgement(progress);
            break;
        case FlightPlanUpload::State::GaveUp: {
            const QString text = tr("Flight plan upload gave up: no acknowledgement after %1")
                                     .arg(count(progress.maxPasses, tr("pass"), tr("passes")));
            m_state->setNote(text, Severity::Error);
            emit problem(text);
            break;
        }
        case FlightPlanUpload::State::Cancelled:
            m_state->setNote(tr("Cancelled"));
            break;
    }
    planEdited();
}

void FlightPlanWidget::showAcknowledgement(const FlightPlanUpload::Progress& progress)
{
    const rcm::plan::Report sent = m_sentPlan ? reportOf(*m_sentPlan) : rcm::plan::Report{};
    const auto held = rcm::plan::Report::read(std::span(
        reinterpret_cast<const std::uint8_t*>(progress.report.constData()), std::size_t(progress.report.size())));
    if (held && *held != sent) {
        const QString text =
            tr("The aircraft acknowledged the flight plan but holds %1; %2 were sent")
                .arg(QString::fromStdString(held->describe()), QString::fromStdString(sent.describe()));
        m_state->setNote(text, Severity::Error);
        emit problem(text);
        return;
    }
    if (!held && sent.format >= 2) {
        const QString text =
            tr("The aircraft acknowledged the flight plan's bytes but did not say it holds the "
               "geofence and rally points (it may read only plan format 1)");
        m_state->setNote(text, Severity::Error);
        emit problem(text);
        return;
    }
    const QString holds = held ? tr(": it holds %1").arg(QString::fromStdString(held->describe())) : QString();
    m_state->setNote(tr("Acknowledged by the aircraft") + holds, Severity::Success);
    emit message(tr("Flight plan acknowledged by the aircraft") + holds);
}

void FlightPlanWidget::updateButtons()
{
    const bool sending = m_upload->progress().state == FlightPlanUpload::State::Sending;
    const bool somethingToSend =
        m_plan && (!m_plan->items.isEmpty() || m_plan->hasFence() || !m_plan->rallyPoints.isEmpty());
    m_send->setEnabled(somethingToSend && m_linkReady && !sending);
    m_cancel->setEnabled(sending);
    m_save->setEnabled(m_plan.has_value());
    if (!somethingToSend && !m_linkReady)
        m_send->setToolTip(tr("Open a plan and connect a link first"));
    else if (!somethingToSend)
        m_send->setToolTip(tr("Open a plan first"));
    else if (!m_linkReady)
        m_send->setToolTip(tr("Connect a link first"));
    else
        m_send->setToolTip(tr("Send the plan in BLOCK 2 sections, one per frame, until the aircraft acknowledges it"));
}

void FlightPlanWidget::setEditing(bool on)
{
    m_editOnMap->setChecked(on);
}

bool FlightPlanWidget::isEditing() const
{
    return m_editOnMap->isChecked();
}
