#include "link/plan/QgcPlanFile.h"

#include "link/plan/PlanReading.h"
#include "link/plan/QgcComplexItemReader.h"

#include "link/json/JsonPosition.h"

#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QLocale>

#include <algorithm>
#include <cmath>
#include <limits>

namespace {

constexpr double kDegreeSteps = MissionPlan::kDegreeSteps;
constexpr double kMillimetres = MissionPlan::kMillimetres;
constexpr int kPlanVersion = 1;
constexpr int kMissionVersion = 2;
constexpr int kGeoFenceVersion = 2;
constexpr int kRallyPointsVersion = 2;
// A plan does not say which autopilot flies it: MAV_AUTOPILOT_GENERIC. The
// aircraft this console commands have engines, flaps and landing gear:
// MAV_TYPE_FIXED_WING. The speeds are QGroundControl's own defaults; it uses
// them only to estimate flight times.
constexpr int kFirmwareType = 0;
constexpr int kVehicleType = 1;
constexpr double kCruiseSpeed = 15;
constexpr double kHoverSpeed = 5;
// QGroundControl requires "groundStation" to be a string and nothing more.
const char* const kGroundStation = "RCM ground control station";
// The largest radius the plan bytes hold: a uint32 of millimetres.
constexpr double kMaxRadius = 4294967.295;

QString number(double value)
{
    return QString::number(value, 'g', QLocale::FloatingPointShortest);
}

// What is wrong with a position, or nothing.
QString positionProblem(double latitude, double longitude)
{
    if (std::abs(latitude) > 90)
        return QStringLiteral("latitude %1 is outside \u00b190").arg(number(latitude));
    if (std::abs(longitude) > 180)
        return QStringLiteral("longitude %1 is outside \u00b1180").arg(number(longitude));
    return {};
}

bool isNumberOrNull(const QJsonValue& v)
{
    return v.isDouble() || v.isNull();
}

std::optional<double> given(const QJsonValue& v)
{
    return v.isDouble() ? std::optional<double>(v.toDouble()) : std::nullopt;
}

QString shown(const QJsonValue& v)
{
    return v.isString() ? v.toString() : number(v.toDouble());
}

// Finds where a value starts in a JSON text that QJsonDocument accepted, to
// say on which line an element the reader refuses starts. QJsonDocument
// keeps no positions, so this walks the text again, only for an error.
class JsonScanner {
public:
    explicit JsonScanner(const QByteArray& text) : m_text(text) {}

    // Byte offset of the value at `path` (object keys, and array indices in
    // decimal), or -1.
    qsizetype offsetOf(const QStringList& path)
    {
        m_pos = 0;
        return descend(path, 0);
    }

private:
    qsizetype descend(const QStringList& path, qsizetype depth)
    {
        skipSpace();
        if (depth == path.size())
            return m_pos;
        if (peek() == '{')
            return descendObject(path, depth);
        if (peek() == '[')
            return descendArray(path, depth);
        return -1;
    }

    qsizetype descendObject(const QStringList& path, qsizetype depth)
    {
        ++m_pos;
        for (;;) {
            skipSpace();
            if (peek() != '"')
                return -1;
            const QByteArray key = readString();
            skipSpace();
            if (peek() != ':')
                return -1;
            ++m_pos;
            if (QString::fromUtf8(key) == path[depth])
                return descend(path, depth + 1);
            if (!skipValueAndComma())
                return -1;
        }
    }

    qsizetype descendArray(const QStringList& path, qsizetype depth)
    {
        bool ok = false;
        const int index = path[depth].toInt(&ok);
        if (!ok)
            return -1;
        ++m_pos;
        for (int i = 0;; ++i) {
            skipSpace();
            if (peek() == ']')
                return -1;
            if (i == index)
                return descend(path, depth + 1);
            if (!skipValueAndComma())
                return -1;
        }
    }

    char peek() const { return m_pos < m_text.size() ? m_text[m_pos] : '\0'; }

    void skipSpace()
    {
        while (m_pos < m_text.size() && std::isspace(static_cast<unsigned char>(m_text[m_pos])))
            ++m_pos;
    }

    // The bytes between the quotes, escapes as written: the keys of a plan
    // need none.
    QByteArray readString()
    {
        const qsizetype start = ++m_pos;
        while (m_pos < m_text.size() && m_text[m_pos] != '"')
            m_pos += m_text[m_pos] == '\\' ? 2 : 1;
        const QByteArray text = m_text.mid(start, m_pos - start);
        ++m_pos;
        return text;
    }

