-- Remote Control Message (RCM) dissector for Wireshark 4.0 and later.
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

-- Sizes and marks of the frame and the blocks (codec/frame/Frame.h, codec/message/ItemTable.h).
local PREAMBLE_SIZE = 90
local PREAMBLE_FILL = 88
local PREAMBLE_FILL_BYTE = 0x55
local PREAMBLE_MARK = 0x0F
local BLOCK_SIZE = 223
local CODEWORD_SIZE = 255
local FRAME_SIZE = 600
local DATAGRAM_SIZE = 510
local PLAN_MAX_DATA = 215
local PAD_55 = 0x55
local PAD_AA = 0xAA
local ID_BEGIN = 0x01
local ID_END = 0x02
local ID_MSG = 0x03

-- Country dialling code -> the ISO 3166-1 alpha-2 the text format prints (codec/message/CountryCodes.cpp).
local countries = {
    [1] = "US", [7] = "RU", [20] = "EG", [27] = "ZA", [30] = "GR", [31] = "NL", [32] = "BE", [33] = "FR", [34] = "ES",
    [36] = "HU", [39] = "IT", [40] = "RO", [41] = "CH", [43] = "AT", [44] = "GB", [45] = "DK", [46] = "SE", [47] = "NO",
    [48] = "PL", [49] = "DE", [51] = "PE", [52] = "MX", [53] = "CU", [54] = "AR", [55] = "BR", [56] = "CL", [57] = "CO",
    [58] = "VE", [60] = "MY", [61] = "AU", [62] = "ID", [63] = "PH", [64] = "NZ", [65] = "SG", [66] = "TH", [81] = "JP",
    [82] = "KR", [84] = "VN", [86] = "CN", [90] = "TR", [91] = "IN", [92] = "PK", [93] = "AF", [94] = "LK", [95] = "MM",
    [98] = "IR", [211] = "SS", [212] = "MA", [213] = "DZ", [216] = "TN", [218] = "LY", [220] = "GM", [221] = "SN",
    [222] = "MR", [223] = "ML", [224] = "GN", [225] = "CI", [226] = "BF", [227] = "NE", [228] = "TG", [229] = "BJ",
    [230] = "MU", [231] = "LR", [232] = "SL", [233] = "GH", [234] = "NG", [235] = "TD", [236] = "CF", [237] = "CM",
    [238] = "CV", [239] = "ST", [240] = "GQ", [241] = "GA", [242] = "CG", [243] = "CD", [244] = "AO", [245] = "GW",
    [246] = "IO", [248] = "SC", [249] = "SD", [250] = "RW", [251] = "ET", [252] = "SO", [253] = "DJ", [254] = "KE",
    [255] = "TZ", [256] = "UG", [257] = "BI", [258] = "MZ", [260] = "ZM", [261] = "MG", [262] = "RE", [263] = "ZW",
    [264] = "NA", [265] = "MW", [266] = "LS", [267] = "BW", [268] = "SZ", [269] = "KM", [290] = "SH", [291] = "ER",
    [297] = "AW", [298] = "FO", [299] = "GL", [350] = "GI", [351] = "PT", [352] = "LU", [353] = "IE", [354] = "IS",
    [355] = "AL", [356] = "MT", [357] = "CY", [358] = "FI", [359] = "BG", [370] = "LT", [371] = "LV", [372] = "EE",
    [373] = "MD", [374] = "AM", [375] = "BY", [376] = "AD", [377] = "MC", [378] = "SM", [380] = "UA", [381] = "RS",
    [382] = "ME", [385] = "HR", [386] = "SI", [387] = "BA", [389] = "MK", [420] = "CZ", [421] = "SK", [423] = "LI",
    [500] = "FK", [501] = "BZ", [502] = "GT", [503] = "SV", [504] = "HN", [505] = "NI", [506] = "CR", [507] = "PA",
    [508] = "PM", [509] = "HT", [590] = "GP", [591] = "BO", [592] = "GY", [593] = "EC", [594] = "GF", [595] = "PY",
    [596] = "MQ", [597] = "SR", [598] = "UY", [599] = "CW", [670] = "TL", [672] = "NF", [673] = "BN", [674] = "NR",
    [675] = "PG", [676] = "TO", [677] = "SB", [678] = "VU", [679] = "FJ", [680] = "PW", [681] = "WF", [682] = "CK",
    [683] = "NU", [685] = "WS", [686] = "KI", [687] = "NC", [688] = "TV", [689] = "PF", [690] = "TK", [691] = "FM",
    [692] = "MH", [850] = "KP", [852] = "HK", [853] = "MO", [855] = "KH", [856] = "LA", [880] = "BD", [886] = "TW",
    [960] = "MV", [961] = "LB", [962] = "JO", [963] = "SY", [964] = "IQ", [965] = "KW", [966] = "SA", [967] = "YE",
    [968] = "OM", [970] = "PS", [971] = "AE", [972] = "IL", [973] = "BH", [974] = "QA", [975] = "BT", [976] = "MN",
    [977] = "NP", [992] = "TJ", [993] = "TM", [994] = "AZ", [995] = "GE", [996] = "KG", [998] = "UZ",
}

