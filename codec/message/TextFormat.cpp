#include "codec/message/TextFormat.h"

#include "codec/message/CountryCodes.h"
#include "codec/message/DigitPairs.h"
#include "codec/message/HexDigits.h"
#include "codec/message/ValueCodec.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <limits>
#include <optional>
#include <span>
#include <vector>

namespace rcm {
namespace {

using DiagKind = Diagnostic::Kind;

constexpr std::string_view kBeginWord = "BEGIN";
constexpr std::string_view kEndWord = "END";

// BLOCK 2 is not in the item table (it is a fixed layout, not items), so its
// section and names live here.
constexpr std::string_view kFlightPlanSection = "FLIGHT_PLAN";
enum PlanField { PlanId, PlanSectionId, PlanData, PlanFieldCount };
constexpr std::array<std::string_view, PlanFieldCount> kPlanNames{"flight_plan_ID", "flight_plan_section_ID",
                                                                   "flight_plan_data"};

constexpr char kHexDigits[] = "0123456789ABCDEF";
constexpr std::string_view kByteOrderMark = "\xEF\xBB\xBF";

// ---------------------------------------------------------------- printer

void appendInt(std::string& out, std::int64_t v)
{
    char buf[24];
    const auto r = std::to_chars(buf, buf + sizeof buf, v);
    out.append(buf, r.ptr);
}

void appendZeroPadded(std::string& out, std::int64_t v, int width)
{
    char buf[24];
    const auto r = std::to_chars(buf, buf + sizeof buf, v);
    for (auto n = r.ptr - buf; n < width; ++n)
        out += '0';
    out.append(buf, r.ptr);
}

// Upper-case 0x form; a negative number (only in an invalid model) prints in
// decimal so that reading it back reports the same number.
void appendHex(std::string& out, std::int64_t v, int width)
{
    if (v < 0) {
        appendInt(out, v);
        return;
    }
    char buf[16];
    char* p = buf + sizeof buf;
    auto u = static_cast<std::uint64_t>(v);
    int digits = 0;
    do {
        *--p = kHexDigits[u & 0xF];
        u >>= 4;
        ++digits;
    } while (u != 0);
    out += "0x";
    for (; digits < width; ++digits)
        out += '0';
    out.append(p, buf + sizeof buf);
}

bool isBareSafe(std::string_view s)
{
    if (s.empty())
        return false;
    for (const char c : s)
        if (c < '!' || c > '~' || c == '#' || c == '"')
            return false;
    return true;
}

void appendText(std::string& out, std::string_view s)
{
    if (isBareSafe(s)) {
        out += s;
        return;
    }
    out += '"';
    for (const char ch : s) {
        const auto c = static_cast<unsigned char>(ch);
        if (c == '"' || c == '\\') {
            out += '\\';
            out += ch;
        } else if (c >= 0x20 && c <= 0x7E) {
            out += ch;
        } else {
            out += "\\x";
            out += kHexDigits[c >> 4];
            out += kHexDigits[c & 0xF];
        }
    }
    out += '"';
}

void appendStation(std::string& out, const Value& v)
{
    std::string_view country;
    if (v.number >= 0 && v.number <= std::numeric_limits<std::uint16_t>::max())
        country = countryForDiallingCode(static_cast<std::uint16_t>(v.number));
    if (country.empty())
        appendInt(out, v.number);
    else
        out += country;
    out += '_';
    appendInt(out, v.second);
}

void appendValue(std::string& out, const ItemInfo& info, const Value& v)
{
    switch (info.kind) {
    case ValueKind::Unsigned:
    case ValueKind::Signed:
        if (info.scale == 1)
            appendInt(out, v.number);
        else
            out += formatScaled(info, v.number);
        break;
    case ValueKind::Raw:
        appendHex(out, v.number, 2);
        break;
    case ValueKind::Station:
        appendStation(out, v);
        break;
    case ValueKind::Time:
        if (v.number >= 0 && v.number <= 999999) {
            const DigitPairs time = DigitPairs::unpack(v.number);
            appendZeroPadded(out, time.high, 2);
            out += ':';
            appendZeroPadded(out, time.middle, 2);
            out += ':';
            appendZeroPadded(out, time.low, 2);
        } else {
            appendInt(out, v.number);
        }
        break;
    case ValueKind::Date:
        if (v.number >= 0 && v.number <= 999999)
            appendZeroPadded(out, v.number, 6);
        else
            appendInt(out, v.number);
        break;
    case ValueKind::BytePair:
        appendInt(out, v.number);
        out += ' ';
        appendInt(out, v.second);
        break;
    case ValueKind::Fields:
        // Names only say what a valid byte means; anything else keeps its bits.
        if (checkValue(info, v).empty()) {
            const auto byte = static_cast<std::uint8_t>(v.number);
            for (std::size_t f = 0; f < info.fields.size(); ++f) {
                if (f > 0)
                    out += ' ';
                out += info.fields[f].name;
                out += '=';
                out += info.fields[f].codes[fieldCode(byte, static_cast<int>(f))];
            }
        } else {
            appendHex(out, v.number, 2);
        }
        break;
    case ValueKind::Text:
    case ValueKind::CameraId:
        // A camera ID is a text with a number after it.
        appendText(out, v.text);
        if (info.kind == ValueKind::CameraId) {
            out += ' ';
            appendInt(out, v.number);
        }
        break;
    }
}

void appendUnit(std::string& out, const Unit& unit)
{
    out += kBeginWord;
    out += ' ';
    out += sectionName(unit.kind());
    out += '\n';
    for (const ItemValue& item : unit.items()) {
        const ItemInfo& info = itemInfo(item.id);
        out += info.name;
        out += ' ';
        appendValue(out, info, item.value);
        out += '\n';
    }
    out += kEndWord;
    out += '\n';
}

void appendFlightPlan(std::string& out, const FlightPlanSection& plan)
{
    out += kBeginWord;
    out += ' ';
    out += kFlightPlanSection;
    out += '\n';
    out += kPlanNames[PlanId];
    out += ' ';
    appendHex(out, plan.planId, 8);
    out += '\n';
    out += kPlanNames[PlanSectionId];
    out += ' ';
    appendInt(out, plan.sectionId);
    out += '\n';
    if (!plan.data.empty()) {
        out += kPlanNames[PlanData];
        out += ' ';
        for (const std::uint8_t b : plan.data) {
            out += kHexDigits[b >> 4];
            out += kHexDigits[b & 0xF];
        }
        out += '\n';
    }
    out += kEndWord;
    out += '\n';
}

// ---------------------------------------------------------------- parser

struct Token {
    std::string_view raw;   // as written, quotes included
    std::string unescaped;  // the value of a quoted token
    int column = 0;         // 1-based
    bool quoted = false;