    void skipValue()
    {
        skipSpace();
        if (peek() == '"') {
            readString();
        } else if (peek() == '{' || peek() == '[') {
            int depth = 0;
            while (m_pos < m_text.size()) {
                const char c = m_text[m_pos];
                if (c == '"') {
                    readString();
                    continue;
                }
                ++m_pos;
                if (c == '{' || c == '[')
                    ++depth;
                else if ((c == '}' || c == ']') && --depth == 0)
                    return;
            }
        } else {
            while (m_pos < m_text.size() && !QByteArrayView(",}] \t\r\n").contains(m_text[m_pos]))
                ++m_pos;
        }
    }

    bool skipValueAndComma()
    {
        skipValue();
        skipSpace();
        if (peek() != ',')
            return false;
        ++m_pos;
        return true;
    }

    const QByteArray& m_text;
    qsizetype m_pos = 0;
};

class PlanReader {
public:
    PlanReader(const QByteArray& json, const QString& source) : m_json(json), m_source(source) {}

    std::optional<MissionPlan> read()
    {
        QJsonParseError parseError;
        const QJsonDocument doc = QJsonDocument::fromJson(m_json, &parseError);
        if (parseError.error != QJsonParseError::NoError) {
            m_error = QStringLiteral("%1: %2: %3")
                          .arg(m_source, jsonPosition(m_json, parseError.offset), parseError.errorString());
            return std::nullopt;
        }
        const QJsonObject root = doc.object();
        const QJsonValue fileType = root.value(QStringLiteral("fileType"));
        MissionPlan plan;
        // A .mission file: the mission object is the whole file.
        if (fileType == QLatin1String("Mission") ||
            (fileType.isUndefined() && root.contains(QStringLiteral("items")))) {
            if (!readMission(root, {}, plan))
                return std::nullopt;
            return plan;
        }
        if (fileType.toString() != QLatin1String("Plan")) {
            fail({}, QStringLiteral("not a QGroundControl plan (its \"fileType\" is not \"Plan\")"));
            return std::nullopt;
        }
        const QJsonValue version = root.value(QStringLiteral("version"));
        if (!version.isUndefined() && version != kPlanVersion) {
            fail({QStringLiteral("version")}, QStringLiteral("plan file version %1; this console reads version %2")
                                                  .arg(shown(version))
                                                  .arg(kPlanVersion));
            return std::nullopt;
        }
        const QJsonObject mission = root.value(QStringLiteral("mission")).toObject();
        if (!mission.value(QStringLiteral("items")).isArray()) {
            fail({}, QStringLiteral("the plan has no \"mission\" with \"items\""));
            return std::nullopt;
        }
        if (!readMission(mission, {QStringLiteral("mission")}, plan) ||
            !readGeoFence(root.value(QStringLiteral("geoFence")), plan) ||
            !readRallyPoints(root.value(QStringLiteral("rallyPoints")), plan))
            return std::nullopt;
        return plan;
    }

    const QString& error() const { return m_error; }

private:
    // Sets the error for the element at `path`; always false.
    bool fail(const QStringList& path, const QString& what)
    {
        m_error = QStringLiteral("%1: %2%3").arg(m_source, linePrefix(path), what);
        return false;
    }

    QString linePrefix(const QStringList& path) const
    {
        if (path.isEmpty())
            return {};
        const qsizetype offset = JsonScanner(m_json).offsetOf(path);
        if (offset < 0)
            return {};
        const int line = jsonLineColumn(m_json, int(offset)).line;
        return line > 1 ? QStringLiteral("line %1: ").arg(line) : QString();
    }

