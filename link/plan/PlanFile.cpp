#include "link/plan/PlanFile.h"

#include "link/plan/KmlFile.h"
#include "link/plan/QgcPlanFile.h"
#include "link/plan/WaypointsFile.h"

#include <QDir>
#include <QFile>
#include <QSaveFile>

#include <algorithm>

namespace PlanFile {

std::optional<MissionPlan> load(const QString& path, QString* error)
{
    QFile file(path);
    if (!file.open(QIODevice::ReadOnly)) {
        if (error)
            *error = QStringLiteral("%1: %2").arg(QDir::toNativeSeparators(path), file.errorString());
        return std::nullopt;
    }
    return read(file.readAll(), QDir::toNativeSeparators(path), error);
}

std::optional<MissionPlan> read(const QByteArray& contents, const QString& source, QString* error)
{
    const auto fail = [&](const QString& what) -> std::optional<MissionPlan> {
        if (error)
            *error = QStringLiteral("%1: %2").arg(source, what);
        return std::nullopt;
    };
    QByteArrayView text(contents);
    if (text.startsWith("\xEF\xBB\xBF"))  // a UTF-8 byte order mark, as Windows programs write
        text = text.sliced(3);
    const QByteArrayView start = text.trimmed();
    if (start.isEmpty())
        return fail(QStringLiteral("the file is empty"));
    if (start.startsWith('{'))
        return QgcPlanFile::read(text.toByteArray(), source, error);
    if (start.startsWith("QGC WPL"))
        return WaypointsFile::read(text.toByteArray(), source, error);
    // An XML declaration and comments may come before the <kml> element.
    if (start.startsWith('<') && start.first(std::min<qsizetype>(start.size(), 4096)).contains("<kml"))
        return KmlFile::read(text.toByteArray(), source, error);
    return fail(
        QStringLiteral("not a plan file this console reads: QGroundControl .plan, Mission Planner .waypoints "
                       "(QGC WPL 110) or KML"));
}

bool save(const MissionPlan& plan, const QString& path, QString* error)
{
    QSaveFile file(path);
    if (!file.open(QIODevice::WriteOnly) || file.write(QgcPlanFile::write(plan)) < 0 || !file.commit()) {
        if (error)
            *error = QStringLiteral("%1: %2").arg(QDir::toNativeSeparators(path), file.errorString());
        return false;
    }
    return true;
}

QString openFilter()
{
    return QStringLiteral(
        "Plans (*.plan *.waypoints *.txt *.mission *.kml);;QGroundControl plans (*.plan);;Mission Planner "
        "waypoints (*.waypoints *.txt);;KML (*.kml);;All files (*)");
}

}  // namespace PlanFile
