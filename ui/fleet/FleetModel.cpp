#include "ui/fleet/FleetModel.h"

#include "link/common/NameTable.h"

#include <QBrush>
#include <QColor>
#include <QDateTime>
#include <QTimeZone>
#include <QTimer>

#include <algorithm>
#include <chrono>
#include <limits>

namespace {

constexpr auto kLinkTexts = std::to_array<Named<LinkState>>({
    {LinkState::Closed, QT_TRANSLATE_NOOP("FleetModel", "Not connected")},
    {LinkState::Waiting, QT_TRANSLATE_NOOP("FleetModel", "Waiting")},
    {LinkState::Connected, QT_TRANSLATE_NOOP("FleetModel", "Connected")},
    {LinkState::Lost, QT_TRANSLATE_NOOP("FleetModel", "Lost")},
});

constexpr auto kColumns = std::to_array<FlatTableModel::Column>({
    {QT_TRANSLATE_NOOP("FleetModel", "Aircraft")},
    {QT_TRANSLATE_NOOP("FleetModel", "Link"),
     QT_TRANSLATE_NOOP("FleetModel", "The best link any online verified station has to the aircraft")},
    {QT_TRANSLATE_NOOP("FleetModel", "In control"),
     QT_TRANSLATE_NOOP("FleetModel", "The station in control as the aircraft last reported it (ID_GCS_destination)")},
    {QT_TRANSLATE_NOOP("FleetModel", "Backup"),
     QT_TRANSLATE_NOOP("FleetModel", "The backup station as the aircraft last reported it (ID_GCS_backup)")},
    {QT_TRANSLATE_NOOP("FleetModel", "Stations"),
     QT_TRANSLATE_NOOP("FleetModel",
                       "Verified stations publishing for this aircraft that are online, of all that have "
                       "reported; and stations whose key is not trusted")},
    {QT_TRANSLATE_NOOP("FleetModel", "Last frame"),
     QT_TRANSLATE_NOOP("FleetModel", "Time since the last good frame from the aircraft any station reported"),
     Qt::AlignRight},
    {QT_TRANSLATE_NOOP("FleetModel", "Frames"),
     QT_TRANSLATE_NOOP("FleetModel",
                       "Frames sent up to the aircraft and received down from it by its stations' links, as "
                       "their statistics say"),
     Qt::AlignRight},
});
static_assert(kColumns.size() == FleetModel::kColumnCount);

// Dark text on a light tint, as the events' warnings: over 7:1 contrast
// whatever the window's palette (Theme's day or night).
struct Colours {
    QColor text;
    QColor background;
};

std::optional<Colours> coloursOf(FleetModel::RowState state)
{
    switch (state) {
        case FleetModel::RowState::Unverified:
            // Red on pink: no trusted key vouches for anything in the row.
            return Colours{QColor(0x5c, 0x00, 0x00), QColor(0xf8, 0xd7, 0xd7)};
        case FleetModel::RowState::Unknown:
        case FleetModel::RowState::Sealed:
        case FleetModel::RowState::Offline:
            return Colours{QColor(0x3a, 0x3a, 0x3a), QColor(0xdc, 0xdc, 0xdc)};
        case FleetModel::RowState::Stale:
            return Colours{QColor(0x3d, 0x2b, 0x00), QColor(0xff, 0xe5, 0x99)};
        case FleetModel::RowState::Live:
            break;
    }
    return std::nullopt;
}

QString isoTime(qint64 utcMicros)
{
    const QDateTime t = QDateTime::fromMSecsSinceEpoch(utcMicros / 1000, QTimeZone::utc());
    return t.toString(QStringLiteral("yyyy-MM-dd hh:mm:ss.zzz 'UTC'"));
}

QString orDash(const QString& text)
{
    return text.isEmpty() ? QStringLiteral("\u2014") : text;
}

}  // namespace

FleetModel::FleetModel(QObject* parent)
    : FlatTableModel(kColumns, parent), m_clock([] {
          return qint64(
              std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::system_clock::now().time_since_epoch())
                  .count());
      })
{
}