    bool readMission(const QJsonObject& mission, const QStringList& path, MissionPlan& plan)
    {
        const QJsonValue itemsValue = mission.value(QStringLiteral("items"));
        if (!itemsValue.isArray())
            return fail({}, QStringLiteral("the mission has no \"items\""));
        const QJsonValue version = mission.value(QStringLiteral("version"));
        if (!version.isUndefined() && version != kMissionVersion)
            return fail(path + QStringList{QStringLiteral("version")},
                        QStringLiteral("the mission is in version %1 of QGroundControl's layout; this console reads "
                                       "version %2 (QGroundControl 3.2 and later): open it in QGroundControl and save "
                                       "it again")
                            .arg(shown(version))
                            .arg(kMissionVersion));
        const QJsonArray items = itemsValue.toArray();
        if (items.size() > std::numeric_limits<quint16>::max())
            return fail({}, QStringLiteral("%1 mission items; a plan holds at most 65535").arg(items.size()));
        const QString homeKey = QStringLiteral("plannedHomePosition");
        if (mission.contains(homeKey) && !readHome(mission.value(homeKey), path + QStringList{homeKey}, plan))
            return false;
        const QStringList itemsPath = path + QStringList{QStringLiteral("items")};
        QgcComplexItemReader complex([this](const QStringList& at, const QString& what) { return fail(at, what); },
                                     [this](const QJsonValue& value, const QString& where, const QStringList& at,
                                            MissionItem& item) { return readItem(value, where, at, item); });
        for (qsizetype i = 0; i < items.size(); ++i) {
            const QString where = QStringLiteral("mission item %1").arg(i + 1);
            const QStringList itemPath = itemsPath + QStringList{QString::number(i)};
            if (items[i].toObject().value(QStringLiteral("type")) == QLatin1String("ComplexItem")) {
                if (!complex.read(items[i].toObject(), where, itemPath, plan.items))
                    return false;
            } else {
                MissionItem item;
                if (!readItem(items[i], where, itemPath, item))
                    return false;
                plan.items.append(item);
            }
            if (plan.items.size() > std::numeric_limits<quint16>::max())
                return fail(itemPath, QStringLiteral("%1 makes the mission more than 65535 items, the most a plan "
                                                     "holds")
                                          .arg(where));
        }
        plan.renumber();
        return true;
    }

    bool readHome(const QJsonValue& value, const QStringList& path, MissionPlan& plan)
    {
        const QJsonArray home = value.toArray();
        if (!value.isArray() || home.size() != 3 || !isNumberOrNull(home[0]) || !isNumberOrNull(home[1]) ||
            !isNumberOrNull(home[2]))
            return fail(path, QStringLiteral("planned home position must be [latitude, longitude, altitude]"));
        plan.homeLatitude = given(home[0]);
        plan.homeLongitude = given(home[1]);
        plan.homeAltitude = given(home[2]);
        const QString problem = positionProblem(plan.homeLatitude.value_or(0), plan.homeLongitude.value_or(0));
        if (!problem.isEmpty())
            return fail(path, QStringLiteral("planned home position: ") + problem);
        if (plan.homeAltitude && !MissionPlan::fitsField(*plan.homeAltitude, kMillimetres))
            return fail(path, QStringLiteral("planned home position: altitude %1 m is out of the range the plan "
                                             "bytes hold")
                                  .arg(number(*plan.homeAltitude)));
        return true;
    }

    // The 7 parameters of an item in any of QGroundControl's three styles.
    bool readParams(const QJsonObject& o, const QString& where, const QStringList& path, QJsonArray& params)
    {
        if (o.contains(QStringLiteral("params"))) {
            if (!o.value(QStringLiteral("params")).isArray())
                return fail(path, QStringLiteral("%1: \"params\" must be an array").arg(where));
            params = o.value(QStringLiteral("params")).toArray();
        } else {
            if (!o.contains(QStringLiteral("param1")))
                return fail(path, QStringLiteral("%1 has neither \"params\" nor \"param1\"..\"param4\"").arg(where));
            for (int p = 1; p <= 4; ++p) {
                const QJsonValue v = o.value(QStringLiteral("param%1").arg(p));
                if (!isNumberOrNull(v))
                    return fail(path, QStringLiteral("%1: \"param%2\" must be a number or null").arg(where).arg(p));
                params.append(v);
            }
        }
        if (!o.contains(QStringLiteral("coordinate")))
            return true;
        const QJsonArray coordinate = o.value(QStringLiteral("coordinate")).toArray();
        if (coordinate.size() != 3 || !isNumberOrNull(coordinate[0]) || !isNumberOrNull(coordinate[1]) ||
            !isNumberOrNull(coordinate[2]))
            return fail(path, QStringLiteral("%1: \"coordinate\" must be [latitude, longitude, altitude]").arg(where));
        if (params.size() != 4)
            return fail(path, QStringLiteral("%1 has a \"coordinate\", so \"params\" must hold 4 values (numbers or "
                                             "null), not %2")
                                  .arg(where)
                                  .arg(params.size()));
        for (const QJsonValue& v : coordinate)
            params.append(v);
        return true;
    }