    std::string_view value() const { return quoted ? std::string_view(unescaped) : raw; }
    int endColumn() const { return column + static_cast<int>(raw.size()); }
};

bool isDigit(char c) { return c >= '0' && c <= '9'; }
bool isAlpha(char c) { return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z'); }
bool allDigits(std::string_view s)
{
    return !s.empty() && std::all_of(s.begin(), s.end(), isDigit);
}
bool equalsIgnoreCase(std::string_view a, std::string_view b)
{
    if (a.size() != b.size())
        return false;
    for (std::size_t i = 0; i < a.size(); ++i) {
        const char x = (a[i] >= 'a' && a[i] <= 'z') ? static_cast<char>(a[i] - 32) : a[i];
        const char y = (b[i] >= 'a' && b[i] <= 'z') ? static_cast<char>(b[i] - 32) : b[i];
        if (x != y)
            return false;
    }
    return true;
}

std::string quote(std::string_view s) { return "'" + echoInput(s) + "'"; }

// "a, b or c"
std::string joinOr(const std::vector<std::string_view>& names, std::string_view last = " or ")
{
    std::string out;
    for (std::size_t i = 0; i < names.size(); ++i) {
        if (i > 0)
            out += i + 1 == names.size() ? last : std::string_view(", ");
        out += names[i];
    }
    return out;
}

std::string join(const std::vector<std::string_view>& names, std::string_view separator)
{
    std::string out;
    for (std::size_t i = 0; i < names.size(); ++i) {
        if (i > 0)
            out += separator;
        out += names[i];
    }
    return out;
}

std::vector<std::string_view> validCodes(const FieldInfo& field)
{
    std::vector<std::string_view> codes;
    for (const std::string_view code : field.codes)
        if (!code.empty())
            codes.push_back(code);
    return codes;
}

std::vector<std::string_view> itemNames(UnitKind kind)
{
    std::vector<std::string_view> names;
    for (const ItemInfo& item : itemTable())
        if (item.owner == kind)
            names.push_back(item.name);
    return names;
}

std::vector<std::string_view> childSections(std::string_view parent)
{
    std::vector<std::string_view> names;
    for (int k = 0; k < kUnitKindCount; ++k)
        if (parentSectionName(static_cast<UnitKind>(k)) == parent)
            names.push_back(sectionName(static_cast<UnitKind>(k)));
    return names;
}

bool isParentSection(std::string_view name)
{
    if (name.empty())
        return false;
    for (int k = 0; k < kUnitKindCount; ++k)
        if (parentSectionName(static_cast<UnitKind>(k)) == name)
            return true;
    return false;
}

// Every name BEGIN accepts, in the order the canonical form uses them.
std::vector<std::string_view> allSections()
{
    std::vector<std::string_view> names;
    for (int k = 0; k < kUnitKindCount; ++k) {
        const std::string_view parent = parentSectionName(static_cast<UnitKind>(k));
        if (!parent.empty() && std::find(names.begin(), names.end(), parent) == names.end())
            names.push_back(parent);
        names.push_back(sectionName(static_cast<UnitKind>(k)));
    }
    names.push_back(kFlightPlanSection);
    return names;
}

// 2 for a scale of 100: the decimals a scaled item is written with.
int decimalsOf(int scale)
{
    int decimals = 0;
    for (int f = scale; f > 1; f /= 10)
        ++decimals;
    return decimals;
}

// What a value of this item looks like, for messages.
std::string expectation(const ItemInfo& info)
{
    switch (info.kind) {
    case ValueKind::Unsigned:
    case ValueKind::Signed:
        if (info.scale != 1)
            return "a number from " + formatScaled(info, info.min) + " to " + formatScaled(info, info.max) +
                   " with at most " + std::to_string(decimalsOf(info.scale)) + " decimals";
        return "an integer from " + std::to_string(info.min) + " to " + std::to_string(info.max) +
               " (decimal or 0x hex)";
    case ValueKind::Raw:
        return "a byte such as 0x5A";
    case ValueKind::Station:
        return "a station COUNTRY_UNIT such as GB_133 or 44_133 (ISO alpha-2 country or dialling code, "
               "then the unit number)";
    case ValueKind::Time:
        return "a time hh:mm:ss such as 16:35:23, or hhmmss";
    case ValueKind::Date:
        return "a date yymmdd of 6 digits such as 071114";
    case ValueKind::BytePair:
        return "two integers from " + std::to_string(info.min) + " to " + std::to_string(info.max);
    case ValueKind::Fields: {
        std::string s = "every field as FIELD=CODE (";
        for (std::size_t f = 0; f < info.fields.size(); ++f) {
            if (f > 0)
                s += ' ';
            s += info.fields[f].name;
            s += '=';
            s += join(validCodes(info.fields[f]), "|");
        }
        return s + "), or the byte as 0xNN";
    }
    case ValueKind::Text:
        return "a text of up to " + std::to_string(info.size) +
               " printable ASCII characters, in double quotes if it has a space, # or \"";
    case ValueKind::CameraId:
        return "a 3-character maker and a camera number, such as NIK 1";
    }
    return {};
}

// Value tokens an item takes; 0: any number (two-bit fields).
std::size_t valueTokenCount(ValueKind kind)
{
    switch (kind) {
    case ValueKind::BytePair:
    case ValueKind::CameraId:
        return 2;
    case ValueKind::Fields:
        return 0;
    default:
        return 1;
    }
}

enum class NumberRead { Ok, Bad, TooLarge };

// Decimal or 0x hex, optional leading '-'.
NumberRead readInteger(std::string_view s, std::int64_t& out)
{
    bool negative = false;
    if (!s.empty() && s.front() == '-') {
        negative = true;
        s.remove_prefix(1);
    }
    int base = 10;
    if (s.size() > 2 && s[0] == '0' && (s[1] == 'x' || s[1] == 'X')) {
        base = 16;
        s.remove_prefix(2);
    }
    if (s.empty() || s.front() == '-' || s.front() == '+')
        return NumberRead::Bad;
    std::uint64_t magnitude = 0;
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), magnitude, base);
    if (end != s.data() + s.size() && ec != std::errc::result_out_of_range)
        return NumberRead::Bad;
    if (ec == std::errc::result_out_of_range)
        return end == s.data() + s.size() ? NumberRead::TooLarge : NumberRead::Bad;
    constexpr auto kMax = static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max());
    if (magnitude > kMax + (negative ? 1 : 0))
        return NumberRead::TooLarge;
    out = negative ? static_cast<std::int64_t>(0 - magnitude) : static_cast<std::int64_t>(magnitude);
    return NumberRead::Ok;
}

