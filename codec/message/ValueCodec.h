// Checking, packing and unpacking one item's value, driven by its ItemInfo.
#pragma once

#include "codec/message/ItemTable.h"
#include "codec/message/Message.h"

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace rcm {

// Empty when `value` is valid for `item`; otherwise what is wrong and by how
// much ("300 is above the maximum 255 by 45").
std::string checkValue(const ItemInfo& item, const Value& value);

// A change of `item` from `from` (nullptr: not commanded) to `to` that its
// LargeChange rule says the operator confirms first: which part of the rule,
// the field for a Fields item, and the button that confirms it. Nothing when
// one action may make the change without asking. A Fields change asks when
// any field moves to the code named for it; of several, the first is named.
struct LargeChangeFound {
    enum class Rule { Step, Extreme, FieldCode };
    Rule rule = Rule::Step;
    int field = -1;
    std::string_view action;
};
std::optional<LargeChangeFound> findLargeChange(const ItemInfo& item, const Value* from, const Value& to);

// Writes item.size bytes. The value must have passed checkValue.
void packValue(const ItemInfo& item, const Value& value, std::uint8_t* out);

// Reads item.size bytes. The result may be invalid; run checkValue on it.
Value unpackValue(const ItemInfo& item, const std::uint8_t* in);

// A number in the item's text units: "-54.64" for hundredths, "120" otherwise.
std::string formatScaled(const ItemInfo& item, std::int64_t number);
// The same for a magnitude that may not fit in an int64 (how far -2^63 lies
// below a minimum of 0), with its sign.
std::string formatScaledMagnitude(const ItemInfo& item, std::uint64_t magnitude, bool negative = false);

// For Fields items: the diagnostics of each corrupt field and of set reserved
// bits, as (field label or "reserved bits", reason) pairs appended to `out`.
struct FieldProblem {
    std::string field;
    std::string reason;
};
void checkFields(const ItemInfo& item, std::uint8_t byte, std::vector<FieldProblem>& out);

}  // namespace rcm
