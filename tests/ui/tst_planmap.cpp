// The plan map: Web Mercator's numbers, and PlanMapView as an operator uses
// it (fit, select, drag, add, delete, zoom) and as it paints without tiles.

#include "ui/plan/PlanMapView.h"
#include "ui/plan/WebMercator.h"

#include <QApplication>
#include <QBuffer>
#include <QMenu>
#include <QSet>
#include <QSignalSpy>
#include <QSqlDatabase>
#include <QSqlError>
#include <QSqlQuery>
#include <QTemporaryDir>
#include <QTimer>
#include <QToolButton>
#include <QtTest>

namespace {

MissionItem waypoint(quint16 seq, quint16 command, double latitude, double longitude, double altitude)
{
    MissionItem item;
    item.seq = seq;
    item.command = command;
    item.frame = 3;  // global, relative altitude
    item.latitude = latitude;
    item.longitude = longitude;
    item.altitude = altitude;
    return item;
}

MissionItem withoutPosition(quint16 seq, quint16 command)
{
    MissionItem item;
    item.seq = seq;
    item.command = command;
    item.frame = 2;  // a mission command, no place
    return item;
}

// resources/plans/sample.plan's mission and home, with a fence and rally
// points around it.
MissionPlan samplePlan()
{
    MissionPlan plan;
    plan.items = {
        waypoint(0, 22, 52.2093412, 0.1189255, 60),
        waypoint(1, 16, 52.2151260, 0.1302118, 120),
        withoutPosition(2, 178),
        waypoint(3, 16, 52.2236903, 0.1468470, 120),
        waypoint(4, 16, 52.2183077, 0.1701564, 150),
        waypoint(5, 19, 52.2069450, 0.1652006, 150),
        waypoint(6, 16, 52.2012587, 0.1397749, 100),
        waypoint(7, 16, 52.2050035, 0.1230921, 80),
        withoutPosition(8, 20),
    };
    plan.homeLatitude = 52.2076813;
    plan.homeLongitude = 0.1145627;
    plan.homeAltitude = 14.2;
    plan.fencePolygons = {
        {true, {{52.1985, 0.1080}, {52.2280, 0.1080}, {52.2280, 0.1790}, {52.1985, 0.1790}}},
        {false, {{52.2110, 0.1430}, {52.2140, 0.1440}, {52.2135, 0.1520}, {52.2108, 0.1505}}},
    };
    plan.fenceCircles = {{false, {52.2140, 0.1590}, 200}};
    plan.rallyPoints = {{{52.2115, 0.1175}, 40}, {{52.2025, 0.1610}, 40}};
    return plan;
}

// Two fence squares side by side and nothing else: their insides are only fill.
MissionPlan fenceOnlyPlan()
{
    MissionPlan plan;
    plan.fencePolygons = {
        {true, {{52.200, 0.100}, {52.210, 0.100}, {52.210, 0.115}, {52.200, 0.115}}},
        {false, {{52.200, 0.125}, {52.210, 0.125}, {52.210, 0.140}, {52.200, 0.140}}},
    };
    return plan;
}

void sendMouse(QWidget* widget, QEvent::Type type, const QPointF& pos, Qt::MouseButton button, Qt::MouseButtons buttons)
{
    QMouseEvent event(type, pos, widget->mapToGlobal(pos), button, buttons, Qt::NoModifier);
    QApplication::sendEvent(widget, &event);
}

// A left-button drag in steps, as a hand moves a mouse.
void drag(QWidget* widget, const QPointF& from, const QPointF& to)
{
    sendMouse(widget, QEvent::MouseButtonPress, from, Qt::LeftButton, Qt::LeftButton);
    for (int step = 1; step <= 4; ++step)
        sendMouse(widget, QEvent::MouseMove, from + (to - from) * step / 4.0, Qt::NoButton, Qt::LeftButton);
    sendMouse(widget, QEvent::MouseButtonRelease, to, Qt::LeftButton, Qt::NoButton);
}

void wheel(QWidget* widget, const QPointF& pos, int angle)
{
    QWheelEvent event(pos, widget->mapToGlobal(pos), QPoint(), QPoint(0, angle), Qt::NoButton, Qt::NoModifier,
                      Qt::NoScrollPhase, false);
    QApplication::sendEvent(widget, &event);
}

GeoPoint itemPoint(const MissionPlan& plan, int index)
{
    return {*plan.items[index].latitude, *plan.items[index].longitude};
}

bool greenish(QRgb pixel)
{
    return qGreen(pixel) > qRed(pixel) + 10 && qGreen(pixel) > qBlue(pixel) + 10;
}

bool reddish(QRgb pixel)
{
    return qRed(pixel) > qGreen(pixel) + 10 && qRed(pixel) > qBlue(pixel) + 10;
}

// How many of the pixels in a square of 9 x 9 around `centre` pass `test`.
int countAround(const QImage& image, const QPoint& centre, bool (*test)(QRgb))
{
    int count = 0;
    for (int dy = -4; dy <= 4; ++dy) {
        for (int dx = -4; dx <= 4; ++dx)
            count += test(image.pixel(centre + QPoint(dx, dy))) ? 1 : 0;
    }
    return count;
}

// Every signal by which the view asks for a change to the plan.
struct PlanRequests {
    explicit PlanRequests(PlanMapView* view)
        : moves(view, &PlanMapView::moveRequested),
          adds(view, &PlanMapView::addRequested),
          deletes(view, &PlanMapView::deleteRequested),
          altitudes(view, &PlanMapView::altitudeRequested)
    {
    }
    int total() const { return int(moves.count() + adds.count() + deletes.count() + altitudes.count()); }
    QSignalSpy moves;
    QSignalSpy adds;
    QSignalSpy deletes;
    QSignalSpy altitudes;
};

}  // namespace

