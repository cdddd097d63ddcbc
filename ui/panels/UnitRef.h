// Which unit of the commanded message a panel control works on. Repeated
// units are addressed by their position in the command, which follows the
// airframe's order (restingCommand builds them so); ReportedState matches the
// aircraft's units to them by key item, never by position.
#pragma once

#include "codec/message/ItemTable.h"

struct UnitRef {
    rcm::UnitKind kind = rcm::UnitKind::Header;
    int index = 0;  // 0 for the single units

    friend bool operator==(const UnitRef&, const UnitRef&) = default;
};
