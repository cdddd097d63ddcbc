// A Wireshark Lua dissector for Remote Control Messages, written from the item
// table so that Wireshark names, sizes and decodes every item exactly as the
// codec does. resources/wireshark/rcm.lua is a checked-in copy of this text;
// tests/link/tst_dissector.cpp keeps the two byte-identical.
//
// The dissector registers for link type 147 (LINKTYPE_USER0, the frame log's)
// and for "Decode As" on UDP ports. It takes the 600-byte frame and the
// 510-byte datagram. It does not apply Reed-Solomon: it shows the bytes as
// logged, so values in a codeword the console had to correct may differ.
//
// Field names: rcm.item.<item name> for every item (rcm.item.ID_msg,
// rcm.item.eng_prop_pitch); an item whose name an earlier item of the table
// already has takes its unit's section name as well, so the cameras'
// ID_GCS_destination is rcm.item.camera.ID_GCS_destination. Parts of an item
// add a suffix: rcm.item.land_wheels.LHS, rcm.item.ID_UA_source.country.
// BLOCK 2 is rcm.block2.x, rcm.block2.flight_plan_ID, ...
#pragma once

#include <string>

namespace rcm {

// The complete Lua source: deterministic, "\n" line ends, ASCII only.
std::string wiresharkDissectorLua();

}  // namespace rcm
