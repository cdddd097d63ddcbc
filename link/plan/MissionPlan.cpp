#include "link/plan/MissionPlan.h"

#include "codec/plan/PlanContents.h"
#include "link/plan/MavCommand.h"

#include <bit>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace {

constexpr double kDegreeSteps = MissionPlan::kDegreeSteps;
constexpr double kMillimetres = MissionPlan::kMillimetres;

// The int32 field scaled by `steps`, or nothing when the value does not fit.
std::optional<std::int32_t> toFixed(double value, double steps)
{
    const double scaled = std::round(value * steps);
    if (!std::isfinite(scaled) || scaled <= double(std::numeric_limits<std::int32_t>::min()) ||
        scaled > double(std::numeric_limits<std::int32_t>::max()))
        return std::nullopt;
    return std::int32_t(scaled);
}

std::optional<double> fromFixed(std::int32_t value, double steps)
{
    return value == rcm::plan::kNotGiven ? std::nullopt : std::optional<double>(value / steps);
}

class Conversion {
public:
    // The field, kNotGiven for no value; records the first value out of range.
    std::int32_t fixed(const std::optional<double>& value, double steps, const QString& what)
    {
        if (!value)
            return rcm::plan::kNotGiven;
        const auto f = toFixed(*value, steps);
        if (!f && m_error.isEmpty())
            m_error = QStringLiteral("%1 (%2) is out of the range the plan bytes hold").arg(what).arg(*value);
        return f.value_or(0);
    }
    rcm::plan::Position position(const GeoPoint& p, const QString& what)
    {
        return {fixed(p.latitude, kDegreeSteps, what + QStringLiteral(" latitude")),
                fixed(p.longitude, kDegreeSteps, what + QStringLiteral(" longitude"))};
    }
    const QString& error() const { return m_error; }

private:
    QString m_error;
};

constexpr double kEarthRadius = 6371008.8;  // metres, mean

double metresBetween(const GeoPoint& a, const GeoPoint& b)
{
    const double radians = std::numbers::pi / 180;
    const double dLat = (b.latitude - a.latitude) * radians;
    const double dLon = (b.longitude - a.longitude) * radians;
    const double h = std::sin(dLat / 2) * std::sin(dLat / 2) + std::cos(a.latitude * radians) *
                                                                   std::cos(b.latitude * radians) * std::sin(dLon / 2) *
                                                                   std::sin(dLon / 2);
    return 2 * kEarthRadius * std::asin(std::min(1.0, std::sqrt(h)));
}

// Even-odd rule: a ray to the east crosses the boundary an odd number of times.
bool inside(const FencePolygon& polygon, const GeoPoint& p)
{
    bool in = false;
    const QList<GeoPoint>& v = polygon.vertices;
    for (qsizetype i = 0, j = v.size() - 1; i < v.size(); j = i++) {
        if ((v[i].latitude > p.latitude) != (v[j].latitude > p.latitude) &&
            p.longitude <
                (v[j].longitude - v[i].longitude) * (p.latitude - v[i].latitude) / (v[j].latitude - v[i].latitude) +
                    v[i].longitude)
            in = !in;
    }
    return in;
}

GeoPoint toGeo(const rcm::plan::Position& p)
{
    return {p.latitude / kDegreeSteps, p.longitude / kDegreeSteps};
}

}  // namespace

QString MissionItem::commandName() const
{
    return MavCommand::nameOf(command);
}

QString MissionItem::frameName() const
{
    // The MAV_FRAME values plans use.
    static constexpr struct {
        int frame;
        const char* name;
    } kFrameNames[] = {
        {0, "AMSL"},
        {2, "mission"},
        {3, "above home"},
        {5, "AMSL (int)"},
        {6, "above home (int)"},
        {10, "above terrain"},
        {11, "above terrain (int)"},
    };
    for (const auto& known : kFrameNames) {
        if (known.frame == frame)
            return QString::fromLatin1(known.name);
    }
    return QStringLiteral("MAV_FRAME %1").arg(frame);
}

bool MissionItem::isGlobalFrame(int frame)
{
    return frame == 0 || frame == 3 || frame == 5 || frame == 6 || frame == 10 || frame == 11;
}

bool MissionItem::hasPosition() const
{
    const MavCommand* known = MavCommand::find(command);
    return (!known || known->position) && isGlobalFrame(frame) && latitude && longitude &&
           !(*latitude == 0 && *longitude == 0);
}