class TestPlanMap : public QObject {
    Q_OBJECT

private slots:
    void initTestCase() { qRegisterMetaType<GeoPoint>("GeoPoint"); }

    void mercatorKnownValues()
    {
        QCOMPARE(WebMercator::toWorld({0, 0}, 0), QPointF(128, 128));
        QCOMPARE(WebMercator::toWorld({0, -180}, 0).x(), 0.0);
        QCOMPARE(WebMercator::toWorld({0, 180}, 1).x(), 512.0);
        QVERIFY(std::abs(WebMercator::toWorld({WebMercator::kMaxLatitude, 0}, 0).y()) < 1e-9);
        QVERIFY(std::abs(WebMercator::toWorld({-WebMercator::kMaxLatitude, 0}, 0).y() - 256) < 1e-9);
        // Beyond the square's edge: on the edge.
        QCOMPARE(WebMercator::toWorld({89.9, 0}, 0).y(), WebMercator::toWorld({WebMercator::kMaxLatitude, 0}, 0).y());
        QCOMPARE(WebMercator::worldSize(0), 256.0);
        QCOMPARE(WebMercator::worldSize(10), 262144.0);
        QVERIFY(qFuzzyCompare(WebMercator::worldSize(1.5), 256 * std::sqrt(8.0)));
        // Central London is OpenStreetMap's tile 10/511/340, Sydney's 10/942/614.
        QCOMPARE(WebMercator::tileAt({51.5074, -0.1278}, 10), QPoint(511, 340));
        QCOMPARE(WebMercator::tileAt({-33.8688, 151.2093}, 10), QPoint(942, 614));
        QCOMPARE(WebMercator::tileAt({0, 0}, 0), QPoint(0, 0));
        QCOMPARE(WebMercator::tileAt({0.001, 0.001}, 1), QPoint(1, 0));
        QCOMPARE(WebMercator::tileAt({85.05, 179.99}, 3), QPoint(7, 0));
        // 2 pi 6378137 / 256 at the equator; half that at 60 degrees; a
        // quarter at the next zoom but one.
        QVERIFY(std::abs(WebMercator::metresPerPixel(0, 0) - 156543.03392804097) < 1e-8);
        QVERIFY(std::abs(WebMercator::metresPerPixel(60, 0) - 78271.51696402048) < 1e-6);
        QVERIFY(std::abs(WebMercator::metresPerPixel(0, 2) - 39135.75848201024) < 1e-8);
        QVERIFY(std::abs(WebMercator::metresPerPixel(-60, 0) - 78271.51696402048) < 1e-6);
    }

