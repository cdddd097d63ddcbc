#include "link/plan/QgcComplexItemReader.h"

#include <QJsonArray>
#include <QLineF>
#include <QLocale>

#include <cmath>
#include <limits>
#include <numbers>

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// MAV_FRAME
constexpr quint8 kGlobal = 0;
constexpr quint8 kMission = 2;
constexpr quint8 kRelative = 3;
// MAV_CMD
constexpr quint16 kWaypoint = 16;
constexpr quint16 kLand = 21;
constexpr quint16 kLoiterToAltitude = 31;
constexpr quint16 kVtolLand = 85;
constexpr quint16 kLandStart = 189;
constexpr quint16 kRoiNextWaypointOffset = 196;
constexpr quint16 kRoiNone = 197;
constexpr quint16 kCameraTriggerDistance = 206;
constexpr quint16 kImageStopCapture = 2001;
constexpr quint16 kVideoStopCapture = 2501;
// QGroundControl 4's plane for polygon offsets: azimuthal equidistant about
// the first vertex on a sphere of this radius (QGCGeo convertGeoToNed).
constexpr double kEquatorialRadius = 6378137.0;

const QString kFixedWingLanding = QStringLiteral("fwLandingPattern");
const QString kVtolLanding = QStringLiteral("vtolLandingPattern");
const QString kSurvey = QStringLiteral("survey");
const QString kCorridorScan = QStringLiteral("CorridorScan");
const QString kStructureScan = QStringLiteral("StructureScan");

QString number(double value)
{
    return QString::number(value, 'g', QLocale::FloatingPointShortest);
}

MissionItem missionItem(quint16 command, quint8 frame, std::array<double, 4> params, std::optional<double> x,
                        std::optional<double> y, std::optional<double> z)
{
    MissionItem item;
    item.command = command;
    item.frame = frame;
    item.params = params;
    item.latitude = x;
    item.longitude = y;
    item.altitude = z;
    return item;
}

// A mission-frame command whose param5..7 are all 0, as QGroundControl writes them.
MissionItem zeroFrameItem(quint16 command, std::array<double, 4> params)
{
    return missionItem(command, kMission, params, 0.0, 0.0, 0.0);
}

// A command whose param2..7 are unused: NaN, which a .plan writes as null.
MissionItem stopCaptureItem(quint16 command)
{
    return missionItem(command, kMission, {0, kNaN, kNaN, kNaN}, std::nullopt, std::nullopt, std::nullopt);
}

MissionItem waypoint(quint8 frame, const GeoPoint& at, double altitude)
{
    return missionItem(kWaypoint, frame, {0, 0, 0, kNaN}, at.latitude, at.longitude, altitude);
}

double radians(double degrees)
{
    return degrees * (std::numbers::pi / 180.0);
}

double degrees(double radians)
{
    return radians * (180.0 / std::numbers::pi);
}

// North and east metres of `point` from `origin` in QGroundControl 4's
// plane, as a QPointF(east, north): the axes its polygon offset works in.
QPointF toPlane(const GeoPoint& point, const GeoPoint& origin)
{
    if (point == origin)
        return {0, 0};
    const double lat = radians(point.latitude);
    const double lon = radians(point.longitude);
    const double originLat = radians(origin.latitude);
    const double originLon = radians(origin.longitude);
    const double cosDLon = std::cos(lon - originLon);
    const double c = std::acos(
        std::clamp(std::sin(originLat) * std::sin(lat) + std::cos(originLat) * std::cos(lat) * cosDLon, -1.0, 1.0));
    const double k = std::abs(c) < std::numeric_limits<double>::epsilon() ? 1.0 : c / std::sin(c);
    const double north =
        k * (std::cos(originLat) * std::sin(lat) - std::sin(originLat) * std::cos(lat) * cosDLon) * kEquatorialRadius;
    const double east = k * std::cos(lat) * std::sin(lon - originLon) * kEquatorialRadius;
    return {east, north};
}

GeoPoint fromPlane(const QPointF& eastNorth, const GeoPoint& origin)
{
    const double x = eastNorth.y() / kEquatorialRadius;
    const double y = eastNorth.x() / kEquatorialRadius;
    const double c = std::sqrt(x * x + y * y);
    const double originLat = radians(origin.latitude);
    const double originLon = radians(origin.longitude);
    if (std::abs(c) <= std::numeric_limits<double>::epsilon())
        return origin;
    const double lat = std::asin(std::cos(c) * std::sin(originLat) + x * std::sin(c) * std::cos(originLat) / c);
    const double lon = originLon + std::atan2(y * std::sin(c), c * std::cos(originLat) * std::cos(c) -
                                                                   x * std::sin(originLat) * std::sin(c));
    return {degrees(lat), degrees(lon)};
}

