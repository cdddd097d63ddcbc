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
    constexpr unsigned kAuto = 1, kNoSlave = 1;
    Message m;
    for (const EngineSpec& e : airframe.engines) {
        Unit& u = m.addEngine(e.id);
        u.setFieldCode(eng_status, 0, kAuto);
        u.setFieldCode(eng_status, 1, kNoSlave);
        u.set(eng_prop_pitch, 0);
        u.set(eng_carb_SET, 0);
    }
    m.flaps.setFieldCode(FLAP_status, 0, kAuto);
    m.flaps.setFieldCode(FLAP_status, 1, kNoSlave);
    for (ItemId id : {F_aileron_LHS_set, F_aileron_RHS_set, F_lift_set, F_rudder_set, F_elev_set, F_airbrake_set})
        m.flaps.set(id, 0);
    // Code 01 in every field: facility disabled, no tank dumped.
    m.fuelDump.set(ENABLE_fuel_dump, 0x55);
    m.settings.set(land_wheels, 0x55);  // all wheels out
    m.settings.set(lights, 0x55);       // all off, brake off
    for (const RadioSpec& r : airframe.radios) {
        Unit& u = m.addRadio(r.systemId);
        u.set(receiver_control, 0x50);  // receiver off, transmitter off
        u.set(Rx_freq, 0);
        u.set(Tx_freq, 0);
        u.set(Tx_OP_power, 0);
    }
    if (airframe.senseAndAvoid)
        for (ItemId id : {SA_zoom_LHS_cam, SA_zoom_FWD_cam, SA_zoom_RHS_cam})
            m.sense.set(id, 0);
    for (const CameraSpec& c : airframe.cameras) {
        Unit& u = m.addCamera(c.maker, c.number);
        u.set(cam_mag_compass, 0);
        u.set(cam_elev, 0);
        u.set(cam_zoom_set, 0);
        u.set(take_one_photo, 0x40);  // none
    }
    return m;
}

}  // namespace rcm