// "-54.64" -> -5464 for scale 100.
NumberRead readScaled(std::string_view s, int scale, std::int64_t& out, bool& tooManyDecimals)
{
    tooManyDecimals = false;
    const int decimals = decimalsOf(scale);
    bool negative = false;
    if (!s.empty() && s.front() == '-') {
        negative = true;
        s.remove_prefix(1);
    }
    const std::size_t dot = s.find('.');
    const std::string_view whole = s.substr(0, dot);
    const std::string_view frac = dot == std::string_view::npos ? std::string_view() : s.substr(dot + 1);
    if (!allDigits(whole) || (dot != std::string_view::npos && !allDigits(frac)))
        return NumberRead::Bad;
    if (static_cast<int>(frac.size()) > decimals) {
        tooManyDecimals = true;
        return NumberRead::Bad;
    }
    std::uint64_t w = 0;
    const auto [end, ec] = std::from_chars(whole.data(), whole.data() + whole.size(), w);
    (void)end;
    const auto limit = static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max() / scale) - 1;
    if (ec != std::errc() || w > limit)
        return NumberRead::TooLarge;
    std::int64_t value = static_cast<std::int64_t>(w) * scale;
    std::int64_t unit = scale;
    for (const char c : frac) {
        unit /= 10;
        value += (c - '0') * unit;
    }
    out = negative ? -value : value;
    return NumberRead::Ok;
}

// "300 is above the maximum 255 by 45", for the BLOCK 2 fields, which have no
// ItemInfo for checkValue to read.
std::string rangeReason(std::int64_t v, std::int64_t min, std::int64_t max)
{
    // Differences in unsigned arithmetic: -2^63 is 2^63 below 0, more than an int64 holds.
    const auto u = [](std::int64_t x) { return static_cast<std::uint64_t>(x); };
    if (v < min)
        return std::to_string(v) + " is below the minimum " + std::to_string(min) + " by " + std::to_string(u(min) - u(v));
    if (v > max)
        return std::to_string(v) + " is above the maximum " + std::to_string(max) + " by " + std::to_string(u(v) - u(max));
    return {};
}

class Parser {
public:
    Parser(std::string_view text, const EncodeOptions& limits, std::span<const ItemId> filledWhenAbsent)
        : m_text(text), m_limits(limits), m_filledWhenAbsent(filledWhenAbsent)
    {
        // Editors on Windows start UTF-8 files with a byte-order mark; it is
        // not part of the first line.
        if (m_text.starts_with(kByteOrderMark))
            m_text.remove_prefix(kByteOrderMark.size());
        m_rankCount = itemTable().size();
        for (int k = 0; k < kUnitKindCount; ++k) {
            m_lastStarted[k] = -1;
            if (!isRepeated(static_cast<UnitKind>(k)))
                m_seen[k].emplace_back(m_rankCount, 0);
        }
    }

    ParseResult run()
    {
        std::vector<Token> tokens;
        std::size_t pos = 0;
        while (pos <= m_text.size()) {
            std::size_t end = m_text.find('\n', pos);
            if (end == std::string_view::npos)
                end = m_text.size();
            std::string_view line = m_text.substr(pos, end - pos);
            if (!line.empty() && line.back() == '\r')
                line.remove_suffix(1);
            ++m_line;
            if (tokenize(line, tokens) && !tokens.empty())
                handleLine(tokens);
            pos = end + 1;
        }
        checkBlock1Fits();
        for (const Frame& frame : m_stack)
            error(DiagKind::Syntax, frame.line, frame.column, "",
                  "section " + std::string(frame.name) + " opened at line " + std::to_string(frame.line) +
                      " has no END");
        std::stable_sort(m_errors.begin(), m_errors.end(), [](const Diagnostic& a, const Diagnostic& b) {
            return a.line != b.line ? a.line < b.line : a.column < b.column;
        });
        return ParseResult{std::move(m_message), std::move(m_errors), m_unlistedErrors};
    }

private:
    enum class FrameType { Parent, Unit, FlightPlan, Unknown };
    struct Frame {
        FrameType type;
        std::string_view name;
        int line;
        int column;
        UnitKind kind;   // Unit frames only
        int unitIndex;   // into the message's units of `kind`, for repeated ones
    };

    // Keeps the first kMaxListedErrors and counts the rest: a file of
    // nonsense gets a screenful, not one error per line. `where` may be a
    // name from the input, so it is echoed as such.
    void error(DiagKind kind, int line, int column, std::string_view where, std::string message)
    {
        if (m_errors.size() >= kMaxListedErrors) {
            ++m_unlistedErrors;
            return;
        }
        m_errors.push_back(Diagnostic{kind, 0, -1, echoInput(where), std::move(message), line, column});
    }
    void error(DiagKind kind, int column, std::string_view where, std::string message)
    {
        error(kind, m_line, column, where, std::move(message));
    }

