#include "link/plan/WaypointsFile.h"

#include "link/plan/PlanReading.h"

#include <QLocale>
#include <QRegularExpression>
#include <QStringList>

#include <cmath>
#include <limits>

namespace {

constexpr double kDegreeSteps = MissionPlan::kDegreeSteps;
constexpr double kMillimetres = MissionPlan::kMillimetres;
constexpr int kFieldCount = 12;
const char* const kFieldNames[kFieldCount] = {"index",  "current", "frame",    "command",   "param1",   "param2",
                                              "param3", "param4",  "latitude", "longitude", "altitude", "autocontinue"};
enum Field { Index, Current, Frame, Command, Param1, Latitude = 8, Longitude, Altitude, AutoContinue };
// MAV_CMD of the fence and rally items (MAV_MISSION_TYPE_FENCE and _RALLY).
constexpr int kFenceReturnPoint = 5000;
constexpr int kFenceVertexInclusion = 5001;
constexpr int kFenceVertexExclusion = 5002;
constexpr int kFenceCircleInclusion = 5003;
constexpr int kFenceCircleExclusion = 5004;
constexpr int kRallyPoint = 5100;
// The largest radius the plan bytes hold: a uint32 of millimetres.
constexpr double kMaxRadius = 4294967.295;

QString number(double value)
{
    return QString::number(value, 'g', QLocale::FloatingPointShortest);
}

// One line of the file, split into its fields.
struct Line {
    int number = 0;
    QStringList fields;
};

class WaypointsReader {
public:
    explicit WaypointsReader(const QString& source) : m_source(source) {}

    std::optional<MissionPlan> read(const QByteArray& text)
    {
        const QStringList lines = QString::fromUtf8(text).split(QLatin1Char('\n'));
        if (!readHeader(lines[0]))
            return std::nullopt;
        MissionPlan plan;
        bool first = true;
        for (qsizetype i = 1; i < lines.size(); ++i) {
            const QString content = lines[i].trimmed();
            if (content.isEmpty() || content.startsWith(QLatin1Char('#')))
                continue;
            const Line line{int(i + 1), content.split(QRegularExpression(QStringLiteral("[ \t]+")))};
            if (line.fields.size() != kFieldCount) {
                fail(line.number, QStringLiteral("%1 fields; a QGC WPL 110 line has 12 (index, current, frame, "
                                                 "command, param1..param4, latitude, longitude, altitude, "
                                                 "autocontinue)")
                                      .arg(line.fields.size()));
                return std::nullopt;
            }
            const auto index = wholeNumber(line, Index, 0, std::numeric_limits<int>::max());
            if (!index)
                return std::nullopt;
            // A fence or rally file (Mission Planner's and MAVProxy's) has no
            // home line: its index 0 is the first vertex or point.
            const auto command = wholeNumber(line, Command, 0, 65535);
            if (!command)
                return std::nullopt;
            const bool isHome = first && *index == 0 && !isFenceOrRally(int(*command));
            first = false;
            MissionItem item;
            if (!readItem(line, isHome || isFenceOrRally(int(*command)), item))
                return std::nullopt;
            if (isHome) {
                // 0 north, 0 east: Mission Planner's home before it knew one.
                if (item.latitude != 0.0 || item.longitude != 0.0) {
                    plan.homeLatitude = item.latitude;
                    plan.homeLongitude = item.longitude;
                    plan.homeAltitude = item.altitude;
                }
                continue;
            }
            if (isFenceOrRally(item.command)) {
                if (!readFenceOrRally(line, item, plan))
                    return std::nullopt;
                continue;
            }
            if (plan.items.size() == std::numeric_limits<quint16>::max()) {
                fail(line.number, QStringLiteral("more than 65535 mission items; a plan holds at most 65535"));
                return std::nullopt;
            }
            item.seq = quint16(plan.items.size());
            plan.items.append(item);
        }
        if (m_polygon) {
            failPolygon();
            return std::nullopt;
        }
        return plan;
    }

    const QString& error() const { return m_error; }

private:
    bool fail(int line, const QString& what)
    {
        m_error = QStringLiteral("%1: line %2: %3").arg(m_source).arg(line).arg(what);
        return false;
    }

    bool failField(const Line& line, int field, const QString& what)
    {
        m_error = QStringLiteral("%1: line %2, field %3 (%4): %5")
                      .arg(m_source)
                      .arg(line.number)
                      .arg(field + 1)
                      .arg(QLatin1String(kFieldNames[field]), what);
        return false;
    }

