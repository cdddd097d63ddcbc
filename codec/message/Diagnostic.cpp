#include "codec/message/Diagnostic.h"

#include <algorithm>

namespace rcm {

std::string Diagnostic::toString() const
{
    std::string out;
    if (block > 0) {
        out += "block " + std::to_string(block);
        if (offset >= 0)
            out += " offset " + std::to_string(offset);
        out += ": ";
    }
    if (line > 0)
        out += "line " + std::to_string(line) + " column " + std::to_string(column) + ": ";
    if (!where.empty())
        out += where + ": ";
    out += message;
    return out;
}

std::string echoInput(std::string_view input)
{
    static constexpr char kHex[] = "0123456789ABCDEF";
    const std::size_t shown = std::min(input.size(), kEchoLimit);
    std::string out;
    for (const char ch : input.substr(0, shown)) {
        const auto c = static_cast<unsigned char>(ch);
        if (c < 0x20 || c >= 0x7F) {
            out += "\\x";
            out += kHex[c >> 4];
            out += kHex[c & 0xF];
        } else {
            out += ch;
        }
    }
    if (shown < input.size())
        out += "... (" + std::to_string(input.size()) + " bytes)";
    return out;
}

}  // namespace rcm
