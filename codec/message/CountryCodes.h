// ISO 3166-1 alpha-2 country codes <-> ITU-T E.164 country calling codes. A
// station ID carries its country as the dialling code (PROFILE.md, item 04);
// people read and type the two letters.
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

namespace rcm {

// "GB" or "gb" -> 44. Countries inside the North American Numbering Plan give
// 1, not their area code (PR -> 1), as that is all the two bytes can hold.
// Nothing for a code that is not assigned or has no calling code.
std::optional<std::uint16_t> diallingCodeForCountry(std::string_view alpha2);

// The one country the text format writes for a dialling code: 1 -> "US",
// 7 -> "RU", 44 -> "GB". Its diallingCodeForCountry is always `code` again, so
// a printed station reads back to the same bytes. Empty when no country has it.
std::string_view countryForDiallingCode(std::uint16_t code);

}  // namespace rcm
