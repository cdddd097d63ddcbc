// The satellite modem model with its times cut to a tenth of a second, for
// suites that must finish in seconds; nothing asserts how long anything took.
#pragma once

#include "link/satmodem/SatelliteModem.h"

#include <chrono>

namespace rcm::test {

inline SatelliteModem::Options quickSatellite(int ringLimit)
{
    using namespace std::chrono_literals;
    SatelliteModem::Options o;
    o.callSetupTime = 150ms;
    o.oneWayDelay = 100ms;
    o.airRate = 6000;
    o.ringInterval = 100ms;
    o.ringLimit = ringLimit;
    return o;
}

}  // namespace rcm::test