    void mercatorRoundTrip()
    {
        const GeoPoint points[] = {{0, 0}, {52.2093412, 0.1189255}, {-33.8688, 151.2093}, {84.9, -179.9}, {-70, 42}};
        for (double zoom : {0.0, 3.5, 10.0, 17.25, 19.0}) {
            for (const GeoPoint& point : points) {
                const GeoPoint back = WebMercator::toGeo(WebMercator::toWorld(point, zoom), zoom);
                QVERIFY2(std::abs(back.latitude - point.latitude) < 1e-9, qPrintable(QString::number(zoom)));
                QVERIFY2(std::abs(back.longitude - point.longitude) < 1e-9, qPrintable(QString::number(zoom)));
            }
        }
        // A step of one pixel is metresPerPixel metres, near enough, along a parallel.
        const double zoom = 15;
        const QPointF world = WebMercator::toWorld({45, 7}, zoom);
        const GeoPoint east = WebMercator::toGeo(world + QPointF(1, 0), zoom);
        const double metres =
            (east.longitude - 7) * std::numbers::pi / 180 * WebMercator::kEarthRadius * std::cos(std::numbers::pi / 4);
        QVERIFY(std::abs(metres - WebMercator::metresPerPixel(45, zoom)) < 1e-6);
    }

    void viewRoundTrip()
    {
        PlanMapView view;
        view.resize(500, 400);
        const MissionPlan plan = samplePlan();
        view.setPlan(&plan);
        for (const QPointF& pos : {QPointF(0, 0), QPointF(250, 200), QPointF(499.5, 13.25), QPointF(-40, 700)}) {
            const QPointF back = view.posOf(view.geoAt(pos));
            QVERIFY(std::abs(back.x() - pos.x()) < 1e-6 && std::abs(back.y() - pos.y()) < 1e-6);
        }
        const GeoPoint place{52.21, 0.13};
        const GeoPoint back = view.geoAt(view.posOf(place));
        QVERIFY(std::abs(back.latitude - place.latitude) < 1e-9);
        QVERIFY(std::abs(back.longitude - place.longitude) < 1e-9);
        const QPointF middle = view.posOf(view.centre());
        QVERIFY(std::abs(middle.x() - 250) < 1e-6 && std::abs(middle.y() - 200) < 1e-6);
    }

    void fitShowsTheWholePlan()
    {
        PlanMapView view;
        view.resize(600, 400);
        const MissionPlan plan = samplePlan();
        view.setPlan(&plan);
        auto allInside = [&] {
            const QRectF area = QRectF(view.rect()).adjusted(10, 10, -10, -10);
            QList<GeoPoint> points{{*plan.homeLatitude, *plan.homeLongitude}};
            for (const MissionItem& item : plan.items) {
                if (item.hasPosition())
                    points.append({*item.latitude, *item.longitude});
            }
            for (const FencePolygon& polygon : plan.fencePolygons)
                points += polygon.vertices;
            for (const RallyPoint& rally : plan.rallyPoints)
                points.append(rally.position);
            for (const GeoPoint& point : points) {
                if (!area.contains(view.posOf(point)))
                    return false;
            }
            return true;
        };
        QVERIFY(allInside());
        // Not a speck in the middle: the plan fills most of one direction.
        const QPointF west = view.posOf({52.2, 0.1080});
        const QPointF east = view.posOf({52.2, 0.1790});
        QVERIFY(east.x() - west.x() > 400 || view.posOf({52.1985, 0.11}).y() - view.posOf({52.228, 0.11}).y() > 280);

        // The first layout gives the view its size after the plan: fitted again.
        view.show();
        QVERIFY(QTest::qWaitForWindowExposed(&view));
        view.resize(1000, 800);
        QVERIFY(allInside());
        QVERIFY(view.posOf({52.2, 0.1790}).x() - view.posOf({52.2, 0.1080}).x() > 700 ||
                view.posOf({52.1985, 0.11}).y() - view.posOf({52.228, 0.11}).y() > 600);

        // Zoomed by the operator, an edit does not throw the view back.
        wheel(&view, QPointF(100, 100), 240);
        const double zoom = view.zoom();
        const GeoPoint centre = view.centre();
        view.planChanged();
        QCOMPARE(view.zoom(), zoom);
        QCOMPARE(view.centre(), centre);
        view.resize(900, 700);
        QCOMPARE(view.zoom(), zoom);
        // Fit (the button) brings it back.
        view.findChild<QToolButton*>(QStringLiteral("fit"))->click();
        QVERIFY(allInside());
    }

