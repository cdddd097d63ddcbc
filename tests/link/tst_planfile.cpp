// Plan files of other programs: QGroundControl .plan and .mission,
// Mission Planner / ArduPilot QGC WPL 110, KML. Real files under
// tests/data/plans (tests/data/plans/README.md says where each comes from),
// small broken ones inline.
#include "link/plan/KmlFile.h"
#include "link/plan/MavCommand.h"
#include "link/plan/MissionPlan.h"
#include "link/plan/PlanFile.h"
#include "link/plan/QgcPlanFile.h"
#include "link/plan/WaypointsFile.h"

#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QTemporaryDir>
#include <QtTest>

#include <cmath>
#include <numbers>

namespace {

const QString kPlans = QStringLiteral(RCM_SOURCE_DIR "/tests/data/plans/");

QByteArray sample(const QString& name)
{
    QFile file(kPlans + name);
    if (!file.open(QIODevice::ReadOnly))
        qFatal("cannot open %s", qPrintable(file.fileName()));
    return file.readAll();
}

MissionPlan load(const QString& name)
{
    QString error;
    const auto plan = PlanFile::load(kPlans + name, &error);
    if (!plan)
        qFatal("%s", qPrintable(error));
    return *plan;
}

// NaN parameters compare unequal to themselves; the plans compare equal when
// they hold NaN in the same places.
MissionPlan nanAsMarker(MissionPlan plan)
{
    for (MissionItem& item : plan.items) {
        for (double& p : item.params) {
            if (std::isnan(p))
                p = -1234.5;
        }
    }
    return plan;
}

bool samePlan(const MissionPlan& a, const MissionPlan& b)
{
    return nanAsMarker(a) == nanAsMarker(b);
}

QString readError(std::optional<MissionPlan> (*reader)(const QByteArray&, const QString&, QString*),
                  const QByteArray& text, const QString& source)
{
    QString error;
    return reader(text, source, &error) ? QStringLiteral("(read without error)") : error;
}

// A plan with something in every field the files carry.
MissionPlan fullPlan()
{
    MissionPlan plan;
    plan.homeLatitude = 52.2076813;
    plan.homeLongitude = 0.1155201;
    plan.homeAltitude = 14.2;
    MissionItem takeoff;
    takeoff.command = 22;
    takeoff.frame = 3;
    takeoff.params = {15, 0, 0, std::nan("")};
    takeoff.latitude = 52.2093412;
    takeoff.longitude = 0.1189255;
    takeoff.altitude = 60;
    MissionItem speed;
    speed.command = 178;
    speed.frame = 2;
    speed.params = {1, 25, -1, 0};
    MissionItem loiter;
    loiter.command = 19;
    loiter.frame = 0;
    loiter.autoContinue = false;
    loiter.params = {30, 0, -75.25, std::nan("")};
    loiter.latitude = -35.36293801;
    loiter.longitude = 149.165085;
    loiter.altitude = 585.125;
    plan.items = {takeoff, speed, loiter};
    plan.renumber();
    plan.fencePolygons = {{true, {{52.2001, 0.1102}, {52.2203, 0.1105}, {52.2208, 0.1401}}},
                          {false, {{52.2101, 0.1201}, {52.2121, 0.1203}, {52.2111, 0.1222}, {52.2105, 0.1210}}}};
    plan.fenceCircles = {{false, {52.2079, 0.1312}, 150.5}, {true, {52.21, 0.12}, 2500}};
    plan.rallyPoints = {{{52.2061, 0.1221}, 50}, {{52.2182, 0.1355}, 75.5}};
    return plan;
}

}  // namespace

class TestPlanFile : public QObject {
    Q_OBJECT

private slots:
    void qgcParamsStyle();
    void qgcCoordinateStyle();
    void qgcParamKeysStyle();
    void qgcMissionFile();
    void qgcFenceOnly();
    void qgcFenceWithoutVersions();
    void qgcRefusals_data();
    void qgcRefusals();
    void qgcWritesWhatQgcLoads();
    void qgcRoundTrip();
    void missionPlannerWaypoints();
    void arduPilotMissionWithComments();
    void waypointsSpacesAndBlankLines();
    void waypointsRefusals_data();
    void waypointsRefusals();
    void waypointsRoundTrip();
    void kmlPolygonFromGoogleEarth();
    void kmlRoutePointsAndPolygon();
    void kmlRefusals_data();
    void kmlRefusals();
    void recognisesFormatByContents();
    void refusesOtherFiles();
    void openFilterListsEveryFormat();
    void saveThenLoad();
    void fenceAndRallyGoToPlanBytes();
    void qgcComplexItemsAsQgcFliesThem();
    void qgcLandingPatternVersions();
    void qgcComplexRefusals_data();
    void qgcComplexRefusals();
    void waypointsFenceOnly();
    void waypointsRallyPoints();
    void waypointsHomeAtZeroIsNoHome();
    void waypointsFenceRefusals_data();
    void waypointsFenceRefusals();
    void commandsNamedAsPlannersNameThem();
    void rallyPointsOutsideTheFenceFlagged();
};

void TestPlanFile::qgcParamsStyle()
{
    const MissionPlan plan = load(QStringLiteral("fence-rally.plan"));
    QCOMPARE(plan.homeLatitude, 52.2076813);
    QCOMPARE(plan.homeLongitude, 0.1155201);
    QCOMPARE(plan.homeAltitude, 14.2);
    QCOMPARE(plan.items.size(), 4);
    const MissionItem& takeoff = plan.items[0];
    QCOMPARE(takeoff.seq, quint16(0));
    QCOMPARE(takeoff.command, quint16(22));
    QCOMPARE(takeoff.frame, quint8(3));
    QCOMPARE(takeoff.params[0], 15.0);
    QVERIFY(std::isnan(takeoff.params[3]));
    QCOMPARE(takeoff.latitude, 52.2093412);
    QCOMPARE(takeoff.longitude, 0.1189255);
    QCOMPARE(takeoff.altitude, 60.0);
    QCOMPARE(plan.items[2].command, quint16(178));
    QCOMPARE(plan.items[2].params[1], 25.0);
    QCOMPARE(plan.items[2].params[2], -1.0);
    QCOMPARE(plan.items[3].command, quint16(20));
    QCOMPARE(plan.items[3].seq, quint16(3));

    QCOMPARE(plan.fencePolygons.size(), 2);
    QCOMPARE(plan.fencePolygons[0].inclusion, true);
    QCOMPARE(plan.fencePolygons[0].vertices.size(), 4);
    QCOMPARE(plan.fencePolygons[0].vertices[2], (GeoPoint{52.2208, 0.1401}));
    QCOMPARE(plan.fencePolygons[1].inclusion, false);
    QCOMPARE(plan.fencePolygons[1].vertices,
             (QList<GeoPoint>{{52.2101, 0.1201}, {52.2121, 0.1203}, {52.2111, 0.1222}}));
    QCOMPARE(plan.fenceCircles.size(), 1);
    QCOMPARE(plan.fenceCircles[0], (FenceCircle{false, {52.2079, 0.1312}, 150.5}));
    QCOMPARE(plan.rallyPoints, (QList<RallyPoint>{{{52.2061, 0.1221}, 50}, {{52.2182, 0.1355}, 75.5}}));
    QCOMPARE(plan.format(), 2);
}

// QGroundControl's own test plan: items with "coordinate" and 4 params.
void TestPlanFile::qgcCoordinateStyle()
{
    const MissionPlan plan = load(QStringLiteral("SectionTest.plan"));
    QCOMPARE(plan.items.size(), 5);
    QCOMPARE(plan.homeLatitude, 47.633389756176875);
    QCOMPARE(plan.homeLongitude, -122.09076300000001);
    QCOMPARE(plan.homeAltitude, 20.0);
    QCOMPARE(plan.items[0].command, quint16(22));
    QCOMPARE(plan.items[0].latitude, 47.63311996);
    QCOMPARE(plan.items[0].longitude, -122.090763);
    QCOMPARE(plan.items[0].altitude, 20.0);
    QCOMPARE(plan.items[0].params[0], 0.0);
    QVERIFY(std::isnan(plan.items[0].params[3]));
    // DO_MOUNT_CONTROL (205), in the mission frame.
    QCOMPARE(plan.items[3].command, quint16(205));
    QCOMPARE(plan.items[3].frame, quint8(2));
    QCOMPARE(plan.items[3].params[3], 0.0);
    QCOMPARE(plan.items[3].altitude, 2.0);
    QCOMPARE(plan.items[4].latitude, 47.63261386);
    QCOMPARE(plan.items[4].longitude, -122.08661094);
    // Its geofence and rally points are version 1 and empty.
    QVERIFY(!plan.hasFence());
    QVERIFY(plan.rallyPoints.isEmpty());
}