QVariant FleetModel::cellData(const QModelIndex& index, int role) const
{
    const Row& row = m_rows[std::size_t(index.row())];
    switch (role) {
        case Qt::DisplayRole:
            return cellText(row, index.column());
        case AircraftRole:
            return row.summary.aircraft;
        case StateRole:
            return int(stateOf(row.summary));
        case VerifiedRole:
            return row.summary.verified() || row.summary.local;
        case SortRole:
            return sortValue(row, index.column());
        case Qt::ToolTipRole:
            if (index.column() == LastFrameColumn && row.summary.lastFrameUtcMicros)
                return isoTime(row.summary.lastFrameUtcMicros);
            if (index.column() == AircraftColumn) {
                switch (stateOf(row.summary)) {
                    case RowState::Unverified:
                        return tr("No station whose key is trusted reports %1: anyone may have published this")
                            .arg(row.summary.aircraft);
                    case RowState::Unknown:
                        return tr("The broker is unreachable: nothing is known of %1 now").arg(row.summary.aircraft);
                    case RowState::Sealed:
                        return tr("%1's sessions are keyed: without the aircraft's key only their existence shows")
                            .arg(row.summary.aircraft);
                    case RowState::Offline:
                        return tr("No station publishing for %1 is online").arg(row.summary.aircraft);
                    case RowState::Stale:
                        return tr("%1 has not been heard for %2 s or more")
                            .arg(row.summary.aircraft)
                            .arg(m_staleLimitMicros / 1'000'000);
                    case RowState::Live:
                        break;
                }
            }
            return {};
        case Qt::ForegroundRole:
            if (const std::optional<Colours> c = coloursOf(stateOf(row.summary)))
                return QBrush(c->text);
            return {};
        case Qt::BackgroundRole:
            if (const std::optional<Colours> c = coloursOf(stateOf(row.summary)))
                return QBrush(c->background);
            return {};
    }
    return {};
}

QString FleetModel::linkText(LinkState state)
{
    return tr(nameOf(kLinkTexts, state));
}

QString FleetModel::linkCellText(const AircraftSummary& s)
{
    if (!s.verified() && !s.local)
        return tr("Unverified");
    if (!s.brokerReachable && !s.local)
        return tr("Unknown: broker unreachable");
    if (s.stations == 0 && s.sealedStations > 0)
        return tr("Sealed: keyed session");
    const QString link = linkText(s.link);
    return s.local ? tr("%1 (this console)").arg(link) : link;
}

QString FleetModel::ageText(qint64 ageMicros)
{
    // Whole seconds, as the view refreshes them once a second.
    const qint64 s = std::max<qint64>(ageMicros, 0) / 1'000'000;
    if (s < 60)
        return tr("%1 s").arg(s);
    if (s < 3600)
        return tr("%1 min %2 s").arg(s / 60).arg(s % 60, 2, 10, QLatin1Char('0'));
    return tr("%1 h %2 min").arg(s / 3600).arg(s / 60 % 60, 2, 10, QLatin1Char('0'));
}

QString FleetModel::cellText(const Row& row, int column) const
{
    const AircraftSummary& s = row.summary;
    switch (column) {
        case AircraftColumn:
            return s.aircraft;
        case LinkColumn:
            return linkCellText(s);
        case InControlColumn:
            return orDash(s.inControl);
        case BackupColumn:
            return orDash(s.backup);
        case StationsColumn: {
            QString text = tr("%1 of %2 online").arg(s.stationsOnline).arg(s.stations);
            if (s.sealedStations)
                text += tr(", %1 sealed").arg(s.sealedStations);
            if (s.unverifiedStations)
                text += tr(", %1 unverified").arg(s.unverifiedStations);
            return text;
        }
        case LastFrameColumn:
            return s.lastFrameUtcMicros ? ageText(m_clock() - s.lastFrameUtcMicros) : QStringLiteral("\u2014");
        case FramesColumn:
            return tr("%1 up, %2 down").arg(s.framesUp).arg(s.framesDown);
    }
    return {};
}

QVariant FleetModel::sortValue(const Row& row, int column) const
{
    const AircraftSummary& s = row.summary;
    // Numbers by their value, names as they are (an unknown one empty, first).
    switch (column) {
        case LinkColumn:
            return -linkRank(s.link);  // the best first
        case StationsColumn:
            return s.stationsOnline;
        case LastFrameColumn:
            // By age: never heard sorts after the oldest.
            return s.lastFrameUtcMicros ? m_clock() - s.lastFrameUtcMicros : std::numeric_limits<qint64>::max();
        case FramesColumn:
            return qulonglong(s.framesUp + s.framesDown);
        case AircraftColumn:
            return s.aircraft;
        case InControlColumn:
            return s.inControl;
        case BackupColumn:
            return s.backup;
    }
    return {};
}

FleetModel::RowState FleetModel::stateOf(const AircraftSummary& summary) const
{
    if (!summary.verified() && !summary.local)
        return RowState::Unverified;
    if (!summary.brokerReachable && !summary.local)
        return RowState::Unknown;
    if (summary.stations == 0)
        return RowState::Sealed;
    if (summary.stationsOnline == 0)
        return RowState::Offline;
    if (summary.lastFrameUtcMicros == 0 || m_clock() - summary.lastFrameUtcMicros > m_staleLimitMicros)
        return RowState::Stale;
    return RowState::Live;
}