    // One simple item; a complex item's are read by QgcComplexItemReader.
    bool readItem(const QJsonValue& value, const QString& where, const QStringList& path, MissionItem& item)
    {
        if (!value.isObject())
            return fail(path, QStringLiteral("%1 is not a JSON object").arg(where));
        const QJsonObject o = value.toObject();
        const QString type = o.value(QStringLiteral("type")).toString();
        // "missionItem": the first style's name for a simple item.
        if (type != QLatin1String("SimpleItem") && type != QLatin1String("missionItem"))
            return fail(path, QStringLiteral("%1 has type \"%2\", not SimpleItem").arg(where, type));
        const QJsonValue command = o.value(QStringLiteral("command"));
        const QJsonValue frame = o.value(QStringLiteral("frame"));
        if (!command.isDouble() || command.toInt(-1) < 0 || command.toInt(-1) > 65535)
            return fail(path, QStringLiteral("%1: \"command\" must be a MAV_CMD number 0..65535").arg(where));
        if (!frame.isDouble() || frame.toInt(-1) < 0 || frame.toInt(-1) > 255)
            return fail(path, QStringLiteral("%1: \"frame\" must be a MAV_FRAME number 0..255").arg(where));
        QJsonArray params;
        if (!readParams(o, where, path, params))
            return false;
        if (params.size() != 7)
            return fail(path, QStringLiteral("%1: \"params\" must hold 7 values (numbers or null)").arg(where));

        item.command = quint16(command.toInt());
        item.frame = quint8(frame.toInt());
        item.autoContinue = o.value(QStringLiteral("autoContinue")).toBool(true);
        for (int p = 0; p < 7; ++p) {
            if (!isNumberOrNull(params[p]))
                return fail(path, QStringLiteral("%1: param%2 must be a number or null").arg(where).arg(p + 1));
        }
        for (int p = 0; p < 4; ++p) {
            const double v = params[p].isNull() ? std::nan("") : params[p].toDouble();
            if (std::isfinite(v) && std::abs(v) > double(std::numeric_limits<float>::max()))
                return fail(path, QStringLiteral("%1: param%2 does not fit a 32-bit float").arg(where).arg(p + 1));
            item.params[std::size_t(p)] = v;
        }
        item.latitude = given(params[4]);
        item.longitude = given(params[5]);
        item.altitude = given(params[6]);
        if (MissionItem::isGlobalFrame(item.frame) &&
            !positionProblem(item.latitude.value_or(0), item.longitude.value_or(0)).isEmpty())
            return fail(
                path, QStringLiteral("%1: latitude must be within +-90 and longitude within +-180 degrees").arg(where));
        if ((item.latitude && !MissionPlan::fitsField(*item.latitude, kDegreeSteps)) ||
            (item.longitude && !MissionPlan::fitsField(*item.longitude, kDegreeSteps)) ||
            (item.altitude && !MissionPlan::fitsField(*item.altitude, kMillimetres)))
            return fail(path, QStringLiteral("%1: param5..param7 out of the range the plan bytes hold").arg(where));
        return true;
    }

    // QGroundControl skips version 1 of the geofence and of the rally points,
    // and those with no version; skipping them here too would lose what they
    // hold without a word.
    bool refuseOldVersion(const QJsonObject& o, const QString& what, const QStringList& path)
    {
        for (auto it = o.begin(); it != o.end(); ++it) {
            if (it.value().isArray() && !it.value().toArray().isEmpty())
                return fail(path, QStringLiteral("the %1 is in QGroundControl's version 1 layout, which neither "
                                                 "QGroundControl nor this console reads any more; draw it again in "
                                                 "QGroundControl and save the plan")
                                      .arg(what));
        }
        return true;
    }

    // A versioned section of the plan ("geoFence", "rallyPoints") before its
    // contents are read: the object to read them from; or none, with `done`
    // what reading the section comes to (true: absent, or an old layout with
    // nothing in it; false: refused).
    struct Section {
        std::optional<QJsonObject> object;
        bool done = true;
    };