    void fitWithoutAPlace()
    {
        PlanMapView view;
        view.resize(400, 300);
        view.setPlan(nullptr);
        QCOMPARE(view.zoom(), PlanMapView::kMinZoom);
        MissionPlan one;
        one.items = {waypoint(0, 16, 47.0, 8.0, 100)};
        view.setPlan(&one);
        // One point: 50 m each way (kMinFitExtent) in the 216 px left of 300
        // between the margins, 36 px above and 48 px below (clear of the scale bar).
        QCOMPARE(view.zoom(), std::log2(216 / (PlanMapView::kMinFitExtent / WebMercator::metresPerPixel(47.0, 0))));
        const QPointF pos = view.posOf(itemPoint(one, 0));
        QVERIFY2(std::abs(pos.x() - 200) < 1e-6 && std::abs(pos.y() - 144) < 1e-6,
                 qPrintable(QStringLiteral("%1, %2").arg(pos.x()).arg(pos.y())));
        // A new, empty plan: the view stays where the operator looks.
        wheel(&view, QPointF(50, 60), -240);
        const double zoom = view.zoom();
        const GeoPoint centre = view.centre();
        const MissionPlan empty;
        view.setPlan(&empty);
        QCOMPARE(view.zoom(), zoom);
        QCOMPARE(view.centre(), centre);
        view.fitToPlan();
        QCOMPARE(view.zoom(), zoom);
    }

    // A 100 m by 60 m survey fills the view: its height takes the whole room
    // between the margins, its width nearly all (kMaxFitZoom of 17 left it
    // 132 px wide).
    void fitFillsTheViewWithASmallPlan()
    {
        PlanMapView view;
        view.resize(600, 400);
        MissionPlan survey;
        survey.items = {waypoint(0, 16, 52.21, 0.12, 50), waypoint(1, 16, 52.21, 0.121466, 50),
                        waypoint(2, 16, 52.21054, 0.121466, 50), waypoint(3, 16, 52.21054, 0.12, 50)};
        view.setPlan(&survey);
        const double width = view.posOf({52.21, 0.121466}).x() - view.posOf({52.21, 0.12}).x();
        const double height = view.posOf({52.21, 0.12}).y() - view.posOf({52.21054, 0.12}).y();
        QVERIFY2(std::abs(height - (400 - 36 - 48)) < 1e-6, qPrintable(QString::number(height)));
        QVERIFY2(width > 520 && width < 600 - 72, qPrintable(QString::number(width)));
        QVERIFY(view.zoom() < PlanMapView::kMaxZoom);
    }

    // A map squeezed to 100 px high keeps the plan as large as it can: 15 px
    // above (a marker and a little), 25 px below (a quarter of the height,
    // towards the scale bar's 48), not 36 px each side that left it 28 px.
    void fitOnASmallMap()
    {
        PlanMapView view;
        view.resize(400, 100);
        MissionPlan square;
        square.items = {waypoint(0, 16, 52.20, 0.12, 50), waypoint(1, 16, 52.21, 0.12, 50)};
        view.setPlan(&square);
        QVERIFY2(std::abs(view.posOf({52.21, 0.12}).y() - 15) < 1e-6,
                 qPrintable(QString::number(view.posOf({52.21, 0.12}).y())));
        QVERIFY2(std::abs(view.posOf({52.20, 0.12}).y() - 75) < 1e-6,
                 qPrintable(QString::number(view.posOf({52.20, 0.12}).y())));
    }

    // Mission Planner's home at 0, 0 is no home: the view fits the waypoints,
    // not the world between them and the Gulf of Guinea.
    void homeAtZeroIsNotFitted()
    {
        MissionPlan plan;
        plan.items = {waypoint(0, 16, 52.2151260, 0.1302118, 120), waypoint(1, 16, 52.2236903, 0.1468470, 120)};
        PlanMapView homeless;
        homeless.resize(600, 400);
        homeless.setPlan(&plan);
        plan.homeLatitude = 0;
        plan.homeLongitude = 0;
        plan.homeAltitude = 0;
        PlanMapView view;
        view.resize(600, 400);
        view.setPlan(&plan);
        QCOMPARE(view.zoom(), homeless.zoom());
        QCOMPARE(view.centre(), homeless.centre());
        QVERIFY(view.zoom() > 12);
    }

    void clickSelectsAMarker()
    {
        PlanMapView view;
        view.resize(600, 400);
        const MissionPlan plan = samplePlan();
        view.setPlan(&plan);
        view.setEditable(true);
        QSignalSpy selected(&view, &PlanMapView::itemSelected);
        PlanRequests requests(&view);
        QCOMPARE(view.selectedItem(), -1);

        QTest::mouseClick(&view, Qt::LeftButton, Qt::NoModifier, view.posOf(itemPoint(plan, 4)).toPoint());
        QCOMPARE(selected.count(), 1);
        QCOMPARE(selected.at(0).at(0).toInt(), 4);
        QCOMPARE(view.selectedItem(), 4);
        // A click, with a twitch of the hand, is not a move.
        drag(&view, view.posOf(itemPoint(plan, 6)), view.posOf(itemPoint(plan, 6)) + QPointF(2, 1));
        QCOMPARE(selected.count(), 2);
        QCOMPARE(selected.at(1).at(0).toInt(), 6);
        QCOMPARE(requests.total(), 0);

        // Set from outside (the table): nothing comes back.
        view.setSelectedItem(1);
        QCOMPARE(view.selectedItem(), 1);
        QCOMPARE(selected.count(), 2);
        view.setSelectedItem(42);
        QCOMPARE(view.selectedItem(), -1);
    }