bool MissionItem::hasAltitude() const
{
    const MavCommand* known = MavCommand::find(command);
    return (known ? known->altitude : isGlobalFrame(frame)) && altitude.has_value();
}

bool MissionPlan::fitsField(double value, double steps)
{
    return toFixed(value, steps).has_value();
}

int MissionPlan::format() const
{
    return fencePolygons.isEmpty() && fenceCircles.isEmpty() && rallyPoints.isEmpty() ? 1 : 2;
}

std::optional<GeoPoint> MissionPlan::home() const
{
    if (!homeLatitude || !homeLongitude || (*homeLatitude == 0 && *homeLongitude == 0))
        return std::nullopt;
    return GeoPoint{*homeLatitude, *homeLongitude};
}

void MissionPlan::renumber()
{
    for (qsizetype i = 0; i < items.size(); ++i)
        items[i].seq = quint16(i);
}

std::optional<QByteArray> MissionPlan::encode(QString* error) const
{
    const auto fail = [&](const QString& what) -> std::optional<QByteArray> {
        if (error)
            *error = what;
        return std::nullopt;
    };
    Conversion c;
    rcm::plan::Contents contents;
    contents.homeLatitude = c.fixed(homeLatitude, kDegreeSteps, QStringLiteral("home latitude"));
    contents.homeLongitude = c.fixed(homeLongitude, kDegreeSteps, QStringLiteral("home longitude"));
    contents.homeAltitude = c.fixed(homeAltitude, kMillimetres, QStringLiteral("home altitude"));
    for (const MissionItem& item : items) {
        const QString name = QStringLiteral("mission item %1").arg(item.seq + 1);
        rcm::plan::Item out;
        out.seq = item.seq;
        out.command = item.command;
        out.frame = item.frame;
        out.autoContinue = item.autoContinue;
        for (std::size_t p = 0; p < 4; ++p) {
            const double v = item.params[p];
            if (std::isfinite(v) && std::abs(v) > double(std::numeric_limits<float>::max()))
                return fail(QStringLiteral("%1: param%2 does not fit a 32-bit float").arg(name).arg(p + 1));
            out.params[p] =
                std::bit_cast<std::uint32_t>(std::isnan(v) ? std::numeric_limits<float>::quiet_NaN() : float(v));
        }
        out.x = c.fixed(item.latitude, kDegreeSteps, name + QStringLiteral(" latitude"));
        out.y = c.fixed(item.longitude, kDegreeSteps, name + QStringLiteral(" longitude"));
        out.z = c.fixed(item.altitude, kMillimetres, name + QStringLiteral(" altitude"));
        contents.items.push_back(out);
    }
    for (qsizetype i = 0; i < fencePolygons.size(); ++i) {
        rcm::plan::FencePolygon out;
        out.inclusion = fencePolygons[i].inclusion;
        for (const GeoPoint& p : fencePolygons[i].vertices)
            out.vertices.push_back(c.position(p, QStringLiteral("fence polygon %1 vertex").arg(i + 1)));
        contents.polygons.push_back(std::move(out));
    }
    for (qsizetype i = 0; i < fenceCircles.size(); ++i) {
        const FenceCircle& circle = fenceCircles[i];
        const QString name = QStringLiteral("fence circle %1").arg(i + 1);
        rcm::plan::FenceCircle out;
        out.inclusion = circle.inclusion;
        out.centre = c.position(circle.centre, name + QStringLiteral(" centre"));
        const double radius = std::round(circle.radius * kMillimetres);
        if (!(radius >= 1 && radius <= double(std::numeric_limits<std::uint32_t>::max())))
            return fail(QStringLiteral("%1: radius %2 m is not between 1 mm and 4294 km").arg(name).arg(circle.radius));
        out.radius = std::uint32_t(radius);
        contents.circles.push_back(out);
    }
    for (qsizetype i = 0; i < rallyPoints.size(); ++i) {
        const QString name = QStringLiteral("rally point %1").arg(i + 1);
        rcm::plan::RallyPoint out;
        out.position = c.position(rallyPoints[i].position, name);
        out.altitude = c.fixed(rallyPoints[i].altitude, kMillimetres, name + QStringLiteral(" altitude"));
        contents.rallyPoints.push_back(out);
    }
    if (!c.error().isEmpty())
        return fail(c.error());
    try {
        const std::vector<std::uint8_t> bytes = rcm::plan::encode(contents);
        return QByteArray(reinterpret_cast<const char*>(bytes.data()), qsizetype(bytes.size()));
    } catch (const std::invalid_argument& e) {
        return fail(QString::fromStdString(e.what()));
    }
}