// QGroundControl's QGCMapPolygon::offset: each edge moved `distance` to its
// side (outward for a polygon drawn clockwise, as QGroundControl draws
// them), the new vertices where neighbouring moved edges meet. Nothing when
// two neighbouring edges are parallel (a vertex in line with its
// neighbours), which QGroundControl does not offset at all.
std::optional<QList<GeoPoint>> offsetPolygon(const QList<GeoPoint>& polygon, double distance, int* inLine)
{
    const GeoPoint origin = polygon.front();
    QList<QPointF> plane;
    for (const GeoPoint& vertex : polygon)
        plane.append(toPlane(vertex, origin));
    QList<QLineF> edges;
    for (qsizetype i = 0; i < plane.size(); ++i) {
        const QLineF edge(plane[i], plane[(i + 1) % plane.size()]);
        QLineF worker = edge;
        worker.setLength(distance);
        worker.setAngle(worker.angle() - 90.0);
        QLineF moved;
        moved.setP1(worker.p2());
        worker.setPoints(edge.p2(), edge.p1());
        worker.setLength(distance);
        worker.setAngle(worker.angle() + 90.0);
        moved.setP2(worker.p2());
        edges.append(moved);
    }
    QList<GeoPoint> result;
    for (qsizetype i = 0; i < edges.size(); ++i) {
        QPointF vertex;
        if (edges[i == 0 ? edges.size() - 1 : i - 1].intersects(edges[i], &vertex) == QLineF::NoIntersection) {
            *inLine = int(i);
            return std::nullopt;
        }
        result.append(fromPlane(vertex, origin));
    }
    return result;
}

}  // namespace

QgcComplexItemReader::QgcComplexItemReader(Fail fail, ReadSimpleItem readSimpleItem)
    : m_fail(std::move(fail)), m_readSimpleItem(std::move(readSimpleItem))
{
}

QString QgcComplexItemReader::kindName(const QString& type)
{
    if (type == kFixedWingLanding)
        return QStringLiteral("fixed-wing landing pattern");
    if (type == kVtolLanding)
        return QStringLiteral("VTOL landing pattern");
    if (type == kSurvey)
        return QStringLiteral("survey");
    if (type == kCorridorScan)
        return QStringLiteral("corridor scan");
    if (type == kStructureScan)
        return QStringLiteral("structure scan");
    return type;
}

bool QgcComplexItemReader::read(const QJsonObject& item, const QString& where, const QStringList& path,
                                QList<MissionItem>& out)
{
    const QString type = item.value(QStringLiteral("complexItemType")).toString();
    const QString named = QStringLiteral("%1 (a %2)").arg(where, kindName(type));
    if (type == kFixedWingLanding || type == kVtolLanding)
        return readLanding(item, type == kVtolLanding, named, path, out);
    if (type == kSurvey || type == kCorridorScan)
        return readTransectStyle(item, named, path, out);
    if (type == kStructureScan)
        return readStructureScan(item, named, path, out);
    if (type.isEmpty())
        return m_fail(path, QStringLiteral("%1 is a ComplexItem without a \"complexItemType\"").arg(where));
    return m_fail(path, QStringLiteral("%1 is a complex item of type \"%2\", which this console does not read (it "
                                       "reads fwLandingPattern, vtolLandingPattern, survey, CorridorScan and "
                                       "StructureScan)")
                            .arg(where, type));
}

bool QgcComplexItemReader::readNumber(const QJsonObject& object, const QString& key, const QString& where,
                                      const QStringList& path, double& value)
{
    const QJsonValue v = object.value(key);
    if (!v.isDouble())
        return m_fail(v.isUndefined() ? path : path + QStringList{key},
                      QStringLiteral("%1: \"%2\" must be a number").arg(where, key));
    value = v.toDouble();
    return true;
}

bool QgcComplexItemReader::readBool(const QJsonObject& object, const QString& key, const QString& where,
                                    const QStringList& path, bool& value, std::optional<bool> byDefault)
{
    const QJsonValue v = object.value(key);
    if (v.isUndefined() && byDefault) {
        value = *byDefault;
        return true;
    }
    if (!v.isBool())
        return m_fail(v.isUndefined() ? path : path + QStringList{key},
                      QStringLiteral("%1: \"%2\" must be true or false").arg(where, key));
    value = v.toBool();
    return true;
}