    void dragAsksForAMove()
    {
        PlanMapView view;
        view.resize(600, 400);
        const MissionPlan plan = samplePlan();
        view.setPlan(&plan);
        view.setEditable(true);
        PlanRequests requests(&view);
        const QPointF from = view.posOf(itemPoint(plan, 3));
        const QPointF to = from + QPointF(40, -25);
        const GeoPoint expected = view.geoAt(to);

        // While held, the marker is drawn where the hand is and nothing is asked.
        sendMouse(&view, QEvent::MouseButtonPress, from, Qt::LeftButton, Qt::LeftButton);
        sendMouse(&view, QEvent::MouseMove, to, Qt::NoButton, Qt::LeftButton);
        QCOMPARE(requests.total(), 0);
        const QImage held = view.grab().toImage();
        QCOMPARE(QColor(held.pixel((to + QPointF(-7, 0)).toPoint())), PlanMapView::kSelectedColour);
        sendMouse(&view, QEvent::MouseButtonRelease, to, Qt::LeftButton, Qt::NoButton);

        QCOMPARE(requests.moves.count(), 1);
        QCOMPARE(requests.total(), 1);
        QCOMPARE(requests.moves.at(0).at(0).toInt(), 3);
        const auto moved = requests.moves.at(0).at(1).value<GeoPoint>();
        QVERIFY(std::abs(moved.latitude - expected.latitude) < 1e-9);
        QVERIFY(std::abs(moved.longitude - expected.longitude) < 1e-9);
        // Pixels to degrees at this zoom: east and north of where it was.
        QVERIFY(moved.longitude > *plan.items[3].longitude);
        QVERIFY(moved.latitude > *plan.items[3].latitude);
        // The view did not move with it.
        QCOMPARE(view.posOf(itemPoint(plan, 3)), from);

        // Dragged away and brought back: no move.
        sendMouse(&view, QEvent::MouseButtonPress, from, Qt::LeftButton, Qt::LeftButton);
        sendMouse(&view, QEvent::MouseMove, from + QPointF(30, 0), Qt::NoButton, Qt::LeftButton);
        sendMouse(&view, QEvent::MouseButtonRelease, from + QPointF(1, 0), Qt::LeftButton, Qt::NoButton);
        QCOMPARE(requests.moves.count(), 1);
    }

    void dragOnEmptyMapPans()
    {
        PlanMapView view;
        view.resize(600, 400);
        const MissionPlan plan = samplePlan();
        view.setPlan(&plan);
        view.setEditable(true);
        PlanRequests requests(&view);
        const QPointF empty(300, 380);
        const GeoPoint under = view.geoAt(empty);
        drag(&view, empty, empty + QPointF(-100, -60));
        QCOMPARE(requests.total(), 0);
        const QPointF now = view.posOf(under);
        QVERIFY(std::abs(now.x() - (empty.x() - 100)) < 1e-6);
        QVERIFY(std::abs(now.y() - (empty.y() - 60)) < 1e-6);
    }

    void doubleClickAsksForAWaypoint()
    {
        PlanMapView view;
        view.resize(600, 400);
        const MissionPlan plan = samplePlan();
        view.setPlan(&plan);
        view.setEditable(true);
        PlanRequests requests(&view);
        const QPoint empty(280, 370);
        const GeoPoint expected = view.geoAt(empty);
        QTest::mouseDClick(&view, Qt::LeftButton, Qt::NoModifier, empty);
        QCOMPARE(requests.adds.count(), 1);
        QCOMPARE(requests.total(), 1);
        const auto at = requests.adds.at(0).at(0).value<GeoPoint>();
        QVERIFY(std::abs(at.latitude - expected.latitude) < 1e-9);
        QVERIFY(std::abs(at.longitude - expected.longitude) < 1e-9);

        // On a marker it is a click.
        QTest::mouseDClick(&view, Qt::LeftButton, Qt::NoModifier, view.posOf(itemPoint(plan, 5)).toPoint());
        QCOMPARE(requests.adds.count(), 1);
        QCOMPARE(view.selectedItem(), 5);
    }