-- Units by UnitKind; a repeated unit begins at its key item.
local units = {
    [0] = {label = "Header", repeated = false},
    [1] = {label = "Engine", repeated = true, key = "eng_ID"},
    [2] = {label = "Flaps", repeated = false},
    [3] = {label = "Fuel dump", repeated = false},
    [4] = {label = "Settings", repeated = false},
    [5] = {label = "Radio", repeated = true, key = "system_ID"},
    [6] = {label = "Sense and avoid", repeated = false},
    [7] = {label = "Camera", repeated = true, key = "cam_ID"},
}

-- BLOCK 1 items by Item_ID, in canonical order.
local items = {}
items[0x03] = {
    id = 0x03, name = "ID_msg", kind = "unsigned", size = 3, owner = 0, key = false,
    min = 0, max = 16777215, scale = 1, unit = "",
    f = field(ProtoField.uint24("rcm.item.ID_msg", "ID_msg", base.DEC, nil, nil, "Message ID")),
}
items[0x04] = {
    id = 0x04, name = "ID_UA_source", kind = "station", size = 4, owner = 0, key = false,
    min = 1, max = 1929, scale = 1, unit = "",
    f = field(ProtoField.string("rcm.item.ID_UA_source", "ID_UA_source", base.ASCII, "Aircraft ID")),
    parts = {
        country = field(ProtoField.uint16("rcm.item.ID_UA_source.country", "country", base.DEC, countries, nil, "Country dialling code")),
        unit = field(ProtoField.uint16("rcm.item.ID_UA_source.unit", "unit", base.DEC, nil, nil, "Unit number")),
    },
}
items[0x05] = {
    id = 0x05, name = "time_UTC", kind = "time", size = 3, owner = 0, key = false,
    min = 0, max = 235959, scale = 1, unit = "",
    f = field(ProtoField.string("rcm.item.time_UTC", "time_UTC", base.ASCII, "Time (UTC)")),
}
items[0x06] = {
    id = 0x06, name = "date_UTC", kind = "date", size = 3, owner = 0, key = false,
    min = 0, max = 991231, scale = 1, unit = "",
    f = field(ProtoField.string("rcm.item.date_UTC", "date_UTC", base.ASCII, "Date (UTC)")),
}
items[0x07] = {
    id = 0x07, name = "ID_BLK12_format", kind = "pair", size = 2, owner = 0, key = false,
    min = 0, max = 255, scale = 1, unit = "",
    f = field(ProtoField.string("rcm.item.ID_BLK12_format", "ID_BLK12_format", base.ASCII, "Block 1 and 2 format IDs")),
    parts = {
        first = field(ProtoField.uint8("rcm.item.ID_BLK12_format.first", "first", base.DEC, nil, nil, "")),
        second = field(ProtoField.uint8("rcm.item.ID_BLK12_format.second", "second", base.DEC, nil, nil, "")),
    },
}
items[0x08] = {
    id = 0x08, name = "ID_GCS_destination", kind = "station", size = 4, owner = 0, key = false,
    min = 1, max = 1929, scale = 1, unit = "",
    f = field(ProtoField.string("rcm.item.ID_GCS_destination", "ID_GCS_destination", base.ASCII, "GCS destination")),
    parts = {
        country = field(ProtoField.uint16("rcm.item.ID_GCS_destination.country", "country", base.DEC, countries, nil, "Country dialling code")),
        unit = field(ProtoField.uint16("rcm.item.ID_GCS_destination.unit", "unit", base.DEC, nil, nil, "Unit number")),
    },
}
items[0x09] = {
    id = 0x09, name = "ID_GCS_backup", kind = "station", size = 4, owner = 0, key = false,
    min = 1, max = 1929, scale = 1, unit = "",
    f = field(ProtoField.string("rcm.item.ID_GCS_backup", "ID_GCS_backup", base.ASCII, "GCS backup")),
    parts = {
        country = field(ProtoField.uint16("rcm.item.ID_GCS_backup.country", "country", base.DEC, countries, nil, "Country dialling code")),
        unit = field(ProtoField.uint16("rcm.item.ID_GCS_backup.unit", "unit", base.DEC, nil, nil, "Unit number")),
    },
}
items[0x31] = {
    id = 0x31, name = "eng_ID", kind = "unsigned", size = 1, owner = 1, key = true,
    min = 0, max = 255, scale = 1, unit = "",
    f = field(ProtoField.uint8("rcm.item.eng_ID", "eng_ID", base.DEC, nil, nil, "Engine ID")),
}
items[0x30] = {
    id = 0x30, name = "eng_status", kind = "fields", size = 1, owner = 1, key = false,
    min = 0, max = 255, scale = 1, unit = "",
    f = field(ProtoField.uint8("rcm.item.eng_status", "eng_status", base.HEX, nil, nil, "Engine status")),
    fields = {
        {name = "control", codes = {[0] = "", [1] = "AUTO", [2] = "GCS", [3] = "RC"},
            f = field(ProtoField.uint8("rcm.item.eng_status.control", "control", base.DEC, {[0] = "corrupt", [1] = "AUTO", [2] = "GCS", [3] = "RC"}, 0xC0, "Control source"))},
        {name = "slave", codes = {[0] = "", [1] = "NO_SLAVE", [2] = "MASTER_SLAVE", [3] = ""},
            f = field(ProtoField.uint8("rcm.item.eng_status.slave", "slave", base.DEC, {[0] = "corrupt", [1] = "NO_SLAVE", [2] = "MASTER_SLAVE", [3] = "corrupt"}, 0x30, "Master/slave mode"))},
    },
    reserved = field(ProtoField.uint8("rcm.item.eng_status.reserved", "reserved bits", base.HEX, nil, 0x0F, "Bits the profile fixes at 0")),
}
items[0x32] = {
    id = 0x32, name = "eng_prop_pitch", kind = "unsigned", size = 1, owner = 1, key = false,
    min = 0, max = 255, scale = 1, unit = "",
    f = field(ProtoField.uint8("rcm.item.eng_prop_pitch", "eng_prop_pitch", base.DEC, nil, nil, "Propeller pitch")),
}
items[0x33] = {
    id = 0x33, name = "eng_carb_SET", kind = "unsigned", size = 1, owner = 1, key = false,
    min = 0, max = 255, scale = 1, unit = "",
    f = field(ProtoField.uint8("rcm.item.eng_carb_SET", "eng_carb_SET", base.DEC, nil, nil, "Carburettor setting")),
}
items[0x40] = {
    id = 0x40, name = "FLAP_status", kind = "fields", size = 1, owner = 2, key = false,
    min = 0, max = 255, scale = 1, unit = "",
    f = field(ProtoField.uint8("rcm.item.FLAP_status", "FLAP_status", base.HEX, nil, nil, "Flaps status")),
    fields = {
        {name = "control", codes = {[0] = "", [1] = "AUTO", [2] = "GCS", [3] = "RC"},
            f = field(ProtoField.uint8("rcm.item.FLAP_status.control", "control", base.DEC, {[0] = "corrupt", [1] = "AUTO", [2] = "GCS", [3] = "RC"}, 0xC0, "Control source"))},
        {name = "slave_aileron", codes = {[0] = "", [1] = "NO_SLAVE", [2] = "MASTER_SLAVE", [3] = ""},
            f = field(ProtoField.uint8("rcm.item.FLAP_status.slave_aileron", "slave_aileron", base.DEC, {[0] = "corrupt", [1] = "NO_SLAVE", [2] = "MASTER_SLAVE", [3] = "corrupt"}, 0x30, "Master LH + slave RH aileron"))},
    },
    reserved = field(ProtoField.uint8("rcm.item.FLAP_status.reserved", "reserved bits", base.HEX, nil, 0x0F, "Bits the profile fixes at 0")),
}
items[0x41] = {
    id = 0x41, name = "F_aileron_LHS_set", kind = "signed", size = 1, owner = 2, key = false,
    min = -127, max = 127, scale = 1, unit = "deg",
    f = field(ProtoField.int8("rcm.item.F_aileron_LHS_set", "F_aileron_LHS_set", base.DEC, nil, nil, "Left aileron")),
}
items[0x42] = {
    id = 0x42, name = "F_aileron_RHS_set", kind = "signed", size = 1, owner = 2, key = false,
    min = -127, max = 127, scale = 1, unit = "deg",
    f = field(ProtoField.int8("rcm.item.F_aileron_RHS_set", "F_aileron_RHS_set", base.DEC, nil, nil, "Right aileron")),
}
items[0x43] = {
    id = 0x43, name = "F_lift_set", kind = "signed", size = 1, owner = 2, key = false,
    min = -127, max = 127, scale = 1, unit = "deg",
    f = field(ProtoField.int8("rcm.item.F_lift_set", "F_lift_set", base.DEC, nil, nil, "Lift flaps")),
}
items[0x44] = {
    id = 0x44, name = "F_rudder_set", kind = "signed", size = 1, owner = 2, key = false,
    min = -127, max = 127, scale = 1, unit = "deg",
    f = field(ProtoField.int8("rcm.item.F_rudder_set", "F_rudder_set", base.DEC, nil, nil, "Rudder")),
}
items[0x45] = {
    id = 0x45, name = "F_elev_set", kind = "signed", size = 1, owner = 2, key = false,
    min = -127, max = 127, scale = 1, unit = "deg",
    f = field(ProtoField.int8("rcm.item.F_elev_set", "F_elev_set", base.DEC, nil, nil, "Elevator")),
}
items[0x46] = {
    id = 0x46, name = "F_airbrake_set", kind = "signed", size = 1, owner = 2, key = false,
    min = -127, max = 127, scale = 1, unit = "deg",
    f = field(ProtoField.int8("rcm.item.F_airbrake_set", "F_airbrake_set", base.DEC, nil, nil, "Airbrake")),
}
items[0x60] = {
    id = 0x60, name = "ENABLE_fuel_dump", kind = "fields", size = 1, owner = 3, key = false,
    min = 0, max = 255, scale = 1, unit = "",
    f = field(ProtoField.uint8("rcm.item.ENABLE_fuel_dump", "ENABLE_fuel_dump", base.HEX, nil, nil, "Fuel dump")),
    fields = {
        {name = "facility", codes = {[0] = "", [1] = "DISABLED", [2] = "ENABLED", [3] = ""},
            f = field(ProtoField.uint8("rcm.item.ENABLE_fuel_dump.facility", "facility", base.DEC, {[0] = "corrupt", [1] = "DISABLED", [2] = "ENABLED", [3] = "corrupt"}, 0xC0, "Fuel dump facility"))},
        {name = "tank1", codes = {[0] = "", [1] = "NO_DUMP", [2] = "DUMP", [3] = ""},
            f = field(ProtoField.uint8("rcm.item.ENABLE_fuel_dump.tank1", "tank1", base.DEC, {[0] = "corrupt", [1] = "NO_DUMP", [2] = "DUMP", [3] = "corrupt"}, 0x30, "Dump tank 1"))},
        {name = "tank2", codes = {[0] = "", [1] = "NO_DUMP", [2] = "DUMP", [3] = ""},
            f = field(ProtoField.uint8("rcm.item.ENABLE_fuel_dump.tank2", "tank2", base.DEC, {[0] = "corrupt", [1] = "NO_DUMP", [2] = "DUMP", [3] = "corrupt"}, 0x0C, "Dump tank 2"))},
        {name = "tank3", codes = {[0] = "", [1] = "NO_DUMP", [2] = "DUMP", [3] = ""},
            f = field(ProtoField.uint8("rcm.item.ENABLE_fuel_dump.tank3", "tank3", base.DEC, {[0] = "corrupt", [1] = "NO_DUMP", [2] = "DUMP", [3] = "corrupt"}, 0x03, "Dump tank 3"))},
    },
}
items[0x70] = {
    id = 0x70, name = "land_wheels", kind = "fields", size = 1, owner = 4, key = false,
    min = 0, max = 255, scale = 1, unit = "",
    f = field(ProtoField.uint8("rcm.item.land_wheels", "land_wheels", base.HEX, nil, nil, "Landing gear")),
    fields = {
        {name = "LHS", codes = {[0] = "", [1] = "OUT", [2] = "RETRACTED", [3] = ""},
            f = field(ProtoField.uint8("rcm.item.land_wheels.LHS", "LHS", base.DEC, {[0] = "corrupt", [1] = "OUT", [2] = "RETRACTED", [3] = "corrupt"}, 0xC0, "Left wheel"))},
        {name = "RHS", codes = {[0] = "", [1] = "OUT", [2] = "RETRACTED", [3] = ""},
            f = field(ProtoField.uint8("rcm.item.land_wheels.RHS", "RHS", base.DEC, {[0] = "corrupt", [1] = "OUT", [2] = "RETRACTED", [3] = "corrupt"}, 0x30, "Right wheel"))},
        {name = "NOSE", codes = {[0] = "", [1] = "OUT", [2] = "RETRACTED", [3] = ""},
            f = field(ProtoField.uint8("rcm.item.land_wheels.NOSE", "NOSE", base.DEC, {[0] = "corrupt", [1] = "OUT", [2] = "RETRACTED", [3] = "corrupt"}, 0x0C, "Nose wheel"))},
        {name = "TAIL", codes = {[0] = "", [1] = "OUT", [2] = "RETRACTED", [3] = ""},
            f = field(ProtoField.uint8("rcm.item.land_wheels.TAIL", "TAIL", base.DEC, {[0] = "corrupt", [1] = "OUT", [2] = "RETRACTED", [3] = "corrupt"}, 0x03, "Tail wheel"))},
    },
}
items[0x71] = {
    id = 0x71, name = "lights", kind = "fields", size = 1, owner = 4, key = false,
    min = 0, max = 255, scale = 1, unit = "",
    f = field(ProtoField.uint8("rcm.item.lights", "lights", base.HEX, nil, nil, "Lights and wheel brake")),
    fields = {
        {name = "wing_RHS", codes = {[0] = "", [1] = "OFF", [2] = "ON", [3] = ""},
            f = field(ProtoField.uint8("rcm.item.lights.wing_RHS", "wing_RHS", base.DEC, {[0] = "corrupt", [1] = "OFF", [2] = "ON", [3] = "corrupt"}, 0xC0, "Right wing light"))},
        {name = "wing_LHS", codes = {[0] = "", [1] = "OFF", [2] = "ON", [3] = ""},
            f = field(ProtoField.uint8("rcm.item.lights.wing_LHS", "wing_LHS", base.DEC, {[0] = "corrupt", [1] = "OFF", [2] = "ON", [3] = "corrupt"}, 0x30, "Left wing light"))},
        {name = "tail", codes = {[0] = "", [1] = "OFF", [2] = "ON", [3] = ""},
            f = field(ProtoField.uint8("rcm.item.lights.tail", "tail", base.DEC, {[0] = "corrupt", [1] = "OFF", [2] = "ON", [3] = "corrupt"}, 0x0C, "Tail light"))},
        {name = "wheel_brake", codes = {[0] = "", [1] = "OFF", [2] = "ON", [3] = ""},
            f = field(ProtoField.uint8("rcm.item.lights.wheel_brake", "wheel_brake", base.DEC, {[0] = "corrupt", [1] = "OFF", [2] = "ON", [3] = "corrupt"}, 0x03, "Wheel brake"))},
    },
}
items[0x72] = {
    id = 0x72, name = "setting_72", kind = "raw", size = 1, owner = 4, key = false,
    min = 0, max = 255, scale = 1, unit = "",
    f = field(ProtoField.uint8("rcm.item.setting_72", "setting_72", base.HEX, nil, nil, "Reserved setting 72")),
}
items[0x81] = {
    id = 0x81, name = "system_ID", kind = "text", size = 8, owner = 5, key = true,
    min = 0, max = 8, scale = 1, unit = "",
    f = field(ProtoField.string("rcm.item.system_ID", "system_ID", base.ASCII, "System ID")),
}
items[0x80] = {
    id = 0x80, name = "receiver_control", kind = "fields", size = 1, owner = 5, key = false,
    min = 0, max = 255, scale = 1, unit = "",
    f = field(ProtoField.uint8("rcm.item.receiver_control", "receiver_control", base.HEX, nil, nil, "Receiver and transmitter")),
    fields = {
        {name = "receiver", codes = {[0] = "", [1] = "OFF", [2] = "ON", [3] = ""},
            f = field(ProtoField.uint8("rcm.item.receiver_control.receiver", "receiver", base.DEC, {[0] = "corrupt", [1] = "OFF", [2] = "ON", [3] = "corrupt"}, 0xC0, "Receiver"))},
        {name = "transmitter", codes = {[0] = "", [1] = "OFF", [2] = "ON", [3] = ""},
            f = field(ProtoField.uint8("rcm.item.receiver_control.transmitter", "transmitter", base.DEC, {[0] = "corrupt", [1] = "OFF", [2] = "ON", [3] = "corrupt"}, 0x30, "Transmitter"))},
    },
    reserved = field(ProtoField.uint8("rcm.item.receiver_control.reserved", "reserved bits", base.HEX, nil, 0x0F, "Bits the profile fixes at 0")),
}
items[0x82] = {
    id = 0x82, name = "Rx_freq", kind = "unsigned", size = 4, owner = 5, key = false,
    min = 0, max = 4294967295, scale = 1, unit = "kHz",
    f = field(ProtoField.uint32("rcm.item.Rx_freq", "Rx_freq", base.DEC, nil, nil, "Receive frequency")),
}
items[0x83] = {
    id = 0x83, name = "Tx_freq", kind = "unsigned", size = 4, owner = 5, key = false,
    min = 0, max = 4294967295, scale = 1, unit = "kHz",
    f = field(ProtoField.uint32("rcm.item.Tx_freq", "Tx_freq", base.DEC, nil, nil, "Transmit frequency")),
}
items[0x84] = {
    id = 0x84, name = "Tx_OP_power", kind = "unsigned", size = 1, owner = 5, key = false,
    min = 0, max = 255, scale = 1, unit = "dBm",
    f = field(ProtoField.uint8("rcm.item.Tx_OP_power", "Tx_OP_power", base.DEC, nil, nil, "Transmit power")),
}
items[0xB0] = {
    id = 0xB0, name = "SA_zoom_LHS_cam", kind = "unsigned", size = 1, owner = 6, key = false,
    min = 0, max = 255, scale = 1, unit = "",
    f = field(ProtoField.uint8("rcm.item.SA_zoom_LHS_cam", "SA_zoom_LHS_cam", base.DEC, nil, nil, "Left camera zoom")),
}
items[0xB1] = {
    id = 0xB1, name = "SA_zoom_FWD_cam", kind = "unsigned", size = 1, owner = 6, key = false,
    min = 0, max = 255, scale = 1, unit = "",
    f = field(ProtoField.uint8("rcm.item.SA_zoom_FWD_cam", "SA_zoom_FWD_cam", base.DEC, nil, nil, "Forward camera zoom")),
}
items[0xB2] = {
    id = 0xB2, name = "SA_zoom_RHS_cam", kind = "unsigned", size = 1, owner = 6, key = false,
    min = 0, max = 255, scale = 1, unit = "",
    f = field(ProtoField.uint8("rcm.item.SA_zoom_RHS_cam", "SA_zoom_RHS_cam", base.DEC, nil, nil, "Right camera zoom")),
}
items[0xC0] = {
    id = 0xC0, name = "cam_ID", kind = "camera", size = 4, owner = 7, key = true,
    min = 0, max = 255, scale = 1, unit = "",
    f = field(ProtoField.string("rcm.item.cam_ID", "cam_ID", base.ASCII, "Camera ID")),
    parts = {
        maker = field(ProtoField.string("rcm.item.cam_ID.maker", "maker", base.ASCII, "Three ASCII characters")),
        number = field(ProtoField.uint8("rcm.item.cam_ID.number", "number", base.DEC, nil, nil, "Camera number")),
    },
}
items[0xC1] = {
    id = 0xC1, name = "cam_mag_compass", kind = "unsigned", size = 2, owner = 7, key = false,
    min = 0, max = 35999, scale = 100, unit = "deg",
    f = field(ProtoField.double("rcm.item.cam_mag_compass", "cam_mag_compass", "Compass bearing")),
}
items[0xC2] = {
    id = 0xC2, name = "cam_elev", kind = "signed", size = 2, owner = 7, key = false,
    min = -32767, max = 32767, scale = 100, unit = "deg",
    f = field(ProtoField.double("rcm.item.cam_elev", "cam_elev", "Elevation")),
}
items[0xC3] = {
    id = 0xC3, name = "cam_zoom_set", kind = "unsigned", size = 1, owner = 7, key = false,
    min = 0, max = 255, scale = 1, unit = "",
    f = field(ProtoField.uint8("rcm.item.cam_zoom_set", "cam_zoom_set", base.DEC, nil, nil, "Zoom")),
}
items[0xC4] = {
    id = 0xC4, name = "take_one_photo", kind = "fields", size = 1, owner = 7, key = false,
    min = 0, max = 255, scale = 1, unit = "",
    f = field(ProtoField.uint8("rcm.item.take_one_photo", "take_one_photo", base.HEX, nil, nil, "Take one photo")),
    fields = {
        {name = "photo", codes = {[0] = "", [1] = "NONE", [2] = "TAKE", [3] = ""},
            f = field(ProtoField.uint8("rcm.item.take_one_photo.photo", "photo", base.DEC, {[0] = "corrupt", [1] = "NONE", [2] = "TAKE", [3] = "corrupt"}, 0xC0, "Take one photograph"))},
    },
    reserved = field(ProtoField.uint8("rcm.item.take_one_photo.reserved", "reserved bits", base.HEX, nil, 0x3F, "Bits the profile fixes at 0")),
}
items[0xC5] = {
    id = 0xC5, name = "ID_GCS_destination", kind = "station", size = 4, owner = 7, key = false,
    min = 1, max = 1929, scale = 1, unit = "",
    f = field(ProtoField.string("rcm.item.camera.ID_GCS_destination", "ID_GCS_destination", base.ASCII, "Imagery destination GCS")),
    parts = {
        country = field(ProtoField.uint16("rcm.item.camera.ID_GCS_destination.country", "country", base.DEC, countries, nil, "Country dialling code")),
        unit = field(ProtoField.uint16("rcm.item.camera.ID_GCS_destination.unit", "unit", base.DEC, nil, nil, "Unit number")),
    },
}
items[0xC6] = {
    id = 0xC6, name = "ID_GCS_backup", kind = "station", size = 4, owner = 7, key = false,
    min = 1, max = 1929, scale = 1, unit = "",
    f = field(ProtoField.string("rcm.item.camera.ID_GCS_backup", "ID_GCS_backup", base.ASCII, "Imagery backup GCS")),
    parts = {
        country = field(ProtoField.uint16("rcm.item.camera.ID_GCS_backup.country", "country", base.DEC, countries, nil, "Country dialling code")),
        unit = field(ProtoField.uint16("rcm.item.camera.ID_GCS_backup.unit", "unit", base.DEC, nil, nil, "Unit number")),
    },
}

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