bool QgcComplexItemReader::readCoordinate(const QJsonObject& item, const QString& key, bool withAltitude,
                                          const QString& where, const QStringList& path, GeoPoint& point,
                                          double* altitude)
{
    const QJsonArray a = item.value(key).toArray();
    const qsizetype size = withAltitude ? 3 : 2;
    bool numbers = a.size() == size;
    for (const QJsonValue& v : a)
        numbers = numbers && v.isDouble();
    const QStringList at = item.contains(key) ? path + QStringList{key} : path;
    if (!numbers)
        return m_fail(at, QStringLiteral("%1: \"%2\" must be [latitude, longitude%3]")
                              .arg(where, key, withAltitude ? QStringLiteral(", altitude") : QString()));
    point = {a[0].toDouble(), a[1].toDouble()};
    if (std::abs(point.latitude) > 90 || std::abs(point.longitude) > 180)
        return m_fail(at, QStringLiteral("%1: \"%2\": latitude must be within \u00b190 and longitude within "
                                         "\u00b1180 degrees")
                              .arg(where, key));
    if (altitude) {
        *altitude = a[2].toDouble();
        if (!MissionPlan::fitsField(*altitude, MissionPlan::kMillimetres))
            return m_fail(at, QStringLiteral("%1: \"%2\": altitude %3 m is out of the range the plan bytes hold")
                                  .arg(where, key, number(*altitude)));
    }
    return true;
}

bool QgcComplexItemReader::readLanding(const QJsonObject& item, bool vtol, const QString& where,
                                       const QStringList& path, QList<MissionItem>& out)
{
    double version = 0;
    if (!readNumber(item, QStringLiteral("version"), where, path, version))
        return false;
    // Fixed wing: versions 1 and 2; VTOL: version 1.
    if (version != 1 && (vtol || version != 2))
        return m_fail(
            path + QStringList{QStringLiteral("version")},
            QStringLiteral("%1 is in version %2, which QGroundControl does not load").arg(where, number(version)));
    bool relative = true;
    if (!vtol && version == 1) {
        // Version 1 had an altitude reference for each point; QGroundControl
        // makes both relative to home when they differ.
        bool loiterRelative = true, landRelative = true;
        if (!readBool(item, QStringLiteral("loiterAltitudeRelative"), where, path, loiterRelative) ||
            !readBool(item, QStringLiteral("landAltitudeRelative"), where, path, landRelative))
            return false;
        relative = loiterRelative == landRelative ? loiterRelative : true;
    } else if (!readBool(item, QStringLiteral("altitudesAreRelative"), where, path, relative)) {
        return false;
    }
    bool changeSpeed = false;
    if (!readBool(item, QStringLiteral("useDoChangeSpeed"), where, path, changeSpeed, false))
        return false;
    if (changeSpeed)
        return m_fail(path + QStringList{QStringLiteral("useDoChangeSpeed")},
                      QStringLiteral("%1 changes speed on the final approach (\"useDoChangeSpeed\"), a QGroundControl "
                                     "5 option whose item this console cannot place as QGroundControl does; switch it "
                                     "off in QGroundControl, or put a DO_CHANGE_SPEED item before the pattern")
                          .arg(where));
    // "loiterCoordinate": the approach point's name before QGroundControl 4.
    const QString approachKey = item.contains(QStringLiteral("landingApproachCoordinate"))
                                    ? QStringLiteral("landingApproachCoordinate")
                                    : QStringLiteral("loiterCoordinate");
    GeoPoint approach, land;
    double approachAltitude = 0, landAltitude = 0, radius = 0;
    bool clockwise = true, loiterToAltitude = true, stopPhotos = false, stopVideo = false;
    if (!readCoordinate(item, approachKey, true, where, path, approach, &approachAltitude) ||
        !readCoordinate(item, QStringLiteral("landCoordinate"), true, where, path, land, &landAltitude) ||
        !readNumber(item, QStringLiteral("loiterRadius"), where, path, radius) ||
        !readBool(item, QStringLiteral("loiterClockwise"), where, path, clockwise) ||
        !readBool(item, QStringLiteral("useLoiterToAlt"), where, path, loiterToAltitude, true) ||
        !readBool(item, QStringLiteral("stopTakingPhotos"), where, path, stopPhotos, false) ||
        !readBool(item, QStringLiteral("stopVideoPhotos"), where, path, stopVideo, false))
        return false;
    const quint8 frame = relative ? kRelative : kGlobal;
    out.append(zeroFrameItem(kLandStart, {0, 0, 0, 0}));
    if (stopPhotos) {
        out.append(zeroFrameItem(kCameraTriggerDistance, {0, 0, 0, 0}));
        out.append(stopCaptureItem(kImageStopCapture));
    }
    if (stopVideo)
        out.append(stopCaptureItem(kVideoStopCapture));
    // QGroundControl gives the approach altitude as a float.
    const double approachAltitudeSent = double(float(approachAltitude));
    if (loiterToAltitude)
        out.append(missionItem(kLoiterToAltitude, frame, {1, clockwise ? radius : -radius, 0, 1}, approach.latitude,
                               approach.longitude, approachAltitudeSent));
    else
        out.append(waypoint(frame, approach, approachAltitudeSent));
    out.append(missionItem(vtol ? kVtolLand : kLand, frame, {0, 0, 0, vtol ? kNaN : 0}, land.latitude, land.longitude,
                           landAltitude));
    return true;
}

