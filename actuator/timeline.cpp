#include "actuator/timeline.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "common/number_text.hpp"

namespace vibscore::actuator {

void Timeline::command(double t_s, const Drive& drive) {
    if (!std::isfinite(t_s)) {
        throw std::invalid_argument("actuator model: command time is not finite");
    }
    if (!(drive.amplitude >= -1.0 && drive.amplitude <= 1.0)) {
        throw std::invalid_argument("actuator model: amplitude " + number_text(drive.amplitude) +
                                    " is outside -1..1");
    }
    if (!std::isfinite(drive.frequency_hz) || drive.frequency_hz < 0.0) {
        throw std::invalid_argument("actuator model: frequency " + number_text(drive.frequency_hz) +
                                    " Hz is not a non-negative number");
    }
    // The state is continuous: the new drive starts from where the old one has got to.
    const double t = commanded_ ? std::max(t_s, t0_s_) : t_s;
    state0_ = state_at(t);
    t0_s_ = t;
    commanded_ = true;
    drive_ = drive;
}

State Timeline::state_at(double t_s) const {
    if (!commanded_) {
        return {};
    }
    if (!(t_s > t0_s_)) {
        return state0_;
    }
    return physics_.advance(state0_, drive_, t_s - t0_s_);
}

}  // namespace vibscore::actuator