    // Splits a line; on a lexical error reports it and returns false, and the
    // line is skipped (its meaning is unknown).
    bool tokenize(std::string_view line, std::vector<Token>& tokens)
    {
        tokens.clear();
        auto isSpace = [](char c) { return c == ' ' || c == '\t'; };
        for (std::size_t i = 0; i < line.size(); ++i) {
            const auto c = static_cast<unsigned char>(line[i]);
            if ((c < 0x20 && c != '\t') || c == 0x7F) {
                error(DiagKind::Syntax, static_cast<int>(i) + 1, "",
                      "control byte " + echoInput(line.substr(i, 1)) +
                          " in the text; the format is printable text (inside quotes write any byte as \\xHH)");
                return false;
            }
        }
        std::size_t i = 0;
        while (i < line.size()) {
            const char c = line[i];
            if (isSpace(c)) {
                ++i;
                continue;
            }
            if (c == '#')
                break;
            Token t;
            t.column = static_cast<int>(i) + 1;
            std::size_t j = i;
            if (c == '"') {
                t.quoted = true;
                bool closed = false;
                for (j = i + 1; j < line.size();) {
                    const char d = line[j];
                    if (d == '"') {
                        closed = true;
                        ++j;
                        break;
                    }
                    if (d != '\\') {
                        t.unescaped += d;
                        ++j;
                        continue;
                    }
                    const char e = j + 1 < line.size() ? line[j + 1] : '\0';
                    if (e == '"' || e == '\\') {
                        t.unescaped += e;
                        j += 2;
                    } else if (e == 'x' && j + 3 < line.size() && hexDigitValue(line[j + 2]) >= 0 &&
                               hexDigitValue(line[j + 3]) >= 0) {
                        t.unescaped += static_cast<char>(hexDigitValue(line[j + 2]) * 16 + hexDigitValue(line[j + 3]));
                        j += 4;
                    } else {
                        error(DiagKind::Syntax, static_cast<int>(j) + 1, "",
                              "unknown escape in quoted text: use \\\" for a quote, \\\\ for a backslash or "
                              "\\xHH (two hex digits) for any byte");
                        return false;
                    }
                }
                if (!closed) {
                    error(DiagKind::Syntax, t.column, "", "quoted text has no closing \"");
                    return false;
                }
                if (j < line.size() && !isSpace(line[j]) && line[j] != '#') {
                    error(DiagKind::Syntax, static_cast<int>(j) + 1, "",
                          "expected a space after the closing \", got " + quote(line.substr(j, 1)));
                    return false;
                }
            } else {
                while (j < line.size() && !isSpace(line[j]) && line[j] != '#') {
                    if (line[j] == '"') {
                        error(DiagKind::Syntax, static_cast<int>(j) + 1, "",
                              "a \" may only start a value: quote the whole text");
                        return false;
                    }
                    ++j;
                }
            }
            t.raw = line.substr(i, j - i);
            tokens.push_back(std::move(t));
            i = j;
        }
        return true;
    }

    void handleLine(const std::vector<Token>& tokens)
    {
        const Token& first = tokens.front();
        if (first.quoted) {
            error(DiagKind::Syntax, first.column, "",
                  "expected an item name, BEGIN or END at the start of the line, got quoted text");
            return;
        }
        if (first.raw == kBeginWord)
            beginSection(tokens);
        else if (first.raw == kEndWord)
            endSection(tokens);
        else
            item(tokens);
    }

    const Frame* innermost() const { return m_stack.empty() ? nullptr : &m_stack.back(); }

    std::string whatSectionHolds(const Frame& frame) const
    {
        switch (frame.type) {
        case FrameType::Parent:
            return "section " + std::string(frame.name) + " holds only its sections " +
                   joinOr(childSections(frame.name), " and ");
        case FrameType::Unit:
            return "section " + std::string(frame.name) + " (BEGIN at line " + std::to_string(frame.line) +
                   ") holds only the items " + joinOr(itemNames(frame.kind), " and ");
        case FrameType::FlightPlan:
            return "section " + std::string(frame.name) + " holds only the items " +
                   joinOr(std::vector<std::string_view>(kPlanNames.begin(), kPlanNames.end()), " and ");
        case FrameType::Unknown:
            break;
        }
        return {};
    }

    void beginSection(const std::vector<Token>& tokens)
    {
        const Token& begin = tokens[0];
        const Frame* outer = innermost();
        if (tokens.size() < 2) {
            error(DiagKind::Syntax, begin.endColumn() + 1, "",
                  "BEGIN needs a section name: " + joinOr(allSections()));
            m_stack.push_back({FrameType::Unknown, "(unnamed)", m_line, begin.column, UnitKind::Header, 0});
            return;
        }
        if (tokens.size() > 2)
            error(DiagKind::Syntax, tokens[2].column, "",
                  "unexpected " + quote(tokens[2].raw) + ": BEGIN takes one section name");
        const Token& nameToken = tokens[1];
        const std::string_view name = nameToken.raw;
        // Misplaced sections are reported and then opened all the same, so
        // that their END still balances and their items are still checked.
        auto misplaced = [&](std::string_view allowedWhere) {
            if (!outer || outer->type == FrameType::Unknown)
                return;
            error(DiagKind::Syntax, nameToken.column, "",
                  "section " + std::string(name) + " cannot be inside section " + std::string(outer->name) + ": " +
                      whatSectionHolds(*outer) + "; " + std::string(name) + " belongs " + std::string(allowedWhere));
        };

        if (const std::optional<UnitKind> kind =
                nameToken.quoted ? std::optional<UnitKind>() : unitKindFromSection(name)) {
            const std::string_view parent = parentSectionName(*kind);
            if (outer && !(outer->type == FrameType::Parent && outer->name == parent))
                misplaced(parent.empty() ? std::string("at the top level")
                                         : "inside section " + std::string(parent) + " or at the top level");
            const int index = isRepeated(*kind) ? startUnit(*kind) : 0;
            m_stack.push_back({FrameType::Unit, sectionName(*kind), m_line, begin.column, *kind, index});
            return;
        }
        if (!nameToken.quoted && (isParentSection(name) || name == kFlightPlanSection)) {
            if (outer)
                misplaced("at the top level");
            m_stack.push_back({name == kFlightPlanSection ? FrameType::FlightPlan : FrameType::Parent, name, m_line,
                               begin.column, UnitKind::Header, 0});
            return;
        }
        std::string message = "unknown section " + quote(name) + "; expected ";
        if (outer && outer->type == FrameType::Parent)
            message += joinOr(childSections(outer->name)) + " inside section " + std::string(outer->name);
        else
            message += joinOr(allSections());
        for (const std::string_view known : allSections())
            if (equalsIgnoreCase(known, name))
                message += " (names are case-sensitive: " + std::string(known) + ")";
        error(DiagKind::Syntax, nameToken.column, "", std::move(message));
        m_stack.push_back({FrameType::Unknown, name, m_line, begin.column, UnitKind::Header, 0});
    }