// The first style: "param1".."param4" and "coordinate", type "missionItem".
void TestPlanFile::qgcParamKeysStyle()
{
    QString error;
    const auto plan = QgcPlanFile::read(R"({"fileType": "Plan", "mission": {"version": 2, "items": [
        {"type": "missionItem", "command": 19, "frame": 3, "autoContinue": false,
         "param1": 30, "param2": 0, "param3": 50.5, "param4": null,
         "coordinate": [-35.3629, 149.1650, 80]}]}})",
                                        QStringLiteral("v1.plan"), &error);
    QVERIFY2(plan, qPrintable(error));
    QCOMPARE(plan->items.size(), 1);
    const MissionItem& item = plan->items[0];
    QCOMPARE(item.command, quint16(19));
    QCOMPARE(item.autoContinue, false);
    QCOMPARE(item.params[0], 30.0);
    QCOMPARE(item.params[2], 50.5);
    QVERIFY(std::isnan(item.params[3]));
    QCOMPARE(item.latitude, -35.3629);
    QCOMPARE(item.longitude, 149.1650);
    QCOMPARE(item.altitude, 80.0);
}

// QGroundControl's older .mission: the mission object alone, no "fileType",
// CRLF line ends.
void TestPlanFile::qgcMissionFile()
{
    const MissionPlan plan = load(QStringLiteral("OldFileFormat.mission"));
    QCOMPARE(plan.items.size(), 6);
    QCOMPARE(plan.homeLatitude, 47.660137763851573);
    QCOMPARE(plan.homeAltitude, 0.0);
    QCOMPARE(plan.items[1].command, quint16(18));
    QCOMPARE(plan.items[1].params[0], 1.0);
    QCOMPARE(plan.items[2].params[0], 3.0);
    QCOMPARE(plan.items[5].command, quint16(21));
    QCOMPARE(plan.items[5].latitude, 47.660153620000003);
    QCOMPARE(plan.items[5].altitude, 3.0);
}

void TestPlanFile::qgcFenceOnly()
{
    const MissionPlan plan = load(QStringLiteral("ce_geofence_rd_2.plan"));
    QVERIFY(plan.items.isEmpty());
    QCOMPARE(plan.homeAltitude, 30.0);
    QCOMPARE(plan.fencePolygons.size(), 2);
    QCOMPARE(plan.fencePolygons[0].inclusion, true);
    QCOMPARE(plan.fencePolygons[1].inclusion, false);
    QCOMPARE(plan.fencePolygons[1].vertices[1], (GeoPoint{38.750850553167055, -77.4972259712925}));
    QCOMPARE(plan.fencePolygons[1].vertices.size(), 4);
    QVERIFY(plan.fenceCircles.isEmpty());
}

// Other programs write the current layout and leave out the versions.
void TestPlanFile::qgcFenceWithoutVersions()
{
    QString error;
    const auto plan = QgcPlanFile::read(R"({"fileType": "Plan", "mission": {"items": []},
        "geoFence": {"polygons": [{"inclusion": true, "polygon": [[19.13, 72.91], [19.14, 72.91], [19.14, 72.92]]}]},
        "rallyPoints": {"points": [[19.132, 72.912, 20.0]]}})",
                                        QStringLiteral("generated.plan"), &error);
    QVERIFY2(plan, qPrintable(error));
    QCOMPARE(plan->fencePolygons, (QList<FencePolygon>{{true, {{19.13, 72.91}, {19.14, 72.91}, {19.14, 72.92}}}}));
    QCOMPARE(plan->rallyPoints, (QList<RallyPoint>{{{19.132, 72.912}, 20}}));
}

void TestPlanFile::qgcRefusals_data()
{
    QTest::addColumn<QByteArray>("json");
    QTest::addColumn<QString>("error");
    QTest::newRow("vertex out of range") << QByteArray(R"({
  "fileType": "Plan",
  "mission": {"items": []},
  "geoFence": {
    "version": 2,
    "polygons": [
      {"inclusion": true, "polygon": [[1, 1], [1, 2], [2, 2]]},
      {"inclusion": true, "polygon": [
        [1, 1],
        [1, 2],
        [2, 2],
        [95, 3]
      ]}
    ]
  }
})") << QStringLiteral("p.plan: line 12: geofence polygon 2, vertex 4: latitude 95 is outside \u00b190");
    QTest::newRow("two vertices") << QByteArray(R"({"fileType": "Plan", "mission": {"items": []},
  "geoFence": {"version": 2, "polygons": [
    {"inclusion": false,
     "polygon": [[1, 1], [1, 2]]}]}})")
                                  << QStringLiteral(
                                         "p.plan: line 4: geofence polygon 1 has 2 vertices; a polygon needs "
                                         "at least 3");
    QTest::newRow("no inclusion") << QByteArray(R"({"fileType": "Plan", "mission": {"items": []},
  "geoFence": {"version": 2, "polygons": [{"polygon": [[1, 1], [1, 2], [2, 2]]}]}})")
                                  << QStringLiteral(
                                         "p.plan: line 2: geofence polygon 1: \"inclusion\" must be true or "
                                         "false");
    QTest::newRow("circle radius") << QByteArray(R"({"fileType": "Plan", "mission": {"items": []},
  "geoFence": {"version": 2, "circles": [
    {"circle": {"center": [1, 2], "radius": 100}, "inclusion": true},
    {"circle": {"center": [1, 2],
                "radius": 0}, "inclusion": true}]}})")
                                   << QStringLiteral(
                                          "p.plan: line 5: geofence circle 2: radius 0 m is not more than 0");
    QTest::newRow("circle centre") << QByteArray(R"({"fileType": "Plan", "mission": {"items": []},
  "geoFence": {"version": 2, "circles": [
    {"circle": {"center": [1, 200], "radius": 100}, "inclusion": true}]}})")
                                   << QStringLiteral(
                                          "p.plan: line 3: geofence circle 1 centre: longitude 200 is outside "
                                          "\u00b1180");
    QTest::newRow("geofence version") << QByteArray(R"({"fileType": "Plan", "mission": {"items": []},
  "geoFence": {"version": 3, "polygons": []}})")
                                      << QStringLiteral(
                                             "p.plan: line 2: geofence version 3; this console reads version "
                                             "2");
    QTest::newRow("geofence version 1 with a fence") << QByteArray(R"({"fileType": "Plan", "mission": {"items": []},
  "geoFence": {"version": 1, "polygon": [[1, 1], [1, 2], [2, 2]]}})")
                                                     << QStringLiteral(
                                                            "p.plan: line 2: the geofence is in QGroundControl's "
                                                            "version 1 layout, which neither QGroundControl nor this "
                                                            "console reads any more; draw it again in QGroundControl "
                                                            "and save the plan");
    QTest::newRow("rally version 1 with points") << QByteArray(R"({"fileType": "Plan", "mission": {"items": []},
  "rallyPoints": {"version": 1, "points": [[1, 2, 30]]}})")
                                                 << QStringLiteral(
                                                        "p.plan: line 2: the rally point list is in QGroundControl's "
                                                        "version 1 layout, which neither QGroundControl nor this "
                                                        "console reads any more; draw it again in QGroundControl and "
                                                        "save the plan");
    QTest::newRow("rally point") << QByteArray(R"({"fileType": "Plan", "mission": {"items": []},
  "rallyPoints": {"version": 2, "points": [
    [1, 2, 30],
    [-91, 2, 30]]}})") << QStringLiteral("p.plan: line 4: rally point 2: latitude -91 is outside \u00b190");
    QTest::newRow("rally altitude null") << QByteArray(R"({"fileType": "Plan", "mission": {"items": []},
  "rallyPoints": {"version": 2, "points": [[1, 2, null]]}})")
                                         << QStringLiteral(
                                                "p.plan: line 2: rally point 1 must be [latitude, "
                                                "longitude, altitude]");
    QTest::newRow("item params") << QByteArray(R"({
    "fileType": "Plan",
    "mission": {"items": [
        {"type": "SimpleItem", "command": 16, "frame": 3, "params": [0, 0, 0, 0, 1, 2, 3]},
        {"type": "SimpleItem", "command": 16, "frame": 3,
         "params": [0, 0, 0, 0, 1, 2]}
    ]}
})") << QStringLiteral("p.plan: line 5: mission item 2: \"params\" must hold 7 values (numbers or null)");
    QTest::newRow("coordinate with 7 params") << QByteArray(R"({"fileType": "Plan", "mission": {"items": [
        {"type": "SimpleItem", "command": 16, "frame": 3, "coordinate": [1, 2, 3],
         "params": [0, 0, 0, 0, 1, 2, 3]}]}})")
                                              << QStringLiteral(
                                                     "p.plan: line 2: mission item 1 has a \"coordinate\", so "
                                                     "\"params\" must hold 4 values (numbers or null), not 7");
    QTest::newRow("param text") << QByteArray(R"({"fileType": "Plan", "mission": {"items": [
        {"type": "missionItem", "command": 16, "frame": 3, "param1": "x", "param2": 0, "param3": 0,
         "param4": 0, "coordinate": [1, 2, 3]}]}})")
                                << QStringLiteral(
                                       "p.plan: line 2: mission item 1: \"param1\" must be a number or null");
    QTest::newRow("home") << QByteArray(R"({"fileType": "Plan", "mission": {"items": [],
  "plannedHomePosition": [10, 190, 0]}})")
                          << QStringLiteral(
                                 "p.plan: line 2: planned home position: longitude 190 is outside \u00b1180");
    QTest::newRow("plan version") << QByteArray(R"({"fileType": "Plan", "version": 2, "mission": {"items": []}})")
                                  << QStringLiteral("p.plan: plan file version 2; this console reads version 1");
    QTest::newRow("mission version") << QByteArray(R"({"fileType": "Plan",
  "mission": {"version": 1, "items": []}})")
                                     << QStringLiteral(
                                            "p.plan: line 2: the mission is in version 1 of QGroundControl's "
                                            "layout; this console reads version 2 (QGroundControl 3.2 and "
                                            "later): open it in QGroundControl and save it again");
}