    // currentKeys: the keys that tell the current layout where "version" is
    // left out, as programs other than QGroundControl may; oldName and
    // versionName: what the refusals call the section.
    Section openSection(const QJsonValue& value, const QString& key, const QStringList& currentKeys,
                        const QString& oldName, const QString& versionName, int currentVersion)
    {
        const QStringList path{key};
        if (value.isUndefined())
            return {};
        if (!value.isObject())
            return {std::nullopt, fail(path, QStringLiteral("\"%1\" must be an object").arg(key))};
        const QJsonObject o = value.toObject();
        const QJsonValue version = o.value(QStringLiteral("version"));
        const bool current =
            std::any_of(currentKeys.begin(), currentKeys.end(), [&](const QString& k) { return o.contains(k); });
        if (version == 1 || (version.isUndefined() && !current))
            return {std::nullopt, refuseOldVersion(o, oldName, path)};
        if (!version.isUndefined() && version != currentVersion)
            return {std::nullopt, fail(path + QStringList{QStringLiteral("version")},
                                       QStringLiteral("%1 version %2; this console reads version %3")
                                           .arg(versionName, shown(version), QString::number(currentVersion)))};
        return {o};
    }

    bool readGeoFence(const QJsonValue& value, MissionPlan& plan)
    {
        const QStringList path{QStringLiteral("geoFence")};
        const Section section = openSection(value, path[0], {QStringLiteral("polygons"), QStringLiteral("circles")},
                                            QStringLiteral("geofence"), QStringLiteral("geofence"), kGeoFenceVersion);
        if (!section.object)
            return section.done;
        const QJsonObject& fence = *section.object;
        const QJsonValue polygons = fence.value(QStringLiteral("polygons"));
        const QJsonValue circles = fence.value(QStringLiteral("circles"));
        if (!polygons.isUndefined() && !polygons.isArray())
            return fail(path, QStringLiteral("geofence \"polygons\" must be an array"));
        if (!circles.isUndefined() && !circles.isArray())
            return fail(path, QStringLiteral("geofence \"circles\" must be an array"));
        return readFenceList(polygons.toArray(), QStringLiteral("polygon"), path, plan.fencePolygons,
                             &PlanReader::readPolygon) &&
               readFenceList(circles.toArray(), QStringLiteral("circle"), path, plan.fenceCircles,
                             &PlanReader::readCircle);
    }

    // Each entry of a fence's "polygons" or "circles" read by readOne and
    // appended to `into`; false at the first refused.
    template <typename Shape>
    bool readFenceList(const QJsonArray& entries, const QString& noun, const QStringList& path, QList<Shape>& into,
                       bool (PlanReader::*readOne)(const QJsonValue&, const QString&, const QStringList&, Shape&))
    {
        const QString key = noun + QLatin1Char('s');
        for (qsizetype i = 0; i < entries.size(); ++i) {
            Shape shape;
            if (!(this->*readOne)(entries[i], QStringLiteral("geofence %1 %2").arg(noun, QString::number(i + 1)),
                                  path + QStringList{key, QString::number(i)}, shape))
                return false;
            into.append(shape);
        }
        return true;
    }

    // A fence polygon's or circle's object: its "inclusion" read, and what
    // its shape's key ("polygon", "circle") holds; nothing when refused.
    std::optional<QJsonValue> readFenceShape(const QJsonValue& value, const QString& key, const QString& where,
                                             const QStringList& path, bool& inclusion)
    {
        if (!value.isObject()) {
            fail(path, QStringLiteral("%1 is not a JSON object").arg(where));
            return std::nullopt;
        }
        const QJsonObject o = value.toObject();
        if (!readInclusion(o, where, path, inclusion))
            return std::nullopt;
        return o.value(key);
    }

    bool readInclusion(const QJsonObject& o, const QString& where, const QStringList& path, bool& inclusion)
    {
        const QJsonValue v = o.value(QStringLiteral("inclusion"));
        if (!v.isBool())
            return fail(path, QStringLiteral("%1: \"inclusion\" must be true or false").arg(where));
        inclusion = v.toBool();
        return true;
    }

    bool readLatLon(const QJsonValue& value, const QString& where, const QStringList& path, GeoPoint& point)
    {
        const QJsonArray a = value.toArray();
        if (a.size() != 2 || !a[0].isDouble() || !a[1].isDouble())
            return fail(path, QStringLiteral("%1 must be [latitude, longitude]").arg(where));
        point = {a[0].toDouble(), a[1].toDouble()};
        const QString problem = positionProblem(point.latitude, point.longitude);
        return problem.isEmpty() || fail(path, QStringLiteral("%1: %2").arg(where, problem));
    }