    void endSection(const std::vector<Token>& tokens)
    {
        const Token& end = tokens[0];
        if (tokens.size() > 1)
            error(DiagKind::Syntax, tokens[1].column, "",
                  "unexpected " + quote(tokens[1].raw) + ": END takes nothing after it");
        if (m_stack.empty()) {
            error(DiagKind::Syntax, end.column, "", "END without a BEGIN to close");
            return;
        }
        const Frame frame = m_stack.back();
        m_stack.pop_back();
        if (frame.type != FrameType::Unit || !isRepeated(frame.kind))
            return;
        const ItemInfo& key = itemInfo(*unitKey(frame.kind));
        if (seenLines(frame.kind, frame.unitIndex)[canonicalRank(key.id)] == 0)
            error(DiagKind::Syntax, end.column, "",
                  "section " + std::string(frame.name) + " (BEGIN at line " + std::to_string(frame.line) +
                      ") ends without its key item " + std::string(key.name) + "; every " +
                      std::string(frame.name) + " needs one");
    }

    int startUnit(UnitKind kind)
    {
        std::vector<Unit>& units = *m_message.repeated(kind);
        units.emplace_back(kind);
        const int k = static_cast<int>(kind);
        m_seen[k].emplace_back(m_rankCount, 0);
        m_lastStarted[k] = static_cast<int>(units.size()) - 1;
        return m_lastStarted[k];
    }

    Unit& unitAt(UnitKind kind, int index)
    {
        if (std::vector<Unit>* units = m_message.repeated(kind))
            return (*units)[static_cast<std::size_t>(index)];
        return *m_message.single(kind);
    }

    std::vector<int>& seenLines(UnitKind kind, int index)
    {
        return m_seen[static_cast<int>(kind)][static_cast<std::size_t>(index)];
    }

    static int planField(std::string_view name)
    {
        for (int f = 0; f < PlanFieldCount; ++f)
            if (kPlanNames[f] == name)
                return f;
        return -1;
    }

    // By name alone; the header's ID_GCS_destination/backup win over the
    // camera's, which are reached only inside a camera section.
    static const ItemInfo* findByName(std::string_view name)
    {
        const ItemInfo* found = nullptr;
        for (const ItemInfo& item : itemTable())
            if (item.name == name && (!found || item.owner == UnitKind::Header))
                found = &item;
        return found;
    }

    std::string unknownItem(std::string_view name) const
    {
        std::string message = "unknown item " + quote(name);
        for (const ItemInfo& item : itemTable())
            if (equalsIgnoreCase(item.name, name)) {
                message += " (names are case-sensitive: " + std::string(item.name) + ")";
                break;
            }
        for (const std::string_view plan : kPlanNames)
            if (equalsIgnoreCase(plan, name))
                message += " (names are case-sensitive: " + std::string(plan) + ")";
        return message;
    }

    void item(const std::vector<Token>& tokens)
    {
        const Token& nameToken = tokens[0];
        const std::string_view name = nameToken.raw;
        const Frame* frame = innermost();
        const FrameType context = frame ? frame->type : FrameType::Unknown;  // Unknown: place by name
        const int plan = planField(name);

        if (context == FrameType::FlightPlan || (plan >= 0 && context == FrameType::Unknown)) {
            if (plan < 0) {
                error(DiagKind::Syntax, nameToken.column, std::string(name),
                      (findByName(name) ? quote(name) + " is not an item of section FLIGHT_PLAN"
                                        : unknownItem(name)) +
                          "; " + whatSectionHolds(*frame));
                return;
            }
            planItem(plan, tokens);
            return;
        }
        if (context == FrameType::Parent) {
            error(DiagKind::Syntax, nameToken.column, std::string(name),
                  whatSectionHolds(*frame) + "; put " + quote(name) + " inside one of them");
            return;
        }

        const ItemInfo* info = nullptr;
        int index = 0;
        if (context == FrameType::Unit) {
            info = findItem(frame->kind, name);
            if (!info) {
                error(DiagKind::Syntax, nameToken.column, std::string(name),
                      (findByName(name) || plan >= 0 ? quote(name) + " is not an item of section " +
                                                           std::string(frame->name)
                                                     : unknownItem(name)) +
                          "; " + whatSectionHolds(*frame));
                return;
            }
            index = frame->unitIndex;
        } else {
            info = findByName(name);
            if (!info) {
                error(DiagKind::Syntax, nameToken.column, std::string(name), unknownItem(name));
                return;
            }
            if (info->key) {
                index = startUnit(info->owner);
            } else if (isRepeated(info->owner)) {
                index = m_lastStarted[static_cast<int>(info->owner)];
                if (index < 0) {
                    const std::string_view key = itemInfo(*unitKey(info->owner)).name;
                    error(DiagKind::Syntax, nameToken.column, std::string(name),
                          std::string(name) + " comes before any " + std::string(key) + ": put it after " +
                              std::string(key) + " or inside BEGIN " + std::string(sectionName(info->owner)) +
                              " ... END");
                    return;
                }
            }
        }

        int& first = seenLines(info->owner, index)[canonicalRank(info->id)];
        const bool repeated = first != 0;
        if (repeated)
            error(DiagKind::Syntax, nameToken.column, std::string(name),
                  std::string(name) + " is given twice in " + describeUnit(unitAt(info->owner, index)) +
                      "; first at line " + std::to_string(first));
        else
            first = m_line;
        std::optional<Value> value = parseValue(*info, tokens);
        if (value && !repeated) {
            unitAt(info->owner, index).set(info->id, std::move(*value));
            m_block1Bytes += 1 + info->size;
            // Header items filled in later only take room, never give it: past
            // the first item that overflows without them, none is needed.
            if (m_block1Items.empty() || block1Overflow(m_block1Items.back().bytesSoFar, m_limits).empty())
                m_block1Items.push_back({m_line, nameToken.column, info->name, m_block1Bytes});
        }
    }

