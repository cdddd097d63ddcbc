#include "link/plan/PlanFile.h"

#include "link/plan/QgcPlanFile.h"

#include <QDir>
#include <QFile>
#include <QSaveFile>

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
    return QgcPlanFile::read(contents, source, error);
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
    return QStringLiteral("QGroundControl plans (*.plan);;All files (*)");
}

}  // namespace PlanFile
