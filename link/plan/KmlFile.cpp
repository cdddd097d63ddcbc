#include "link/plan/KmlFile.h"

#include "link/plan/PlanReading.h"

#include <QLocale>
#include <QStringList>
#include <QXmlStreamReader>

#include <cmath>
#include <limits>

namespace {

constexpr double kMillimetres = MissionPlan::kMillimetres;
constexpr quint8 kFrameAmsl = 0;       // MAV_FRAME_GLOBAL
constexpr quint8 kFrameAboveHome = 3;  // MAV_FRAME_GLOBAL_RELATIVE_ALT
constexpr quint16 kNavWaypoint = 16;

QString number(double value)
{
    return QString::number(value, 'g', QLocale::FloatingPointShortest);
}

// One "lon,lat[,alt]" of a <coordinates>, with where it starts.
struct Tuple {
    GeoPoint position;
    std::optional<double> altitude;
    int line = 0;
    int column = 0;
};

class KmlReader {
public:
    explicit KmlReader(const QString& source) : m_source(source) {}

    std::optional<MissionPlan> read(const QByteArray& kml)
    {
        QXmlStreamReader xml(kml);
        while (!xml.atEnd()) {
            xml.readNext();
            if (xml.isStartElement()) {
                if (!startElement(xml))
                    return std::nullopt;
            } else if (xml.isEndElement() && !m_open.isEmpty()) {
                m_open.removeLast();
            }
        }
        if (xml.hasError()) {
            fail(int(xml.lineNumber()), int(xml.columnNumber()) + 1, xml.errorString());
            return std::nullopt;
        }
        if (m_plan.items.isEmpty() && m_plan.fencePolygons.isEmpty() && m_plan.rallyPoints.isEmpty()) {
            m_error = QStringLiteral("%1: no LineString, Polygon or Point in it to make a plan of").arg(m_source);
            return std::nullopt;
        }
        return m_plan;
    }

    const QString& error() const { return m_error; }

private:
    bool fail(int line, int column, const QString& what)
    {
        m_error = QStringLiteral("%1: line %2, column %3: %4").arg(m_source).arg(line).arg(column).arg(what);
        return false;
    }

    bool startElement(QXmlStreamReader& xml)
    {
        const QString name = xml.name().toString();
        const int line = int(xml.lineNumber());
        const int column = int(xml.columnNumber()) + 1;
        if (m_open.isEmpty() && name != QLatin1String("kml"))
            return fail(line, column, QStringLiteral("not a KML document (its root element is <%1>)").arg(name));
        // The elements read whole here hold text only; they are not pushed,
        // since readElementText() reads their end as well.
        if (name == QLatin1String("name") && !m_open.isEmpty() && m_open.last() == QLatin1String("Placemark")) {
            m_placemarkName = xml.readElementText().trimmed();
            return true;
        }
        if (name == QLatin1String("altitudeMode")) {
            m_altitudeMode = xml.readElementText().trimmed();
            return true;
        }
        if (name == QLatin1String("coordinates")) {
            const QString text = xml.readElementText();
            return xml.hasError() || coordinates(text, line, column);
        }
        if (name == QLatin1String("Placemark"))
            m_placemarkName.clear();
        if (name == QLatin1String("LineString") || name == QLatin1String("Polygon") || name == QLatin1String("Point"))
            m_altitudeMode.clear();
        m_open.append(name);
        return true;
    }

    // The innermost open geometry whose coordinates make something of the plan.
    QString geometry() const
    {
        for (qsizetype i = m_open.size() - 1; i >= 0; --i) {
            const QString& name = m_open[i];
            if (name == QLatin1String("LineString") || name == QLatin1String("LinearRing") ||
                name == QLatin1String("Point"))
                return name;
        }
        return {};
    }

    QString ringKind() const
    {
        const qsizetype ring = m_open.lastIndexOf(QStringLiteral("LinearRing"));
        return ring > 0 ? m_open[ring - 1] : QString();
    }

    QString element(const QString& geometryName) const
    {
        QString what = QStringLiteral("<coordinates> of ");
        if (geometryName != QLatin1String("LinearRing"))
            what += geometryName;
        else if (ringKind() == QLatin1String("innerBoundaryIs"))
            what += QStringLiteral("a Polygon's inner boundary");
        else
            what += QStringLiteral("a Polygon's outer boundary");
        if (!m_placemarkName.isEmpty())
            what += QStringLiteral(" in placemark \"%1\"").arg(m_placemarkName);
        return what;
    }

    // `line` and `column`: where the text of <coordinates> starts.
    bool coordinates(const QString& text, int line, int column)
    {
        const QString geometryName = geometry();
        if (geometryName.isEmpty())
            return true;
        const QString what = element(geometryName);
        QList<Tuple> tuples;
        if (!parseTuples(text, line, column, what, tuples))
            return false;
        if (tuples.isEmpty())
            return fail(line, column, QStringLiteral("%1: no coordinates").arg(what));
        if (geometryName == QLatin1String("LineString"))
            return addWaypoints(tuples, what);
        if (geometryName == QLatin1String("LinearRing"))
            return addPolygon(tuples, what, line, column);
        if (tuples.size() != 1)
            return fail(line, column, QStringLiteral("%1: %2 positions; a Point has one").arg(what).arg(tuples.size()));
        if (m_placemarkName.startsWith(QLatin1String("Rally"), Qt::CaseInsensitive))
            return addRallyPoint(tuples[0], what);
        return addWaypoints(tuples, what);
    }

