// What went wrong, and where: every codec error and warning is one of these.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace rcm {

struct Diagnostic {
    enum class Kind {
        OutOfRange,      // a value outside its item's range
        DoesNotFit,      // the message needs more than a block holds
        MissingKey,      // a unit without its key item (eng_ID, system_ID, cam_ID)
        CorruptField,    // a two-bit field reading 00 or 11 where that means corruption
        ReservedBits,    // bits the profile fixes at 0 are not
        UnknownItem,     // an Item_ID the profile does not define
        Truncated,       // an item runs past the end of its block
        Orphan,          // a unit item before any key item
        Repeated,        // an item given twice in one unit
        BadPadding,      // BLOCK 2 padding or End_Of_String is not as specified
        Uncorrectable,   // more errors in a codeword than RS(255,223) corrects
        Syntax,          // text format
        Forged,          // authentication failed
    };
    Kind kind;
    int block = 0;       // 1 or 2; 0 when not about a block
    int offset = -1;     // byte offset in the block, -1 when not about a byte
    std::string where;   // item or field, with its unit: "engine 2 eng_prop_pitch"
    std::string message; // what is wrong, in full
    int line = 0;        // text format: 1-based line and column, 0 when not about text
    int column = 0;

    // "block 1 offset 57: engine 2 eng_prop_pitch: ..." or "line 3 column 8: ..."
    // with the parts that apply.
    std::string toString() const;
};

using Diagnostics = std::vector<Diagnostic>;

// Bytes of input as a message quotes them: printable ASCII as it is, every
// other byte written \xHH (so a NUL cannot end the message, and a byte of
// 0x80 or above, a piece of UTF-8 or not, cannot reach a terminal or a log
// raw), and at most kEchoLimit bytes, the rest counted:
// "AAAA... (10485760 bytes)".
inline constexpr std::size_t kEchoLimit = 40;
std::string echoInput(std::string_view input);

}  // namespace rcm