    // Reports, at the first item BLOCK 1 has no room for, that the items do
    // not fit; the header items to be filled in count as coming first.
    void checkBlock1Fits()
    {
        std::size_t filled = 0;
        std::vector<std::string_view> filledNames;
        for (const ItemId id : m_filledWhenAbsent)
            if (!m_message.header.has(id)) {
                filled += 1 + itemInfo(id).size;
                filledNames.push_back(itemInfo(id).name);
            }
        const std::string overflow = block1Overflow(m_block1Bytes + filled, m_limits);
        if (overflow.empty())
            return;
        for (const Block1Item& item : m_block1Items) {
            if (block1Overflow(item.bytesSoFar + filled, m_limits).empty())
                continue;
            std::string message = "BLOCK 1 is full here: " + overflow;
            if (!filledNames.empty())
                message += " (counting " + joinOr(filledNames, " and ") + ", filled in when not given)";
            error(DiagKind::DoesNotFit, item.line, item.column, item.name, std::move(message));
            return;
        }
    }

    // Checks the number of value tokens; false (reported) when it is wrong.
    bool checkTokenCount(std::string_view name, std::size_t want, const std::string& expected,
                         const std::vector<Token>& tokens)
    {
        const std::size_t have = tokens.size() - 1;
        if (have == 0 || (want > 0 && have < want)) {
            error(DiagKind::Syntax, tokens.back().endColumn() + 1, std::string(name),
                  std::string(name) + " needs " + (have == 0 ? "a value" : "another value") + ": " + expected);
            return false;
        }
        if (want > 0 && have > want) {
            error(DiagKind::Syntax, tokens[want + 1].column, std::string(name),
                  "unexpected " + quote(tokens[want + 1].raw) + " after the value: " + std::string(name) +
                      " takes " + expected);
            return false;
        }
        return true;
    }

    // An integer token; false (reported) when it is not one.
    bool integer(const Token& t, std::string_view name, const std::string& expected, std::int64_t& out)
    {
        if (t.quoted) {
            error(DiagKind::Syntax, t.column, std::string(name),
                  "expected " + expected + ", got quoted text " + echoInput(t.raw));
            return false;
        }
        switch (readInteger(t.raw, out)) {
        case NumberRead::Ok:
            return true;
        case NumberRead::Bad:
            error(DiagKind::Syntax, t.column, std::string(name), "expected " + expected + ", got " + quote(t.raw));
            return false;
        case NumberRead::TooLarge:
            error(DiagKind::OutOfRange, t.column, std::string(name),
                  quote(t.raw) + " does not fit in 64 bits; expected " + expected);
            return false;
        }
        return false;
    }

    std::optional<Value> parseValue(const ItemInfo& info, const std::vector<Token>& tokens)
    {
        const std::string_view name = info.name;
        const std::string expected = expectation(info);
        if (!checkTokenCount(name, valueTokenCount(info.kind), expected, tokens))
            return std::nullopt;
        const std::span<const Token> values(tokens.begin() + 1, tokens.end());
        const Token& t = values[0];
        auto syntax = [&](const Token& at) {
            error(DiagKind::Syntax, at.column, std::string(name),
                  "expected " + expected + ", got " + (at.quoted ? "quoted text " + echoInput(at.raw) : quote(at.raw)));
        };

        Value v;
        int offending = t.column;  // the token a range error points at
        switch (info.kind) {
        case ValueKind::Unsigned:
        case ValueKind::Signed:
        case ValueKind::Raw:
            if (info.scale == 1) {
                if (!integer(t, name, expected, v.number))
                    return std::nullopt;
                break;
            }
            {
                bool tooManyDecimals = false;
                const NumberRead r = t.quoted ? NumberRead::Bad : readScaled(t.raw, info.scale, v.number, tooManyDecimals);
                if (tooManyDecimals) {
                    error(DiagKind::Syntax, t.column, std::string(name),
                          std::string(name) + " takes at most " + std::to_string(decimalsOf(info.scale)) +
                              " decimals (it is sent in units of 1/" + std::to_string(info.scale) + "), got " +
                              quote(t.raw));
                    return std::nullopt;
                }
                if (r == NumberRead::TooLarge) {
                    error(DiagKind::OutOfRange, t.column, std::string(name),
                          quote(t.raw) + " is far out of range: expected " + expected);
                    return std::nullopt;
                }
                if (r != NumberRead::Ok) {
                    syntax(t);
                    return std::nullopt;
                }
            }
            break;
        case ValueKind::Station:
            if (!station(t, name, expected, v))
                return std::nullopt;
            break;
        case ValueKind::Time:
            if (!time(t, v.number)) {
                syntax(t);
                return std::nullopt;
            }
            break;
        case ValueKind::Date:
            if (t.quoted || t.raw.size() != 6 || !allDigits(t.raw)) {
                syntax(t);
                return std::nullopt;
            }
            readInteger(t.raw, v.number);
            break;
        case ValueKind::BytePair: {
            const bool a = integer(values[0], name, expected, v.number);
            const bool b = integer(values[1], name, expected, v.second);
            if (!a || !b)
                return std::nullopt;
            if (!checkValue(info, Value::pair(v.number, info.min)).empty())
                offending = values[0].column;
            else
                offending = values[1].column;
            break;
        }
        case ValueKind::Fields:
            if (!fields(info, values, expected, v.number))
                return std::nullopt;
            break;
        case ValueKind::Text:
            v.text = std::string(t.value());
            break;
        case ValueKind::CameraId:
            v.text = std::string(values[0].value());
            if (!integer(values[1], name, expected, v.number))
                return std::nullopt;
            offending = checkValue(info, Value::string(v.text, info.min)).empty() ? values[1].column
                                                                                  : values[0].column;
            break;
        }
        std::string reason = checkValue(info, v);
        if (!reason.empty()) {
            error(DiagKind::OutOfRange, offending, std::string(name), std::move(reason));
            return std::nullopt;
        }
        return v;
    }

