// The text format of a Remote Control Message: what an operator writes in a
// script and reads in a log. One printer, one parser, both driven by the item
// table (ItemTable.h), so a name or range is never spelled twice.
//
// ## The format
//
//     # a comment runs to the end of the line; blank lines are ignored
//     BEGIN HEADER
//     ID_msg 133
//     ID_UA_source GB_133          # country as ISO alpha-2 or dialling code: 44_133 is the same
//     time_UTC 16:35:23
//     date_UTC 071114              # yymmdd as the source document writes it
//     ID_BLK12_format 5 15
//     ID_GCS_destination GB_30226
//     ID_GCS_backup GB_41251
//     END
//     BEGIN FCU
//     BEGIN engine
//     eng_ID 1
//     eng_status control=GCS slave=NO_SLAVE
//     eng_prop_pitch 228
//     eng_carb_SET 136
//     END
//     BEGIN flaps
//     FLAP_status control=GCS slave_aileron=NO_SLAVE
//     F_aileron_LHS_set 121
//     F_aileron_RHS_set -19
//     END
//     BEGIN FCU_general
//     ENABLE_fuel_dump facility=DISABLED tank1=NO_DUMP tank2=NO_DUMP tank3=DUMP
//     END
//     END
//     BEGIN SETTINGS
//     land_wheels LHS=OUT RHS=OUT NOSE=OUT TAIL=OUT
//     lights wing_RHS=ON wing_LHS=OFF tail=OFF wheel_brake=ON
//     setting_72 0x5A
//     END
//     BEGIN COMMS
//     BEGIN comms_system
//     system_ID VHF1
//     receiver_control receiver=OFF transmitter=OFF
//     Rx_freq 127712
//     Tx_freq 121961
//     Tx_OP_power 170
//     END
//     END
//     BEGIN SENSE
//     SA_zoom_LHS_cam 35
//     SA_zoom_FWD_cam 105
//     SA_zoom_RHS_cam 35
//     END
//     BEGIN PAYLOAD
//     BEGIN camera
//     cam_ID SNY 1
//     cam_mag_compass 264.95
//     cam_elev -54.64
//     cam_zoom_set 88
//     take_one_photo photo=NONE
//     ID_GCS_destination 1808_49113
//     ID_GCS_backup 178_57535
//     END
//     END
//     BEGIN FLIGHT_PLAN
//     flight_plan_ID 0xDEADBEEF
//     flight_plan_section_ID 3
//     flight_plan_data 000102030405060708090A0B0C0D0E0F
//     END
//
// ### Lines and tokens
// One item per line: its name, a space, its value. Tokens are separated by
// spaces or tabs; `#` outside quotes starts a comment; a line may end in
// "\r\n". A control byte (other than tab) is an error anywhere; a UTF-8
// byte-order mark at the very start is skipped. Names of items, sections, fields and codes are case-sensitive and
// are the item table's. Section lines are `BEGIN <name>` and `END`.
//
// ### Sections
// Sections group items the way the source document draws them; BEGIN/END are
// never sent. HEADER, SETTINGS, SENSE and FLIGHT_PLAN stand at the top level;
// FCU holds engine, flaps and FCU_general; COMMS holds comms_system; PAYLOAD
// holds camera. engine, comms_system and camera are repeated units: each
// BEGIN of one makes a new unit, which must have its key item (eng_ID,
// system_ID, cam_ID) by its END.
//
// Sections are optional when reading. Inside a unit's section only that
// unit's items are allowed; a parent section (FCU, COMMS, PAYLOAD) holds only
// its child sections; a child section may also stand at the top level.
// Outside any unit section an item goes where its name says: the key item of
// a repeated unit starts a new unit, and that kind's other items go to the
// last unit of the kind started (by a key item or a BEGIN). The header's
// ID_GCS_destination/backup are the ones outside a camera section.
//
// ### Values
//   integers           decimal or 0x hex, `-` for negatives: 133, 0x85, -19
//   hundredths         cam_mag_compass, cam_elev: up to two decimals, 264.95,
//                      264.9 or 264; more decimals are an error, not rounded
//   station            COUNTRY_UNIT: the country as ISO 3166-1 alpha-2 in any
//                      case or as the dialling code, then the unit number:
//                      GB_133 = gb_133 = 44_133
//   time_UTC           hh:mm:ss, or the number hhmmss (163523)
//   date_UTC           yymmdd, exactly six digits
//   ID_BLK12_format    two integers, BLOCK 1 and BLOCK 2 format IDs
//   two-bit fields     every field as name=CODE, in any order, each once:
//                      control=GCS slave=NO_SLAVE; or the whole byte as 0xNN
//                      (which must still be valid)
//   setting_72         a byte, printed 0xNN
//   system_ID          text of up to 8 printable ASCII characters; in double
//                      quotes if it is empty or has a space, `#` or `"`.
//                      Inside quotes: \" \\ and \xHH
//   cam_ID             the 3-character maker (quoted by the same rule) and
//                      the camera number: SNY 1
//   flight_plan_ID     uint32, printed 0x%08X
//   flight_plan_section_ID  uint16
//   flight_plan_data   the data bytes as hex digits in one token, up to 215
//                      bytes; no line when there are none
// Every value is checked against the item table as the encoder would check it.
//
// ### Canonical form (what formatMessage writes)
// Sections nested as above and only when they have items (a parent only when
// a child has items; FLIGHT_PLAN only when the section is not empty); items in
// canonical order, one per line; no indentation, no comments, no trailing
// spaces, "\n" line ends. A station's country is printed as the alpha-2 of
// countryForDiallingCode when there is one, else as the number. A two-bit
// field byte that is not fully valid (a corrupt code, reserved bits set) is
// printed as 0xNN so no byte the decoder kept is lost.
//
// For every valid Message m: parseMessage(formatMessage(m)).message == m, and
// formatMessage of that is formatMessage(m) again.
#pragma once

#include "codec/message/Diagnostic.h"
#include "codec/message/Message.h"
#include "codec/message/MessageEncoder.h"

#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace rcm {

// The canonical text of a message. Prints whatever the message holds, valid
// or not; an invalid value prints so that parsing it reports the problem.
std::string formatMessage(const Message& message);

// Errors a parse lists; it counts the rest.
inline constexpr std::size_t kMaxListedErrors = 20;

struct ParseResult {
    Message message;                 // what could be read; not to be encoded unless ok()
    Diagnostics errors;              // at most kMaxListedErrors, each with line and column, in line order;
                                     // kind Syntax, OutOfRange or DoesNotFit
    std::size_t unlistedErrors = 0;  // errors found beyond those listed
    bool ok() const { return errors.empty(); }
};

// Reads a whole text, reporting every error it finds rather than the first
// (up to kMaxListedErrors). A UTF-8 byte-order mark at the start is skipped.
// What the encoder would refuse for size under `limits` is reported at the
// line of the first item that does not fit (or of flight_plan_data); header
// items in `filledWhenAbsent` that the text lacks count as given before it,
// for a caller that fills them in before encoding.
ParseResult parseMessage(std::string_view text, const EncodeOptions& limits = {},
                         std::span<const ItemId> filledWhenAbsent = {});

// One station as the text format writes it ("GB_30226") and reads it (also
// "44_30226"): for command lines and settings that name a station. The
// error says what is wrong, without a line or column.
std::string formatStation(StationId station);
std::optional<StationId> parseStation(std::string_view text, std::string* error = nullptr);

}  // namespace rcm
