#include "codec/message/Airframe.h"

namespace rcm {

Airframe Airframe::wellEquipped()
{
    Airframe a;
    a.name = "Well-equipped UA";
    a.engines = {{1, "Engine 1"}, {2, "Engine 2"}, {3, "Engine 3"}};
    a.radios = {{"VHF1", "VHF 1"}, {"VHF2", "VHF 2"}, {"VHF3", "VHF 3"}};
    a.cameras = {{"NIK", 1, "Payload camera 1"}, {"NIK", 2, "Payload camera 2"}};
    a.senseAndAvoid = true;
    return a;
}

Message restingCommand(const Airframe& airframe)
{
    using enum ItemId;
    Message m;
    for (const EngineSpec& e : airframe.engines) {
        Unit& u = m.addEngine(e.id);
        u.setFieldCode(eng_status, 0, code::kAuto);
        u.setFieldCode(eng_status, 1, code::kNoSlave);
        u.set(eng_prop_pitch, 0);
        u.set(eng_carb_SET, 0);
    }
    m.flaps.setFieldCode(FLAP_status, 0, code::kAuto);
    m.flaps.setFieldCode(FLAP_status, 1, code::kNoSlave);
    for (ItemId id : kFlapSurfaces)
        m.flaps.set(id, 0);
    static_assert(code::kDisabled == code::kNoDump && code::kOut == code::kOff);
    m.fuelDump.set(ENABLE_fuel_dump, withEveryFieldCode(code::kDisabled));  // no tank dumped either
    m.settings.set(land_wheels, withEveryFieldCode(code::kOut));
    m.settings.set(lights, withEveryFieldCode(code::kOff));  // the brake too
    for (const RadioSpec& r : airframe.radios) {
        Unit& u = m.addRadio(r.systemId);
        u.set(receiver_control, withEveryFieldCode(code::kOff, 2));  // receiver and transmitter
        u.set(Rx_freq, 0);
        u.set(Tx_freq, 0);
        u.set(Tx_OP_power, 0);
    }
    if (airframe.senseAndAvoid)
        for (ItemId id : kSenseAndAvoidZooms)
            m.sense.set(id, 0);
    for (const CameraSpec& c : airframe.cameras) {
        Unit& u = m.addCamera(c.maker, c.number);
        u.set(cam_mag_compass, 0);
        u.set(cam_elev, 0);
        u.set(cam_zoom_set, 0);
        u.set(take_one_photo, withEveryFieldCode(code::kNone, 1));
    }
    return m;
}

}  // namespace rcm
