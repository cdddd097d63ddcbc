#pragma once

// QGroundControl's .plan (JSON): the mission, the geofence and the rally
// points.

#include "link/plan/MissionPlan.h"

#include <optional>

namespace QgcPlanFile {

std::optional<MissionPlan> read(const QByteArray& json, const QString& source, QString* error = nullptr);
QByteArray write(const MissionPlan& plan);

}  // namespace QgcPlanFile
