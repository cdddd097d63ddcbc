#include "ui/plan/PlanMapView.h"

#include "ui/plan/WebMercator.h"

#include <QContextMenuEvent>
#include <QKeyEvent>
#include <QMenu>
#include <QMouseEvent>
#include <QPainter>
#include <QSet>
#include <QPainterPath>
#include <QToolButton>
#include <QWheelEvent>

#include <algorithm>
#include <array>
#include <cmath>

namespace {

constexpr double kMarkerRadius = 11;
// Pixels around the plan's outermost points after a fit: room for a marker
// and its number, and for the buttons' corner.
constexpr double kFitMargin = 36;
// Pixels below the lowest marker's centre that keep it clear of the scale
// bar (35 px from the bottom) and the attribution.
constexpr double kScaleBarRoom = 35 + kMarkerRadius + 2;
// A wheel notch zooms by half a step: two notches double the scale.
constexpr double kWheelZoomPerNotch = 0.5;
// Tiles are scaled from the nearest whole zoom; beyond this many zoom
// steps of overscaling they are blocks, and the grid says more.
constexpr int kMaxTileOverscale = 4;
// Pixmaps of the tiles drawn, kept while the tile zoom stays: a pan over a
// few screens' worth re-uses them; more than this starts afresh.
constexpr qsizetype kMaxTilePixmaps = 400;
// Lines of the grid at least this far apart.
constexpr double kMinGridSpacing = 90;
constexpr int kScaleBarMaxWidth = 140;

QPointF zoomZeroWorld(const GeoPoint& point)
{
    return WebMercator::toWorld(point, 0);
}

// "52.21°N", "0.12°W"; the equator and the prime meridian are just "0°".
QString degreesLabel(double value, int decimals, QChar positive, QChar negative)
{
    const QString number = QString::number(std::abs(value), 'f', decimals);
    if (number.toDouble() == 0)
        return QStringLiteral("0\u00b0");
    return number + QChar(0x00b0) + (value > 0 ? positive : negative);
}

// Round lengths for the scale bar: 1, 2 and 5 times a power of ten metres.
double roundLength(double maxMetres)
{
    const double power = std::pow(10.0, std::floor(std::log10(maxMetres)));
    for (double mantissa : {5.0, 2.0, 1.0}) {
        if (mantissa * power <= maxMetres)
            return mantissa * power;
    }
    return power;
}

QString lengthLabel(double metres)
{
    if (metres >= 1000)
        return QStringLiteral("%1 km").arg(metres / 1000, 0, 'g', 6);
    if (metres >= 1)
        return QStringLiteral("%1 m").arg(metres, 0, 'g', 6);
    return QStringLiteral("%1 cm").arg(metres * 100, 0, 'g', 6);
}

QColor withAlpha(QColor colour, double alpha)
{
    colour.setAlphaF(float(alpha));
    return colour;
}

QFont scaledFont(QFont font, double factor, bool bold = false)
{
    if (font.pointSizeF() > 0)
        font.setPointSizeF(font.pointSizeF() * factor);
    else
        font.setPixelSize(std::max(6, int(font.pixelSize() * factor)));
    font.setBold(bold);
    return font;
}

enum class MarkerShape { Circle, Square, Diamond };

// A filled marker with a white rim (it reads on light tiles, dark tiles and
// the grid alike) and its label in the middle; wider than round for long
// numbers.
void drawMarker(QPainter& p, const QPointF& centre, const QString& label, const QColor& fill, const QColor& text,
                MarkerShape shape)
{
    const QFontMetricsF fm(p.font());
    const double halfWidth = std::max(kMarkerRadius, fm.horizontalAdvance(label) / 2 + 5);
    const QRectF box(centre.x() - halfWidth, centre.y() - kMarkerRadius, 2 * halfWidth, 2 * kMarkerRadius);
    p.setPen(QPen(Qt::white, 2));
    p.setBrush(fill);
    switch (shape) {
        case MarkerShape::Circle:
            p.drawRoundedRect(box, kMarkerRadius, kMarkerRadius);
            break;
        case MarkerShape::Square:
            p.drawRect(box.adjusted(1, 1, -1, -1));
            break;
        case MarkerShape::Diamond: {
            const double r = kMarkerRadius + 2;
            const QPolygonF diamond{{centre.x(), centre.y() - r},
                                    {centre.x() + std::max(r, halfWidth + 2), centre.y()},
                                    {centre.x(), centre.y() + r},
                                    {centre.x() - std::max(r, halfWidth + 2), centre.y()}};
            p.drawPolygon(diamond);
            break;
        }
    }
    p.setPen(text);
    p.drawText(box, Qt::AlignCenter, label);
}

// Text on a box of the window colour, mostly opaque: readable over tiles of
// any colour and over the grid.
QRectF drawBoxedText(QPainter& p, const QRectF& rect, const QString& text, const QPalette& palette)
{
    p.setPen(Qt::NoPen);
    p.setBrush(withAlpha(palette.color(QPalette::Window), 0.8));
    p.drawRect(rect);
    p.setPen(palette.color(QPalette::WindowText));
    p.drawText(rect.adjusted(4, 0, -4, 0), Qt::AlignCenter, text);
    return rect;
}

}  // namespace