    void deleteKeyAsksToDelete()
    {
        PlanMapView view;
        view.resize(600, 400);
        const MissionPlan plan = samplePlan();
        view.setPlan(&plan);
        view.setEditable(true);
        PlanRequests requests(&view);
        QTest::keyClick(&view, Qt::Key_Delete);
        QCOMPARE(requests.total(), 0);  // nothing selected
        view.setSelectedItem(2);
        QTest::keyClick(&view, Qt::Key_Delete);
        QCOMPARE(requests.deletes.count(), 1);
        QCOMPARE(requests.deletes.at(0).at(0).toInt(), 2);
        QCOMPARE(requests.total(), 1);
    }

    void contextMenuAsksForAltitude()
    {
        PlanMapView view;
        view.resize(600, 400);
        const MissionPlan plan = samplePlan();
        view.setPlan(&plan);
        view.setEditable(true);
        view.show();
        QVERIFY(QTest::qWaitForWindowExposed(&view));
        PlanRequests requests(&view);
        QSignalSpy selected(&view, &PlanMapView::itemSelected);
        const QPoint pos = view.posOf(itemPoint(plan, 7)).toPoint();
        bool menuSeen = false;
        // The menu runs its own loop: choose from inside it.
        QTimer::singleShot(0, &view, [&] {
            auto* menu = view.findChild<QMenu*>();
            if (!menu)
                return;
            menuSeen = true;
            QCOMPARE(menu->actions().size(), 1);
            QVERIFY(menu->actions().at(0)->text().startsWith(QStringLiteral("Change altitude")));
            menu->setActiveAction(menu->actions().at(0));
            QTest::keyClick(menu, Qt::Key_Return);
        });
        QContextMenuEvent event(QContextMenuEvent::Mouse, pos, view.mapToGlobal(pos));
        QApplication::sendEvent(&view, &event);
        QVERIFY(menuSeen);
        QCOMPARE(requests.altitudes.count(), 1);
        QCOMPARE(requests.altitudes.at(0).at(0).toInt(), 7);
        QCOMPARE(requests.total(), 1);
        QCOMPARE(view.selectedItem(), 7);
        QCOMPARE(selected.count(), 1);
    }

    void notEditableOnlySelects()
    {
        PlanMapView view;
        view.resize(600, 400);
        const MissionPlan plan = samplePlan();
        view.setPlan(&plan);
        QVERIFY(!view.isEditable());  // until the owner says it handles requests
        view.show();
        QVERIFY(QTest::qWaitForWindowExposed(&view));
        QSignalSpy selected(&view, &PlanMapView::itemSelected);
        PlanRequests requests(&view);

        const QPointF marker = view.posOf(itemPoint(plan, 3));
        drag(&view, marker, marker + QPointF(50, 40));
        QCOMPARE(selected.count(), 1);
        QCOMPARE(view.selectedItem(), 3);
        QTest::mouseDClick(&view, Qt::LeftButton, Qt::NoModifier, QPoint(280, 370));
        QTest::keyClick(&view, Qt::Key_Delete);
        bool menuSeen = false;
        QTimer::singleShot(0, &view, [&] {
            if (auto* menu = view.findChild<QMenu*>()) {
                menuSeen = true;
                menu->close();
            }
        });
        const QPoint pos = view.posOf(itemPoint(plan, 3)).toPoint();
        QContextMenuEvent event(QContextMenuEvent::Mouse, pos, view.mapToGlobal(pos));
        QApplication::sendEvent(&view, &event);
        QVERIFY(!menuSeen);
        QCOMPARE(requests.total(), 0);
    }

    void wheelOnlyZooms()
    {
        PlanMapView view;
        view.resize(600, 400);
        const MissionPlan plan = samplePlan();
        view.setPlan(&plan);
        view.setEditable(true);
        view.setSelectedItem(4);
        QSignalSpy selected(&view, &PlanMapView::itemSelected);
        PlanRequests requests(&view);
        const double zoom = view.zoom();

        // Over a marker, as a stray wheel would be.
        const QPointF over = view.posOf(itemPoint(plan, 4));
        wheel(&view, over, 120);
        QCOMPARE(view.zoom(), zoom + 0.5);
        // About the cursor: the marker stays under it.
        const QPointF still = view.posOf(itemPoint(plan, 4));
        QVERIFY(std::abs(still.x() - over.x()) < 1e-6 && std::abs(still.y() - over.y()) < 1e-6);
        wheel(&view, QPointF(10, 10), -360);
        QCOMPARE(view.zoom(), zoom - 1);
        for (int i = 0; i < 100; ++i)
            wheel(&view, QPointF(300, 200), 120);
        QCOMPARE(view.zoom(), PlanMapView::kMaxZoom);
        for (int i = 0; i < 100; ++i)
            wheel(&view, QPointF(300, 200), -120);
        QCOMPARE(view.zoom(), PlanMapView::kMinZoom);

        QCOMPARE(selected.count(), 0);
        QCOMPARE(requests.total(), 0);
        QCOMPARE(view.selectedItem(), 4);
    }