bool FleetModel::tell(Row& row)
{
    const RowState now = stateOf(row.summary);
    if (row.told == now)
        return false;
    if (row.told)
        --m_told[std::size_t(*row.told)];
    ++m_told[std::size_t(now)];
    row.told = now;
    return true;
}

FleetModel::RowState FleetModel::rowState(int row) const
{
    return stateOf(m_rows[std::size_t(row)].summary);
}

void FleetModel::setClock(Clock clock)
{
    m_clock = std::move(clock);
    refreshAges();
}

void FleetModel::setStaleLimitMicros(qint64 micros)
{
    m_staleLimitMicros = micros;
    refreshAges();
}

int FleetModel::rowOf(const QString& aircraft) const
{
    const int row = m_index.value(aircraft, -1);
    return row < int(m_rows.size()) ? row : -1;
}

void FleetModel::update(const AircraftSummary& summary)
{
    ++m_pendingUpdates;
    const auto found = m_index.constFind(summary.aircraft);
    if (found == m_index.cend()) {
        m_index.insert(summary.aircraft, int(m_rows.size() + m_pending.size()));
        m_pending.push_back(Row{summary, std::nullopt});
    } else if (const int row = *found; row >= int(m_rows.size())) {
        m_pending[std::size_t(row) - m_rows.size()].summary = summary;
    } else {
        // Changed in place now, told in the flush: a view reads cells only
        // when it paints, after this pass.
        m_rows[std::size_t(row)].summary = summary;
        m_changedFirst = m_changedFirst < 0 ? row : std::min(m_changedFirst, row);
        m_changedLast = std::max(m_changedLast, row);
    }
    scheduleFlush();
}

void FleetModel::remove(const QString& aircraft)
{
    if (!m_index.contains(aircraft))
        return;
    // What is pending is told first, so that rows keep the numbers the
    // views know them by.
    flushPending();
    const int row = m_index.value(aircraft);
    beginRemoveRows({}, row, row);
    Row& gone = m_rows[std::size_t(row)];
    if (gone.told)
        --m_told[std::size_t(*gone.told)];
    m_rows.erase(m_rows.begin() + row);
    m_index.remove(aircraft);
    for (auto it = m_index.begin(); it != m_index.end(); ++it)
        if (*it > row)
            --*it;
    endRemoveRows();
}

void FleetModel::scheduleFlush()
{
    if (m_flushQueued)
        return;
    m_flushQueued = true;
    // Once per event-loop pass, but not more than ten times a second: at a
    // hundred aircraft a pass each message would repaint the view hundreds of
    // times a second (docs/performance.md, "Fleet through one broker"), and
    // no operator reads a row faster than that.
    const qint64 wait = m_sinceFlush.isValid() ? kMinFlushIntervalMs - m_sinceFlush.elapsed() : 0;
    if (wait <= 0)
        QMetaObject::invokeMethod(this, &FleetModel::flushPending, Qt::QueuedConnection);
    else
        QTimer::singleShot(int(wait), this, &FleetModel::flushPending);
}

void FleetModel::flushPending()
{
    m_sinceFlush.start();
    m_flushQueued = false;
    m_pendingUpdates = 0;
    if (m_changedFirst >= 0) {
        const int first = m_changedFirst;
        const int last = m_changedLast;
        m_changedFirst = m_changedLast = -1;
        bool stateChanged = false;
        for (int r = first; r <= last; ++r)
            stateChanged = tell(m_rows[std::size_t(r)]) || stateChanged;
        // From the link column on unless a row's colours changed: a row's
        // aircraft never changes, so a view sorted by aircraft has nothing
        // to move.
        emit dataChanged(index(first, stateChanged ? AircraftColumn : LinkColumn), index(last, kColumnCount - 1));
    }
    if (!m_pending.empty()) {
        const int first = int(m_rows.size());
        beginInsertRows({}, first, first + int(m_pending.size()) - 1);
        for (Row& row : m_pending) {
            tell(row);
            m_rows.push_back(std::move(row));
        }
        m_pending.clear();
        endInsertRows();
    }
}

void FleetModel::refreshAges()
{
    if (m_rows.empty())
        return;
    const int last = int(m_rows.size()) - 1;
    emit dataChanged(index(0, LastFrameColumn), index(last, LastFrameColumn),
                     {Qt::DisplayRole, Qt::ToolTipRole, SortRole});
    // Rows the passing time made stale (or live again, under a fake clock):
    // their whole row, in runs of neighbours.
    int runStart = -1;
    for (int r = 0; r <= last + 1; ++r) {
        const bool moved = r <= last && tell(m_rows[std::size_t(r)]);
        if (moved && runStart < 0)
            runStart = r;
        if (!moved && runStart >= 0) {
            rowsChanged(runStart, r - 1, {Qt::ForegroundRole, Qt::BackgroundRole, Qt::ToolTipRole, StateRole});
            runStart = -1;
        }
    }
}