// Blue and amber and red and green, as on other ground stations' maps;
// saturated enough to read on imagery, street maps and the grid.
const QColor PlanMapView::kPathColour = QColor(0x19, 0x76, 0xd2);
const QColor PlanMapView::kSelectedColour = QColor(0xff, 0xa0, 0x00);
const QColor PlanMapView::kHomeColour = QColor(0x2e, 0x3b, 0x43);
const QColor PlanMapView::kRallyColour = QColor(0x7b, 0x1f, 0xa2);
const QColor PlanMapView::kInclusionColour = QColor(0x2e, 0x7d, 0x32);
const QColor PlanMapView::kExclusionColour = QColor(0xd3, 0x2f, 0x2f);

PlanMapView::PlanMapView(QWidget* parent) : QWidget(parent)
{
    setObjectName(QStringLiteral("planMapView"));
    setAccessibleName(tr("Flight plan map"));
    setFocusPolicy(Qt::StrongFocus);
    setMouseTracking(true);  // the cursor tells a marker from empty map
    setAttribute(Qt::WA_OpaquePaintEvent);
    setSizePolicy(QSizePolicy::Expanding, QSizePolicy::Expanding);
    m_centre0 = zoomZeroWorld({20, 0});

    auto makeButton = [this](const QString& text, const QString& name, const QString& tip) {
        auto* button = new QToolButton(this);
        button->setText(text);
        button->setObjectName(name);
        button->setToolTip(tip);
        button->setAccessibleName(tip);
        // The keys stay with the map (Delete, + and -).
        button->setFocusPolicy(Qt::NoFocus);
        return button;
    };
    m_zoomInButton = makeButton(QStringLiteral("+"), QStringLiteral("zoomIn"), tr("Zoom in (+)"));
    m_zoomOutButton = makeButton(QStringLiteral("\u2212"), QStringLiteral("zoomOut"), tr("Zoom out (-)"));
    m_fitButton = makeButton(tr("Fit"), QStringLiteral("fit"), tr("Show the whole plan (F)"));
    connect(m_zoomInButton, &QToolButton::clicked, this, &PlanMapView::zoomIn);
    connect(m_zoomOutButton, &QToolButton::clicked, this, &PlanMapView::zoomOut);
    connect(m_fitButton, &QToolButton::clicked, this, &PlanMapView::fitToPlan);
    placeButtons();
    updateButtons();
}

PlanMapView::~PlanMapView() = default;

QSize PlanMapView::sizeHint() const
{
    // Modest: the plan shares the bottom of a 1366-pixel window with the frame log.
    return {360, 240};
}

QSize PlanMapView::minimumSizeHint() const
{
    return {240, 180};
}

void PlanMapView::setTiles(MapTiles* tiles)
{
    if (m_tiles == tiles)
        return;
    if (m_tiles)
        disconnect(m_tiles, nullptr, this, nullptr);
    m_tiles = tiles;
    if (m_tiles) {
        connect(m_tiles, &MapTiles::tileArrived, this, &PlanMapView::tileArrived);
        connect(m_tiles, &MapTiles::sourceChanged, this, &PlanMapView::tileSourceChanged);
    }
    tileSourceChanged();
}

void PlanMapView::setPlan(const MissionPlan* plan)
{
    m_plan = plan;
    m_selected = -1;
    m_drag.reset();
    rebuildGeometry();
    fitToPlan();
}

void PlanMapView::planChanged()
{
    rebuildGeometry();
    const qsizetype count = m_plan ? m_plan->items.size() : 0;
    if (m_selected >= count)
        m_selected = -1;
    if (m_drag && (m_drag->index >= count || !m_geometry.items[m_drag->index]))
        m_drag.reset();
    update();
}

