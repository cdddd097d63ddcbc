#include "codec/message/Diagnostic.h"

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

}  // namespace rcm