bool QgcComplexItemReader::readTransectStyle(const QJsonObject& item, const QString& where, const QStringList& path,
                                             QList<MissionItem>& out)
{
    const QString innerKey = QStringLiteral("TransectStyleComplexItem");
    if (!item.value(innerKey).isObject())
        return m_fail(path, QStringLiteral("%1 has no \"TransectStyleComplexItem\" with the waypoints QGroundControl "
                                           "saved: it is in QGroundControl 3.3's layout; open the plan in a later "
                                           "QGroundControl and save it again")
                                .arg(where));
    const QJsonObject inner = item.value(innerKey).toObject();
    const QStringList innerPath = path + QStringList{innerKey};
    const QJsonValue version = inner.value(QStringLiteral("version"));
    if (!version.isUndefined() && version != 1 && version != 2)
        return m_fail(innerPath + QStringList{QStringLiteral("version")},
                      QStringLiteral("%1: TransectStyleComplexItem version %2, which QGroundControl does not load")
                          .arg(where, number(version.toDouble())));
    const QJsonValue itemsValue = inner.value(QStringLiteral("Items"));
    const QStringList itemsPath = innerPath + QStringList{QStringLiteral("Items")};
    if (!itemsValue.isArray() || itemsValue.toArray().isEmpty())
        return m_fail(itemsValue.isUndefined() ? innerPath : itemsPath,
                      QStringLiteral("%1 holds no waypoints (\"Items\"): QGroundControl saves them with a "
                                     "complete pattern; open the plan in QGroundControl, finish the "
                                     "pattern and save it again")
                          .arg(where));
    const QJsonArray items = itemsValue.toArray();
    for (qsizetype i = 0; i < items.size(); ++i) {
        MissionItem simple;
        if (!m_readSimpleItem(items[i], QStringLiteral("%1, its item %2").arg(where).arg(i + 1),
                              itemsPath + QStringList{QString::number(i)}, simple))
            return false;
        out.append(simple);
    }
    return true;
}