void PlanMapView::setSelectedItem(int index)
{
    const qsizetype count = m_plan ? m_plan->items.size() : 0;
    const int selected = index >= 0 && index < count ? index : -1;
    if (selected == m_selected)
        return;
    m_selected = selected;
    update();
}

void PlanMapView::setEditable(bool editable)
{
    m_editable = editable;
    if (!editable && m_drag) {
        m_drag.reset();
        update();
    }
}

void PlanMapView::fitToPlan()
{
    // Nothing to show (no plan, a new empty one): the view stays where the
    // operator was looking, where the first waypoint is likely to go.
    const QRectF& bounds = m_geometry.bounds;
    if (!m_geometry.hasBounds)
        return;
    // On a small map the full margin would leave the plan a few pixels: at
    // most 15 % of each side, and never less than a marker needs; at the
    // bottom, clear of the scale bar, up to a quarter of the height.
    const auto margin = [](int size) { return std::clamp(0.15 * size, kMarkerRadius + 4, kFitMargin); };
    const double side = margin(width());
    const double top = margin(height());
    const double bottom = std::max(top, std::min(kScaleBarRoom, 0.25 * height()));
    const double availableWidth = std::max(1.0, width() - 2 * side);
    const double availableHeight = std::max(1.0, height() - top - bottom);
    // The least extent in zoom-0 pixels where the plan is.
    const double least =
        kMinFitExtent / WebMercator::metresPerPixel(WebMercator::toGeo(bounds.center(), 0).latitude, 0);
    const double scale =
        std::min(availableWidth / std::max(bounds.width(), least), availableHeight / std::max(bounds.height(), least));
    const double zoom = std::clamp(std::log2(scale), kMinZoom, kMaxZoom);
    // The plan in the middle of the room between the margins.
    setView(zoom, bounds.center() + QPointF(0, (bottom - top) / 2 / std::exp2(zoom)));
    m_fitted = true;
}

void PlanMapView::zoomIn()
{
    zoomAbout(std::floor(m_zoom + 1e-9) + 1, QPointF(width() / 2.0, height() / 2.0));
}

void PlanMapView::zoomOut()
{
    zoomAbout(std::ceil(m_zoom - 1e-9) - 1, QPointF(width() / 2.0, height() / 2.0));
}

GeoPoint PlanMapView::centre() const
{
    return WebMercator::toGeo(m_centre0, 0);
}

GeoPoint PlanMapView::geoAt(const QPointF& widgetPos) const
{
    const QPointF half(width() / 2.0, height() / 2.0);
    return WebMercator::toGeo(m_centre0 + (widgetPos - half) / std::exp2(m_zoom), 0);
}

QPointF PlanMapView::posOf(const GeoPoint& point) const
{
    return toWidget(zoomZeroWorld(point));
}

QPointF PlanMapView::toWidget(const QPointF& world0) const
{
    return (world0 - m_centre0) * std::exp2(m_zoom) + QPointF(width() / 2.0, height() / 2.0);
}

void PlanMapView::setView(double zoom, const QPointF& centre0)
{
    m_zoom = std::clamp(zoom, kMinZoom, kMaxZoom);
    const double size = WebMercator::kTileSize;
    m_centre0 = QPointF(std::clamp(centre0.x(), 0.0, size), std::clamp(centre0.y(), 0.0, size));
    m_fitted = false;
    updateButtons();
    update();
}

void PlanMapView::zoomAbout(double newZoom, const QPointF& anchor)
{
    // The place under the anchor stays under it.
    const QPointF half(width() / 2.0, height() / 2.0);
    const QPointF anchor0 = m_centre0 + (anchor - half) / std::exp2(m_zoom);
    const double zoom = std::clamp(newZoom, kMinZoom, kMaxZoom);
    setView(zoom, anchor0 - (anchor - half) / std::exp2(zoom));
}