    bool readHeader(QString first)
    {
        first = first.trimmed();
        if (first.startsWith(QChar(0xFEFF)))
            first = first.mid(1).trimmed();
        if (!first.startsWith(QLatin1String("QGC WPL")))
            return fail(1, first.isEmpty()
                               ? QStringLiteral("not a QGC WPL 110 file (its first line is empty)")
                               : QStringLiteral("not a QGC WPL 110 file (it starts with \"%1\")").arg(first.left(40)));
        const QString version = first.mid(7).trimmed();
        if (version == QLatin1String("110"))
            return true;
        if (version == QLatin1String("120"))
            return fail(1, QStringLiteral("QGC WPL 120 (QGroundControl's format before 2016, without a home) is not "
                                          "read; open the file in QGroundControl and save it as a .plan"));
        return fail(1, QStringLiteral("QGC WPL version \"%1\"; this console reads QGC WPL 110").arg(version));
    }

    std::optional<qint64> wholeNumber(const Line& line, int field, qint64 min, qint64 max)
    {
        bool ok = false;
        const qint64 value = line.fields[field].toLongLong(&ok);
        if (!ok) {
            failField(line, field, QStringLiteral("\"%1\" is not a whole number").arg(line.fields[field]));
            return std::nullopt;
        }
        if (value < min || value > max) {
            failField(line, field, QStringLiteral("%1 is outside %2..%3").arg(value).arg(min).arg(max));
            return std::nullopt;
        }
        return value;
    }

    std::optional<double> real(const Line& line, int field)
    {
        bool ok = false;
        const double value = line.fields[field].toDouble(&ok);
        if (!ok) {
            failField(line, field, QStringLiteral("\"%1\" is not a number").arg(line.fields[field]));
            return std::nullopt;
        }
        return value;
    }

    // Latitude, longitude and altitude: not given when NaN; in range for the
    // plan bytes and, in a frame of latitudes and longitudes, on the globe.
    bool readPosition(const Line& line, bool global, std::optional<double> (&position)[3])
    {
        for (int i = 0; i < 3; ++i) {
            const int field = Latitude + i;
            const auto value = real(line, field);
            if (!value)
                return false;
            if (std::isnan(*value))
                continue;
            const double limit = field == Latitude ? 90 : 180;
            if (global && field != Altitude && std::abs(*value) > limit)
                return failField(line, field, QStringLiteral("%1 is outside \u00b1%2").arg(number(*value)).arg(limit));
            if (!MissionPlan::fitsField(*value, field == Altitude ? kMillimetres : kDegreeSteps))
                return failField(line, field,
                                 QStringLiteral("%1 is out of the range the plan bytes hold").arg(number(*value)));
            position[i] = *value;
        }
        return true;
    }

    static bool isFenceOrRally(int command)
    {
        return (command >= kFenceReturnPoint && command <= kFenceCircleExclusion) || command == kRallyPoint;
    }

    // A polygon's vertices come one a line, each saying how many the polygon
    // has (param1); the polygon ends when that many have come.
    bool readFenceOrRally(const Line& line, const MissionItem& item, MissionPlan& plan)
    {
        const GeoPoint at{item.latitude.value_or(0), item.longitude.value_or(0)};
        const double count = item.params[0];
        const bool vertex = item.command == kFenceVertexInclusion || item.command == kFenceVertexExclusion;
        if (m_polygon && (!vertex || item.command != m_polygon->command || count != m_polygon->count))
            return failPolygon(line.number);
        if (vertex) {
            if (!m_polygon) {
                if (!(count >= 3 && count <= std::numeric_limits<quint16>::max() && count == std::floor(count)))
                    return failField(line, Param1,
                                     QStringLiteral("a fence polygon's vertex count is %1; it must be a whole "
                                                    "number, 3 or more")
                                         .arg(number(count)));
                m_polygon = OpenPolygon{item.command, count, line.number, int(plan.fencePolygons.size()) + 1, 0};
                plan.fencePolygons.append(FencePolygon{item.command == kFenceVertexInclusion, {}});
            }
            plan.fencePolygons.back().vertices.append(at);
            if (++m_polygon->seen == qsizetype(count))
                m_polygon.reset();
            return true;
        }
        switch (item.command) {
            case kFenceCircleInclusion:
            case kFenceCircleExclusion:
                if (!(count > 0 && count <= kMaxRadius))
                    return failField(line, Param1,
                                     QStringLiteral("a fence circle's radius is %1 m; it must be more than 0 and at "
                                                    "most 4294 km")
                                         .arg(number(count)));
                plan.fenceCircles.append({item.command == kFenceCircleInclusion, at, count});
                return true;
            case kRallyPoint:
                plan.rallyPoints.append({at, item.altitude.value_or(0)});
                return true;
            default:
                // FENCE_RETURN_POINT: where ArduPilot flies on a breach; a
                // MissionPlan has no place for it (nor for QGroundControl's
                // breach return point).
                return true;
        }
    }

