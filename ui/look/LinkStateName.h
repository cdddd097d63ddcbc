#pragma once

// A link's state as the console names it in the status bar and the link
// strip: "Not connected", "Waiting for the aircraft", "Connected", "Lost".

#include "link/session/LinkStatistics.h"

#include <QString>

QString linkStateName(LinkState state);