    void zoomKeysAndButtons()
    {
        PlanMapView view;
        view.resize(600, 400);
        const MissionPlan plan = samplePlan();
        view.setPlan(&plan);
        view.setEditable(true);
        PlanRequests requests(&view);
        const double zoom = view.zoom();
        const GeoPoint centre = view.centre();
        QTest::keyClick(&view, Qt::Key_Plus);
        QCOMPARE(view.zoom(), std::floor(zoom) + 1);
        view.findChild<QToolButton*>(QStringLiteral("zoomIn"))->click();
        QCOMPARE(view.zoom(), std::floor(zoom) + 2);
        QTest::keyClick(&view, Qt::Key_Minus);
        view.findChild<QToolButton*>(QStringLiteral("zoomOut"))->click();
        QCOMPARE(view.zoom(), std::floor(zoom));
        // About the middle: the centre stays.
        QVERIFY(std::abs(view.centre().latitude - centre.latitude) < 1e-9);
        QVERIFY(std::abs(view.centre().longitude - centre.longitude) < 1e-9);
        QTest::keyClick(&view, Qt::Key_F);
        QCOMPARE(view.zoom(), zoom);
        QCOMPARE(requests.total(), 0);
    }

    void gridAndFenceWithoutTiles()
    {
        PlanMapView view;
        view.resize(600, 400);
        view.setTiles(nullptr);
        const MissionPlan plan = fenceOnlyPlan();
        view.setPlan(&plan);
        const QImage image = view.grab().toImage();
        QCOMPARE(image.size(), QSize(600, 400) * image.devicePixelRatio());

        // The inclusion square green inside, the exclusion square red.
        const QPoint inclusion = view.posOf({52.205, 0.1075}).toPoint();
        const QPoint exclusion = view.posOf({52.205, 0.1325}).toPoint();
        QVERIFY(countAround(image, inclusion, greenish) > 60);
        QVERIFY(countAround(image, exclusion, reddish) > 60);
        // Between them, neither.
        const QPoint between = view.posOf({52.205, 0.1175}).toPoint();
        QCOMPARE(countAround(image, between, greenish), 0);
        QCOMPARE(countAround(image, between, reddish), 0);

        // The grid: lines across the empty map, not one flat colour.
        QSet<QRgb> colours;
        for (int x = 0; x < image.width(); ++x)
            colours.insert(image.pixel(x, between.y()));
        QVERIFY(colours.size() >= 2);
        const QRgb blank = image.pixel(between);
        int gridPixels = 0;
        for (int y = 0; y < image.height() - 40; ++y)
            gridPixels += image.pixel(between.x(), y) != blank ? 1 : 0;
        QVERIFY(gridPixels > 0);
    }

    void emptyViewIsAGrid()
    {
        PlanMapView view;
        view.resize(400, 300);
        const QImage image = view.grab().toImage();
        QSet<QRgb> colours;
        for (int y = 0; y < image.height(); y += 3) {
            for (int x = 0; x < image.width(); x += 3)
                colours.insert(image.pixel(x, y));
        }
        QVERIFY(colours.size() > 3);
    }