void PlanMapView::rebuildGeometry()
{
    m_geometry = Geometry();
    if (!m_plan)
        return;
    double left = INFINITY, top = INFINITY, right = -INFINITY, bottom = -INFINITY;
    auto include = [&](const QPointF& point, double radius = 0) {
        left = std::min(left, point.x() - radius);
        right = std::max(right, point.x() + radius);
        top = std::min(top, point.y() - radius);
        bottom = std::max(bottom, point.y() + radius);
    };
    m_geometry.items.reserve(m_plan->items.size());
    for (const MissionItem& item : m_plan->items) {
        if (!item.hasPosition()) {
            m_geometry.items.append(std::nullopt);
            continue;
        }
        const QPointF world = zoomZeroWorld({*item.latitude, *item.longitude});
        m_geometry.items.append(world);
        include(world);
    }
    // A home at 0, 0 is none (MissionPlan::home()): no marker in the Gulf of
    // Guinea, and no fit to the whole world.
    if (const auto home = m_plan->home()) {
        m_geometry.home = zoomZeroWorld(*home);
        include(*m_geometry.home);
    }
    for (const FencePolygon& polygon : m_plan->fencePolygons) {
        Geometry::Polygon projected{polygon.inclusion, {}};
        projected.vertices.reserve(polygon.vertices.size());
        for (const GeoPoint& vertex : polygon.vertices) {
            projected.vertices.append(zoomZeroWorld(vertex));
            include(projected.vertices.back());
        }
        m_geometry.polygons.append(projected);
    }
    for (const FenceCircle& circle : m_plan->fenceCircles) {
        const Geometry::Circle projected{circle.inclusion, zoomZeroWorld(circle.centre),
                                         circle.radius / WebMercator::metresPerPixel(circle.centre.latitude, 0)};
        m_geometry.circles.append(projected);
        include(projected.centre, projected.radius);
    }
    for (const RallyPoint& rally : m_plan->rallyPoints) {
        m_geometry.rally.append(zoomZeroWorld(rally.position));
        include(m_geometry.rally.back());
    }
    if (left <= right) {
        m_geometry.bounds = QRectF(QPointF(left, top), QPointF(right, bottom));
        m_geometry.hasBounds = true;
    }
}

int PlanMapView::markerAt(const QPointF& pos) const
{
    const double reach = kMarkerRadius + 3;
    auto hits = [&](int index) {
        if (!m_geometry.items.value(index))
            return false;
        const QPointF d = markerPos(index) - pos;
        return d.x() * d.x() + d.y() * d.y() <= reach * reach;
    };
    // The selected marker is drawn on top, then the later ones over the earlier.
    if (m_selected >= 0 && hits(m_selected))
        return m_selected;
    for (int i = int(m_geometry.items.size()) - 1; i >= 0; --i) {
        if (hits(i))
            return i;
    }
    return -1;
}

QPointF PlanMapView::markerPos(int index) const
{
    if (m_drag && m_drag->index == index && m_drag->moved)
        return m_drag->currentPos;
    return toWidget(*m_geometry.items[index]);
}

void PlanMapView::placeButtons()
{
    const int size = std::max(26, fontMetrics().height() + 10);
    const int fitWidth = std::max(size, fontMetrics().horizontalAdvance(m_fitButton->text()) + 14);
    const int x = width() - fitWidth - 8;
    m_zoomInButton->setGeometry(x, 8, fitWidth, size);
    m_zoomOutButton->setGeometry(x, 8 + size + 2, fitWidth, size);
    m_fitButton->setGeometry(x, 8 + 2 * (size + 2) + 6, fitWidth, size);
}

void PlanMapView::updateButtons()
{
    m_zoomInButton->setEnabled(m_zoom < kMaxZoom);
    m_zoomOutButton->setEnabled(m_zoom > kMinZoom);
}

void PlanMapView::tileArrived(const TileId& id)
{
    if (id.z == m_tileZoom)
        update();
}

void PlanMapView::tileSourceChanged()
{
    m_tilePixmaps.clear();
    m_tileZoom = -1;
    update();
}

void PlanMapView::resizeEvent(QResizeEvent* event)
{
    QWidget::resizeEvent(event);
    placeButtons();
    // A plan fitted before the first layout (or into a smaller window) is
    // fitted again into the size it really has.
    if (m_fitted)
        fitToPlan();
}

// --- painting

void PlanMapView::paintEvent(QPaintEvent*)
{
    QPainter p(this);
    paintGrid(p);
    paintTiles(p);
    p.setRenderHint(QPainter::Antialiasing);
    paintFence(p);
    paintMission(p);
    paintScaleBar(p);
    paintAttribution(p);
}

