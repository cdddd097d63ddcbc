#include "ui/plan/MissionPlan.h"

#include "link/simulation/JsonPosition.h"

#include <QDir>
#include <QFile>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QtEndian>

#include <bit>
#include <cmath>
#include <limits>

namespace {

// Frames whose x and y are a latitude and a longitude.
bool isGlobalFrame(quint8 frame)
{
    return frame == 0 || frame == 3 || frame == 5 || frame == 6 || frame == 10 || frame == 11;
}

constexpr double kDegreeSteps = 1e7;
constexpr double kMillimetres = 1e3;

// Fits the int32 field scaled by `steps`.
bool fitsInt32(double value, double steps)
{
    const double scaled = std::round(value * steps);
    return std::isfinite(scaled) && scaled > double(std::numeric_limits<std::int32_t>::min()) &&
           scaled <= double(std::numeric_limits<std::int32_t>::max());
}

std::int32_t toFixed(const std::optional<double>& value, double steps)
{
    return value ? std::int32_t(std::lround(*value * steps)) : MissionPlan::kNotGiven;
}

std::optional<double> fromFixed(std::int32_t value, double steps)
{
    return value == MissionPlan::kNotGiven ? std::nullopt : std::optional<double>(value / steps);
}

template <typename T>
void put(QByteArray& out, T value)
{
    char bytes[sizeof(T)];
    qToBigEndian(value, bytes);
    out.append(bytes, sizeof(T));
}

template <typename T>
T take(const char*& at)
{
    const T value = qFromBigEndian<T>(at);
    at += sizeof(T);
    return value;
}

}  // namespace

QString MissionItem::commandName() const
{
    switch (command) {
        case 16:
            return QStringLiteral("NAV_WAYPOINT");
        case 17:
            return QStringLiteral("NAV_LOITER_UNLIM");
        case 18:
            return QStringLiteral("NAV_LOITER_TURNS");
        case 19:
            return QStringLiteral("NAV_LOITER_TIME");
        case 20:
            return QStringLiteral("NAV_RETURN_TO_LAUNCH");
        case 21:
            return QStringLiteral("NAV_LAND");
        case 22:
            return QStringLiteral("NAV_TAKEOFF");
        case 31:
            return QStringLiteral("NAV_LOITER_TO_ALT");
        case 84:
            return QStringLiteral("NAV_VTOL_TAKEOFF");
        case 85:
            return QStringLiteral("NAV_VTOL_LAND");
        case 112:
            return QStringLiteral("CONDITION_DELAY");
        case 177:
            return QStringLiteral("DO_JUMP");
        case 178:
            return QStringLiteral("DO_CHANGE_SPEED");
        case 189:
            return QStringLiteral("DO_LAND_START");
        case 201:
            return QStringLiteral("DO_SET_ROI");
        case 203:
            return QStringLiteral("DO_DIGICAM_CONTROL");
        case 206:
            return QStringLiteral("DO_SET_CAM_TRIGG_DIST");
        case 2000:
            return QStringLiteral("IMAGE_START_CAPTURE");
        case 2001:
            return QStringLiteral("IMAGE_STOP_CAPTURE");
    }
    return QStringLiteral("MAV_CMD %1").arg(command);
}

QString MissionItem::frameName() const
{
    switch (frame) {
        case 0:
            return QStringLiteral("AMSL");
        case 2:
            return QStringLiteral("mission");
        case 3:
            return QStringLiteral("above home");
        case 5:
            return QStringLiteral("AMSL (int)");
        case 6:
            return QStringLiteral("above home (int)");
        case 10:
            return QStringLiteral("above terrain");
        case 11:
            return QStringLiteral("above terrain (int)");
    }
    return QStringLiteral("MAV_FRAME %1").arg(frame);
}

std::optional<MissionPlan> MissionPlan::load(const QString& path, QString* error)
{
    QFile file(path);
    if (!file.open(QIODevice::ReadOnly)) {
        if (error)
            *error = QStringLiteral("%1: %2").arg(QDir::toNativeSeparators(path), file.errorString());
        return std::nullopt;
    }
    return fromQgcJson(file.readAll(), QDir::toNativeSeparators(path), error);
}

std::optional<MissionPlan> MissionPlan::fromQgcJson(const QByteArray& json, const QString& source, QString* error)
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

QByteArray MissionPlan::toBytes() const
{
    QByteArray out;
    out.reserve(kHeaderBytes + kItemBytes * items.size());
    put<quint8>(out, kFormat);
    put<quint8>(out, 0);
    put<quint16>(out, quint16(items.size()));
    put<qint32>(out, toFixed(homeLatitude, kDegreeSteps));
    put<qint32>(out, toFixed(homeLongitude, kDegreeSteps));
    put<qint32>(out, toFixed(homeAltitude, kMillimetres));
    for (const MissionItem& item : items) {
        put<quint16>(out, item.seq);
        put<quint16>(out, item.command);
        put<quint8>(out, item.frame);
        put<quint8>(out, item.autoContinue ? 1 : 0);
        for (double p : item.params)
            put<quint32>(out,
                         std::bit_cast<quint32>(std::isnan(p) ? std::numeric_limits<float>::quiet_NaN() : float(p)));
        put<qint32>(out, toFixed(item.latitude, kDegreeSteps));
        put<qint32>(out, toFixed(item.longitude, kDegreeSteps));
        put<qint32>(out, toFixed(item.altitude, kMillimetres));
    }
    return out;
}

std::optional<MissionPlan> MissionPlan::fromBytes(const QByteArray& bytes, QString* error)
{
    const auto fail = [&](const QString& what) -> std::optional<MissionPlan> {
        if (error)
            *error = what;
        return std::nullopt;
    };
    if (bytes.size() < kHeaderBytes)
        return fail(QStringLiteral("%1 bytes: shorter than the plan header").arg(bytes.size()));
    const char* at = bytes.constData();
    const quint8 format = take<quint8>(at);
    take<quint8>(at);
    const quint16 count = take<quint16>(at);
    if (format != kFormat)
        return fail(QStringLiteral("plan format %1; this console reads format %2").arg(format).arg(kFormat));
    if (bytes.size() != kHeaderBytes + kItemBytes * qsizetype(count))
        return fail(QStringLiteral("%1 bytes for %2 items; expected %3")
                        .arg(bytes.size())
                        .arg(count)
                        .arg(kHeaderBytes + kItemBytes * qsizetype(count)));
    MissionPlan plan;
    plan.homeLatitude = fromFixed(take<qint32>(at), kDegreeSteps);
    plan.homeLongitude = fromFixed(take<qint32>(at), kDegreeSteps);
    plan.homeAltitude = fromFixed(take<qint32>(at), kMillimetres);
    for (int i = 0; i < count; ++i) {
        MissionItem item;
        item.seq = take<quint16>(at);
        item.command = take<quint16>(at);
        item.frame = take<quint8>(at);
        item.autoContinue = (take<quint8>(at) & 1) != 0;
        for (double& p : item.params)
            p = double(std::bit_cast<float>(take<quint32>(at)));
        item.latitude = fromFixed(take<qint32>(at), kDegreeSteps);
        item.longitude = fromFixed(take<qint32>(at), kDegreeSteps);
        item.altitude = fromFixed(take<qint32>(at), kMillimetres);
        plan.items.append(item);
    }
    return plan;
}