void TestPlanFile::qgcRefusals()
{
    QFETCH(QByteArray, json);
    QFETCH(QString, error);
    QCOMPARE(readError(&QgcPlanFile::read, json, QStringLiteral("p.plan")), error);
}

// The keys QGroundControl's PlanMasterController, MissionController,
// GeoFenceController and RallyPointController require, with the versions
// they accept.
void TestPlanFile::qgcWritesWhatQgcLoads()
{
    const QJsonObject root = QJsonDocument::fromJson(QgcPlanFile::write(fullPlan())).object();
    QCOMPARE(root.value(QStringLiteral("fileType")).toString(), QStringLiteral("Plan"));
    QCOMPARE(root.value(QStringLiteral("version")).toInt(), 1);
    QVERIFY(root.value(QStringLiteral("groundStation")).isString());
    const QJsonObject mission = root.value(QStringLiteral("mission")).toObject();
    QCOMPARE(mission.value(QStringLiteral("version")).toInt(), 2);
    QVERIFY(mission.value(QStringLiteral("firmwareType")).isDouble());
    QVERIFY(mission.value(QStringLiteral("vehicleType")).isDouble());
    QVERIFY(mission.value(QStringLiteral("cruiseSpeed")).isDouble());
    QVERIFY(mission.value(QStringLiteral("hoverSpeed")).isDouble());
    QCOMPARE(mission.value(QStringLiteral("plannedHomePosition")).toArray(), (QJsonArray{52.2076813, 0.1155201, 14.2}));
    const QJsonArray items = mission.value(QStringLiteral("items")).toArray();
    QCOMPARE(items.size(), 3);
    const QJsonObject takeoff = items[0].toObject();
    QCOMPARE(takeoff.value(QStringLiteral("type")).toString(), QStringLiteral("SimpleItem"));
    QCOMPARE(takeoff.value(QStringLiteral("command")).toInt(), 22);
    QCOMPARE(takeoff.value(QStringLiteral("frame")).toInt(), 3);
    QCOMPARE(takeoff.value(QStringLiteral("autoContinue")).toBool(), true);
    QCOMPARE(takeoff.value(QStringLiteral("doJumpId")).toInt(), 1);
    QCOMPARE(takeoff.value(QStringLiteral("params")).toArray(),
             (QJsonArray{15, 0, 0, QJsonValue::Null, 52.2093412, 0.1189255, 60}));
    // No position: null, as QGroundControl writes NaN.
    QCOMPARE(items[1].toObject().value(QStringLiteral("params")).toArray(),
             (QJsonArray{1, 25, -1, 0, QJsonValue::Null, QJsonValue::Null, QJsonValue::Null}));

    const QJsonObject fence = root.value(QStringLiteral("geoFence")).toObject();
    QCOMPARE(fence.value(QStringLiteral("version")).toInt(), 2);
    const QJsonObject polygon = fence.value(QStringLiteral("polygons")).toArray()[1].toObject();
    QCOMPARE(polygon.value(QStringLiteral("inclusion")).toBool(), false);
    QCOMPARE(polygon.value(QStringLiteral("version")).toInt(), 1);
    QCOMPARE(polygon.value(QStringLiteral("polygon")).toArray()[0].toArray(), (QJsonArray{52.2101, 0.1201}));
    const QJsonObject circle = fence.value(QStringLiteral("circles")).toArray()[0].toObject();
    QCOMPARE(circle.value(QStringLiteral("inclusion")).toBool(), false);
    QCOMPARE(circle.value(QStringLiteral("version")).toInt(), 1);
    QCOMPARE(circle.value(QStringLiteral("circle")).toObject(),
             (QJsonObject{{QStringLiteral("center"), QJsonArray{52.2079, 0.1312}}, {QStringLiteral("radius"), 150.5}}));
    const QJsonObject rally = root.value(QStringLiteral("rallyPoints")).toObject();
    QCOMPARE(rally.value(QStringLiteral("version")).toInt(), 2);
    QCOMPARE(rally.value(QStringLiteral("points")).toArray()[1].toArray(), (QJsonArray{52.2182, 0.1355, 75.5}));

    MissionPlan homeless;
    const QJsonObject empty = QJsonDocument::fromJson(QgcPlanFile::write(homeless)).object();
    QCOMPARE(empty.value(QStringLiteral("mission")).toObject().value(QStringLiteral("plannedHomePosition")).toArray(),
             (QJsonArray{QJsonValue::Null, QJsonValue::Null, QJsonValue::Null}));
}

void TestPlanFile::qgcRoundTrip()
{
    QString error;
    for (const MissionPlan& plan : {fullPlan(), load(QStringLiteral("fence-rally.plan")),
                                    load(QStringLiteral("SectionTest.plan")), MissionPlan()}) {
        const auto back = QgcPlanFile::read(QgcPlanFile::write(plan), QStringLiteral("written.plan"), &error);
        QVERIFY2(back, qPrintable(error));
        QVERIFY(samePlan(*back, plan));
    }
}

// Mission Planner's file from QGroundControl's tests: CRLF, home on index 0.
void TestPlanFile::missionPlannerWaypoints()
{
    const MissionPlan plan = load(QStringLiteral("MissionPlanner.waypoints"));
    QCOMPARE(plan.homeLatitude, 47.660459);
    QCOMPARE(plan.homeLongitude, -122.103167);
    QCOMPARE(plan.homeAltitude, 5.21);
    QCOMPARE(plan.items.size(), 5);
    for (const MissionItem& item : plan.items) {
        QCOMPARE(item.command, quint16(16));
        QCOMPARE(item.frame, quint8(3));
        QCOMPARE(item.altitude, 100.0);
        QVERIFY(item.autoContinue);
    }
    QCOMPARE(plan.items[0].seq, quint16(0));
    QCOMPARE(plan.items[0].latitude, 47.661298);
    QCOMPARE(plan.items[0].longitude, -122.103274);
    QCOMPARE(plan.items[4].latitude, 47.660459);
    QCOMPARE(plan.items[4].longitude, -122.105538);
    QCOMPARE(plan.items[4].seq, quint16(4));
}

// ArduPilot's autotest mission with '#' comment lines.
void TestPlanFile::arduPilotMissionWithComments()
{
    const MissionPlan plan = load(QStringLiteral("rtl.txt"));
    QCOMPARE(plan.homeLatitude, -35.362938);
    QCOMPARE(plan.homeLongitude, 149.165085);
    QCOMPARE(plan.homeAltitude, 585.0);
    QCOMPARE(plan.items.size(), 8);
    QCOMPARE(plan.items[0].command, quint16(22));
    QCOMPARE(plan.items[0].params[0], 15.0);
    QCOMPARE(plan.items[0].latitude, -35.361279);
    QCOMPARE(plan.items[3].command, quint16(20));
    QCOMPARE(plan.items[3].frame, quint8(0));
    QCOMPARE(plan.items[4].command, quint16(189));
    QCOMPARE(plan.items[7].command, quint16(21));
    QCOMPARE(plan.items[7].params[3], 1.0);
    QCOMPARE(plan.items[7].altitude, 0.0);
}