void PlanMapView::paintGrid(QPainter& p)
{
    const QPalette& pal = palette();
    // Beyond the world's edges (the poles' cut, the antimeridian) the window's
    // own colour; the world in the base colour, as a blank sheet.
    p.fillRect(rect(), pal.color(QPalette::Window));
    const QRectF world(toWidget({0, 0}), toWidget({WebMercator::kTileSize, WebMercator::kTileSize}));
    const QRectF visibleWorld = world.intersected(QRectF(rect()));
    p.fillRect(visibleWorld, pal.color(QPalette::Base));

    static constexpr std::array kSteps{30.0,  20.0,  10.0,  5.0,    2.0,    1.0,    0.5,  0.2,  0.1,  0.05, 0.02, 0.01,
                                       0.005, 0.002, 0.001, 0.0005, 0.0002, 0.0001, 5e-5, 2e-5, 1e-5, 5e-6, 2e-6, 1e-6};
    const double pixelsPerDegree = WebMercator::worldSize(m_zoom) / 360;
    double step = kSteps.front();
    for (double candidate : kSteps) {
        if (candidate * pixelsPerDegree < kMinGridSpacing)
            break;
        step = candidate;
    }
    const int decimals = std::max(0, int(std::ceil(-std::log10(step) - 1e-9)));

    const GeoPoint topLeft = geoAt(visibleWorld.topLeft());
    const GeoPoint bottomRight = geoAt(visibleWorld.bottomRight());
    const QColor text = pal.color(QPalette::Text);
    const QPen linePen(withAlpha(text, 0.18), 1);
    const QColor labelColour = withAlpha(text, 0.65);
    p.setFont(scaledFont(font(), 0.85));
    const QFontMetricsF fm(p.font());

    // Meridians, labelled along the top edge, left of the buttons.
    const double labelsEnd = m_zoomInButton->geometry().left() - 4;
    const long long firstLon = std::llround(std::ceil(topLeft.longitude / step - 1e-9));
    const long long lastLon = std::llround(std::floor(bottomRight.longitude / step + 1e-9));
    for (long long k = firstLon; k <= lastLon; ++k) {
        const double longitude = double(k) * step;
        const double x = std::round(posOf({0, longitude}).x()) + 0.5;
        p.setPen(linePen);
        p.drawLine(QPointF(x, visibleWorld.top()), QPointF(x, visibleWorld.bottom()));
        const QString label = degreesLabel(longitude, decimals, QLatin1Char('E'), QLatin1Char('W'));
        if (x + 3 + fm.horizontalAdvance(label) > labelsEnd)
            continue;
        p.setPen(labelColour);
        p.drawText(QPointF(x + 3, visibleWorld.top() + fm.ascent() + 2), label);
    }
    // Parallels, labelled along the left edge.
    const long long firstLat = std::llround(std::ceil(bottomRight.latitude / step - 1e-9));
    const long long lastLat = std::llround(std::floor(topLeft.latitude / step + 1e-9));
    for (long long k = firstLat; k <= lastLat; ++k) {
        const double latitude = double(k) * step;
        const double y = std::round(posOf({latitude, 0}).y()) + 0.5;
        p.setPen(linePen);
        p.drawLine(QPointF(visibleWorld.left(), y), QPointF(visibleWorld.right(), y));
        p.setPen(labelColour);
        p.drawText(QPointF(visibleWorld.left() + 3, y - fm.descent() - 1),
                   degreesLabel(latitude, decimals, QLatin1Char('N'), QLatin1Char('S')));
    }
}

void PlanMapView::paintTiles(QPainter& p)
{
    if (!m_tiles || m_tiles->source() == MapTiles::Source::None)
        return;
    const int tileZoom =
        std::clamp(int(std::lround(m_zoom)), std::max(0, m_tiles->minZoom()), std::max(0, m_tiles->maxZoom()));
    // Far below the source's least zoom tiles would be many and tiny; far
    // above its greatest, blocks: the grid shows there.
    if (m_zoom < tileZoom - 1 || m_zoom > tileZoom + kMaxTileOverscale)
        return;
    if (tileZoom != m_tileZoom || m_tilePixmaps.size() > kMaxTilePixmaps) {
        m_tilePixmaps.clear();
        m_tileZoom = tileZoom;
    }
    const double tiles = std::exp2(tileZoom);
    const double tileSize0 = WebMercator::kTileSize / tiles;  // a tile in zoom-0 pixels
    const QPointF half(width() / 2.0, height() / 2.0);
    const double scale = std::exp2(m_zoom);
    const QPointF topLeft0 = m_centre0 - half / scale;
    const QPointF bottomRight0 = m_centre0 + half / scale;
    const int last = int(tiles) - 1;
    const int firstX = std::clamp(int(std::floor(topLeft0.x() / tileSize0)), 0, last);
    const int lastX = std::clamp(int(std::floor(bottomRight0.x() / tileSize0)), 0, last);
    const int firstY = std::clamp(int(std::floor(topLeft0.y() / tileSize0)), 0, last);
    const int lastY = std::clamp(int(std::floor(bottomRight0.y() / tileSize0)), 0, last);
    p.setRenderHint(QPainter::SmoothPixmapTransform, std::abs(m_zoom - tileZoom) > 1e-6);
    for (int y = firstY; y <= lastY; ++y) {
        for (int x = firstX; x <= lastX; ++x) {
            const TileId id{tileZoom, x, y};
            auto cached = m_tilePixmaps.constFind(id);
            if (cached == m_tilePixmaps.constEnd()) {
                const QImage image = m_tiles->tile(id);
                if (image.isNull())
                    continue;  // asked for; the grid shows until it arrives
                cached = m_tilePixmaps.insert(id, QPixmap::fromImage(image));
            }
            // Edges rounded to whole pixels, shared by neighbours: no seams.
            const QPoint from = toWidget(QPointF(x * tileSize0, y * tileSize0)).toPoint();
            const QPoint to = toWidget(QPointF((x + 1) * tileSize0, (y + 1) * tileSize0)).toPoint();
            p.drawPixmap(QRect(from, to - QPoint(1, 1)), *cached);
        }
    }
}