bool QgcComplexItemReader::readStructureScan(const QJsonObject& item, const QString& where, const QStringList& path,
                                             QList<MissionItem>& out)
{
    double version = 0;
    if (!readNumber(item, QStringLiteral("version"), where, path, version))
        return false;
    if (version != 3)
        return m_fail(path + QStringList{QStringLiteral("version")},
                      QStringLiteral("%1 is in version %2; QGroundControl loads only version 3: draw it again in "
                                     "QGroundControl and save the plan")
                          .arg(where, number(version)));
    double bottom = 0, height = 0, entrance = 0, gimbalPitch = 0;
    bool fromTop = false;
    if (!readNumber(item, QStringLiteral("ScanBottomAlt"), where, path, bottom) ||
        !readNumber(item, QStringLiteral("StructureHeight"), where, path, height) ||
        !readNumber(item, QStringLiteral("EntranceAltitude"), where, path, entrance) ||
        !readNumber(item, QStringLiteral("GimbalPitch"), where, path, gimbalPitch) ||
        !readBool(item, QStringLiteral("StartFromTop"), where, path, fromTop))
        return false;
    const QString cameraKey = QStringLiteral("CameraCalc");
    if (!item.value(cameraKey).isObject())
        return m_fail(path, QStringLiteral("%1: \"CameraCalc\" must be an object").arg(where));
    const QJsonObject camera = item.value(cameraKey).toObject();
    const QStringList cameraPath = path + QStringList{cameraKey};
    double distance = 0, frontal = 0, side = 0;
    if (!readNumber(camera, QStringLiteral("DistanceToSurface"), where, cameraPath, distance) ||
        !readNumber(camera, QStringLiteral("AdjustedFootprintFrontal"), where, cameraPath, frontal) ||
        !readNumber(camera, QStringLiteral("AdjustedFootprintSide"), where, cameraPath, side))
        return false;
    if (!(frontal > 0))
        return m_fail(cameraPath + QStringList{QStringLiteral("AdjustedFootprintFrontal")},
                      QStringLiteral("%1: the layer height (\"AdjustedFootprintFrontal\") is %2 m; it must be more "
                                     "than 0")
                          .arg(where, number(frontal)));
    const QJsonArray vertices = item.value(QStringLiteral("polygon")).toArray();
    const QStringList polygonPath = path + QStringList{QStringLiteral("polygon")};
    if (vertices.size() < 3)
        return m_fail(item.contains(QStringLiteral("polygon")) ? polygonPath : path,
                      QStringLiteral("%1: the structure's \"polygon\" has %2 vertices; it needs at least 3")
                          .arg(where)
                          .arg(vertices.size()));
    QList<GeoPoint> structure;
    for (qsizetype i = 0; i < vertices.size(); ++i) {
        const QJsonArray v = vertices[i].toArray();
        if (v.size() < 2 || !v[0].isDouble() || !v[1].isDouble() || std::abs(v[0].toDouble()) > 90 ||
            std::abs(v[1].toDouble()) > 180)
            return m_fail(polygonPath + QStringList{QString::number(i)},
                          QStringLiteral("%1: structure vertex %2 must be [latitude, longitude] on the globe")
                              .arg(where)
                              .arg(i + 1));
        structure.append({v[0].toDouble(), v[1].toDouble()});
    }
    int inLine = 0;
    const auto flight = offsetPolygon(structure, distance, &inLine);
    if (!flight)
        return m_fail(polygonPath + QStringList{QString::number(inLine)},
                      QStringLiteral("%1: structure vertex %2 is in line with its neighbours, so the flight path "
                                     "around the structure cannot be drawn (QGroundControl would fly the "
                                     "structure's own outline); remove the vertex in QGroundControl")
                          .arg(where)
                          .arg(inLine + 1));
    for (const GeoPoint& p : *flight) {
        if (!(std::abs(p.latitude) <= 90 && std::abs(p.longitude) <= 180))
            return m_fail(polygonPath, QStringLiteral("%1: the flight path %2 m from the structure leaves the globe")
                                           .arg(where, number(distance)));
    }
    const int layers = std::max(int(std::ceil(std::max(height - bottom, 0.0) / frontal)), 1);
    if (qsizetype(layers) * (flight->size() + 3) > std::numeric_limits<quint16>::max())
        return m_fail(path, QStringLiteral("%1 makes %2 layers, more items than a plan holds").arg(where).arg(layers));

    const GeoPoint entry = flight->front();
    out.append(waypoint(kRelative, entry, entrance));
    // Points the camera at the structure: 90 degrees to the right of the way
    // to the next waypoint, pitched by the gimbal pitch (param5).
    out.append(missionItem(kRoiNextWaypointOffset, kMission, {0, 0, 0, 0}, gimbalPitch, 0.0, 90.0));
    const double step = frontal * (fromTop ? -1 : 1);
    double layerAltitude = (fromTop ? height : bottom) + step / 2;
    for (int layer = 0; layer < layers; ++layer) {
        for (qsizetype v = 0; v <= flight->size(); ++v) {
            out.append(waypoint(kRelative, (*flight)[v % flight->size()], layerAltitude));
            if (v == 0)
                out.append(zeroFrameItem(kCameraTriggerDistance, {side, 0, 1, 0}));
        }
        out.append(zeroFrameItem(kCameraTriggerDistance, {0, 0, 0, 0}));
        layerAltitude += step;
    }
    out.append(zeroFrameItem(kRoiNone, {0, 0, 0, 0}));
    out.append(waypoint(kRelative, entry, entrance));
    return true;
}
