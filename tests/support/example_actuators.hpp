#pragma once

#include "actuator/declaration.hpp"

namespace vibscore::testing {

// The two actuators of the feel issue (issue 22) that the tests and benchmarks measure against,
// as examples/actuator/erm.conf and lra.conf declare them: a phone ERM and a phone LRA, both on
// a board that can drive them backwards.
inline actuator::Declaration example_erm(actuator::Brake brake = actuator::Brake::reverse) {
    actuator::Declaration erm;
    erm.kind = actuator::Kind::erm;
    erm.rated_drive = 0.7;
    erm.spin_up_s = 0.040;
    erm.spin_down_s = 0.080;
    erm.brake = brake;
    return erm;
}

inline actuator::Declaration example_lra(double resonance_hz = 175.0, double q = 15.0,
                                         actuator::Brake brake = actuator::Brake::reverse) {
    actuator::Declaration lra;
    lra.kind = actuator::Kind::lra;
    lra.rated_drive = 0.7;
    lra.resonance_hz = resonance_hz;
    lra.q = q;
    lra.brake = brake;
    return lra;
}

}  // namespace vibscore::testing