    bool readPolygon(const QJsonValue& value, const QString& where, const QStringList& path, FencePolygon& polygon)
    {
        const std::optional<QJsonValue> verticesValue =
            readFenceShape(value, QStringLiteral("polygon"), where, path, polygon.inclusion);
        if (!verticesValue)
            return false;
        if (!verticesValue->isArray())
            return fail(path, QStringLiteral("%1: \"polygon\" must be an array of [latitude, longitude]").arg(where));
        const QStringList verticesPath = path + QStringList{QStringLiteral("polygon")};
        const QJsonArray vertices = verticesValue->toArray();
        if (vertices.size() < 3)
            return fail(
                verticesPath,
                QStringLiteral("%1 has %2 vertices; a polygon needs at least 3").arg(where).arg(vertices.size()));
        for (qsizetype v = 0; v < vertices.size(); ++v) {
            GeoPoint point;
            if (!readLatLon(vertices[v], QStringLiteral("%1, vertex %2").arg(where).arg(v + 1),
                            verticesPath + QStringList{QString::number(v)}, point))
                return false;
            polygon.vertices.append(point);
        }
        return true;
    }

    bool readCircle(const QJsonValue& value, const QString& where, const QStringList& path, FenceCircle& circle)
    {
        const std::optional<QJsonValue> shapeValue =
            readFenceShape(value, QStringLiteral("circle"), where, path, circle.inclusion);
        if (!shapeValue)
            return false;
        const QJsonObject shape = shapeValue->toObject();
        const QStringList shapePath = path + QStringList{QStringLiteral("circle")};
        if (!readLatLon(shape.value(QStringLiteral("center")), where + QStringLiteral(" centre"),
                        shapePath + QStringList{QStringLiteral("center")}, circle.centre))
            return false;
        const QJsonValue radius = shape.value(QStringLiteral("radius"));
        const QStringList radiusPath = shapePath + QStringList{QStringLiteral("radius")};
        if (!radius.isDouble())
            return fail(shapePath, QStringLiteral("%1: \"radius\" must be a number of metres").arg(where));
        circle.radius = radius.toDouble();
        if (!(circle.radius > 0))
            return fail(radiusPath,
                        QStringLiteral("%1: radius %2 m is not more than 0").arg(where, number(circle.radius)));
        if (circle.radius > kMaxRadius)
            return fail(radiusPath, QStringLiteral("%1: radius %2 m is more than the 4294 km a plan holds")
                                        .arg(where, number(circle.radius)));
        return true;
    }

    bool readRallyPoints(const QJsonValue& value, MissionPlan& plan)
    {
        const QStringList path{QStringLiteral("rallyPoints")};
        const Section section =
            openSection(value, path[0], {QStringLiteral("points")}, QStringLiteral("rally point list"),
                        QStringLiteral("rally points"), kRallyPointsVersion);
        if (!section.object)
            return section.done;
        const QJsonObject& rally = *section.object;
        const QJsonValue pointsValue = rally.value(QStringLiteral("points"));
        if (!pointsValue.isUndefined() && !pointsValue.isArray())
            return fail(path, QStringLiteral("rally \"points\" must be an array"));
        const QJsonArray points = pointsValue.toArray();
        for (qsizetype i = 0; i < points.size(); ++i) {
            const QString where = QStringLiteral("rally point %1").arg(i + 1);
            const QStringList pointPath = path + QStringList{QStringLiteral("points"), QString::number(i)};
            const QJsonArray a = points[i].toArray();
            if (a.size() != 3 || !a[0].isDouble() || !a[1].isDouble() || !a[2].isDouble())
                return fail(pointPath, QStringLiteral("%1 must be [latitude, longitude, altitude]").arg(where));
            RallyPoint point{{a[0].toDouble(), a[1].toDouble()}, a[2].toDouble()};
            const QString problem = positionProblem(point.position.latitude, point.position.longitude);
            if (!problem.isEmpty())
                return fail(pointPath, QStringLiteral("%1: %2").arg(where, problem));
            if (!MissionPlan::fitsField(point.altitude, kMillimetres))
                return fail(pointPath, QStringLiteral("%1: altitude %2 m is out of the range the plan bytes hold")
                                           .arg(where, number(point.altitude)));
            plan.rallyPoints.append(point);
        }
        return true;
    }

