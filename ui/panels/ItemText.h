// What people read about an item, all of it taken from the item table:
// labels, tool tips with range and unit, values as the text format writes
// them. Panels use these instead of spelling a name, range or unit again.
#pragma once

#include "codec/message/ItemTable.h"
#include "codec/message/Message.h"

#include <QString>
#include <QStringList>

namespace ItemText {

// The text format's name, "eng_status", or with a field "eng_status.control":
// what panels name their controls by (QObject::objectName), for tests and tools.
QString name(rcm::ItemId id, int field = -1);
// "Propeller pitch"; with a field, the field's label: "Control source"
QString label(rcm::ItemId id, int field = -1);
// "Propeller pitch, 0..255"; "Compass bearing, 0.00..359.99 deg"
QString toolTip(rcm::ItemId id);
// "Control source (Engine status): AUTO, GCS, RC"
QString fieldToolTip(rcm::ItemId id, int field);
// The table's name of a field code ("GCS"); "corrupt (00)" for a code meaning data corruption.
QString fieldCodeName(rcm::ItemId id, int field, unsigned code);
// The valid codes of a field, in code order.
QList<unsigned> validFieldCodes(rcm::ItemId id, int field);
// A value as the text format writes it, with the unit: "120", "-54.64 deg", "GB_133", "NIK 1".
QString value(rcm::ItemId id, const rcm::Value& value);
// One field of a Fields item's value: its code name.
QString fieldValue(rcm::ItemId id, int field, const rcm::Value& value);

}  // namespace ItemText
