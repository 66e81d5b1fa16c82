#pragma once

#include <cmath>

#include "actuator/declaration.hpp"

namespace vibscore::bench {

// One actuator of issue 32's population, as bench/calibrate and bench/calibrated_feel draw it:
// `truth` is how it is built (an LRA at 150-235 Hz with Q 5-30, spread evenly in log Q; an ERM
// spinning up in 20-80 ms and down in 40-200 ms), `nominal` what its datasheet would declare
// (the resonance within 10 % of the truth, Q and the time constants within 30 %). Only the
// numbers of the kind are drawn; the rest of both is left as given. `between(lo, hi)` draws
// uniformly, in this order, so that a seed draws the same actuators in both benchmarks.
template <class Between>
void draw_actuator(actuator::Kind kind, Between&& between, actuator::Declaration& truth,
                   actuator::Declaration& nominal) {
    if (kind == actuator::Kind::lra) {
        truth.resonance_hz = between(150.0, 235.0);
        truth.q = 5.0 * std::pow(6.0, between(0.0, 1.0));
        nominal.resonance_hz = truth.resonance_hz * between(0.9, 1.1);
        nominal.q = truth.q * between(0.7, 1.3);
    } else {
        truth.spin_up_s = between(0.020, 0.080);
        truth.spin_down_s = between(0.040, 0.200);
        nominal.spin_up_s = truth.spin_up_s * between(0.7, 1.3);
        nominal.spin_down_s = truth.spin_down_s * between(0.7, 1.3);
    }
}

}  // namespace vibscore::bench
