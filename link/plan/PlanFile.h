#pragma once

// Plan files of the programs operators already use, read into a MissionPlan
// and written back as a QGroundControl plan. Every refusal names the file,
// the line (where the format has lines) and the item, and says what is wrong.

#include "link/plan/MissionPlan.h"

#include <optional>

namespace PlanFile {

// Reads a plan file, recognising its format by its contents, whatever its
// name: a JSON object is a QGroundControl .plan or .mission
// (link/plan/QgcPlanFile.h), a first line "QGC WPL" a Mission Planner
// .waypoints (link/plan/WaypointsFile.h), an XML document with <kml> a KML
// one (link/plan/KmlFile.h). Anything else is refused with the list of the
// formats read. A UTF-8 byte order mark is passed over.
std::optional<MissionPlan> load(const QString& path, QString* error = nullptr);
// The same over bytes already read; `source` names them in errors.
std::optional<MissionPlan> read(const QByteArray& contents, const QString& source, QString* error = nullptr);

// Writes `plan` as a QGroundControl .plan; false, with the reason, when the
// file cannot be written. Writes to a temporary file and renames, so a plan
// on disk is never half written.
bool save(const MissionPlan& plan, const QString& path, QString* error = nullptr);

// For QFileDialog: every format load() reads.
QString openFilter();

}  // namespace PlanFile
