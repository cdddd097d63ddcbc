#include "link/plan/MavCommand.h"

#include <algorithm>
#include <array>

namespace {

constexpr bool kPosition = true;
constexpr bool kAltitude = true;
constexpr bool kNavigation = true;

// Sorted by number.
constexpr std::array kCommands{
    MavCommand{16, "WAYPOINT", kPosition, kAltitude, kNavigation},
    MavCommand{17, "LOITER_UNLIM", kPosition, kAltitude, kNavigation},
    MavCommand{18, "LOITER_TURNS", kPosition, kAltitude, kNavigation},
    MavCommand{19, "LOITER_TIME", kPosition, kAltitude, kNavigation},
    MavCommand{20, "RETURN_TO_LAUNCH", false, false, kNavigation},
    MavCommand{21, "LAND", kPosition, kAltitude, kNavigation},
    MavCommand{22, "TAKEOFF", kPosition, kAltitude, kNavigation},
    MavCommand{23, "LAND_LOCAL", false, false, kNavigation},
    MavCommand{24, "TAKEOFF_LOCAL", false, false, kNavigation},
    MavCommand{25, "FOLLOW", kPosition, kAltitude, kNavigation},
    MavCommand{30, "CONTINUE_AND_CHANGE_ALT", false, kAltitude, kNavigation},
    MavCommand{31, "LOITER_TO_ALT", kPosition, kAltitude, kNavigation},
    MavCommand{80, "ROI", kPosition, kAltitude, kNavigation},
    MavCommand{81, "PATHPLANNING", kPosition, kAltitude, kNavigation},
    MavCommand{82, "SPLINE_WAYPOINT", kPosition, kAltitude, kNavigation},
    MavCommand{83, "ALTITUDE_WAIT", false, false, kNavigation},
    MavCommand{84, "VTOL_TAKEOFF", kPosition, kAltitude, kNavigation},
    MavCommand{85, "VTOL_LAND", kPosition, kAltitude, kNavigation},
    MavCommand{92, "GUIDED_ENABLE", false, false, kNavigation},
    MavCommand{93, "DELAY", false, false, kNavigation},
    MavCommand{94, "PAYLOAD_PLACE", kPosition, kAltitude, kNavigation},
    MavCommand{112, "CONDITION_DELAY", false, false, false},
    MavCommand{113, "CONDITION_CHANGE_ALT", false, kAltitude, false},
    MavCommand{114, "CONDITION_DISTANCE", false, false, false},
    MavCommand{115, "CONDITION_YAW", false, false, false},
    MavCommand{176, "DO_SET_MODE", false, false, false},
    MavCommand{177, "DO_JUMP", false, false, false},
    MavCommand{178, "DO_CHANGE_SPEED", false, false, false},
    MavCommand{179, "DO_SET_HOME", kPosition, kAltitude, false},
    MavCommand{180, "DO_SET_PARAMETER", false, false, false},
    MavCommand{181, "DO_SET_RELAY", false, false, false},
    MavCommand{182, "DO_REPEAT_RELAY", false, false, false},
    MavCommand{183, "DO_SET_SERVO", false, false, false},
    MavCommand{184, "DO_REPEAT_SERVO", false, false, false},
    MavCommand{185, "DO_FLIGHTTERMINATION", false, false, false},
    MavCommand{186, "DO_CHANGE_ALTITUDE", false, false, false},
    MavCommand{189, "DO_LAND_START", kPosition, false, false},
    MavCommand{190, "DO_RALLY_LAND", false, false, false},
    MavCommand{191, "DO_GO_AROUND", false, false, false},
    MavCommand{192, "DO_REPOSITION", kPosition, kAltitude, false},
    MavCommand{193, "DO_PAUSE_CONTINUE", false, false, false},
    MavCommand{194, "DO_SET_REVERSE", false, false, false},
    MavCommand{195, "DO_SET_ROI_LOCATION", kPosition, kAltitude, false},
    MavCommand{196, "DO_SET_ROI_WPNEXT_OFFSET", false, false, false},
    MavCommand{197, "DO_SET_ROI_NONE", false, false, false},
    MavCommand{200, "DO_CONTROL_VIDEO", false, false, false},
    MavCommand{201, "DO_SET_ROI", kPosition, kAltitude, false},
    MavCommand{202, "DO_DIGICAM_CONFIGURE", false, false, false},
    MavCommand{203, "DO_DIGICAM_CONTROL", false, false, false},
    MavCommand{204, "DO_MOUNT_CONFIGURE", false, false, false},
    MavCommand{205, "DO_MOUNT_CONTROL", false, false, false},
    MavCommand{206, "DO_SET_CAM_TRIGG_DIST", false, false, false},
    MavCommand{207, "DO_FENCE_ENABLE", false, false, false},
    MavCommand{208, "DO_PARACHUTE", false, false, false},
    MavCommand{209, "DO_MOTOR_TEST", false, false, false},
    MavCommand{210, "DO_INVERTED_FLIGHT", false, false, false},
    MavCommand{211, "DO_GRIPPER", false, false, false},
    MavCommand{212, "DO_AUTOTUNE_ENABLE", false, false, false},
    MavCommand{213, "SET_YAW_SPEED", false, false, kNavigation},
    MavCommand{214, "DO_SET_CAM_TRIGG_INTERVAL", false, false, false},
    MavCommand{215, "DO_SET_RESUME_REPEAT_DIST", false, false, false},
    MavCommand{216, "DO_SPRAYER", false, false, false},
    MavCommand{217, "DO_SEND_SCRIPT_MESSAGE", false, false, false},
    MavCommand{218, "DO_AUX_FUNCTION", false, false, false},
    MavCommand{220, "DO_MOUNT_CONTROL_QUAT", false, false, false},
    MavCommand{221, "DO_GUIDED_MASTER", false, false, false},
    MavCommand{222, "DO_GUIDED_LIMITS", false, false, false},
    MavCommand{223, "DO_ENGINE_CONTROL", false, false, false},
    MavCommand{224, "DO_SET_MISSION_CURRENT", false, false, false},
    MavCommand{530, "SET_CAMERA_MODE", false, false, false},
    MavCommand{531, "SET_CAMERA_ZOOM", false, false, false},
    MavCommand{532, "SET_CAMERA_FOCUS", false, false, false},
    MavCommand{600, "JUMP_TAG", false, false, false},
    MavCommand{601, "DO_JUMP_TAG", false, false, false},
    MavCommand{1000, "DO_GIMBAL_MANAGER_PITCHYAW", false, false, false},
    MavCommand{1001, "DO_GIMBAL_MANAGER_CONFIGURE", false, false, false},
    MavCommand{2000, "IMAGE_START_CAPTURE", false, false, false},
    MavCommand{2001, "IMAGE_STOP_CAPTURE", false, false, false},
    MavCommand{2003, "DO_TRIGGER_CONTROL", false, false, false},
    MavCommand{2500, "VIDEO_START_CAPTURE", false, false, false},
    MavCommand{2501, "VIDEO_STOP_CAPTURE", false, false, false},
    MavCommand{3000, "DO_VTOL_TRANSITION", false, false, false},
    MavCommand{5000, "FENCE_RETURN_POINT", kPosition, kAltitude, kNavigation},
    MavCommand{5001, "FENCE_POLYGON_VERTEX_INCLUSION", kPosition, false, kNavigation},
    MavCommand{5002, "FENCE_POLYGON_VERTEX_EXCLUSION", kPosition, false, kNavigation},
    MavCommand{5003, "FENCE_CIRCLE_INCLUSION", kPosition, false, kNavigation},
    MavCommand{5004, "FENCE_CIRCLE_EXCLUSION", kPosition, false, kNavigation},
    MavCommand{5100, "RALLY_POINT", kPosition, kAltitude, kNavigation},
    MavCommand{42600, "DO_WINCH", false, false, false},
    MavCommand{42702, "SCRIPT_TIME", false, false, kNavigation},
    MavCommand{42703, "ATTITUDE_TIME", false, false, kNavigation},
};

static_assert(std::is_sorted(kCommands.begin(), kCommands.end(),
                             [](const MavCommand& a, const MavCommand& b) { return a.number < b.number; }));

}  // namespace

const MavCommand* MavCommand::find(int number)
{
    const auto it = std::lower_bound(kCommands.begin(), kCommands.end(), number,
                                     [](const MavCommand& c, int n) { return c.number < n; });
    return it != kCommands.end() && it->number == number ? &*it : nullptr;
}

QString MavCommand::nameOf(int number)
{
    const MavCommand* command = find(number);
    return command ? QLatin1String(command->name) : QStringLiteral("MAV_CMD %1").arg(number);
}

QString MavCommand::mavlinkNameOf(int number)
{
    const MavCommand* command = find(number);
    if (!command)
        return QStringLiteral("MAV_CMD %1").arg(number);
    return QStringLiteral("MAV_CMD_%1%2 (%3)")
        .arg(command->navigation ? QStringLiteral("NAV_") : QString(), QLatin1String(command->name))
        .arg(number);
}