void TestPlanFile::waypointsSpacesAndBlankLines()
{
    QString error;
    const auto plan = WaypointsFile::read(
        "QGC WPL 110\r\n"
        "0 1 0 16 0 0 0 0 -35.5 149.25 584 1\r\n"
        "1   0  3 22   15 0 0 nan   -35.4 149.2   80 1\r\n"
        "2\t0\t3  16\t0\t0\t0\t0 \t-35.3\t149.1\t100\t0\r\n"
        "\r\n   \n\n",
        QStringLiteral("s.waypoints"), &error);
    QVERIFY2(plan, qPrintable(error));
    QCOMPARE(plan->homeAltitude, 584.0);
    QCOMPARE(plan->items.size(), 2);
    QCOMPARE(plan->items[0].command, quint16(22));
    QVERIFY(std::isnan(plan->items[0].params[3]));
    QCOMPARE(plan->items[0].altitude, 80.0);
    QCOMPARE(plan->items[1].latitude, -35.3);
    QCOMPARE(plan->items[1].autoContinue, false);

    // Without an index 0 first, every line is a mission item.
    const auto homeless =
        WaypointsFile::read("QGC WPL 110\n1 0 3 16 0 0 0 0 -35.3 149.1 100 1\n", QStringLiteral("h.waypoints"), &error);
    QVERIFY2(homeless, qPrintable(error));
    QCOMPARE(homeless->items.size(), 1);
    QVERIFY(!homeless->homeLatitude);
}

void TestPlanFile::waypointsRefusals_data()
{
    QTest::addColumn<QByteArray>("text");
    QTest::addColumn<QString>("error");
    const QByteArray head = "QGC WPL 110\n0\t1\t0\t16\t0\t0\t0\t0\t-35.36\t149.16\t584\t1\n";
    QTest::newRow("latitude text") << head +
                                          "1\t0\t3\t16\t0\t0\t0\t0\t-35.36\t149.16\t100\t1\n"
                                          "\n"
                                          "# a comment\n"
                                          "2\t0\t3\t16\t0\t0\t0\t0\tabc\t149.16\t100\t1\n"
                                   << QStringLiteral(
                                          "m.waypoints: line 6, field 9 (latitude): \"abc\" is not a number");
    QTest::newRow("not QGC WPL") << QByteArray("Version 2 mission\n1 2 3\n")
                                 << QStringLiteral(
                                        "m.waypoints: line 1: not a QGC WPL 110 file (it starts with "
                                        "\"Version 2 mission\")");
    QTest::newRow("version 120") << QByteArray("QGC WPL 120\n0\t1\t0\t16\t0\t0\t0\t0\t1\t2\t3\t1\n")
                                 << QStringLiteral(
                                        "m.waypoints: line 1: QGC WPL 120 (QGroundControl's format before "
                                        "2016, without a home) is not read; open the file in "
                                        "QGroundControl and save it as a .plan");
    QTest::newRow("version 111") << QByteArray("QGC WPL 111\n")
                                 << QStringLiteral(
                                        "m.waypoints: line 1: QGC WPL version \"111\"; this console reads QGC "
                                        "WPL 110");
    QTest::newRow("11 fields") << head + "1\t0\t3\t16\t0\t0\t0\t0\t-35.36\t149.16\t100\n"
                               << QStringLiteral(
                                      "m.waypoints: line 3: 11 fields; a QGC WPL 110 line has 12 (index, "
                                      "current, frame, command, param1..param4, latitude, longitude, "
                                      "altitude, autocontinue)");
    QTest::newRow("command range") << head + "1\t0\t3\t70000\t0\t0\t0\t0\t-35.36\t149.16\t100\t1\n"
                                   << QStringLiteral(
                                          "m.waypoints: line 3, field 4 (command): 70000 is outside 0..65535");
    QTest::newRow("frame text") << head + "1\t0\t3.5\t16\t0\t0\t0\t0\t-35.36\t149.16\t100\t1\n"
                                << QStringLiteral(
                                       "m.waypoints: line 3, field 3 (frame): \"3.5\" is not a whole number");
    QTest::newRow("latitude range") << head + "1\t0\t3\t16\t0\t0\t0\t0\t95\t149.16\t100\t1\n"
                                    << QStringLiteral(
                                           "m.waypoints: line 3, field 9 (latitude): 95 is outside \u00b190");
    QTest::newRow("home longitude") << QByteArray("QGC WPL 110\n0\t1\t0\t16\t0\t0\t0\t0\t-35.36\t-181\t584\t1\n")
                                    << QStringLiteral(
                                           "m.waypoints: line 2, field 10 (longitude): -181 is outside "
                                           "\u00b1180");
    QTest::newRow("autocontinue") << head + "1\t0\t3\t16\t0\t0\t0\t0\t-35.36\t149.16\t100\t2\n"
                                  << QStringLiteral("m.waypoints: line 3, field 12 (autocontinue): 2 is outside 0..1");
    QTest::newRow("param float") << head + "1\t0\t3\t16\t1e39\t0\t0\t0\t-35.36\t149.16\t100\t1\n"
                                 << QStringLiteral(
                                        "m.waypoints: line 3, field 5 (param1): 1e+39 does not fit a 32-bit "
                                        "float");
}

void TestPlanFile::waypointsRefusals()
{
    QFETCH(QByteArray, text);
    QFETCH(QString, error);
    QCOMPARE(readError(&WaypointsFile::read, text, QStringLiteral("m.waypoints")), error);
}

void TestPlanFile::waypointsRoundTrip()
{
    MissionPlan plan = fullPlan();
    plan.fencePolygons.clear();
    plan.fenceCircles.clear();
    plan.rallyPoints.clear();
    // The format has no "not given": a position is always written.
    plan.items[1].latitude = plan.items[1].longitude = plan.items[1].altitude = 0.0;
    QString error;
    const QByteArray text = WaypointsFile::write(plan);
    QVERIFY(text.startsWith("QGC WPL 110\n0\t1\t0\t16\t0\t0\t0\t0\t52.2076813\t0.1155201\t14.2\t1\n"));
    const auto back = WaypointsFile::read(text, QStringLiteral("w.waypoints"), &error);
    QVERIFY2(back, qPrintable(error));
    QVERIFY(samePlan(*back, plan));
    const auto mission = load(QStringLiteral("MissionPlanner.waypoints"));
    QVERIFY(samePlan(*WaypointsFile::read(WaypointsFile::write(mission), QStringLiteral("w"), &error), mission));
}

// QGroundControl's test polygon, exported from Google Earth: a closed ring.
void TestPlanFile::kmlPolygonFromGoogleEarth()
{
    const MissionPlan plan = load(QStringLiteral("GoodPolygon.kml"));
    QVERIFY(plan.items.isEmpty());
    QVERIFY(plan.rallyPoints.isEmpty());
    QCOMPARE(plan.fencePolygons.size(), 1);
    QCOMPARE(plan.fencePolygons[0].inclusion, true);
    QCOMPARE(plan.fencePolygons[0].vertices, (QList<GeoPoint>{{47.65965281788451, -122.1059149362712},
                                                              {47.66002598220988, -122.1044593196253},
                                                              {47.66034166158975, -122.1047336695092},
                                                              {47.6599810708829, -122.1061470943783}}));
}

