// What an aircraft carries: how many engines, radios and cameras, and what
// they are called. The panels follow it; the default is the source document's
// "well equipped" aircraft.
#pragma once

#include "codec/message/Message.h"

#include <cstdint>
#include <string>
#include <vector>

namespace rcm {

struct CameraSpec {
    std::string maker;       // three ASCII characters, e.g. "NIK"
    std::uint8_t number = 1;
    std::string name;        // for people
};

struct RadioSpec {
    std::string systemId;    // up to eight ASCII characters
    std::string name;
};

struct EngineSpec {
    std::uint8_t id = 1;
    std::string name;
};

struct Airframe {
    std::string name;
    std::vector<EngineSpec> engines;
    std::vector<RadioSpec> radios;
    std::vector<CameraSpec> cameras;
    bool senseAndAvoid = true;

    // Three engines, three VHF radios, sense and avoid, two payload cameras.
    static Airframe wellEquipped();
};

// A complete command for `airframe` in a safe resting state: engines and
// surfaces under AUTO control, surfaces at 0, gear out, lights off, fuel dump
// disabled, radios off, zooms at minimum, no photo. Header items not set.
Message restingCommand(const Airframe& airframe);

}  // namespace rcm
