// Bytes as hexadecimal digits, as key files, station public keys and the
// text format's flight plan data write them. Whoever reads them reads them here.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

namespace rcm {

// The value of a hexadecimal digit, either case; -1 for any other character.
constexpr int hexDigitValue(char c)
{
    if (c >= '0' && c <= '9')
        return c - '0';
    if (c >= 'a' && c <= 'f')
        return c - 'a' + 10;
    if (c >= 'A' && c <= 'F')
        return c - 'A' + 10;
    return -1;
}

// `out` from exactly 2 * out.size() digits, the high digit of each byte
// first; false when `hex` is anything else (then `out` holds the bytes read
// so far).
inline bool decodeHex(std::string_view hex, std::span<std::uint8_t> out)
{
    if (hex.size() != 2 * out.size())
        return false;
    for (std::size_t i = 0; i < out.size(); ++i) {
        const int high = hexDigitValue(hex[2 * i]);
        const int low = hexDigitValue(hex[2 * i + 1]);
        if (high < 0 || low < 0)
            return false;
        out[i] = static_cast<std::uint8_t>(high << 4 | low);
    }
    return true;
}

}  // namespace rcm