void TestPlanFile::kmlRoutePointsAndPolygon()
{
    const MissionPlan plan = load(QStringLiteral("route.kml"));
    QVERIFY(!plan.homeLatitude);
    QCOMPARE(plan.items.size(), 4);
    for (qsizetype i = 0; i < plan.items.size(); ++i) {
        QCOMPARE(plan.items[i].seq, quint16(i));
        QCOMPARE(plan.items[i].command, quint16(16));
        QCOMPARE(plan.items[i].frame, quint8(3));
    }
    QCOMPARE(plan.items[0].latitude, 52.2093412);
    QCOMPARE(plan.items[0].longitude, 0.1189255);
    QCOMPARE(plan.items[0].altitude, 60.0);
    QCOMPARE(plan.items[1].altitude, 120.0);
    // No altitude in the tuple; then a clampToGround point: the default.
    QCOMPARE(plan.items[2].latitude, 52.21);
    QCOMPARE(plan.items[2].altitude, KmlFile::kDefaultAltitude);
    QCOMPARE(plan.items[3].latitude, 52.212);
    QCOMPARE(plan.items[3].altitude, 100.0);
    QCOMPARE(plan.rallyPoints, (QList<RallyPoint>{{{52.2182, 0.1355}, 75}}));
    QCOMPARE(plan.fencePolygons.size(), 2);
    QCOMPARE(plan.fencePolygons[0].inclusion, true);
    QCOMPARE(plan.fencePolygons[0].vertices,
             (QList<GeoPoint>{{52.2001, 0.1102}, {52.2203, 0.1105}, {52.2208, 0.1401}, {52.1999, 0.1398}}));
    QCOMPARE(plan.fencePolygons[1].inclusion, false);
    QCOMPARE(plan.fencePolygons[1].vertices,
             (QList<GeoPoint>{{52.2101, 0.1201}, {52.2121, 0.1203}, {52.2111, 0.1222}}));
}

void TestPlanFile::kmlRefusals_data()
{
    QTest::addColumn<QByteArray>("kml");
    QTest::addColumn<QString>("error");
    QTest::newRow("tuple text") << QByteArray(
                                       "<kml xmlns=\"http://www.opengis.net/kml/2.2\">\n"
                                       "<Placemark><name>Route</name>\n"
                                       "<LineString><coordinates>\n"
                                       "  1,2,3 abc,5\n"
                                       "</coordinates></LineString></Placemark></kml>\n")
                                << QStringLiteral(
                                       "k.kml: line 4, column 9: <coordinates> of LineString in placemark "
                                       "\"Route\": \"abc,5\" is not longitude,latitude[,altitude]");
    QTest::newRow("latitude") << QByteArray(
                                     "<kml><Placemark><Point><coordinates>10,95</coordinates></Point>"
                                     "</Placemark></kml>")
                              << QStringLiteral(
                                     "k.kml: line 1, column 37: <coordinates> of Point: latitude 95 is outside "
                                     "\u00b190");
    QTest::newRow("two vertices") << QByteArray(
                                         "<kml><Placemark><name>Small</name><Polygon><outerBoundaryIs>\n"
                                         "<LinearRing><coordinates>1,1 2,2 1,1</coordinates></LinearRing>\n"
                                         "</outerBoundaryIs></Polygon></Placemark></kml>")
                                  << QStringLiteral(
                                         "k.kml: line 2, column 26: <coordinates> of a Polygon's outer "
                                         "boundary in placemark \"Small\": 2 vertices; a fence polygon needs "
                                         "at least 3");
    QTest::newRow("absolute rally") << QByteArray(
                                           "<kml><Placemark><name>rally 1</name><Point>\n"
                                           "<altitudeMode>absolute</altitudeMode>\n"
                                           "<coordinates>1,2,300</coordinates></Point></Placemark></kml>")
                                    << QStringLiteral(
                                           "k.kml: line 3, column 14: <coordinates> of Point in placemark "
                                           "\"rally 1\": a rally point's altitude is above home, and this one "
                                           "is absolute (above mean sea level); make it relativeToGround");
    QTest::newRow("not kml") << QByteArray("<?xml version=\"1.0\"?>\n<gpx version=\"1.1\"></gpx>")
                             << QStringLiteral(
                                    "k.kml: line 2, column 20: not a KML document (its root element is <gpx>)");
    QTest::newRow("broken xml") << QByteArray("<kml>\n<Placemark>\n</kml>")
                                << QStringLiteral("k.kml: line 3, column 7: Opening and ending tag mismatch.");
    QTest::newRow("nothing") << QByteArray("<kml><Document><name>empty</name></Document></kml>")
                             << QStringLiteral("k.kml: no LineString, Polygon or Point in it to make a plan of");
}

void TestPlanFile::kmlRefusals()
{
    QFETCH(QByteArray, kml);
    QFETCH(QString, error);
    QCOMPARE(readError(&KmlFile::read, kml, QStringLiteral("k.kml")), error);
}

void TestPlanFile::recognisesFormatByContents()
{
    // A Mission Planner file once went to the JSON reader and came back as
    // "line 1, column 2: illegal value".
    QString error;
    const auto waypoints =
        PlanFile::read(sample(QStringLiteral("MissionPlanner.waypoints")), QStringLiteral("mission.plan"), &error);
    QVERIFY2(waypoints, qPrintable(error));
    QCOMPARE(waypoints->items.size(), 5);
    const auto kml = PlanFile::read(sample(QStringLiteral("GoodPolygon.kml")), QStringLiteral("x"), &error);
    QVERIFY2(kml, qPrintable(error));
    QCOMPARE(kml->fencePolygons.size(), 1);
    const auto plan = PlanFile::read(sample(QStringLiteral("fence-rally.plan")), QStringLiteral("x"), &error);
    QVERIFY2(plan, qPrintable(error));
    QCOMPARE(plan->rallyPoints.size(), 2);
    // Windows programs may start a file with a UTF-8 byte order mark.
    const auto marked = PlanFile::read("\xEF\xBB\xBF" + sample(QStringLiteral("rtl.txt")), QStringLiteral("x"), &error);
    QVERIFY2(marked, qPrintable(error));
    QCOMPARE(marked->items.size(), 8);
    // Errors of the reader chosen come through.
    QVERIFY(!PlanFile::read("QGC WPL 110\n0 1 0 16 0 0 0 0 1 2 3 x\n", QStringLiteral("m.txt"), &error));
    QCOMPARE(error, QStringLiteral("m.txt: line 2, field 12 (autocontinue): \"x\" is not a whole number"));
}

void TestPlanFile::refusesOtherFiles()
{
    QString error;
    QVERIFY(!PlanFile::read("lat,lon\n1,2\n", QStringLiteral("x.txt"), &error));
    QCOMPARE(error, QStringLiteral("x.txt: not a plan file this console reads: QGroundControl .plan, Mission Planner "
                                   ".waypoints (QGC WPL 110) or KML"));
    QVERIFY(!PlanFile::read("<html><body></body></html>", QStringLiteral("x.html"), &error));
    QCOMPARE(error, QStringLiteral("x.html: not a plan file this console reads: QGroundControl .plan, Mission "
                                   "Planner .waypoints (QGC WPL 110) or KML"));
    QVERIFY(!PlanFile::read(" \n", QStringLiteral("e.plan"), &error));
    QCOMPARE(error, QStringLiteral("e.plan: the file is empty"));
    QVERIFY(!PlanFile::load(kPlans + QStringLiteral("no such file.plan"), &error));
    QVERIFY2(error.startsWith(QDir::toNativeSeparators(kPlans + QStringLiteral("no such file.plan: "))),
             qPrintable(error));
}

void TestPlanFile::openFilterListsEveryFormat()
{
    QCOMPARE(PlanFile::openFilter(),
             QStringLiteral("Plans (*.plan *.waypoints *.txt *.mission *.kml);;QGroundControl plans (*.plan);;Mission "
                            "Planner waypoints (*.waypoints *.txt);;KML (*.kml);;All files (*)"));
}

void TestPlanFile::saveThenLoad()
{
    QTemporaryDir dir;
    QVERIFY(dir.isValid());
    const QString path = dir.filePath(QStringLiteral("saved.plan"));
    QString error;
    QVERIFY2(PlanFile::save(fullPlan(), path, &error), qPrintable(error));
    const auto back = PlanFile::load(path, &error);
    QVERIFY2(back, qPrintable(error));
    QVERIFY(samePlan(*back, fullPlan()));
    QVERIFY(!PlanFile::save(fullPlan(), dir.filePath(QStringLiteral("no/such/dir/x.plan")), &error));
    QVERIFY(error.contains(QStringLiteral("x.plan: ")));
}

// What a file held reaches the aircraft: format 2 plan bytes carry the
// fence and the rally points, and decode to the same plan.
void TestPlanFile::fenceAndRallyGoToPlanBytes()
{
    for (const QString& name : {QStringLiteral("fence-rally.plan"), QStringLiteral("route.kml")}) {
        const MissionPlan plan = load(name);
        QString error;
        const auto bytes = plan.encode(&error);
        QVERIFY2(bytes, qPrintable(error));
        QCOMPARE(int(quint8(bytes->at(0))), 2);
        const auto back = MissionPlan::fromBytes(*bytes, &error);
        QVERIFY2(back, qPrintable(error));
        QCOMPARE(back->fencePolygons, plan.fencePolygons);
        QCOMPARE(back->fenceCircles, plan.fenceCircles);
        QCOMPARE(back->rallyPoints, plan.rallyPoints);
        QVERIFY(samePlan(*back, plan));
    }
}

