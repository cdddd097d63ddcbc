#pragma once

// Web Mercator (EPSG:3857) as tile servers and MBTiles files use it: the
// world is a square of 256 * 2^zoom pixels, x from 180 degrees west, y from
// the north, rows of 256-pixel tiles numbered XYZ (slippy map). Zoom may be
// fractional (the plan view zooms smoothly; tiles come from the nearest whole
// zoom, scaled). Latitudes beyond +-85.0511 degrees, where the square ends,
// are clamped to its edge.

#include "link/plan/MissionPlan.h"

#include <QPoint>
#include <QPointF>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace WebMercator {

inline constexpr int kTileSize = 256;
// atan(sinh(pi)): the latitude of the square's top edge.
inline constexpr double kMaxLatitude = 85.05112877980659;
// The WGS 84 equatorial radius, which the projection takes for a sphere.
inline constexpr double kEarthRadius = 6378137.0;
// 2 * pi * R / 256: ground metres per pixel at the equator at zoom 0.
inline constexpr double kEquatorMetresPerPixel = 2 * std::numbers::pi * kEarthRadius / kTileSize;

// The world's width and height in pixels.
inline double worldSize(double zoom)
{
    return kTileSize * std::exp2(zoom);
}

inline QPointF toWorld(const GeoPoint& point, double zoom)
{
    const double size = worldSize(zoom);
    const double latitude = std::clamp(point.latitude, -kMaxLatitude, kMaxLatitude) * std::numbers::pi / 180;
    const double x = (point.longitude + 180) / 360 * size;
    const double y = (1 - std::asinh(std::tan(latitude)) / std::numbers::pi) / 2 * size;
    return {x, y};
}

inline GeoPoint toGeo(const QPointF& world, double zoom)
{
    const double size = worldSize(zoom);
    const double latitude = std::atan(std::sinh(std::numbers::pi * (1 - 2 * world.y() / size)));
    return {latitude * 180 / std::numbers::pi, world.x() / size * 360 - 180};
}

// Ground metres one pixel spans at `latitude` (the projection stretches by
// 1 / cos(latitude) away from the equator).
inline double metresPerPixel(double latitude, double zoom)
{
    const double clamped = std::clamp(latitude, -kMaxLatitude, kMaxLatitude);
    return kEquatorMetresPerPixel * std::cos(clamped * std::numbers::pi / 180) / std::exp2(zoom);
}

// Column (x) and row (y) of the tile holding `point` at whole zoom `zoom`.
inline QPoint tileAt(const GeoPoint& point, int zoom)
{
    const QPointF world = toWorld(point, zoom);
    const int last = (1 << zoom) - 1;
    return {std::clamp(int(std::floor(world.x() / kTileSize)), 0, last),
            std::clamp(int(std::floor(world.y() / kTileSize)), 0, last)};
}

}  // namespace WebMercator
