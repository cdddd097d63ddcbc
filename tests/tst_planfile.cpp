// Plan files of other programs: QGroundControl .plan and .mission,
// Mission Planner / ArduPilot QGC WPL 110, KML. Real files under
// tests/data/plans (tests/data/plans/README.md says where each comes from),
// small broken ones inline.
#include "link/plan/KmlFile.h"
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

QTEST_GUILESS_MAIN(TestPlanFile)
#include "tst_planfile.moc"
