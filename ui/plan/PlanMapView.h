#pragma once

// The flight plan on a map: mission items with a position as numbered
// markers joined in mission order, home ("H"), the geofence (inclusion in
// green, exclusion in hatched red) and the rally points ("R"), over map tiles
// in Web Mercator (ui/plan/WebMercator.h). Where a tile has not arrived, or
// there is no tile source at all, a grid of latitude and longitude lines
// shows instead, so the pane is never empty. A scale bar, and the tile
// provider's attribution, at the bottom.
//
// The view is the operator's to move: the wheel zooms about the cursor, a
// left drag on empty map pans, + and - (buttons or keys) zoom, "Fit" (or F)
// shows the whole plan. None of that touches the plan.
//
// The widget never edits the plan: it asks. When editable, dragging a marker
// previews it at the cursor and asks for the move on release
// (moveRequested), a double click on empty map asks for a new waypoint there
// (addRequested), Delete asks to remove the selected item, a marker's
// context menu asks to change its altitude. The owner edits the MissionPlan
// and calls planChanged(). Editing is off until setEditable(true).

#include "link/plan/MissionPlan.h"
#include "link/maptiles/MapTiles.h"

#include <QColor>
#include <QHash>
#include <QPixmap>
#include <QPointF>
#include <QPointer>
#include <QPolygonF>
#include <QWidget>

#include <optional>

class QToolButton;

class PlanMapView : public QWidget {
    Q_OBJECT

public:
    explicit PlanMapView(QWidget* parent = nullptr);
    ~PlanMapView() override;

    // The view's zoom range. The grid works at any zoom; the tile source's own
    // range only decides which tiles are scaled to fill the view.
    static constexpr double kMinZoom = 2;
    static constexpr double kMaxZoom = 19;
    // Fit shows at least this many metres each way: a plan of one point, or
    // a tiny one, with some ground around it; a 100 m survey fills the view.
    static constexpr double kMinFitExtent = 50;
    // A press and release closer than this is a click, not a move.
    static constexpr int kMoveThreshold = 4;

    static const QColor kPathColour;
    static const QColor kSelectedColour;
    static const QColor kHomeColour;
    static const QColor kRallyColour;
    static const QColor kInclusionColour;
    static const QColor kExclusionColour;

    QSize sizeHint() const override;
    QSize minimumSizeHint() const override;

    // nullptr: grid only. Not owned.
    void setTiles(MapTiles* tiles);
    // Not owned; it must outlive this view or be replaced first. Fits the view
    // to it. nullptr: no plan.
    void setPlan(const MissionPlan* plan);
    // The plan was edited: draws it again, the view stays where it is.
    void planChanged();
    // Index into plan->items, -1 for none; emits nothing.
    void setSelectedItem(int index);
    int selectedItem() const { return m_selected; }
    // false (the default): clicks only select, nothing moves.
    void setEditable(bool editable);
    bool isEditable() const { return m_editable; }

    // Shows the plan's items, home, fence and rally points as large as the
    // view holds them (at least kMinFitExtent metres across, at most
    // kMaxZoom); with nothing to show the view stays.
    void fitToPlan();
    void zoomIn();
    void zoomOut();

    double zoom() const { return m_zoom; }
    GeoPoint centre() const;
    GeoPoint geoAt(const QPointF& widgetPos) const;
    QPointF posOf(const GeoPoint& point) const;

signals:
    void itemSelected(int index);                // the operator clicked a marker
    void moveRequested(int index, GeoPoint to);  // a marker dragged and released (editable only)
    void addRequested(GeoPoint at);              // a double click on empty map (editable only)
    void deleteRequested(int index);             // Delete with an item selected (editable only)
    void altitudeRequested(int index);           // "Change altitude…" on a marker (editable only)

protected:
    void paintEvent(QPaintEvent* event) override;
    void resizeEvent(QResizeEvent* event) override;
    void mousePressEvent(QMouseEvent* event) override;
    void mouseMoveEvent(QMouseEvent* event) override;
    void mouseReleaseEvent(QMouseEvent* event) override;
    void mouseDoubleClickEvent(QMouseEvent* event) override;
    void wheelEvent(QWheelEvent* event) override;
    void keyPressEvent(QKeyEvent* event) override;
    void contextMenuEvent(QContextMenuEvent* event) override;

private:
    // The plan projected once at zoom 0 (world pixels of a 256-pixel world),
    // so that painting at any zoom is a multiplication, not trigonometry.
    struct Geometry {
        QList<std::optional<QPointF>> items;  // per plan item; none without a position
        std::optional<QPointF> home;
        struct Polygon {
            bool inclusion = true;
            QPolygonF vertices;
        };
        QList<Polygon> polygons;
        struct Circle {
            bool inclusion = true;
            QPointF centre;
            double radius = 0;  // zoom-0 pixels at the circle's latitude
        };
        QList<Circle> circles;
        QList<QPointF> rally;
        QRectF bounds;  // of everything above (a point's has no size)
        bool hasBounds = false;
    };
    // A marker pressed and perhaps being dragged.
    struct MarkerDrag {
        int index = -1;
        QPointF pressPos;
        QPointF markerPos;   // the marker's centre at the press
        QPointF currentPos;  // where the marker is drawn while dragged
        bool moved = false;
    };
    struct Pan {
        QPointF pressPos;
        QPointF centre0;
    };

    void rebuildGeometry();
    void setView(double zoom, const QPointF& centre0);
    void zoomAbout(double newZoom, const QPointF& anchor);
    QPointF toWidget(const QPointF& world0) const;  // zoom-0 world pixels to widget
    int markerAt(const QPointF& pos) const;
    QPointF markerPos(int index) const;  // drawn position: the drag preview while dragged
    void placeButtons();
    void updateButtons();
    void tileArrived(const TileId& id);
    void tileSourceChanged();

    void paintTiles(QPainter& p);
    void paintGrid(QPainter& p);
    void paintFence(QPainter& p);
    void paintMission(QPainter& p);
    void paintScaleBar(QPainter& p);
    void paintAttribution(QPainter& p);

    QPointer<MapTiles> m_tiles;
    const MissionPlan* m_plan = nullptr;
    Geometry m_geometry;
    int m_selected = -1;
    bool m_editable = false;
    double m_zoom = kMinZoom;
    QPointF m_centre0;  // the view's centre in zoom-0 world pixels
    // The view shows the fit and the operator has not moved it: a resize
    // (the first layout, a larger window) fits again.
    bool m_fitted = false;
    std::optional<MarkerDrag> m_drag;
    std::optional<Pan> m_pan;
    int m_tileZoom = -1;  // the whole zoom of the tiles last painted
    QHash<TileId, QPixmap> m_tilePixmaps;
    QToolButton* m_zoomInButton;
    QToolButton* m_zoomOutButton;
    QToolButton* m_fitButton;
};