// The plan bytes' fixed point (1e-7 degree): what the aircraft gets.
qint64 steps(const std::optional<double>& degrees)
{
    return degrees ? qRound64(*degrees * MissionPlan::kDegreeSteps) : -1;
}

// A .plan in QGroundControl 4's layout with each complex item it writes:
// the mission items are those QGroundControl uploads (QGroundControl's
// LandingComplexItem, TransectStyleComplexItem and StructureScanComplexItem
// appendMissionItems).
void TestPlanFile::qgcComplexItemsAsQgcFliesThem()
{
    const MissionPlan plan = load(QStringLiteral("complex-items.plan"));
    QCOMPARE(plan.items.size(), 43);
    for (qsizetype i = 0; i < plan.items.size(); ++i)
        QCOMPARE(plan.items[i].seq, quint16(i));
    QCOMPARE(plan.items[0].command, quint16(22));

    // The survey (items 2..15): the 14 items QGroundControl saved with it, as saved.
    QCOMPARE(plan.items[1].command, quint16(16));
    QCOMPARE(plan.items[1].latitude, 52.21);
    QCOMPARE(plan.items[1].longitude, 0.119853);
    QCOMPARE(plan.items[1].altitude, 50.0);
    QVERIFY(std::isnan(plan.items[1].params[3]));
    QCOMPARE(plan.items[2].command, quint16(206));
    QCOMPARE(plan.items[2].params, (std::array<double, 4>{25, 0, 1, 0}));
    QCOMPARE(plan.items[13].latitude, 52.2105);
    QCOMPARE(plan.items[13].longitude, 0.121613);
    QCOMPARE(plan.items[14].command, quint16(206));
    QCOMPARE(plan.items[14].params[0], 0.0);

    // The structure scan (items 16..33): the 20 m square moved 10 m out,
    // entered at its first vertex at 40 m, two layers at 10 and 20 m (5 to
    // 25 m in layers of 10), the camera every 15 m.
    const qint64 flightLatitudes[4] = {522109102, 522112698, 522112698, 522109102};
    const qint64 flightLongitudes[4] = {1148534, 1148534, 1154366, 1154366};
    const auto isFlightVertex = [&](const MissionItem& item, int vertex, double altitude) {
        return item.command == 16 && item.frame == 3 && steps(item.latitude) == flightLatitudes[vertex] &&
               steps(item.longitude) == flightLongitudes[vertex] && item.altitude == altitude &&
               std::isnan(item.params[3]);
    };
    QVERIFY(isFlightVertex(plan.items[15], 0, 40));
    QCOMPARE(plan.items[16].command, quint16(196));  // DO_SET_ROI_WPNEXT_OFFSET
    QCOMPARE(plan.items[16].frame, quint8(2));
    QCOMPARE(plan.items[16].latitude, 0.0);   // param5: the gimbal pitch
    QCOMPARE(plan.items[16].altitude, 90.0);  // param7: the yaw offset towards the structure
    for (int layer = 0; layer < 2; ++layer) {
        const int first = 17 + layer * 7;
        const double altitude = 10 + 10 * layer;
        QVERIFY(isFlightVertex(plan.items[first], 0, altitude));
        QCOMPARE(plan.items[first + 1].command, quint16(206));
        QCOMPARE(plan.items[first + 1].params, (std::array<double, 4>{15, 0, 1, 0}));
        for (int v = 1; v <= 4; ++v)
            QVERIFY2(isFlightVertex(plan.items[first + 1 + v], v % 4, altitude), qPrintable(QString::number(v)));
        QCOMPARE(plan.items[first + 6].command, quint16(206));
        QCOMPARE(plan.items[first + 6].params, (std::array<double, 4>{0, 0, 0, 0}));
    }
    QCOMPARE(plan.items[31].command, quint16(197));  // DO_SET_ROI_NONE
    QVERIFY(isFlightVertex(plan.items[32], 0, 40));
    // 10 m out from each side: the first vertex 10 m south and 10 m west of the structure's.
    const double metresSouth = (52.211 - *plan.items[32].latitude) * 6371008.8 * std::numbers::pi / 180;
    const double metresWest = (0.115 - *plan.items[32].longitude) * 6371008.8 * std::numbers::pi / 180 *
                              std::cos(52.211 * std::numbers::pi / 180);
    QVERIFY2(std::abs(metresSouth - 10) < 0.05 && std::abs(metresWest - 10) < 0.05,
             qPrintable(QStringLiteral("%1 m south, %2 m west").arg(metresSouth).arg(metresWest)));

    // The corridor scan (items 34..38), as saved.
    QCOMPARE(plan.items[33].latitude, 52.2095);
    QCOMPARE(plan.items[34].params[0], 20.0);
    QCOMPARE(plan.items[37].command, quint16(206));

    // The landing pattern (items 39..43): DO_LAND_START, stop taking photos,
    // loiter down to the approach altitude anticlockwise, land.
    const MissionItem& start = plan.items[38];
    QCOMPARE(start.command, quint16(189));
    QCOMPARE(start.frame, quint8(2));
    QCOMPARE(start.params, (std::array<double, 4>{0, 0, 0, 0}));
    QCOMPARE(start.latitude, 0.0);
    QCOMPARE(start.altitude, 0.0);
    QCOMPARE(plan.items[39].command, quint16(206));
    QCOMPARE(plan.items[39].params, (std::array<double, 4>{0, 0, 0, 0}));
    QCOMPARE(plan.items[40].command, quint16(2001));
    QCOMPARE(plan.items[40].params[0], 0.0);
    QVERIFY(std::isnan(plan.items[40].params[1]) && !plan.items[40].latitude && !plan.items[40].altitude);
    const MissionItem& approach = plan.items[41];
    QCOMPARE(approach.command, quint16(31));
    QCOMPARE(approach.frame, quint8(3));
    QCOMPARE(approach.params, (std::array<double, 4>{1, -75, 0, 1}));
    QCOMPARE(approach.latitude, 52.208);
    QCOMPARE(approach.longitude, 0.11);
    QCOMPARE(approach.altitude, double(45.3f));  // QGroundControl gives it as a float
    const MissionItem& land = plan.items[42];
    QCOMPARE(land.command, quint16(21));
    QCOMPARE(land.frame, quint8(3));
    QCOMPARE(land.params, (std::array<double, 4>{0, 0, 0, 0}));
    QCOMPARE(land.latitude, 52.208);
    QCOMPARE(land.longitude, 0.114);
    QCOMPARE(land.altitude, 0.0);

    // Every one of them goes into the plan bytes.
    QString error;
    QVERIFY2(plan.encode(&error), qPrintable(error));
}

// Version 1 of the fixed-wing pattern (an altitude reference for each
// point: both relative to home when they differ), a waypoint instead of the
// loiter, video stopped; the VTOL pattern lands with VTOL_LAND, yaw unset.
void TestPlanFile::qgcLandingPatternVersions()
{
    const auto plan = [](const QByteArray& item) {
        QString error;
        const auto read = QgcPlanFile::read(R"({"fileType": "Plan", "mission": {"items": [)" + item + "]}}",
                                            QStringLiteral("l.plan"), &error);
        if (!read)
            qFatal("%s", qPrintable(error));
        return *read;
    };
    const MissionPlan v1 = plan(R"({"type": "ComplexItem", "complexItemType": "fwLandingPattern", "version": 1,
        "loiterAltitudeRelative": false, "landAltitudeRelative": false,
        "loiterCoordinate": [-35.36, 149.16, 120.5], "landCoordinate": [-35.37, 149.17, 584],
        "loiterRadius": 60, "loiterClockwise": true, "useLoiterToAlt": false, "stopVideoPhotos": true})");
    QCOMPARE(v1.items.size(), 4);
    QCOMPARE(v1.items[0].command, quint16(189));
    QCOMPARE(v1.items[1].command, quint16(2501));  // VIDEO_STOP_CAPTURE
    QCOMPARE(v1.items[2].command, quint16(16));
    QCOMPARE(v1.items[2].frame, quint8(0));  // both absolute
    QCOMPARE(v1.items[2].params[0], 0.0);
    QVERIFY(std::isnan(v1.items[2].params[3]));
    QCOMPARE(v1.items[2].altitude, 120.5);
    QCOMPARE(v1.items[3].frame, quint8(0));
    QCOMPARE(v1.items[3].altitude, 584.0);

    const MissionPlan mixed = plan(R"({"type": "ComplexItem", "complexItemType": "fwLandingPattern", "version": 1,
        "loiterAltitudeRelative": false, "landAltitudeRelative": true,
        "loiterCoordinate": [-35.36, 149.16, 120], "landCoordinate": [-35.37, 149.17, 0],
        "loiterRadius": 60, "loiterClockwise": true})");
    QCOMPARE(mixed.items.size(), 3);
    QCOMPARE(mixed.items[1].command, quint16(31));
    QCOMPARE(mixed.items[1].params[1], 60.0);  // clockwise: positive
    QCOMPARE(mixed.items[1].frame, quint8(3));
    QCOMPARE(mixed.items[2].frame, quint8(3));

    const MissionPlan vtol = plan(R"({"type": "ComplexItem", "complexItemType": "vtolLandingPattern", "version": 1,
        "altitudesAreRelative": true, "landingApproachCoordinate": [47.1, 8.5, 30],
        "landCoordinate": [47.101, 8.5, 0], "loiterRadius": 40, "loiterClockwise": true})");
    QCOMPARE(vtol.items.size(), 3);
    QCOMPARE(vtol.items[2].command, quint16(85));
    QVERIFY(std::isnan(vtol.items[2].params[3]));
    QCOMPARE(vtol.items[2].latitude, 47.101);
}