    bool station(const Token& t, std::string_view name, const std::string& expected, Value& v)
    {
        const std::size_t underscore = t.raw.find('_');
        if (t.quoted || underscore == std::string_view::npos) {
            error(DiagKind::Syntax, t.column, std::string(name),
                  "expected " + expected + ", got " + (t.quoted ? echoInput(t.raw) : quote(t.raw)));
            return false;
        }
        const std::string_view country = t.raw.substr(0, underscore);
        const std::string_view unit = t.raw.substr(underscore + 1);
        bool ok = true;
        if (country.size() == 2 && isAlpha(country[0]) && isAlpha(country[1])) {
            if (const auto code = diallingCodeForCountry(country)) {
                v.number = *code;
            } else {
                error(DiagKind::Syntax, t.column, std::string(name),
                      "unknown country " + quote(country) +
                          ": expected an ISO 3166-1 alpha-2 code such as GB or a dialling code such as 44");
                ok = false;
            }
        } else if (readInteger(country, v.number) != NumberRead::Ok) {
            error(DiagKind::Syntax, t.column, std::string(name),
                  "expected a country before '_' (ISO 3166-1 alpha-2 such as GB, or a dialling code such as 44), "
                  "got " + quote(country));
            ok = false;
        }
        if (readInteger(unit, v.second) != NumberRead::Ok) {
            error(DiagKind::Syntax, t.column + static_cast<int>(underscore) + 1, std::string(name),
                  "expected a unit number after '_', got " + quote(unit));
            ok = false;
        }
        return ok;
    }

    static bool time(const Token& t, std::int64_t& out)
    {
        const std::string_view s = t.raw;
        if (t.quoted)
            return false;
        if (s.find(':') == std::string_view::npos) {
            if (s.size() > 6 || !allDigits(s))
                return false;
            readInteger(s, out);
            return true;
        }
        if (s.size() != 8 || s[2] != ':' || s[5] != ':')
            return false;
        const std::string_view hh = s.substr(0, 2), mm = s.substr(3, 2), ss = s.substr(6, 2);
        if (!allDigits(hh) || !allDigits(mm) || !allDigits(ss))
            return false;
        std::int64_t h = 0, m = 0, sec = 0;
        readInteger(hh, h);
        readInteger(mm, m);
        readInteger(ss, sec);
        out = DigitPairs{h, m, sec}.packed();
        return true;
    }

    bool fields(const ItemInfo& info, std::span<const Token> values, const std::string& expected, std::int64_t& out)
    {
        const std::string where(info.name);
        if (values.size() == 1 && !values[0].quoted && values[0].raw.find('=') == std::string_view::npos)
            return integer(values[0], info.name, expected, out);

        std::uint8_t byte = 0;
        std::vector<bool> named(info.fields.size(), false);
        bool ok = true, malformed = false;
        for (const Token& t : values) {
            const std::size_t eq = t.raw.find('=');
            if (t.quoted || eq == std::string_view::npos) {
                error(DiagKind::Syntax, t.column, where,
                      "expected FIELD=CODE, got " + (t.quoted ? echoInput(t.raw) : quote(t.raw)) + "; " +
                          std::string(info.name) + " takes " + expected);
                ok = false;
                malformed = true;
                continue;
            }
            const std::string_view fieldName = t.raw.substr(0, eq), codeName = t.raw.substr(eq + 1);
            std::size_t f = 0;
            while (f < info.fields.size() && info.fields[f].name != fieldName)
                ++f;
            if (f == info.fields.size()) {
                std::vector<std::string_view> names;
                for (const FieldInfo& field : info.fields)
                    names.push_back(field.name);
                error(DiagKind::Syntax, t.column, where,
                      std::string(info.name) + " has no field " + quote(fieldName) + "; its fields are " +
                          joinOr(names, " and "));
                ok = false;
                malformed = true;
                continue;
            }
            if (named[f]) {
                error(DiagKind::Syntax, t.column, where, "field " + std::string(fieldName) + " is given twice");
                ok = false;
                continue;
            }
            named[f] = true;
            const FieldInfo& field = info.fields[f];
            unsigned code = 0;
            while (code < 4 && (field.codes[code].empty() || field.codes[code] != codeName))
                ++code;
            if (code == 4) {
                error(DiagKind::Syntax, t.column + static_cast<int>(eq) + 1, where,
                      "field " + std::string(fieldName) + " takes " + joinOr(validCodes(field)) + ", not " +
                          quote(codeName));
                ok = false;
                continue;
            }
            byte = withFieldCode(byte, static_cast<int>(f), code);
        }
        // A malformed or misspelt field is most likely the missing one: one
        // error for it is enough.
        if (!malformed) {
            for (std::size_t f = 0; f < info.fields.size(); ++f) {
                if (named[f])
                    continue;
                error(DiagKind::Syntax, values.back().endColumn() + 1, where,
                      std::string(info.name) + " is missing field " + std::string(info.fields[f].name) + " (" +
                          joinOr(validCodes(info.fields[f])) + ")");
                ok = false;
            }
        }
        out = byte;
        return ok;
    }