void PlanMapView::paintFence(QPainter& p)
{
    const QRectF visible = QRectF(rect()).adjusted(-4, -4, 4, 4);
    auto style = [&p](bool inclusion) {
        if (inclusion) {
            p.setPen(QPen(kInclusionColour, 2));
            p.setBrush(withAlpha(kInclusionColour, 0.2));
        } else {
            p.setPen(QPen(kExclusionColour, 2));
            p.setBrush(withAlpha(kExclusionColour, 0.18));
        }
    };
    // Exclusion areas hatched over their light fill: told apart from
    // inclusion by more than colour.
    const QBrush hatch(withAlpha(kExclusionColour, 0.55), Qt::BDiagPattern);
    const double scale = std::exp2(m_zoom);
    for (const Geometry::Polygon& polygon : m_geometry.polygons) {
        QPolygonF screen;
        screen.reserve(polygon.vertices.size());
        for (const QPointF& vertex : polygon.vertices)
            screen.append(toWidget(vertex));
        if (!screen.boundingRect().intersects(visible))
            continue;
        style(polygon.inclusion);
        p.drawPolygon(screen);
        if (!polygon.inclusion) {
            p.setPen(Qt::NoPen);
            p.setBrush(hatch);
            p.drawPolygon(screen);
        }
    }
    for (const Geometry::Circle& circle : m_geometry.circles) {
        const QPointF centre = toWidget(circle.centre);
        const double radius = circle.radius * scale;
        if (!QRectF(centre.x() - radius, centre.y() - radius, 2 * radius, 2 * radius).intersects(visible))
            continue;
        style(circle.inclusion);
        p.drawEllipse(centre, radius, radius);
        if (!circle.inclusion) {
            p.setPen(Qt::NoPen);
            p.setBrush(hatch);
            p.drawEllipse(centre, radius, radius);
        }
    }
}

