#pragma once

// The MAVLink mission commands (MAV_CMD) a plan may hold: their names and
// which of the item's fields they use. The names are Mission Planner's
// (MAVLink's without "MAV_CMD_" and "NAV_": "WAYPOINT", "DO_MOUNT_CONTROL"),
// the ones operators of both Mission Planner and QGroundControl read in plan
// files and ArduPilot's documentation. Whether a command takes a position
// and an altitude follows MAVLink's common.xml and ardupilotmega.xml (a
// TAKEOFF's latitude and longitude are optional: ArduPilot ignores them,
// PX4 flies towards them).

#include <QString>

#include <cstdint>

struct MavCommand {
    std::uint16_t number = 0;
    const char* name = "";    // Mission Planner's: "WAYPOINT", "DO_LAND_START"
    bool position = false;    // param5 and param6 are a latitude and a longitude
    bool altitude = false;    // param7 is an altitude
    bool navigation = false;  // MAVLink names it MAV_CMD_NAV_...

    // The command's entry; nullptr for one not in the table.
    static const MavCommand* find(int number);
    // "DO_MOUNT_CONTROL"; "MAV_CMD 1234" for a command not in the table.
    static QString nameOf(int number);
    // "MAV_CMD_DO_MOUNT_CONTROL (205)", MAVLink's own name: for tool tips.
    static QString mavlinkNameOf(int number);
};