    void tilesUnderThePlan()
    {
        // An MBTiles file with one tile of one colour, at zoom 10, where the
        // view will look.
        const GeoPoint place{52.2053, 0.1218};
        const QPoint tile = WebMercator::tileAt(place, 10);
        const QColor tileColour(200, 30, 200);
        QTemporaryDir dir;
        QVERIFY(dir.isValid());
        const QString path = dir.filePath(QStringLiteral("one.mbtiles"));
        {
            QImage image(256, 256, QImage::Format_RGB32);
            image.fill(tileColour);
            QByteArray png;
            QBuffer buffer(&png);
            buffer.open(QIODevice::WriteOnly);
            QVERIFY(image.save(&buffer, "PNG"));
            QSqlDatabase database = QSqlDatabase::addDatabase(QStringLiteral("QSQLITE"), QStringLiteral("tst_planmap"));
            database.setDatabaseName(path);
            QVERIFY2(database.open(), qPrintable(database.lastError().text()));
            QSqlQuery query(database);
            for (const char* sql :
                 {"CREATE TABLE metadata (name TEXT, value TEXT)",
                  "CREATE TABLE tiles (zoom_level INTEGER, tile_column INTEGER, tile_row INTEGER, "
                  "tile_data BLOB)",
                  "INSERT INTO metadata VALUES ('name', 'one tile')", "INSERT INTO metadata VALUES ('format', 'png')",
                  "INSERT INTO metadata VALUES ('minzoom', '10')", "INSERT INTO metadata VALUES ('maxzoom', '10')",
                  "INSERT INTO metadata VALUES ('attribution', 'Test tiles')"})
                QVERIFY2(query.exec(QString::fromLatin1(sql)), qPrintable(query.lastError().text()));
            QVERIFY(query.prepare(QStringLiteral("INSERT INTO tiles VALUES (10, ?, ?, ?)")));
            query.addBindValue(tile.x());
            query.addBindValue((1 << 10) - 1 - tile.y());  // MBTiles rows count from the south
            query.addBindValue(png);
            QVERIFY2(query.exec(), qPrintable(query.lastError().text()));
            query.clear();
            database.close();
        }
        QSqlDatabase::removeDatabase(QStringLiteral("tst_planmap"));

        MapTiles tiles;
        QSignalSpy sourceChanged(&tiles, &MapTiles::sourceChanged);
        QSignalSpy arrived(&tiles, &MapTiles::tileArrived);
        TileSettings settings;
        settings.mbtilesPath = path;
        tiles.configure(settings);
        QTRY_COMPARE(sourceChanged.count(), 1);
        QCOMPARE(tiles.source(), MapTiles::Source::MbTiles);

        // Looking at the middle of that tile at zoom 10.
        PlanMapView view;
        view.resize(600, 400);
        view.setTiles(&tiles);
        MissionPlan plan;
        plan.items = {waypoint(0, 16, 0, 0, 100)};
        const GeoPoint middle = WebMercator::toGeo(QPointF((tile.x() + 0.5) * 256, (tile.y() + 0.5) * 256), 10);
        plan.items[0].latitude = middle.latitude;
        plan.items[0].longitude = middle.longitude;
        view.setPlan(&plan);
        while (view.zoom() > 10)
            QTest::keyClick(&view, Qt::Key_Minus);
        QCOMPARE(view.zoom(), 10.0);

        view.grab();  // asks for the tiles in sight
        QTRY_VERIFY(!arrived.isEmpty());
        QCOMPARE(arrived.at(0).at(0).value<TileId>(), (TileId{10, tile.x(), tile.y()}));
        const QImage image = view.grab().toImage();
        // Inside the tile, off the marker: the tile's colour.
        const QPoint inside = view.posOf(middle).toPoint() + QPoint(60, 40);
        QCOMPARE(QColor(image.pixel(inside)), tileColour);
        // Beyond it the file has nothing: the grid shows there.
        const QPoint beyond = view.posOf(middle).toPoint() + QPoint(-200, 0);
        QVERIFY(QColor(image.pixel(beyond)) != tileColour);
        // The provider's attribution, on its box at the bottom right.
        QCOMPARE(tiles.attribution(), QStringLiteral("Test tiles"));
        QVERIFY(QColor(image.pixel(image.width() - 3, image.height() - 3)) != tileColour);
        const QString screenshot = qEnvironmentVariable("PLANMAP_SCREENSHOT");
        if (!screenshot.isEmpty())
            image.save(QFileInfo(screenshot).path() + QStringLiteral("/planmap-tile.png"));
    }

    // Not a check: a picture of the sample plan for people to look at, when
    // PLANMAP_SCREENSHOT names a file.
    void screenshot()
    {
        const QString path = qEnvironmentVariable("PLANMAP_SCREENSHOT");
        if (path.isEmpty())
            QSKIP("PLANMAP_SCREENSHOT not set");
        PlanMapView view;
        view.resize(900, 600);
        const MissionPlan plan = samplePlan();
        view.setPlan(&plan);
        view.setSelectedItem(3);
        QVERIFY(view.grab().save(path));
    }
};

QTEST_MAIN(TestPlanMap)
#include "tst_planmap.moc"