void PlanMapView::paintMission(QPainter& p)
{
    const QRectF visible =
        QRectF(rect()).adjusted(-3 * kMarkerRadius, -kMarkerRadius, 3 * kMarkerRadius, kMarkerRadius);
    // The path, in mission order, through the drag preview as well.
    QPolygonF path;
    for (int i = 0; i < m_geometry.items.size(); ++i) {
        if (m_geometry.items[i])
            path.append(markerPos(i));
    }
    if (path.size() > 1 && path.boundingRect().intersects(visible)) {
        p.setBrush(Qt::NoBrush);
        p.setPen(QPen(withAlpha(Qt::white, 0.8), 5, Qt::SolidLine, Qt::RoundCap, Qt::RoundJoin));
        p.drawPolyline(path);
        p.setPen(QPen(kPathColour, 2.5, Qt::SolidLine, Qt::RoundCap, Qt::RoundJoin));
        p.drawPolyline(path);
    }

    p.setFont(scaledFont(font(), 0.9, true));
    for (const QPointF& rally : m_geometry.rally) {
        const QPointF pos = toWidget(rally);
        if (visible.contains(pos))
            drawMarker(p, pos, QStringLiteral("R"), kRallyColour, Qt::white, MarkerShape::Diamond);
    }
    if (m_geometry.home) {
        const QPointF pos = toWidget(*m_geometry.home);
        if (visible.contains(pos))
            drawMarker(p, pos, QStringLiteral("H"), kHomeColour, Qt::white, MarkerShape::Square);
    }

    const int dragged = m_drag && m_drag->moved ? m_drag->index : -1;
    auto drawItem = [&](int index, bool selected) {
        const QPointF pos = markerPos(index);
        if (!visible.contains(pos))
            return;
        const QString label = QString::number(m_plan->items[index].seq + 1);  // as the table numbers them
        if (selected) {
            p.setPen(QPen(kHomeColour, 2));
            p.setBrush(Qt::NoBrush);
            p.drawEllipse(pos, kMarkerRadius + 5, kMarkerRadius + 5);
            drawMarker(p, pos, label, kSelectedColour, Qt::black, MarkerShape::Circle);
        } else {
            drawMarker(p, pos, label, kPathColour, Qt::white, MarkerShape::Circle);
        }
    };
    // One marker a cell of a marker's size: a long survey zoomed out would
    // otherwise paint thousands of markers on top of each other (seconds of
    // GUI time for what looks the same). The later item wins its cell, as
    // it would be drawn on top.
    const double cell = 2 * kMarkerRadius;
    QSet<quint64> taken;
    for (int i = int(m_geometry.items.size()) - 1; i >= 0; --i) {
        if (!m_geometry.items[i] || i == m_selected || i == dragged)
            continue;
        const QPointF pos = markerPos(i);
        if (!visible.contains(pos))
            continue;
        const quint64 key = quint64(quint32(qint32(std::floor(pos.x() / cell)))) << 32 |
                            quint32(qint32(std::floor(pos.y() / cell)));
        if (taken.contains(key))
            continue;
        taken.insert(key);
        drawItem(i, false);
    }
    if (dragged >= 0) {
        // Where it was, faint, until the owner moves it.
        p.setOpacity(0.35);
        const QPointF was = toWidget(*m_geometry.items[dragged]);
        drawMarker(p, was, QString::number(m_plan->items[dragged].seq + 1), kPathColour, Qt::white,
                   MarkerShape::Circle);
        p.setOpacity(1);
    }
    if (m_selected >= 0 && m_geometry.items.value(m_selected) && m_selected != dragged)
        drawItem(m_selected, true);
    if (dragged >= 0)
        drawItem(dragged, dragged == m_selected);
}

void PlanMapView::paintScaleBar(QPainter& p)
{
    const double metresPerPixel = WebMercator::metresPerPixel(centre().latitude, m_zoom);
    const int maxWidth = std::min(kScaleBarMaxWidth, width() / 3);
    if (maxWidth < 20)
        return;
    const double metres = roundLength(metresPerPixel * maxWidth);
    const double length = metres / metresPerPixel;
    p.setFont(scaledFont(font(), 0.85));
    const QFontMetricsF fm(p.font());
    const QString label = lengthLabel(metres);
    const double boxWidth = std::max(length, fm.horizontalAdvance(label)) + 12;
    const double boxHeight = fm.height() + 12;
    const QRectF box(8, height() - 8 - boxHeight, boxWidth, boxHeight);
    p.setPen(Qt::NoPen);
    p.setBrush(withAlpha(palette().color(QPalette::Window), 0.8));
    p.drawRect(box);
    const QColor ink = palette().color(QPalette::WindowText);
    p.setPen(ink);
    p.drawText(QRectF(box.left() + 6, box.top() + 2, length, fm.height()), Qt::AlignLeft | Qt::AlignVCenter, label);
    const double barY = box.bottom() - 5;
    const double x0 = box.left() + 6;
    p.setPen(QPen(ink, 2, Qt::SolidLine, Qt::FlatCap));
    p.drawLine(QPointF(x0, barY), QPointF(x0 + length, barY));
    p.drawLine(QPointF(x0, barY - 5), QPointF(x0, barY));
    p.drawLine(QPointF(x0 + length, barY - 5), QPointF(x0 + length, barY));
}

void PlanMapView::paintAttribution(QPainter& p)
{
    const bool hasTiles = m_tiles && m_tiles->source() != MapTiles::Source::None;
    const QString text = hasTiles ? m_tiles->attribution() : tr("No map tiles: grid only");
    if (text.isEmpty())
        return;
    p.setFont(scaledFont(font(), 0.8));
    const QFontMetricsF fm(p.font());
    // Leaves the scale bar its corner.
    const double room = width() - kScaleBarMaxWidth - 40;
    const QString shown = fm.elidedText(text, Qt::ElideLeft, std::max(40.0, room));
    const double boxWidth = fm.horizontalAdvance(shown) + 10;
    const double boxHeight = fm.height() + 4;
    drawBoxedText(p, QRectF(width() - boxWidth, height() - boxHeight, boxWidth, boxHeight), shown, palette());
}