    void planItem(int field, const std::vector<Token>& tokens)
    {
        const std::string_view name = kPlanNames[field];
        const Token& nameToken = tokens[0];
        int& first = m_planSeen[field];
        const bool repeated = first != 0;
        if (repeated)
            error(DiagKind::Syntax, nameToken.column, std::string(name),
                  std::string(name) + " is given twice; first at line " + std::to_string(first));
        else
            first = m_line;

        FlightPlanSection& plan = m_message.flightPlan;
        if (field == PlanData) {
            const std::string expected = "the data bytes as hex digits, two per byte, in one token, at most " +
                                         std::to_string(m_limits.maxFlightPlanData) + " bytes";
            if (!checkTokenCount(name, 1, expected, tokens))
                return;
            const Token& t = tokens[1];
            if (t.quoted) {
                error(DiagKind::Syntax, t.column, std::string(name), "expected " + expected + ", got quoted text");
                return;
            }
            for (std::size_t i = 0; i < t.raw.size(); ++i) {
                if (hexDigitValue(t.raw[i]) < 0) {
                    error(DiagKind::Syntax, t.column + static_cast<int>(i), std::string(name),
                          quote(t.raw.substr(i, 1)) + " is not a hex digit; expected " + expected);
                    return;
                }
            }
            if (t.raw.size() % 2 != 0) {
                error(DiagKind::Syntax, t.column, std::string(name),
                      "an odd number of hex digits (" + std::to_string(t.raw.size()) +
                          "): two digits make each byte");
                return;
            }
            const std::size_t bytes = t.raw.size() / 2;
            if (bytes > m_limits.maxFlightPlanData) {
                error(DiagKind::OutOfRange, t.column, std::string(name),
                      std::to_string(bytes) + " bytes is above the maximum " +
                          std::to_string(m_limits.maxFlightPlanData) + " by " +
                          std::to_string(bytes - m_limits.maxFlightPlanData));
                return;
            }
            if (repeated)
                return;
            plan.data.resize(bytes);
            for (std::size_t i = 0; i < bytes; ++i)
                plan.data[i] = static_cast<std::uint8_t>(hexDigitValue(t.raw[2 * i]) * 16 + hexDigitValue(t.raw[2 * i + 1]));
            return;
        }

        const std::int64_t max = field == PlanId ? std::numeric_limits<std::uint32_t>::max()
                                                 : std::numeric_limits<std::uint16_t>::max();
        const std::string expected = "an integer from 0 to " + std::to_string(max) + " (decimal or 0x hex)";
        if (!checkTokenCount(name, 1, expected, tokens))
            return;
        std::int64_t v = 0;
        if (!integer(tokens[1], name, expected, v))
            return;
        if (std::string reason = rangeReason(v, 0, max); !reason.empty()) {
            error(DiagKind::OutOfRange, tokens[1].column, std::string(name), std::move(reason));
            return;
        }
        if (repeated)
            return;
        if (field == PlanId)
            plan.planId = static_cast<std::uint32_t>(v);
        else
            plan.sectionId = static_cast<std::uint16_t>(v);
    }

    std::string_view m_text;
    EncodeOptions m_limits;
    std::span<const ItemId> m_filledWhenAbsent;
    // BLOCK 1 items in the text's order, with the bytes taken up to and
    // including each, to name the first one that does not fit.
    struct Block1Item {
        int line;
        int column;
        std::string_view name;
        std::size_t bytesSoFar;
    };
    std::vector<Block1Item> m_block1Items;
    std::size_t m_block1Bytes = 0;
    int m_line = 0;
    std::size_t m_rankCount = 0;
    Message m_message;
    Diagnostics m_errors;
    std::size_t m_unlistedErrors = 0;
    std::vector<Frame> m_stack;
    // Per unit, the line where each item (by canonical rank) was first given,
    // 0 when not yet: for "given twice; first at line N" and the key check.
    std::array<std::vector<std::vector<int>>, kUnitKindCount> m_seen;
    std::array<int, kUnitKindCount> m_lastStarted{};
    std::array<int, PlanFieldCount> m_planSeen{};
};

}  // namespace

std::string formatMessage(const Message& message)
{
    std::string out;
    out.reserve(2048);
    std::string_view openParent;
    message.forEachUnit([&](const Unit& unit) {
        if (unit.empty())
            return;
        const std::string_view parent = parentSectionName(unit.kind());
        if (parent != openParent) {
            if (!openParent.empty()) {
                out += kEndWord;
                out += '\n';
            }
            if (!parent.empty()) {
                out += kBeginWord;
                out += ' ';
                out += parent;
                out += '\n';
            }
            openParent = parent;
        }
        appendUnit(out, unit);
    });
    if (!openParent.empty()) {
        out += kEndWord;
        out += '\n';
    }
    if (!message.flightPlan.empty())
        appendFlightPlan(out, message.flightPlan);
    return out;
}

ParseResult parseMessage(std::string_view text, const EncodeOptions& limits, std::span<const ItemId> filledWhenAbsent)
{
    return Parser(text, limits, filledWhenAbsent).run();
}

std::string formatStation(StationId station)
{
    std::string out;
    appendStation(out, Value::station(station));
    return out;
}

std::optional<StationId> parseStation(std::string_view text, std::string* error)
{
    // Through the one parser, so that a station reads the same everywhere.
    const std::string_view item = itemInfo(ItemId::ID_GCS_destination).name;
    const std::string line = std::string(item) + ' ' + std::string(text);
    const bool oneToken = !text.empty() && text.find_first_of(" \t\n\"#") == std::string_view::npos;
    ParseResult parsed = oneToken ? parseMessage(line) : ParseResult{};
    const Value* value = parsed.message.header.find(ItemId::ID_GCS_destination);
    if (oneToken && parsed.ok() && value)
        return StationId{static_cast<std::uint16_t>(value->number), static_cast<std::uint16_t>(value->second)};
    if (error) {
        if (!oneToken)
            *error = "expected a station COUNTRY_UNIT such as GB_133, got " + quote(text);
        else
            *error = parsed.errors.empty() ? std::string("not a station") : parsed.errors.front().message;
    }
    return std::nullopt;
}

}  // namespace rcm
