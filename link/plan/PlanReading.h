#pragma once

// What the plan file readers (KmlFile, QgcPlanFile, WaypointsFile) share: the
// way a reader's outcome is handed to the caller.

#include "link/plan/MissionPlan.h"

#include <QString>

#include <optional>

namespace PlanReading {

// `plan` as the reader made it; when there is none, the reader's error()
// goes to *error (when asked for). The reader is taken by reference so that
// its error is read after read() has run.
template <typename Reader>
std::optional<MissionPlan> outcome(const Reader& reader, std::optional<MissionPlan> plan, QString* error)
{
    if (!plan && error)
        *error = reader.error();
    return plan;
}

}  // namespace PlanReading