    // The open polygon ended before it had its vertices: at `lineNumber`, or
    // (0) at the end of the file.
    bool failPolygon(int lineNumber = 0)
    {
        const QString what = QStringLiteral(
                                 "fence polygon %1 (from line %2) has %3 of the %4 vertices its lines "
                                 "give as param1; a polygon's vertices follow one another")
                                 .arg(m_polygon->number)
                                 .arg(m_polygon->line)
                                 .arg(m_polygon->seen)
                                 .arg(number(m_polygon->count));
        if (lineNumber == 0) {
            m_error = QStringLiteral("%1: %2").arg(m_source, what);
            return false;
        }
        return fail(lineNumber, what);
    }

    // Every field of a line, the home's as well as an item's. The home, and
    // a fence's or rally point's position, is a place on the globe whatever
    // its frame says.
    bool readItem(const Line& line, bool isHome, MissionItem& item)
    {
        const auto current = wholeNumber(line, Current, 0, 1);
        const auto frame = current ? wholeNumber(line, Frame, 0, 255) : std::nullopt;
        const auto command = frame ? wholeNumber(line, Command, 0, 65535) : std::nullopt;
        if (!command)
            return false;
        item.frame = quint8(*frame);
        item.command = quint16(*command);
        for (int p = 0; p < 4; ++p) {
            const auto value = real(line, Param1 + p);
            if (!value)
                return false;
            if (std::isfinite(*value) && std::abs(*value) > double(std::numeric_limits<float>::max()))
                return failField(line, Param1 + p,
                                 QStringLiteral("%1 does not fit a 32-bit float").arg(number(*value)));
            item.params[std::size_t(p)] = *value;
        }
        std::optional<double> position[3];
        if (!readPosition(line, isHome || MissionItem::isGlobalFrame(item.frame), position))
            return false;
        item.latitude = position[0];
        item.longitude = position[1];
        item.altitude = position[2];
        const auto autoContinue = wholeNumber(line, AutoContinue, 0, 1);
        if (!autoContinue)
            return false;
        item.autoContinue = *autoContinue == 1;
        return true;
    }

    // A fence polygon whose vertices are still coming.
    struct OpenPolygon {
        quint16 command = 0;
        double count = 0;  // param1 of its lines
        int line = 0;      // its first
        int number = 0;    // 1-based, among the plan's polygons
        qsizetype seen = 0;
    };

    const QString& m_source;
    QString m_error;
    std::optional<OpenPolygon> m_polygon;
};

QByteArray field(double value)
{
    return std::isnan(value) ? QByteArray("nan") : QByteArray::number(value, 'g', QLocale::FloatingPointShortest);
}

QByteArray line(const QList<QByteArray>& fields)
{
    return fields.join('\t') + '\n';
}

}  // namespace

namespace WaypointsFile {

std::optional<MissionPlan> read(const QByteArray& text, const QString& source, QString* error)
{
    WaypointsReader reader(source);
    return PlanReading::outcome(reader, reader.read(text), error);
}

QByteArray write(const MissionPlan& plan)
{
    QByteArray out = "QGC WPL 110\n";
    // The home line as Mission Planner writes it: current, absolute frame, NAV_WAYPOINT.
    out += line({"0", "1", "0", "16", "0", "0", "0", "0", field(plan.homeLatitude.value_or(0)),
                 field(plan.homeLongitude.value_or(0)), field(plan.homeAltitude.value_or(0)), "1"});
    for (qsizetype i = 0; i < plan.items.size(); ++i) {
        const MissionItem& item = plan.items[i];
        out += line({QByteArray::number(i + 1), "0", QByteArray::number(item.frame), QByteArray::number(item.command),
                     field(item.params[0]), field(item.params[1]), field(item.params[2]), field(item.params[3]),
                     field(item.latitude.value_or(0)), field(item.longitude.value_or(0)),
                     field(item.altitude.value_or(0)), item.autoContinue ? "1" : "0"});
    }
    return out;
}

}  // namespace WaypointsFile
