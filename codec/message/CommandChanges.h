// Two commands (or a command and the aircraft's status, which has the
// command's shape) compared item by item, units matched by their key item:
// what the console shows before it resumes commanding, what its event log
// writes for each change, and how it carries a command over to another
// airframe or takes the aircraft's report into its panels.
//
// Only the units' items count: the header (message counter, time, the
// stations the frame names) changes with every frame and is the link's.
#pragma once

#include "codec/message/Message.h"

#include <optional>
#include <string>
#include <vector>

namespace rcm {

// One item of one unit, or one two-bit field of a Fields item, that differs.
struct ItemChange {
    UnitKind kind = UnitKind::Header;
    std::string unit;  // describeUnit(): "engine 1", "flaps", "radio VHF1"
    // The unit's key item's value (engine number, system ID, camera ID);
    // none for the single units.
    std::optional<Value> key;
    ItemId id = ItemId::ID_msg;
    int field = -1;           // a Fields item: the field that differs; -1 for the whole item
    std::optional<Value> from;  // none: the first message has no such item (or unit)
    std::optional<Value> to;    // none: the second has none
    friend bool operator==(const ItemChange&, const ItemChange&) = default;
};

// Every unit item whose value differs between `from` and `to`, units
// matched by key, in canonical order, Fields items field by field. An item
// or unit only one of them has is a change with the other side empty.
std::vector<ItemChange> commandChanges(const Message& from, const Message& to);

// The value `message` has for the item of `change` in the unit of `change`
// (matched by key); null when it has none.
const Value* valueAt(const Message& message, const ItemChange& change);
// Whether `message` has the value `change` changes to (for a Fields item,
// the changed field's code).
bool holdsChange(const Message& message, const ItemChange& change);

// `target` with each unit item it carries set to the value `source` has
// for the same item of the same unit (matched by key), where `source` has
// one; one-shot items (kOneShotItems) and the header stay as in `target`.
// Adopting the aircraft's report into the panels is withValuesOf(command,
// report); carrying a command over to another airframe is
// withValuesOf(restingCommand(newAirframe), command).
Message withValuesOf(const Message& target, const Message& source);

// The units of `source` that `target` has no unit for (matched by key):
// what a change of airframe leaves behind.
std::vector<Unit> unitsMissingFrom(const Message& source, const Message& target);

// What a console sends while it holds its commands back: `command`'s
// header alone, no unit and no flight plan section. An item a frame does
// not carry means "keep" to the aircraft (docs/protocol.md section 2), so
// such a frame changes nothing the aircraft does.
Message heldCommand(const Message& command);

}  // namespace rcm
