#include "link/plan/QgcPlanFile.h"

#include "link/simulation/JsonPosition.h"

#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>

#include <cmath>
#include <limits>

namespace {

constexpr double kDegreeSteps = 1e7;
constexpr double kMillimetres = 1e3;

// Fits the int32 field scaled by `steps`.
bool fitsInt32(double value, double steps)
{
    const double scaled = std::round(value * steps);
    return std::isfinite(scaled) && scaled > double(std::numeric_limits<std::int32_t>::min()) &&
           scaled <= double(std::numeric_limits<std::int32_t>::max());
}

// Frames whose x and y are a latitude and a longitude.
bool isGlobalFrame(quint8 frame)
{
    return frame == 0 || frame == 3 || frame == 5 || frame == 6 || frame == 10 || frame == 11;
}

}  // namespace

namespace QgcPlanFile {

std::optional<MissionPlan> read(const QByteArray& json, const QString& source, QString* error)
{
    const auto fail = [&](const QString& what) -> std::optional<MissionPlan> {
        if (error)
            *error = QStringLiteral("%1: %2").arg(source, what);
        return std::nullopt;
    };
    QJsonParseError parseError;
    const QJsonDocument doc = QJsonDocument::fromJson(json, &parseError);
    if (parseError.error != QJsonParseError::NoError)
        return fail(QStringLiteral("%1: %2").arg(jsonPosition(json, parseError.offset), parseError.errorString()));
    const QJsonObject root = doc.object();
    if (root.value(QStringLiteral("fileType")).toString() != QLatin1String("Plan"))
        return fail(QStringLiteral("not a QGroundControl plan (its \"fileType\" is not \"Plan\")"));
    const QJsonObject mission = root.value(QStringLiteral("mission")).toObject();
    const QJsonValue itemsValue = mission.value(QStringLiteral("items"));
    if (!itemsValue.isArray())
        return fail(QStringLiteral("the plan has no \"mission\" with \"items\""));
    const QJsonArray items = itemsValue.toArray();
    if (items.size() > std::numeric_limits<quint16>::max())
        return fail(QStringLiteral("%1 mission items; a plan holds at most 65535").arg(items.size()));

    MissionPlan plan;
    const QJsonArray home = mission.value(QStringLiteral("plannedHomePosition")).toArray();
    if (home.size() == 3) {
        const auto coordinate = [](const QJsonValue& v) {
            return v.isDouble() ? std::optional<double>(v.toDouble()) : std::nullopt;
        };
        plan.homeLatitude = coordinate(home[0]);
        plan.homeLongitude = coordinate(home[1]);
        plan.homeAltitude = coordinate(home[2]);
        if ((plan.homeLatitude && std::abs(*plan.homeLatitude) > 90) ||
            (plan.homeLongitude && std::abs(*plan.homeLongitude) > 180) ||
            (plan.homeAltitude && !fitsInt32(*plan.homeAltitude, kMillimetres)))
            return fail(QStringLiteral("the planned home position is out of range"));
    }

    for (qsizetype i = 0; i < items.size(); ++i) {
        const QJsonObject o = items[i].toObject();
        const QString where = QStringLiteral("mission item %1").arg(i + 1);
        const QString type = o.value(QStringLiteral("type")).toString();
        if (type == QLatin1String("ComplexItem"))
            return fail(QStringLiteral("%1 is a %2 (a ComplexItem); only simple items can be sent, so convert it "
                                       "to waypoints in QGroundControl first")
                            .arg(where, o.value(QStringLiteral("complexItemType")).toString()));
        if (type != QLatin1String("SimpleItem"))
            return fail(QStringLiteral("%1 has type \"%2\", not SimpleItem").arg(where, type));
        const QJsonValue command = o.value(QStringLiteral("command"));
        const QJsonValue frame = o.value(QStringLiteral("frame"));
        const QJsonArray params = o.value(QStringLiteral("params")).toArray();
        if (!command.isDouble() || command.toInt(-1) < 0 || command.toInt(-1) > 65535)
            return fail(QStringLiteral("%1: \"command\" must be a MAV_CMD number 0..65535").arg(where));
        if (!frame.isDouble() || frame.toInt(-1) < 0 || frame.toInt(-1) > 255)
            return fail(QStringLiteral("%1: \"frame\" must be a MAV_FRAME number 0..255").arg(where));
        if (params.size() != 7)
            return fail(QStringLiteral("%1: \"params\" must hold 7 values (numbers or null)").arg(where));

        MissionItem item;
        item.seq = quint16(i);
        item.command = quint16(command.toInt());
        item.frame = quint8(frame.toInt());
        item.autoContinue = o.value(QStringLiteral("autoContinue")).toBool(true);
        for (int p = 0; p < 7; ++p) {
            const QJsonValue v = params[p];
            if (!v.isNull() && !v.isDouble())
                return fail(QStringLiteral("%1: param%2 must be a number or null").arg(where).arg(p + 1));
        }
        for (int p = 0; p < 4; ++p) {
            const double v = params[p].isNull() ? std::nan("") : params[p].toDouble();
            if (std::isfinite(v) && std::abs(v) > double(std::numeric_limits<float>::max()))
                return fail(QStringLiteral("%1: param%2 does not fit a 32-bit float").arg(where).arg(p + 1));
            item.params[std::size_t(p)] = v;
        }
        const auto given = [&](int p) {
            return params[p].isNull() ? std::nullopt : std::optional<double>(params[p].toDouble());
        };
        item.latitude = given(4);
        item.longitude = given(5);
        item.altitude = given(6);
        if (isGlobalFrame(item.frame) &&
            ((item.latitude && std::abs(*item.latitude) > 90) || (item.longitude && std::abs(*item.longitude) > 180)))
            return fail(
                QStringLiteral("%1: latitude must be within +-90 and longitude within +-180 degrees").arg(where));
        if ((item.latitude && !fitsInt32(*item.latitude, kDegreeSteps)) ||
            (item.longitude && !fitsInt32(*item.longitude, kDegreeSteps)) ||
            (item.altitude && !fitsInt32(*item.altitude, kMillimetres)))
            return fail(QStringLiteral("%1: param5..param7 out of the range the plan bytes hold").arg(where));
        plan.items.append(item);
    }
    return plan;
}


QByteArray write(const MissionPlan&)
{
    return {};  // written by the plan file work
}

}  // namespace QgcPlanFile
