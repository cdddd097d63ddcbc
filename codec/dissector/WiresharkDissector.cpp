#include "codec/dissector/WiresharkDissector.h"

#include "codec/message/CountryCodes.h"
#include "codec/frame/Frame.h"
#include "codec/message/ItemTable.h"
#include "codec/message/Message.h"

#include <cstdio>
#include <stdexcept>
#include <string_view>

namespace rcm {
namespace {

// The Lua written around the generated tables. Everything that names, sizes or
// decodes an item comes from the tables, so this part changes only when the
// way of showing a kind of value does.
constexpr std::string_view kHeader = R"lua(-- Remote Control Message (RCM) dissector for Wireshark 4.0 and later.
--
-- GENERATED from the item table (codec/message/ItemTable.cpp) by
-- codec/dissector/WiresharkDissector.cpp. Do not edit: regenerate with
--     rcm dissector > resources/wireshark/rcm.lua
-- so that the names, sizes and codes below never drift from the console's.
--
-- Use:   tshark -X lua_script:rcm.lua -r session.pcapng -V
-- or copy this file into ~/.local/lib/wireshark/plugins/ for Wireshark.
-- Frame logs (pcapng, link type 147 LINKTYPE_USER0) are dissected as RCM
-- by themselves; for UDP traffic use Decode As... > UDP port > RCM.
--
-- A packet is a 600-byte frame (90-byte preamble, two RS(255,223) codewords)
-- or a 510-byte datagram (the two codewords). This dissector does NOT apply
-- Reed-Solomon correction: it shows the bytes as captured, so a codeword the
-- console corrected may show wrong values here. The console's verdict is in
-- the frame comment ("rcm corrected symbols=3/0").

local rcm = Proto("rcm", "Remote Control Message")

-- rcm.fields must list every ProtoField; field() collects them as they are made.
local fields = {}
local function field(f)
    fields[#fields + 1] = f
    return f
end
)lua";

constexpr std::string_view kBody = R"lua(
local CORRUPT = "corrupt"

local itemNames = {}
for id, it in pairs(items) do
    itemNames[id] = it.name
end

local F = {
    form = field(ProtoField.string("rcm.form", "Form", base.ASCII, "600-byte frame or 510-byte datagram")),
    preamble = field(ProtoField.bytes("rcm.preamble", "Preamble", base.NONE, "BLOCK 0: 88 x 55, then 0F 0F")),
    codeword = {
        field(ProtoField.bytes("rcm.codeword1", "BLOCK 1 codeword", base.NONE)),
        field(ProtoField.bytes("rcm.codeword2", "BLOCK 2 codeword", base.NONE)),
    },
    data = {
        field(ProtoField.bytes("rcm.block1.data", "BLOCK 1 data", base.NONE)),
        field(ProtoField.bytes("rcm.block2.data", "BLOCK 2 data", base.NONE)),
    },
    parity = {
        field(ProtoField.bytes("rcm.block1.parity", "BLOCK 1 parity", base.NONE, "Reed-Solomon parity, not checked")),
        field(ProtoField.bytes("rcm.block2.parity", "BLOCK 2 parity", base.NONE, "Reed-Solomon parity, not checked")),
    },
    item_id = field(ProtoField.uint8("rcm.item_id", "Item_ID", base.HEX, itemNames)),
    unit = field(ProtoField.string("rcm.unit", "Unit", base.ASCII, "An engine, radio, camera or single unit")),
    padding1 = field(ProtoField.bytes("rcm.block1.padding", "Padding", base.NONE, "Runs of NULL_0101 (55) and NULL_1010 (AA)")),
    begin_end = field(ProtoField.bytes("rcm.block1.begin_end", "BEGIN/END", base.NONE, "Never sent; skipped")),
    undecoded = field(ProtoField.bytes("rcm.block1.undecoded", "Not read", base.NONE)),
    x = field(ProtoField.uint8("rcm.block2.x", "x", base.DEC, nil, nil, "Flight plan data bytes in this section")),
    plan_id = field(ProtoField.uint32("rcm.block2.flight_plan_ID", "flight_plan_ID", base.HEX)),
    section_id = field(ProtoField.uint16("rcm.block2.flight_plan_section_ID", "flight_plan_section_ID", base.DEC)),
    plan_data = field(ProtoField.bytes("rcm.block2.flight_plan_data", "flight_plan_data", base.NONE)),
    padding2 = field(ProtoField.bytes("rcm.block2.padding", "Padding", base.NONE)),
    eos = field(ProtoField.uint8("rcm.block2.End_Of_String", "End_Of_String", base.HEX)),
}

local E = {
    length = ProtoExpert.new("rcm.expert.length", "Neither a frame nor a datagram",
        expert.group.MALFORMED, expert.severity.ERROR),
    preamble = ProtoExpert.new("rcm.expert.preamble", "Preamble differs from 88 x 55, 0F 0F",
        expert.group.PROTOCOL, expert.severity.WARN),
    unknown = ProtoExpert.new("rcm.expert.unknown_item", "Unknown Item_ID",
        expert.group.MALFORMED, expert.severity.ERROR),
    truncated = ProtoExpert.new("rcm.expert.truncated", "Item runs past the end of BLOCK 1",
        expert.group.MALFORMED, expert.severity.ERROR),
    range = ProtoExpert.new("rcm.expert.out_of_range", "Value out of range",
        expert.group.PROTOCOL, expert.severity.WARN),
    corrupt = ProtoExpert.new("rcm.expert.corrupt_field", "Two-bit field reads data corruption",
        expert.group.PROTOCOL, expert.severity.WARN),
    reserved = ProtoExpert.new("rcm.expert.reserved_bits", "Reserved bits are not 0",
        expert.group.PROTOCOL, expert.severity.WARN),
    orphan = ProtoExpert.new("rcm.expert.orphan", "Unit item before any key item",
        expert.group.PROTOCOL, expert.severity.WARN),
    begin_end = ProtoExpert.new("rcm.expert.begin_end", "BEGIN/END in a block, never sent",
        expert.group.PROTOCOL, expert.severity.NOTE),
    x = ProtoExpert.new("rcm.expert.x", "Flight plan data length out of range",
        expert.group.MALFORMED, expert.severity.ERROR),
    padding2 = ProtoExpert.new("rcm.expert.block2_padding", "BLOCK 2 padding or End_Of_String not as specified",
        expert.group.PROTOCOL, expert.severity.WARN),
}

rcm.fields = fields
rcm.experts = {E.length, E.preamble, E.unknown, E.truncated, E.range, E.corrupt, E.reserved, E.orphan, E.begin_end,
    E.x, E.padding2}

local function int(n)
    return string.format("%d", n)
end

local function formatScaled(n, scale)
    if scale ~= 100 then
        return int(n)
    end
    local mag = math.abs(n)
    return string.format("%s%d.%02d", n < 0 and "-" or "", math.floor(mag / 100), mag % 100)
end

local function rangeProblem(it, n, what)
    if n < it.min then
        return what .. " " .. formatScaled(n, it.scale) .. " is below the minimum " .. formatScaled(it.min, it.scale)
    end
    if n > it.max then
        return what .. " " .. formatScaled(n, it.scale) .. " is above the maximum " .. formatScaled(it.max, it.scale)
    end
    return nil
end

local function withUnit(it, text)
    return it.unit ~= "" and text .. " " .. it.unit or text
end

-- Non-printable bytes appear as \xHH, as in the text format.
local function asciiText(r)
    local bytes = r:bytes()
    local out, printable = {}, true
    for i = 0, bytes:len() - 1 do
        local b = bytes:get_index(i)
        if b >= 0x20 and b <= 0x7E then
            out[#out + 1] = string.char(b)
        else
            out[#out + 1] = string.format("\\x%02X", b)
            printable = false
        end
    end
    return table.concat(out), printable
end

-- Field k (1-based) of a byte: k = 1 is B1_0B1_1, the most significant bits.
local function fieldCode(byte, k)
    return math.floor(byte / 4 ^ (4 - k)) % 4
end

local function daysInMonth(yy, mm)
    local days = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31}
    -- Two-digit years are 2000-2099, where every fourth year is a leap year.
    if mm == 2 and yy % 4 == 0 then
        return 29
    end
    return days[mm]
end

-- Per kind of value: the field's value, its text, and what is wrong with it.
local decoders = {}

decoders.unsigned = function(it, r)
    local n = r:uint()
    return it.scale == 1 and n or n / it.scale, withUnit(it, formatScaled(n, it.scale)), rangeProblem(it, n, "value")
end

decoders.signed = function(it, r)
    local n = r:int()
    return it.scale == 1 and n or n / it.scale, withUnit(it, formatScaled(n, it.scale)), rangeProblem(it, n, "value")
end

decoders.time = function(it, r)
    local n = r:uint()
    local hh, mm, ss = math.floor(n / 10000), math.floor(n / 100) % 100, n % 100
    if hh > 23 or mm > 59 or ss > 59 then
        return int(n), int(n), "not a time hhmmss: " .. int(n)
    end
    local t = string.format("%02d:%02d:%02d", hh, mm, ss)
    return t, t
end

decoders.date = function(it, r)
    local n = r:uint()
    local yy, mm, dd = math.floor(n / 10000), math.floor(n / 100) % 100, n % 100
    local t = string.format("%06d", n)
    if yy > 99 or mm < 1 or mm > 12 or dd < 1 or dd > daysInMonth(yy, mm) then
        return t, t, "not a date yymmdd: " .. t
    end
    return t, string.format("%s (20%02d-%02d-%02d)", t, yy, mm, dd)
end

decoders.station = function(it, r)
    local country, number = r:range(0, 2):uint(), r:range(2, 2):uint()
    local t = (countries[country] or int(country)) .. "_" .. int(number)
    return t, t, rangeProblem(it, country, "country dialling code")
end

decoders.pair = function(it, r)
    local t = int(r:range(0, 1):uint()) .. " " .. int(r:range(1, 1):uint())
    return t, t
end

decoders.fields = function(it, r)
    local byte = r:uint()
    local parts = {}
    for k, fd in ipairs(it.fields) do
        local name = fd.codes[fieldCode(byte, k)]
        parts[#parts + 1] = fd.name .. "=" .. (name ~= "" and name or CORRUPT)
    end
    return byte, table.concat(parts, " ") .. string.format(" (0x%02X)", byte)
end

decoders.text = function(it, r)
    local s, printable = asciiText(r)
    s = s:gsub(" +$", "")
    return s, s, not printable and "text must be printable ASCII" or nil
end

decoders.camera = function(it, r)
    local maker, printable = asciiText(r:range(0, 3))
    local t = maker .. " " .. int(r:range(3, 1):uint())
    return t, t, not printable and "maker must be printable ASCII" or nil
end

decoders.raw = function(it, r)
    local byte = r:uint()
    return byte, string.format("0x%02X", byte)
end

-- Per kind of value with parts: adds the parts under the item.
local parts = {}

parts.station = function(ti, it, r)
    ti:add(it.parts.country, r:range(0, 2))
    ti:add(it.parts.unit, r:range(2, 2))
end

parts.pair = function(ti, it, r)
    ti:add(it.parts.first, r:range(0, 1))
    ti:add(it.parts.second, r:range(1, 1))
end

parts.camera = function(ti, it, r)
    ti:add(it.parts.maker, r:range(0, 3))
    ti:add(it.parts.number, r:range(3, 1))
end

-- A corrupt field is reported but the item stays: its other fields were read
-- correctly (the decoder keeps it the same way).
parts.fields = function(ti, it, r, where, summary)
    local byte = r:uint()
    for k, fd in ipairs(it.fields) do
        local sub = ti:add(fd.f, r)
        local code = fieldCode(byte, k)
        if fd.codes[code] == "" then
            sub:add_tvb_expert_info(E.corrupt, r, string.format("%s %s: code %s means data corruption; ignored",
                where, fd.name, code == 0 and "00" or "11"))
            summary.problems = summary.problems + 1
        end
    end
    if it.reserved then
        local sub = ti:add(it.reserved, r)
        if byte % 4 ^ (4 - #it.fields) ~= 0 then
            sub:add_tvb_expert_info(E.reserved, r, string.format("%s: reserved bits are not 0 (byte 0x%02X)",
                where, byte))
            summary.problems = summary.problems + 1
        end
    end
end

local function addItem(parent, tvb, at, it, where, summary)
    local r = tvb(at + 1, it.size)
    local value, text, problem = decoders[it.kind](it, r)
    local ti = parent:add(it.f, tvb(at, 1 + it.size), value)
    ti:set_text(it.name .. ": " .. text)
    ti:add(F.item_id, tvb(at, 1))
    if parts[it.kind] then
        parts[it.kind](ti, it, r, where, summary)
    end
    if problem then
        ti:add_tvb_expert_info(E.range, r, where .. ": " .. problem)
        summary.problems = summary.problems + 1
    end
    if it.id == ID_MSG then
        summary.idMsg = text
    end
    summary.items = summary.items + 1
    return ti
end

local function paddingText(n55, nAA)
    if nAA == 0 then
        return string.format("Padding: %d bytes of 55", n55)
    end
    if n55 == 0 then
        return string.format("Padding: %d bytes of AA", nAA)
    end
    return string.format("Padding: %d bytes (%d of 55, %d of AA)", n55 + nAA, n55, nAA)
end

-- A unit's subtree grows to cover its items while they follow one another.
local function extend(unit, at, length)
    if at + length > unit.finish then
        unit.finish = at + length
        unit.tree:set_len(unit.finish - unit.start)
    end
end

-- Mirrors the console's decoder: padding anywhere between items, BEGIN/END
-- skipped, a repeated unit's items attached to its last key item, and the
-- rest of the block left unread after an unknown Item_ID, whose length is
-- unknown.
local function dissectBlock1(tvb, tree, base, summary)
    local current = {}
    local i = 0
    while i < BLOCK_SIZE do
        local at = base + i
        local id = tvb(at, 1):uint()
        local it = items[id]
        if id == PAD_55 or id == PAD_AA then
            local j, n55, nAA = i, 0, 0
            while j < BLOCK_SIZE do
                local b = tvb(base + j, 1):uint()
                if b == PAD_55 then
                    n55 = n55 + 1
                elseif b == PAD_AA then
                    nAA = nAA + 1
                else
                    break
                end
                j = j + 1
            end
            tree:add(F.padding1, tvb(at, j - i)):set_text(paddingText(n55, nAA) .. string.format(" at offset %d", i))
            i = j
        elseif id == ID_BEGIN or id == ID_END then
            local length = id == ID_BEGIN and math.min(2, BLOCK_SIZE - i) or 1
            local ti = tree:add(F.begin_end, tvb(at, length))
            ti:set_text(string.format("%s at offset %d: skipped", id == ID_BEGIN and "BEGIN" or "END", i))
            ti:add_proto_expert_info(E.begin_end)
            i = i + length
        elseif not it then
            local ti = tree:add(F.undecoded, tvb(at, BLOCK_SIZE - i))
            ti:set_text(string.format("Not read: the last %d bytes of the block", BLOCK_SIZE - i))
            ti:add_tvb_expert_info(E.unknown, tvb(at, 1), string.format("Unknown Item_ID 0x%02X at block 1 offset " ..
                "%d (packet offset %d): the length of what follows is unknown", id, i, at))
            summary.problems = summary.problems + 1
            return
        elseif i + 1 + it.size > BLOCK_SIZE then
            local ti = tree:add(F.undecoded, tvb(at, BLOCK_SIZE - i))
            ti:set_text(string.format("Not read: the last %d bytes of the block", BLOCK_SIZE - i))
            ti:add_tvb_expert_info(E.truncated, tvb(at, BLOCK_SIZE - i), string.format("%s at block 1 offset %d " ..
                "needs %d value bytes, only %d left in the block", it.name, i, it.size, BLOCK_SIZE - i - 1))
            summary.problems = summary.problems + 1
            return
        else
            local owner = units[it.owner]
            local unit = current[it.owner]
            local length = 1 + it.size
            if it.key then
                local _, keyText = decoders[it.kind](it, tvb(at + 1, it.size))
                local label = owner.label .. " " .. keyText
                unit = {tree = tree:add(F.unit, tvb(at, length), label), start = at, finish = at + length, label = label}
                unit.tree:set_text(label)
                current[it.owner] = unit
            elseif not unit and not owner.repeated then
                unit = {tree = tree:add(F.unit, tvb(at, length), owner.label), start = at, finish = at + length,
                    label = owner.label}
                unit.tree:set_text(owner.label)
                current[it.owner] = unit
            end
            if unit then
                extend(unit, at, length)
                addItem(unit.tree, tvb, at, it, unit.label .. " " .. it.name, summary)
            else
                local ti = addItem(tree, tvb, at, it, it.name, summary)
                ti:add_tvb_expert_info(E.orphan, tvb(at, 1), string.format(
                    "%s at block 1 offset %d comes before any %s; the console ignores it", it.name, i, owner.key))
                summary.problems = summary.problems + 1
            end
            i = i + length
        end
    end
end

local function dissectBlock2(tvb, tree, base, summary)
    local x = tvb(base, 1):uint()
    local xi = tree:add(F.x, tvb(base, 1))
    if x > PLAN_MAX_DATA then
        xi:add_tvb_expert_info(E.x, tvb(base, 1), string.format(
            "x = %d is above the maximum %d by %d; the section is not read", x, PLAN_MAX_DATA, x - PLAN_MAX_DATA))
        summary.problems = summary.problems + 1
        return
    end
    local planId, sectionId = tvb(base + 1, 4):uint(), tvb(base + 5, 2):uint()
    tree:add(F.plan_id, tvb(base + 1, 4))
    tree:add(F.section_id, tvb(base + 5, 2))
    if x > 0 then
        tree:add(F.plan_data, tvb(base + 7, x))
    end
    if x > 0 or planId ~= 0 or sectionId ~= 0 then
        summary.plan = string.format("flight plan 0x%08X section %d, %d bytes", planId, sectionId, x)
    end
    local padStart, padEnd = 7 + x, BLOCK_SIZE - 1
    if padEnd > padStart then
        local pad = tree:add(F.padding2, tvb(base + padStart, padEnd - padStart))
        local bad, first = 0, nil
        for i = padStart, padEnd - 1 do
            if tvb(base + i, 1):uint() ~= PAD_55 then
                bad = bad + 1
                first = first or i
            end
        end
        pad:set_text(string.format("Padding: %d bytes of 55 at offset %d", padEnd - padStart, padStart))
        if first then
            pad:add_tvb_expert_info(E.padding2, tvb(base + first, 1), string.format(
                "%d padding bytes are not 55, the first 0x%02X at block 2 offset %d", bad,
                tvb(base + first, 1):uint(), first))
            summary.problems = summary.problems + 1
        end
    end
    local eos = tvb(base + padEnd, 1):uint()
    local ei = tree:add(F.eos, tvb(base + padEnd, 1))
    if eos ~= 0 then
        ei:add_tvb_expert_info(E.padding2, tvb(base + padEnd, 1), string.format(
            "End_Of_String is 0x%02X at block 2 offset %d; 0x00 belongs there", eos, padEnd))
        summary.problems = summary.problems + 1
    end
end

local function dissectPreamble(tvb, root)
    local ti = root:add(F.preamble, tvb(0, PREAMBLE_SIZE))
    local wrong = 0
    for i = 0, PREAMBLE_SIZE - 1 do
        local expected = i < PREAMBLE_FILL and PREAMBLE_FILL_BYTE or PREAMBLE_MARK
        if tvb(i, 1):uint() ~= expected then
            wrong = wrong + 1
        end
    end
    if wrong > 0 then
        ti:add_proto_expert_info(E.preamble, string.format("%d of the %d preamble bytes differ", wrong, PREAMBLE_SIZE))
    end
end

local function addCodeword(root, tvb, at, n)
    local cw = root:add(F.codeword[n], tvb(at, CODEWORD_SIZE))
    cw:set_text(string.format("BLOCK %d codeword: %d data + %d parity bytes, not corrected", n, BLOCK_SIZE,
        CODEWORD_SIZE - BLOCK_SIZE))
    cw:add(tvb(at, CODEWORD_SIZE), "Reed-Solomon RS(255,223) is not applied by this dissector: the bytes are shown " ..
        "as captured; the frame comment gives the console's decode status")
    local data = cw:add(F.data[n], tvb(at, BLOCK_SIZE))
    cw:add(F.parity[n], tvb(at + BLOCK_SIZE, CODEWORD_SIZE - BLOCK_SIZE))
    return data
end

local DIRECTIONS = {[0] = "Sent ", [1] = "Received "}

function rcm.dissector(tvb, pinfo, tree)
    local length = tvb:len()
    pinfo.cols.protocol = "RCM"
    local root = tree:add(rcm, tvb())
    local start, form
    if length == FRAME_SIZE then
        start, form = PREAMBLE_SIZE, "frame"
    elseif length == DATAGRAM_SIZE then
        start, form = 0, "datagram"
    else
        local text = string.format("%d bytes: a frame is %d bytes and a datagram %d", length, FRAME_SIZE,
            DATAGRAM_SIZE)
        root:add_proto_expert_info(E.length, text)
        pinfo.cols.info = text
        return length
    end
    root:append_text(string.format(", %s (%d bytes)", form, length))
    root:add(F.form, tvb(), form)
    if start > 0 then
        dissectPreamble(tvb, root)
    end
    local summary = {items = 0, problems = 0}
    local block1 = addCodeword(root, tvb, start, 1)
    dissectBlock1(tvb, block1, start, summary)
    local block2 = addCodeword(root, tvb, start + CODEWORD_SIZE, 2)
    dissectBlock2(tvb, block2, start + CODEWORD_SIZE, summary)

    local info = (DIRECTIONS[pinfo.p2p_dir] or "") .. form
    if summary.idMsg then
        info = info .. " " .. items[ID_MSG].name .. " " .. summary.idMsg
    end
    info = info .. string.format(", %d items", summary.items)
    if summary.plan then
        info = info .. ", " .. summary.plan
    end
    if summary.problems > 0 then
        info = info .. string.format(" [%d problems]", summary.problems)
    end
    pinfo.cols.info = info
    return length
end

DissectorTable.get("wtap_encap"):add(wtap_encaps.USER0, rcm)
DissectorTable.get("udp.port"):add_for_decode_as(rcm)
)lua";

std::string luaString(std::string_view s)
{
    std::string out = "\"";
    for (char c : s) {
        if (c == '"' || c == '\\')
            out += '\\';
        out += c;
    }
    return out + "\"";
}

std::string hex(unsigned value, int digits)
{
    char buf[16];
    std::snprintf(buf, sizeof buf, "0x%0*X", digits, value);
    return buf;
}

std::string constant(std::string_view name, std::int64_t value)
{
    return "local " + std::string(name) + " = " + std::to_string(value) + "\n";
}

// A later item with an earlier item's name (the cameras' GCS IDs, named as
// the header's) would otherwise register the same filter name twice.
std::string abbreviation(const ItemInfo& item)
{
    for (const ItemInfo& other : itemTable()) {
        if (&other == &item)
            break;
        if (other.name == item.name)
            return "rcm.item." + std::string(sectionName(item.owner)) + "." + std::string(item.name);
    }
    return "rcm.item." + std::string(item.name);
}

std::string_view kindName(ValueKind kind)
{
    switch (kind) {
        case ValueKind::Unsigned:
            return "unsigned";
        case ValueKind::Signed:
            return "signed";
        case ValueKind::Station:
            return "station";
        case ValueKind::Time:
            return "time";
        case ValueKind::Date:
            return "date";
        case ValueKind::BytePair:
            return "pair";
        case ValueKind::Fields:
            return "fields";
        case ValueKind::Text:
            return "text";
        case ValueKind::CameraId:
            return "camera";
        case ValueKind::Raw:
            return "raw";
    }
    throw std::logic_error("kindName: unknown ValueKind");
}

std::string integerField(bool isSigned, int bytes, const std::string& abbr, std::string_view name,
                         std::string_view base, std::string_view valueString, std::string_view mask,
                         std::string_view description)
{
    if (bytes < 1 || bytes > 4)
        throw std::logic_error("wiresharkDissectorLua: no integer field of " + std::to_string(bytes) + " bytes");
    return "field(ProtoField." + std::string(isSigned ? "int" : "uint") + std::to_string(8 * bytes) + "(" +
           luaString(abbr) + ", " + luaString(name) + ", " + std::string(base) + ", " + std::string(valueString) +
           ", " + std::string(mask) + ", " + luaString(description) + "))";
}

std::string stringField(const std::string& abbr, std::string_view name, std::string_view description)
{
    return "field(ProtoField.string(" + luaString(abbr) + ", " + luaString(name) + ", base.ASCII, " +
           luaString(description) + "))";
}

// The item's own ProtoField; the value type is what a display filter compares.
std::string itemField(const ItemInfo& item, const std::string& abbr)
{
    switch (item.kind) {
        case ValueKind::Unsigned:
        case ValueKind::Signed:
            if (item.scale != 1)
                return "field(ProtoField.double(" + luaString(abbr) + ", " + luaString(item.name) + ", " +
                       luaString(item.label) + "))";
            return integerField(item.kind == ValueKind::Signed, item.size, abbr, item.name, "base.DEC", "nil", "nil",
                                item.label);
        case ValueKind::Fields:
        case ValueKind::Raw:
            return integerField(false, item.size, abbr, item.name, "base.HEX", "nil", "nil", item.label);
        case ValueKind::Station:
        case ValueKind::Time:
        case ValueKind::Date:
        case ValueKind::BytePair:
        case ValueKind::Text:
        case ValueKind::CameraId:
            return stringField(abbr, item.name, item.label);
    }
    throw std::logic_error("itemField: unknown ValueKind");
}

std::string codeTable(const FieldInfo& f, bool forDisplay)
{
    std::string out = "{";
    for (unsigned code = 0; code < 4; ++code) {
        std::string_view name = f.codes[code];
        if (forDisplay && name.empty())
            name = "corrupt";
        out += (code ? ", [" : "[") + std::to_string(code) + "] = " + luaString(name);
    }
    return out + "}";
}

std::string itemEntry(const ItemInfo& item)
{
    const std::string abbr = abbreviation(item);
    const bool numeric = item.kind == ValueKind::Unsigned || item.kind == ValueKind::Signed;
    std::string out = "items[" + hex(static_cast<unsigned>(item.id), 2) + "] = {\n";
    out += "    id = " + hex(static_cast<unsigned>(item.id), 2) + ", name = " + luaString(item.name) +
           ", kind = " + luaString(kindName(item.kind)) + ", size = " + std::to_string(item.size) +
           ", owner = " + std::to_string(static_cast<int>(item.owner)) + ", key = " + (item.key ? "true" : "false") +
           ",\n";
    out += "    min = " + std::to_string(item.min) + ", max = " + std::to_string(item.max) +
           ", scale = " + std::to_string(item.scale) + ", unit = " + luaString(numeric ? item.unit : "") + ",\n";
    out += "    f = " + itemField(item, abbr) + ",\n";
    switch (item.kind) {
        case ValueKind::Station:
            out += "    parts = {\n";
            out += "        country = " +
                   integerField(false, 2, abbr + ".country", "country", "base.DEC", "countries", "nil",
                                "Country dialling code") +
                   ",\n";
            out += "        unit = " +
                   integerField(false, 2, abbr + ".unit", "unit", "base.DEC", "nil", "nil", "Unit number") + ",\n";
            out += "    },\n";
            break;
        case ValueKind::BytePair:
            out += "    parts = {\n";
            out += "        first = " + integerField(false, 1, abbr + ".first", "first", "base.DEC", "nil", "nil", "") +
                   ",\n";
            out +=
                "        second = " + integerField(false, 1, abbr + ".second", "second", "base.DEC", "nil", "nil", "") +
                ",\n";
            out += "    },\n";
            break;
        case ValueKind::CameraId:
            out += "    parts = {\n";
            out += "        maker = " + stringField(abbr + ".maker", "maker", "Three ASCII characters") + ",\n";
            out += "        number = " +
                   integerField(false, 1, abbr + ".number", "number", "base.DEC", "nil", "nil", "Camera number") +
                   ",\n";
            out += "    },\n";
            break;
        case ValueKind::Fields: {
            out += "    fields = {\n";
            const int n = static_cast<int>(item.fields.size());
            for (int k = 0; k < n; ++k) {
                const FieldInfo& f = item.fields[k];
                out += "        {name = " + luaString(f.name) + ", codes = " + codeTable(f, false) + ",\n";
                out += "            f = " +
                       integerField(false, 1, abbr + "." + std::string(f.name), f.name, "base.DEC", codeTable(f, true),
                                    hex(withFieldCode(0, k, 3), 2), f.label) +
                       "},\n";
            }
            out += "    },\n";
            if (n < 4)
                out += "    reserved = " +
                       integerField(false, 1, abbr + ".reserved", "reserved bits", "base.HEX", "nil",
                                    hex(0xFFu >> (2 * n), 2), "Bits the profile fixes at 0") +
                       ",\n";
            break;
        }
        default:
            break;
    }
    return out + "}\n";
}

}  // namespace

std::string wiresharkDissectorLua()
{
    std::string out(kHeader);

    out += "\n-- Sizes and marks of the frame and the blocks (codec/frame/Frame.h, codec/message/ItemTable.h).\n";
    out += constant("PREAMBLE_SIZE", kPreambleSize);
    out += constant("PREAMBLE_FILL", kPreambleFill);
    out += "local PREAMBLE_FILL_BYTE = " + hex(kPreambleFillByte, 2) + "\n";
    out += "local PREAMBLE_MARK = " + hex(kPreambleMark, 2) + "\n";
    out += constant("BLOCK_SIZE", kBlockSize);
    out += constant("CODEWORD_SIZE", kCodewordSize);
    out += constant("FRAME_SIZE", kFrameSize);
    out += constant("DATAGRAM_SIZE", kDatagramSize);
    out += constant("PLAN_MAX_DATA", FlightPlanSection::kMaxData);
    out += "local PAD_55 = " + hex(kPad55, 2) + "\n";
    out += "local PAD_AA = " + hex(kPadAA, 2) + "\n";
    out += "local ID_BEGIN = " + hex(kBegin, 2) + "\n";
    out += "local ID_END = " + hex(kEnd, 2) + "\n";
    out += "local ID_MSG = " + hex(static_cast<unsigned>(ItemId::ID_msg), 2) + "\n";

    // The range a station's country may take is the item table's; only codes
    // inside it are worth a name.
    std::int64_t countryMax = 0;
    for (const ItemInfo& item : itemTable())
        if (item.kind == ValueKind::Station && item.max > countryMax)
            countryMax = item.max;
    out += "\n-- Country dialling code -> the ISO 3166-1 alpha-2 the text format prints (codec/message/CountryCodes.cpp).\n";
    out += "local countries = {\n";
    std::string line;
    for (std::int64_t code = 1; code <= countryMax; ++code) {
        const std::string_view alpha2 = countryForDiallingCode(static_cast<std::uint16_t>(code));
        if (alpha2.empty())
            continue;
        std::string entry = "[" + std::to_string(code) + "] = " + luaString(alpha2) + ",";
        if (!line.empty() && line.size() + 1 + entry.size() > 116) {
            out += "    " + line + "\n";
            line.clear();
        }
        line += (line.empty() ? "" : " ") + entry;
    }
    if (!line.empty())
        out += "    " + line + "\n";
    out += "}\n";

    out += "\n-- Units by UnitKind; a repeated unit begins at its key item.\n";
    out += "local units = {\n";
    for (int k = 0; k < kUnitKindCount; ++k) {
        const auto kind = static_cast<UnitKind>(k);
        out += "    [" + std::to_string(k) + "] = {label = " + luaString(unitLabel(kind)) +
               ", repeated = " + (isRepeated(kind) ? "true" : "false");
        if (const auto key = unitKey(kind))
            out += ", key = " + luaString(itemInfo(*key).name);
        out += "},\n";
    }
    out += "}\n";

    out += "\n-- BLOCK 1 items by Item_ID, in canonical order.\n";
    out += "local items = {}\n";
    for (const ItemInfo& item : itemTable())
        out += itemEntry(item);

    out += kBody;
    return out;
}

}  // namespace rcm