void TestPlanFile::qgcComplexRefusals_data()
{
    QTest::addColumn<QByteArray>("json");
    QTest::addColumn<QString>("error");
    QTest::newRow("unknown type") << QByteArray(R"({"fileType": "Plan", "mission": {"items": [
        {"type": "ComplexItem", "complexItemType": "Spiral"}]}})")
                                  << QStringLiteral(
                                         "p.plan: line 2: mission item 1 is a complex item of type \"Spiral\", "
                                         "which this console does not read (it reads fwLandingPattern, "
                                         "vtolLandingPattern, survey, CorridorScan and StructureScan)");
    QTest::newRow("survey of QGroundControl 3.3") << QByteArray(R"({"fileType": "Plan", "mission": {"items": [
        {"type": "SimpleItem", "command": 22, "frame": 3, "params": [0, 0, 0, null, 1, 2, 30]},
        {"type": "ComplexItem", "complexItemType": "survey", "version": 3, "grid": {}}]}})")
                                                  << QStringLiteral(
                                                         "p.plan: line 3: mission item 2 (a survey) has no "
                                                         "\"TransectStyleComplexItem\" with the waypoints "
                                                         "QGroundControl saved: it is in QGroundControl 3.3's "
                                                         "layout; open the plan in a later QGroundControl and save "
                                                         "it again");
    QTest::newRow("survey item") << QByteArray(R"({"fileType": "Plan", "mission": {"items": [
        {"type": "ComplexItem", "complexItemType": "survey", "version": 5,
         "TransectStyleComplexItem": {"version": 2, "Items": [
            {"type": "SimpleItem", "command": 16, "frame": 3, "params": [0, 0, 0, null, 1, 2, 30]},
            {"type": "SimpleItem", "command": 16, "frame": 3,
             "params": [0, 0, 0, null, 1, 200, 30]}]}}]}})")
                                 << QStringLiteral(
                                        "p.plan: line 5: mission item 1 (a survey), its item 2: latitude must be "
                                        "within +-90 and longitude within +-180 degrees");
    QTest::newRow("corridor without items") << QByteArray(R"({"fileType": "Plan", "mission": {"items": [
        {"type": "ComplexItem", "complexItemType": "CorridorScan", "version": 3,
         "TransectStyleComplexItem": {"version": 2,
                                      "Items": []}}]}})")
                                            << QStringLiteral(
                                                   "p.plan: line 4: mission item 1 (a corridor scan) holds no "
                                                   "waypoints (\"Items\"): QGroundControl saves them with a "
                                                   "complete pattern; open the plan in QGroundControl, finish the "
                                                   "pattern and save it again");
    QTest::newRow("landing speed change") << QByteArray(R"({"fileType": "Plan", "mission": {"items": [
        {"type": "ComplexItem", "complexItemType": "fwLandingPattern", "version": 2, "altitudesAreRelative": true,
         "useDoChangeSpeed": true, "finalApproachSpeed": 18}]}})")
                                          << QStringLiteral(
                                                 "p.plan: line 3: mission item 1 (a fixed-wing landing pattern) "
                                                 "changes speed on the final approach (\"useDoChangeSpeed\"), a "
                                                 "QGroundControl 5 option whose item this console cannot place as "
                                                 "QGroundControl does; switch it off in QGroundControl, or put a "
                                                 "DO_CHANGE_SPEED item before the pattern");
    QTest::newRow("landing without radius") << QByteArray(R"({"fileType": "Plan", "mission": {"items": [
        {"type": "ComplexItem", "complexItemType": "fwLandingPattern", "version": 2, "altitudesAreRelative": true,
         "landingApproachCoordinate": [1, 2, 3], "landCoordinate": [1, 2.01, 0],
         "loiterClockwise": true}]}})")
                                            << QStringLiteral(
                                                   "p.plan: line 2: mission item 1 (a fixed-wing landing pattern): "
                                                   "\"loiterRadius\" must be a number");
    QTest::newRow("landing coordinate") << QByteArray(R"({"fileType": "Plan", "mission": {"items": [
        {"type": "ComplexItem", "complexItemType": "fwLandingPattern", "version": 2, "altitudesAreRelative": true,
         "landingApproachCoordinate": [1, 2],
         "landCoordinate": [1, 2.01, 0], "loiterRadius": 60, "loiterClockwise": true}]}})")
                                        << QStringLiteral(
                                               "p.plan: line 3: mission item 1 (a fixed-wing landing pattern): "
                                               "\"landingApproachCoordinate\" must be [latitude, longitude, "
                                               "altitude]");
    QTest::newRow("landing version") << QByteArray(R"({"fileType": "Plan", "mission": {"items": [
        {"type": "ComplexItem", "complexItemType": "vtolLandingPattern",
         "version": 2}]}})")
                                     << QStringLiteral(
                                            "p.plan: line 3: mission item 1 (a VTOL landing pattern) is in version 2, "
                                            "which QGroundControl does not load");
    const QByteArray structure = R"({"fileType": "Plan", "mission": {"items": [
        {"type": "ComplexItem", "complexItemType": "StructureScan", "version": 3,
         "CameraCalc": {"AdjustedFootprintFrontal": 10, "AdjustedFootprintSide": 15, "DistanceToSurface": 10},
         "EntranceAltitude": 40, "GimbalPitch": 0, "ScanBottomAlt": 5, "StartFromTop": false, "StructureHeight": 25,
         "polygon": [[52.211, 0.115], [52.21118, 0.115], [52.21136, 0.115],
                     [52.211, 0.11529]]}]}})";
    QTest::newRow("structure vertex in line")
        << structure
        << QStringLiteral(
               "p.plan: line 5: mission item 1 (a structure scan): structure vertex 2 is in line with its "
               "neighbours, so the flight path around the structure cannot be drawn (QGroundControl would fly the "
               "structure's own outline); remove the vertex in QGroundControl");
    QByteArray v2 = structure;
    v2.replace(R"("version": 3)", R"("version": 2)");
    QTest::newRow("structure version 2") << v2
                                         << QStringLiteral(
                                                "p.plan: line 2: mission item 1 (a structure scan) is in version 2; "
                                                "QGroundControl loads only version 3: draw it again in "
                                                "QGroundControl and save the plan");
    QByteArray noCamera = structure;
    noCamera.replace(R"("AdjustedFootprintFrontal": 10, )", "");
    QTest::newRow("structure camera") << noCamera
                                      << QStringLiteral(
                                             "p.plan: line 3: mission item 1 (a structure scan): "
                                             "\"AdjustedFootprintFrontal\" must be a number");
}

void TestPlanFile::qgcComplexRefusals()
{
    QFETCH(QByteArray, json);
    QFETCH(QString, error);
    QCOMPARE(readError(&QgcPlanFile::read, json, QStringLiteral("p.plan")), error);
}