QByteArray MissionPlan::toBytes() const
{
    return encode().value_or(QByteArray());
}

std::optional<MissionPlan> MissionPlan::fromBytes(const QByteArray& bytes, QString* error)
{
    std::string reason;
    const auto contents = rcm::plan::decode(
        std::span(reinterpret_cast<const std::uint8_t*>(bytes.constData()), std::size_t(bytes.size())), &reason);
    if (!contents) {
        if (error)
            *error = QString::fromStdString(reason);
        return std::nullopt;
    }
    MissionPlan plan;
    plan.homeLatitude = fromFixed(contents->homeLatitude, kDegreeSteps);
    plan.homeLongitude = fromFixed(contents->homeLongitude, kDegreeSteps);
    plan.homeAltitude = fromFixed(contents->homeAltitude, kMillimetres);
    for (const rcm::plan::Item& in : contents->items) {
        MissionItem item;
        item.seq = in.seq;
        item.command = in.command;
        item.frame = in.frame;
        item.autoContinue = in.autoContinue;
        for (std::size_t p = 0; p < 4; ++p)
            item.params[p] = double(std::bit_cast<float>(in.params[p]));
        item.latitude = fromFixed(in.x, kDegreeSteps);
        item.longitude = fromFixed(in.y, kDegreeSteps);
        item.altitude = fromFixed(in.z, kMillimetres);
        plan.items.append(item);
    }
    for (const rcm::plan::FencePolygon& in : contents->polygons) {
        FencePolygon polygon;
        polygon.inclusion = in.inclusion;
        for (const rcm::plan::Position& p : in.vertices)
            polygon.vertices.append(toGeo(p));
        plan.fencePolygons.append(polygon);
    }
    for (const rcm::plan::FenceCircle& in : contents->circles)
        plan.fenceCircles.append({in.inclusion, toGeo(in.centre), in.radius / kMillimetres});
    for (const rcm::plan::RallyPoint& in : contents->rallyPoints)
        plan.rallyPoints.append({toGeo(in.position), in.altitude / kMillimetres});
    return plan;
}

QStringList MissionPlan::fenceViolations() const
{
    QStringList found;
    bool anyInclusion = false;
    for (const FencePolygon& p : fencePolygons)
        anyInclusion |= p.inclusion;
    for (const FenceCircle& c : fenceCircles)
        anyInclusion |= c.inclusion;
    const auto check = [&](const GeoPoint& at, const QString& name) {
        bool included = false;
        QString excluded;
        for (qsizetype i = 0; i < fencePolygons.size(); ++i) {
            const bool in = inside(fencePolygons[i], at);
            if (in && fencePolygons[i].inclusion)
                included = true;
            else if (in && excluded.isEmpty())
                excluded = QStringLiteral("exclusion polygon %1").arg(i + 1);
        }
        for (qsizetype i = 0; i < fenceCircles.size(); ++i) {
            const bool in = metresBetween(fenceCircles[i].centre, at) <= fenceCircles[i].radius;
            if (in && fenceCircles[i].inclusion)
                included = true;
            else if (in && excluded.isEmpty())
                excluded = QStringLiteral("exclusion circle %1").arg(i + 1);
        }
        if (!excluded.isEmpty())
            found << QStringLiteral("%1 is inside %2").arg(name, excluded);
        else if (anyInclusion && !included)
            found << QStringLiteral("%1 is outside every inclusion area").arg(name);
    };
    for (const MissionItem& item : items) {
        if (item.hasPosition())
            check({*item.latitude, *item.longitude}, QStringLiteral("mission item %1").arg(item.seq + 1));
    }
    // A rally point is where the aircraft goes when the mission is given up:
    // one the fence forbids would breach it on the way home.
    for (qsizetype i = 0; i < rallyPoints.size(); ++i)
        check(rallyPoints[i].position, QStringLiteral("rally point %1").arg(i + 1));
    return found;
}
