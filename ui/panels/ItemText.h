// What people read about an item, all of it taken from the item table:
// labels, tool tips with range and unit, values as the text format writes
// them. Panels use these instead of spelling a name, range or unit again.
#pragma once

#include "codec/message/CommandChanges.h"
#include "codec/message/ItemTable.h"
#include "codec/message/Message.h"

#include <QString>
#include <QStringList>

#include <cstdint>
#include <optional>

namespace ItemText {

// The text format's name, "eng_status", or with a field "eng_status.control":
// what panels name their controls by (QObject::objectName), for tests and tools.
QString name(rcm::ItemId id, int field = -1);
// "Propeller pitch"; with a field, the field's label: "Control source"
QString label(rcm::ItemId id, int field = -1);
// "Propeller pitch, 0.0..100.0 %"; "Compass bearing, 0.00..359.99°": the range the console offers
QString toolTip(rcm::ItemId id);
// A number as people read it (rcm::presentation): 127712 kHz -> "127.712", 128 -> "50.2"; no unit.
QString number(rcm::ItemId id, std::int64_t wire);
// What follows a number: " MHz", " %", "°"; empty for items without a unit.
QString unitSuffix(rcm::ItemId id);
// A number typed as number() writes it (unit optional) to the value on the
// wire, the nearest one; nothing when it is not a number with at most the
// shown decimals or lies outside the range the console offers.
std::optional<std::int64_t> parseNumber(rcm::ItemId id, QString text);
// "Control source (Engine status): Automatic, Ground station, RC transmitter"
QString fieldToolTip(rcm::ItemId id, int field);
// The table's name of a field code ("GCS"); "corrupt (00)" for a code meaning data corruption.
QString fieldCodeName(rcm::ItemId id, int field, unsigned code);
// The code in words ("Ground station"), as panels show it; "corrupt (00)" likewise.
QString fieldCodeWord(rcm::ItemId id, int field, unsigned code);
// The same on the card of `unit`, where a word depends on which unit it is:
// an engine's master/slave mode reads "Master of engine 3" on engine 1,
// "Slave of engine 1" on engine 3. `unit` may be null: the words above.
QString fieldCodeWord(rcm::ItemId id, int field, unsigned code, const rcm::Unit* unit);
// The valid codes of a field, in code order.
QList<unsigned> validFieldCodes(rcm::ItemId id, int field);
// A value as people read it, with the unit: "47.1 %", "-54.64°", "127.712 MHz", "GB_133", "NIK 1".
QString value(rcm::ItemId id, const rcm::Value& value);
// One field of a Fields item's value, in words; on the card of `unit` as fieldCodeWord says.
QString fieldValue(rcm::ItemId id, int field, const rcm::Value& value, const rcm::Unit* unit = nullptr);

// A unit for people: "Engine 1", "Radio VHF1", "Camera NIK 1", "Flaps";
// `key` its key item's value (none for the single units).
QString unitName(rcm::UnitKind kind, const std::optional<rcm::Value>& key);
QString unitName(const rcm::Unit& unit);
// "Engine 2, Engine 3, Camera NIK 1"
QString unitNames(const std::vector<rcm::Unit>& units);
// Where a change is: "Engine 1, Propeller pitch", "Landing gear, Nose wheel".
QString changeWhere(const rcm::ItemChange& change);
// One side of a change in words ("25.1 %", "Retracted"); "nothing" when
// that side has no such item.
QString changeValue(const rcm::ItemChange& change, const std::optional<rcm::Value>& side);
// "Engine 1, Propeller pitch: 0.0 % -> 25.1 %"
QString change(const rcm::ItemChange& change);

}  // namespace ItemText