    const QByteArray& m_json;
    const QString& m_source;
    QString m_error;
};

QJsonValue jsonNumber(double value)
{
    // JSON has no NaN or infinity; QGroundControl reads null as NaN.
    return std::isfinite(value) ? QJsonValue(value) : QJsonValue(QJsonValue::Null);
}

QJsonValue jsonNumber(const std::optional<double>& value)
{
    return value ? jsonNumber(*value) : QJsonValue(QJsonValue::Null);
}

QJsonArray latLon(const GeoPoint& point)
{
    return {point.latitude, point.longitude};
}

QJsonObject missionObject(const MissionPlan& plan)
{
    QJsonArray items;
    for (qsizetype i = 0; i < plan.items.size(); ++i) {
        const MissionItem& item = plan.items[i];
        QJsonArray params;
        for (double p : item.params)
            params.append(jsonNumber(p));
        params.append(jsonNumber(item.latitude));
        params.append(jsonNumber(item.longitude));
        params.append(jsonNumber(item.altitude));
        items.append(QJsonObject{
            {QStringLiteral("autoContinue"), item.autoContinue},
            {QStringLiteral("command"), int(item.command)},
            // QGroundControl numbers the items from 1: home is 0.
            {QStringLiteral("doJumpId"), int(i + 1)},
            {QStringLiteral("frame"), int(item.frame)},
            {QStringLiteral("params"), params},
            {QStringLiteral("type"), QStringLiteral("SimpleItem")},
        });
    }
    return {
        {QStringLiteral("cruiseSpeed"), kCruiseSpeed},
        {QStringLiteral("firmwareType"), kFirmwareType},
        {QStringLiteral("hoverSpeed"), kHoverSpeed},
        {QStringLiteral("items"), items},
        {QStringLiteral("plannedHomePosition"),
         QJsonArray{jsonNumber(plan.homeLatitude), jsonNumber(plan.homeLongitude), jsonNumber(plan.homeAltitude)}},
        {QStringLiteral("vehicleType"), kVehicleType},
        {QStringLiteral("version"), kMissionVersion},
    };
}

QJsonObject geoFenceObject(const MissionPlan& plan)
{
    QJsonArray polygons;
    for (const FencePolygon& polygon : plan.fencePolygons) {
        QJsonArray vertices;
        for (const GeoPoint& vertex : polygon.vertices)
            vertices.append(latLon(vertex));
        polygons.append(QJsonObject{
            {QStringLiteral("inclusion"), polygon.inclusion},
            {QStringLiteral("polygon"), vertices},
            {QStringLiteral("version"), 1},
        });
    }
    QJsonArray circles;
    for (const FenceCircle& circle : plan.fenceCircles) {
        circles.append(QJsonObject{
            {QStringLiteral("circle"),
             QJsonObject{{QStringLiteral("center"), latLon(circle.centre)}, {QStringLiteral("radius"), circle.radius}}},
            {QStringLiteral("inclusion"), circle.inclusion},
            {QStringLiteral("version"), 1},
        });
    }
    return {
        {QStringLiteral("circles"), circles},
        {QStringLiteral("polygons"), polygons},
        {QStringLiteral("version"), kGeoFenceVersion},
    };
}

QJsonObject rallyPointsObject(const MissionPlan& plan)
{
    QJsonArray points;
    for (const RallyPoint& point : plan.rallyPoints)
        points.append(QJsonArray{point.position.latitude, point.position.longitude, point.altitude});
    return {
        {QStringLiteral("points"), points},
        {QStringLiteral("version"), kRallyPointsVersion},
    };
}

}  // namespace

namespace QgcPlanFile {

std::optional<MissionPlan> read(const QByteArray& json, const QString& source, QString* error)
{
    PlanReader reader(json, source);
    return PlanReading::outcome(reader, reader.read(), error);
}

QByteArray write(const MissionPlan& plan)
{
    const QJsonObject root{
        {QStringLiteral("fileType"), QStringLiteral("Plan")},
        {QStringLiteral("geoFence"), geoFenceObject(plan)},
        {QStringLiteral("groundStation"), QLatin1String(kGroundStation)},
        {QStringLiteral("mission"), missionObject(plan)},
        {QStringLiteral("rallyPoints"), rallyPointsObject(plan)},
        {QStringLiteral("version"), kPlanVersion},
    };
    return QJsonDocument(root).toJson(QJsonDocument::Indented);
}

}  // namespace QgcPlanFile