// --- the operator

void PlanMapView::mousePressEvent(QMouseEvent* event)
{
    if (event->button() != Qt::LeftButton || m_drag || m_pan) {
        QWidget::mousePressEvent(event);
        return;
    }
    const QPointF pos = event->position();
    const int index = markerAt(pos);
    if (index >= 0) {
        if (index != m_selected) {
            m_selected = index;
            update();
        }
        emit itemSelected(index);
        if (m_editable)
            m_drag = MarkerDrag{index, pos, markerPos(index), markerPos(index), false};
    } else {
        m_pan = Pan{pos, m_centre0};
        setCursor(Qt::ClosedHandCursor);
    }
    event->accept();
}

void PlanMapView::mouseMoveEvent(QMouseEvent* event)
{
    const QPointF pos = event->position();
    if (m_drag) {
        const QPointF delta = pos - m_drag->pressPos;
        if (!m_drag->moved && delta.manhattanLength() > kMoveThreshold)
            m_drag->moved = true;
        if (m_drag->moved) {
            m_drag->currentPos = m_drag->markerPos + delta;
            update();
        }
        return;
    }
    if (m_pan) {
        setView(m_zoom, m_pan->centre0 - (pos - m_pan->pressPos) / std::exp2(m_zoom));
        return;
    }
    const int index = markerAt(pos);
    if (index >= 0)
        setCursor(m_editable ? Qt::SizeAllCursor : Qt::PointingHandCursor);
    else
        setCursor(Qt::OpenHandCursor);
}

void PlanMapView::mouseReleaseEvent(QMouseEvent* event)
{
    if (event->button() != Qt::LeftButton) {
        QWidget::mouseReleaseEvent(event);
        return;
    }
    if (m_drag) {
        const MarkerDrag drag = *m_drag;
        m_drag.reset();
        update();
        const QPointF to = drag.markerPos + (event->position() - drag.pressPos);
        // A click, or a drag brought back to where it started, moves nothing.
        if (drag.moved && (to - drag.markerPos).manhattanLength() > kMoveThreshold && m_editable)
            emit moveRequested(drag.index, geoAt(to));
    }
    if (m_pan) {
        m_pan.reset();
        setCursor(Qt::OpenHandCursor);
    }
    event->accept();
}

void PlanMapView::mouseDoubleClickEvent(QMouseEvent* event)
{
    if (event->button() != Qt::LeftButton)
        return;
    const QPointF pos = event->position();
    if (markerAt(pos) >= 0) {
        mousePressEvent(event);  // as a click: selects it
        return;
    }
    if (m_editable)
        emit addRequested(geoAt(pos));
    event->accept();
}

void PlanMapView::wheelEvent(QWheelEvent* event)
{
    event->accept();
    // A marker or the view in the middle of a drag stays where the operator holds it.
    if (m_drag || m_pan)
        return;
    const double notches = event->angleDelta().y() / 120.0;
    if (notches == 0)
        return;
    zoomAbout(m_zoom + notches * kWheelZoomPerNotch, event->position());
}

void PlanMapView::keyPressEvent(QKeyEvent* event)
{
    switch (event->key()) {
        case Qt::Key_Delete:
            if (m_editable && m_selected >= 0 && !m_drag) {
                emit deleteRequested(m_selected);
                return;
            }
            break;
        case Qt::Key_Plus:
        case Qt::Key_Equal:
            zoomIn();
            return;
        case Qt::Key_Minus:
            zoomOut();
            return;
        case Qt::Key_F:
            fitToPlan();
            return;
        case Qt::Key_Escape:
            if (m_drag) {
                m_drag.reset();
                update();
                return;
            }
            break;
        default:
            break;
    }
    QWidget::keyPressEvent(event);
}

void PlanMapView::contextMenuEvent(QContextMenuEvent* event)
{
    const int index = markerAt(event->pos());
    if (!m_editable || index < 0 || m_drag) {
        event->ignore();
        return;
    }
    if (index != m_selected) {
        m_selected = index;
        update();
    }
    emit itemSelected(index);
    QMenu menu(this);
    QAction* altitude = menu.addAction(tr("Change altitude\u2026"));
    if (menu.exec(event->globalPos()) == altitude)
        emit altitudeRequested(index);
}
