#include "codec/message/ValueCodec.h"

#include "codec/message/Diagnostic.h"
#include "codec/message/DigitPairs.h"

#include <cstdio>
#include <initializer_list>

namespace rcm {
namespace {

// How far `v` lies outside [min, max], as a magnitude: the difference of
// two int64 values need not fit in an int64 (-2^63 is 2^63 below 0).
std::uint64_t distanceOutside(std::int64_t v, std::int64_t min, std::int64_t max)
{
    return v < min ? static_cast<std::uint64_t>(min) - static_cast<std::uint64_t>(v)
                   : static_cast<std::uint64_t>(v) - static_cast<std::uint64_t>(max);
}

std::string rangeError(const ItemInfo& item, std::int64_t v, std::int64_t min, std::int64_t max, const char* what = nullptr)
{
    if (v >= min && v <= max)
        return {};
    std::string subject = what ? std::string(what) + " " : std::string();
    const bool below = v < min;
    return subject + formatScaled(item, v) + (below ? " is below the minimum " : " is above the maximum ") +
           formatScaled(item, below ? min : max) + " by " + formatScaledMagnitude(item, distanceOutside(v, min, max));
}

std::string plainRange(std::int64_t v, std::int64_t min, std::int64_t max, const char* what)
{
    if (v >= min && v <= max)
        return {};
    const bool below = v < min;
    return std::string(what) + " " + std::to_string(v) + (below ? " is below the minimum " : " is above the maximum ") +
           std::to_string(below ? min : max) + " by " + std::to_string(distanceOutside(v, min, max));
}

// A value in parts (a station's code and unit, a time's digit pairs): the
// reason names the first part out of its range; empty when all are in range.
struct Part {
    std::int64_t value;
    std::int64_t min;
    std::int64_t max;
    const char* what;
};

std::string firstOutOfRange(std::initializer_list<Part> parts)
{
    for (const Part& p : parts) {
        std::string e = plainRange(p.value, p.min, p.max, p.what);
        if (!e.empty())
            return e;
    }
    return {};
}

bool printableAscii(const std::string& s)
{
    for (unsigned char c : s)
        if (c < 0x20 || c > 0x7E)
            return false;
    return true;
}

int daysInMonth(int yy, int mm)
{
    static constexpr int days[] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
    // Two-digit years: 2000-2099, where every fourth year is a leap year.
    return mm == 2 && yy % 4 == 0 ? 29 : days[mm - 1];
}

}  // namespace

std::string formatScaledMagnitude(const ItemInfo& item, std::uint64_t magnitude, bool negative)
{
    if (item.scale != 100)
        return (negative ? "-" : "") + std::to_string(magnitude);
    char buf[32];
    std::snprintf(buf, sizeof buf, "%s%llu.%02llu", negative ? "-" : "", static_cast<unsigned long long>(magnitude / 100),
                  static_cast<unsigned long long>(magnitude % 100));
    return buf;
}

std::string formatScaled(const ItemInfo& item, std::int64_t number)
{
    // 0 - x in unsigned arithmetic: -number overflows for -2^63.
    const bool negative = number < 0;
    const std::uint64_t magnitude =
        negative ? std::uint64_t{0} - static_cast<std::uint64_t>(number) : static_cast<std::uint64_t>(number);
    return formatScaledMagnitude(item, magnitude, negative);
}

void checkFields(const ItemInfo& item, std::uint8_t byte, std::vector<FieldProblem>& out)
{
    const int n = static_cast<int>(item.fields.size());
    for (int f = 0; f < n; ++f) {
        const unsigned code = fieldCode(byte, f);
        if (!fieldCodeValid(item.fields[f], code))
            out.push_back({std::string(item.fields[f].name),
                           std::string("code ") + (code == 0 ? "00" : "11") + " means data corruption"});
    }
    const unsigned reservedMask = n >= 4 ? 0u : (0xFFu >> (2 * n));
    if (byte & reservedMask) {
        char buf[80];
        std::snprintf(buf, sizeof buf, "reserved bits are not 0 (byte 0x%02X, mask 0x%02X)", byte, reservedMask);
        out.push_back({"reserved bits", buf});
    }
}

std::string checkValue(const ItemInfo& item, const Value& value)
{
    switch (item.kind) {
    case ValueKind::Unsigned:
    case ValueKind::Signed:
        return rangeError(item, value.number, item.min, item.max);
    case ValueKind::Raw:
        return plainRange(value.number, 0, 255, "value");
    case ValueKind::Station:
        return firstOutOfRange({{value.number, item.min, item.max, "country dialling code"},
                                {value.second, 0, 65535, "unit number"}});
    case ValueKind::BytePair:
        return firstOutOfRange({{value.number, 0, 255, "first format ID"}, {value.second, 0, 255, "second format ID"}});
    case ValueKind::Time: {
        // Checked digit pair by digit pair so the reason names the part that is wrong.
        if (value.number < 0)
            return plainRange(value.number, 0, 235959, "time hhmmss");
        const auto [hh, mm, ss] = DigitPairs::unpack(value.number);
        return firstOutOfRange({{hh, 0, 23, "hours"}, {mm, 0, 59, "minutes"}, {ss, 0, 59, "seconds"}});
    }
    case ValueKind::Date: {
        if (value.number < 0)
            return plainRange(value.number, 0, 991231, "date yymmdd");
        const auto [yy, mm, dd] = DigitPairs::unpack(value.number);
        if (yy > 99)
            return plainRange(yy, 0, 99, "year");
        if (mm < 1 || mm > 12)
            return plainRange(mm, 1, 12, "month");
        return plainRange(dd, 1, daysInMonth(static_cast<int>(yy), static_cast<int>(mm)), "day");
    }
    case ValueKind::Fields: {
        if (value.number < 0 || value.number > 255)
            return plainRange(value.number, 0, 255, "byte");
        std::vector<FieldProblem> problems;
        checkFields(item, static_cast<std::uint8_t>(value.number), problems);
        if (problems.empty())
            return {};
        return "field " + problems.front().field + ": " + problems.front().reason;
    }
    case ValueKind::Text:
        if (value.text.size() > item.size)
            return "text \"" + echoInput(value.text) + "\" is " + std::to_string(value.text.size()) +
                   " characters, " + std::to_string(value.text.size() - item.size) + " more than the " +
                   std::to_string(item.size) + " allowed";
        if (!printableAscii(value.text))
            return "text must be printable ASCII";
        // Trailing spaces are the padding on the wire: they would not come back.
        if (!value.text.empty() && value.text.back() == ' ')
            return "text \"" + echoInput(value.text) +
                   "\" ends in a space, which the wire cannot keep (spaces pad the field)";
        return {};
    case ValueKind::CameraId:
        if (value.text.size() != 3 || !printableAscii(value.text))
            return "maker must be exactly 3 printable ASCII characters, got \"" + echoInput(value.text) + "\"";
        return plainRange(value.number, 0, 255, "camera number");
    }
    return {};
}

std::optional<LargeChangeFound> findLargeChange(const ItemInfo& item, const Value* from, const Value& to)
{
    using Rule = LargeChangeFound::Rule;
    const LargeChange& rule = item.largeChange;
    if (from && *from == to)
        return std::nullopt;
    switch (item.kind) {
        case ValueKind::Unsigned:
        case ValueKind::Signed:
            if (rule.extremes && (to.number == item.min || to.number == item.max))
                return LargeChangeFound{Rule::Extreme, -1, rule.action};
            // Values are at most 32 bits wide: the difference cannot overflow.
            if (from && rule.step != kAnyStep &&
                (to.number > from->number + rule.step || to.number < from->number - rule.step))
                return LargeChangeFound{Rule::Step, -1, rule.action};
            return std::nullopt;
        case ValueKind::Fields:
            for (int f = 0; f < static_cast<int>(item.fields.size()); ++f) {
                const FieldConfirmation& field = rule.fields[static_cast<std::size_t>(f)];
                if (field.code == 0)
                    continue;
                const unsigned now = fieldCode(static_cast<std::uint8_t>(to.number), f);
                const bool was = from && fieldCode(static_cast<std::uint8_t>(from->number), f) == field.code;
                if (now == field.code && !was)
                    return LargeChangeFound{Rule::FieldCode, f, field.action};
            }
            return std::nullopt;
        default:
            return std::nullopt;
    }
}

void packValue(const ItemInfo& item, const Value& value, std::uint8_t* out)
{
    auto putBE = [](std::uint8_t* p, std::uint64_t v, int n) {
        for (int i = n - 1; i >= 0; --i) {
            p[i] = static_cast<std::uint8_t>(v);
            v >>= 8;
        }
    };
    switch (item.kind) {
    case ValueKind::Unsigned:
    case ValueKind::Signed:
    case ValueKind::Time:
    case ValueKind::Date:
    case ValueKind::Fields:
    case ValueKind::Raw:
        putBE(out, static_cast<std::uint64_t>(value.number), item.size);
        break;
    case ValueKind::Station:
        putBE(out, static_cast<std::uint64_t>(value.number), 2);
        putBE(out + 2, static_cast<std::uint64_t>(value.second), 2);
        break;
    case ValueKind::BytePair:
        out[0] = static_cast<std::uint8_t>(value.number);
        out[1] = static_cast<std::uint8_t>(value.second);
        break;
    case ValueKind::Text:
        for (std::size_t i = 0; i < item.size; ++i)
            out[i] = i < value.text.size() ? static_cast<std::uint8_t>(value.text[i]) : ' ';
        break;
    case ValueKind::CameraId:
        for (std::size_t i = 0; i < 3; ++i)
            out[i] = static_cast<std::uint8_t>(value.text[i]);
        out[3] = static_cast<std::uint8_t>(value.number);
        break;
    }
}

Value unpackValue(const ItemInfo& item, const std::uint8_t* in)
{
    auto getBE = [](const std::uint8_t* p, int n) {
        std::uint64_t v = 0;
        for (int i = 0; i < n; ++i)
            v = (v << 8) | p[i];
        return v;
    };
    Value v;
    switch (item.kind) {
    case ValueKind::Unsigned:
    case ValueKind::Time:
    case ValueKind::Date:
    case ValueKind::Fields:
    case ValueKind::Raw:
        v.number = static_cast<std::int64_t>(getBE(in, item.size));
        break;
    case ValueKind::Signed: {
        const std::uint64_t raw = getBE(in, item.size);
        const std::uint64_t sign = 1ull << (8 * item.size - 1);
        v.number = static_cast<std::int64_t>(raw ^ sign) - static_cast<std::int64_t>(sign);
        break;
    }
    case ValueKind::Station:
        v.number = static_cast<std::int64_t>(getBE(in, 2));
        v.second = static_cast<std::int64_t>(getBE(in + 2, 2));
        break;
    case ValueKind::BytePair:
        v.number = in[0];
        v.second = in[1];
        break;
    case ValueKind::Text: {
        std::size_t n = item.size;
        while (n > 0 && in[n - 1] == ' ')
            --n;
        v.text.assign(reinterpret_cast<const char*>(in), n);
        break;
    }
    case ValueKind::CameraId:
        v.text.assign(reinterpret_cast<const char*>(in), 3);
        v.number = in[3];
        break;
    }
    return v;
}

}  // namespace rcm