    bool parseTuples(const QString& text, int line, int column, const QString& what, QList<Tuple>& tuples)
    {
        qsizetype i = 0;
        while (i < text.size()) {
            while (i < text.size() && text[i].isSpace())
                ++i;
            const qsizetype start = i;
            while (i < text.size() && !text[i].isSpace())
                ++i;
            if (start == i)
                break;
            Tuple tuple;
            placeOf(text, start, line, column, tuple);
            if (!parseTuple(text.mid(start, i - start), what, tuple))
                return false;
            tuples.append(tuple);
        }
        return true;
    }

    // Line and column of text[offset], the text starting at line, column.
    static void placeOf(const QString& text, qsizetype offset, int line, int column, Tuple& tuple)
    {
        const QStringView before = QStringView(text).left(offset);
        const qsizetype newlines = before.count(QLatin1Char('\n'));
        tuple.line = line + int(newlines);
        tuple.column = newlines == 0 ? column + int(offset) : int(offset - before.lastIndexOf(QLatin1Char('\n')));
    }

    bool parseTuple(const QString& token, const QString& what, Tuple& tuple)
    {
        const QStringList parts = token.split(QLatin1Char(','));
        double values[3] = {0, 0, 0};
        bool ok = parts.size() == 2 || parts.size() == 3;
        for (qsizetype p = 0; ok && p < parts.size(); ++p)
            values[p] = parts[p].toDouble(&ok);
        if (!ok || !std::isfinite(values[0]) || !std::isfinite(values[1]) || !std::isfinite(values[2]))
            return fail(tuple.line, tuple.column,
                        QStringLiteral("%1: \"%2\" is not longitude,latitude[,altitude]").arg(what, token));
        tuple.position = {values[1], values[0]};
        if (parts.size() == 3)
            tuple.altitude = values[2];
        if (std::abs(tuple.position.latitude) > 90)
            return fail(tuple.line, tuple.column,
                        QStringLiteral("%1: latitude %2 is outside \u00b190").arg(what, number(values[1])));
        if (std::abs(tuple.position.longitude) > 180)
            return fail(tuple.line, tuple.column,
                        QStringLiteral("%1: longitude %2 is outside \u00b1180").arg(what, number(values[0])));
        if (tuple.altitude && !MissionPlan::fitsField(*tuple.altitude, kMillimetres))
            return fail(tuple.line, tuple.column,
                        QStringLiteral("%1: altitude %2 m is out of the range the plan bytes hold")
                            .arg(what, number(*tuple.altitude)));
        return true;
    }

    bool addWaypoints(const QList<Tuple>& tuples, const QString& what)
    {
        for (const Tuple& tuple : tuples) {
            if (m_plan.items.size() == std::numeric_limits<quint16>::max())
                return fail(tuple.line, tuple.column,
                            QStringLiteral("%1: more than 65535 waypoints; a plan holds at most 65535").arg(what));
            MissionItem item;
            item.seq = quint16(m_plan.items.size());
            item.command = kNavWaypoint;
            // Hold 0 s, the autopilot's own acceptance and pass radii, and
            // yaw NaN: the autopilot keeps its own heading.
            item.params = {0, 0, 0, std::nan("")};
            item.latitude = tuple.position.latitude;
            item.longitude = tuple.position.longitude;
            const bool absolute = m_altitudeMode == QLatin1String("absolute") && tuple.altitude;
            const bool aboveGround = m_altitudeMode == QLatin1String("relativeToGround") && tuple.altitude;
            item.frame = absolute ? kFrameAmsl : kFrameAboveHome;
            item.altitude = absolute || aboveGround ? *tuple.altitude : KmlFile::kDefaultAltitude;
            m_plan.items.append(item);
        }
        return true;
    }

    bool addPolygon(QList<Tuple> tuples, const QString& what, int line, int column)
    {
        if (tuples.size() > 1 && tuples.first().position == tuples.last().position)
            tuples.removeLast();
        if (tuples.size() < 3)
            return fail(
                line, column,
                QStringLiteral("%1: %2 vertices; a fence polygon needs at least 3").arg(what).arg(tuples.size()));
        FencePolygon polygon;
        polygon.inclusion = ringKind() != QLatin1String("innerBoundaryIs");
        for (const Tuple& tuple : tuples)
            polygon.vertices.append(tuple.position);
        m_plan.fencePolygons.append(polygon);
        return true;
    }

    bool addRallyPoint(const Tuple& tuple, const QString& what)
    {
        if (m_altitudeMode == QLatin1String("absolute") && tuple.altitude)
            return fail(tuple.line, tuple.column,
                        QStringLiteral("%1: a rally point's altitude is above home, and this one is absolute (above "
                                       "mean sea level); make it relativeToGround")
                            .arg(what));
        const bool aboveGround = m_altitudeMode == QLatin1String("relativeToGround") && tuple.altitude;
        m_plan.rallyPoints.append({tuple.position, aboveGround ? *tuple.altitude : KmlFile::kDefaultAltitude});
        return true;
    }

    const QString& m_source;
    QString m_error;
    MissionPlan m_plan;
    QStringList m_open;  // the elements open now, outermost first
    QString m_placemarkName;
    QString m_altitudeMode;
};

}  // namespace

namespace KmlFile {

std::optional<MissionPlan> read(const QByteArray& kml, const QString& source, QString* error)
{
    KmlReader reader(source);
    return PlanReading::outcome(reader, reader.read(kml), error);
}

}  // namespace KmlFile