// A fence saved on its own (MAVProxy's fence save; Mission Planner's fence
// file): a fence, not a flight path; no home line.
void TestPlanFile::waypointsFenceOnly()
{
    const MissionPlan plan = load(QStringLiteral("fence-only.waypoints"));
    QVERIFY(plan.items.isEmpty());
    QVERIFY(!plan.homeLatitude && !plan.home());
    QCOMPARE(plan.fencePolygons.size(), 2);
    QCOMPARE(plan.fencePolygons[0].inclusion, true);
    QCOMPARE(plan.fencePolygons[0].vertices,
             (QList<GeoPoint>{{52.2001, 0.1102}, {52.2203, 0.1105}, {52.2208, 0.1401}, {52.1999, 0.1398}}));
    QCOMPARE(plan.fencePolygons[1].inclusion, false);
    QCOMPARE(plan.fencePolygons[1].vertices,
             (QList<GeoPoint>{{52.2101, 0.1201}, {52.2121, 0.1203}, {52.2111, 0.1222}}));
    QCOMPARE(plan.fenceCircles.size(), 1);
    QCOMPARE(plan.fenceCircles[0], (FenceCircle{false, {52.2079, 0.1312}, 150.5}));
    QVERIFY(plan.rallyPoints.isEmpty());  // and the return point (5000) has no place in a plan
    QCOMPARE(plan.format(), 2);
}

void TestPlanFile::waypointsRallyPoints()
{
    QString error;
    const auto plan = WaypointsFile::read(
        "QGC WPL 110\n"
        "0\t0\t3\t5100\t0\t0\t0\t0\t52.21\t0.12\t80\t1\n"
        "1\t0\t3\t5100\t0\t0\t0\t0\t52.22\t0.13\t100.5\t1\n",
        QStringLiteral("r.waypoints"), &error);
    QVERIFY2(plan, qPrintable(error));
    QVERIFY(plan->items.isEmpty() && !plan->homeLatitude);
    QCOMPARE(plan->rallyPoints, (QList<RallyPoint>{{{52.21, 0.12}, 80}, {{52.22, 0.13}, 100.5}}));
}

// Mission Planner writes a home of 0, 0 until it knows one: no home.
void TestPlanFile::waypointsHomeAtZeroIsNoHome()
{
    QString error;
    const auto plan = WaypointsFile::read(
        "QGC WPL 110\n"
        "0\t1\t0\t16\t0\t0\t0\t0\t0\t0\t0\t1\n"
        "1\t0\t3\t22\t15\t0\t0\t0\t0\t0\t80\t1\n"
        "2\t0\t3\t16\t0\t0\t0\t0\t52.21\t0.12\t100\t1\n",
        QStringLiteral("m.waypoints"), &error);
    QVERIFY2(plan, qPrintable(error));
    QVERIFY(!plan->homeLatitude && !plan->homeLongitude && !plan->homeAltitude);
    QVERIFY(!plan->home());
    QCOMPARE(plan->items.size(), 2);
    QVERIFY(!plan->items[0].hasPosition());  // the takeoff climbs where it is
    QVERIFY(plan->items[0].hasAltitude());
    QVERIFY(plan->items[1].hasPosition());
    // A real home stays one.
    const MissionPlan planner = load(QStringLiteral("MissionPlanner.waypoints"));
    QCOMPARE(planner.home(), (std::optional<GeoPoint>(GeoPoint{47.660459, -122.103167})));
}

void TestPlanFile::waypointsFenceRefusals_data()
{
    QTest::addColumn<QByteArray>("text");
    QTest::addColumn<QString>("error");
    QTest::newRow("polygon cut short") << QByteArray(
                                              "QGC WPL 110\n"
                                              "0\t0\t0\t5001\t4\t0\t0\t0\t52.20\t0.11\t0\t1\n"
                                              "1\t0\t0\t5001\t4\t0\t0\t0\t52.22\t0.11\t0\t1\n"
                                              "2\t0\t0\t5001\t4\t0\t0\t0\t52.22\t0.14\t0\t1\n"
                                              "3\t0\t0\t5002\t3\t0\t0\t0\t52.21\t0.12\t0\t1\n")
                                       << QStringLiteral(
                                              "f.waypoints: line 5: fence polygon 1 (from line 2) has 3 of the 4 "
                                              "vertices its lines give as param1; a polygon's vertices follow one "
                                              "another");
    QTest::newRow("polygon at the end") << QByteArray(
                                               "QGC WPL 110\n"
                                               "0\t0\t0\t5002\t3\t0\t0\t0\t52.20\t0.11\t0\t1\n"
                                               "1\t0\t0\t5002\t3\t0\t0\t0\t52.22\t0.11\t0\t1\n")
                                        << QStringLiteral(
                                               "f.waypoints: fence polygon 1 (from line 2) has 2 of the 3 vertices "
                                               "its lines give as param1; a polygon's vertices follow one another");
    QTest::newRow("two vertices") << QByteArray(
                                         "QGC WPL 110\n"
                                         "0\t0\t0\t5001\t2\t0\t0\t0\t52.20\t0.11\t0\t1\n")
                                  << QStringLiteral(
                                         "f.waypoints: line 2, field 5 (param1): a fence polygon's vertex count is "
                                         "2; it must be a whole number, 3 or more");
    QTest::newRow("circle radius") << QByteArray(
                                          "QGC WPL 110\n"
                                          "0\t0\t0\t5003\t0\t0\t0\t0\t52.20\t0.11\t0\t1\n")
                                   << QStringLiteral(
                                          "f.waypoints: line 2, field 5 (param1): a fence circle's radius is 0 m; it "
                                          "must be more than 0 and at most 4294 km");
    QTest::newRow("vertex off the globe")
        << QByteArray(
               "QGC WPL 110\n"
               "0\t0\t2\t5001\t3\t0\t0\t0\t95\t0.11\t0\t1\n")
        << QStringLiteral("f.waypoints: line 2, field 9 (latitude): 95 is outside \u00b190");
}

void TestPlanFile::waypointsFenceRefusals()
{
    QFETCH(QByteArray, text);
    QFETCH(QString, error);
    QCOMPARE(readError(&WaypointsFile::read, text, QStringLiteral("f.waypoints")), error);
}

// Mission Planner's names (MAVLink's without MAV_CMD_ and NAV_), and which
// fields each command uses.
void TestPlanFile::commandsNamedAsPlannersNameThem()
{
    MissionItem item;
    item.frame = 3;
    item.latitude = 52.2;
    item.longitude = 0.12;
    item.altitude = 80;
    const auto named = [&](int command) {
        item.command = quint16(command);
        return item.commandName();
    };
    QCOMPARE(named(205), QStringLiteral("DO_MOUNT_CONTROL"));
    QCOMPARE(named(16), QStringLiteral("WAYPOINT"));
    QCOMPARE(named(20), QStringLiteral("RETURN_TO_LAUNCH"));
    QCOMPARE(named(22), QStringLiteral("TAKEOFF"));
    QCOMPARE(named(2000), QStringLiteral("IMAGE_START_CAPTURE"));
    QCOMPARE(named(31000), QStringLiteral("MAV_CMD 31000"));
    QCOMPARE(MavCommand::mavlinkNameOf(205), QStringLiteral("MAV_CMD_DO_MOUNT_CONTROL (205)"));
    QCOMPARE(MavCommand::mavlinkNameOf(21), QStringLiteral("MAV_CMD_NAV_LAND (21)"));
    // A RETURN_TO_LAUNCH in a global frame has neither place nor altitude;
    // a DO_LAND_START a place and no altitude; a command not known, what its frame says.
    item.command = 20;
    QVERIFY(!item.hasPosition() && !item.hasAltitude());
    item.command = 189;
    QVERIFY(item.hasPosition() && !item.hasAltitude());
    item.command = 31000;
    QVERIFY(item.hasPosition() && item.hasAltitude());
    item.frame = 2;
    QVERIFY(!item.hasPosition() && !item.hasAltitude());
}

void TestPlanFile::rallyPointsOutsideTheFenceFlagged()
{
    MissionPlan plan = load(QStringLiteral("fence-rally.plan"));
    QCOMPARE(plan.fenceViolations(), QStringList());
    plan.rallyPoints.append({{52.25, 0.12}, 60});      // north of the inclusion polygon
    plan.rallyPoints.append({{52.2079, 0.1312}, 60});  // in the exclusion circle
    QCOMPARE(plan.fenceViolations(), (QStringList{QStringLiteral("rally point 3 is outside every inclusion area"),
                                                  QStringLiteral("rally point 4 is inside exclusion circle 1")}));
}

QTEST_GUILESS_MAIN(TestPlanFile)
#include "tst_planfile.moc"
