#include "ui/plan/PlanCommandLine.h"

#include "ui/plan/FlightPlanWidget.h"

PlanCommandLine::PlanCommandLine(QCommandLineParser& parser)
    : m_parser(parser),
      m_plan(QStringLiteral("plan"),
             QStringLiteral("Show this flight plan (QGroundControl .plan, Mission Planner .waypoints or KML)."),
             QStringLiteral("file")),
      m_mbtiles(QStringLiteral("mbtiles"), QStringLiteral("Offline map tiles for the plan view (an MBTiles file)."),
                QStringLiteral("file")),
      m_tileUrl(QStringLiteral("tile-url"),
                QStringLiteral("A tile server for the plan view, e.g. https://tile.example.org/{z}/{x}/{y}.png."),
                QStringLiteral("template")),
      m_attribution(QStringLiteral("tile-attribution"),
                    QStringLiteral("The attribution the tile server asks to be shown."), QStringLiteral("text"))
{
    parser.addOptions({m_plan, m_mbtiles, m_tileUrl, m_attribution});
}

bool PlanCommandLine::apply(FlightPlanWidget& widget, QString* error) const
{
    if (m_parser.isSet(m_mbtiles) || m_parser.isSet(m_tileUrl)) {
        TileSettings tiles = widget.tiles()->settings();
        tiles.mbtilesPath = m_parser.value(m_mbtiles);
        tiles.urlTemplate = m_parser.value(m_tileUrl);
        tiles.attribution = m_parser.value(m_attribution);
        widget.setTileSettings(tiles);
    }
    return !m_parser.isSet(m_plan) || widget.loadPlan(m_parser.value(m_plan), error);
}
