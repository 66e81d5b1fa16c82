#include "daemon/drivers/actuator_model.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "common/number_text.hpp"

namespace vibscore::drivers {

namespace {

void require_positive(double value, const char* name) {
    if (!std::isfinite(value) || value <= 0.0) {
        throw std::invalid_argument(std::string("actuator model: ") + name +
                                    " must be positive, not " + number_text(value));
    }
}

}  // namespace

ActuatorModel::ActuatorModel(const ModelSettings& settings) : settings_(settings) {
    require_positive(settings_.spin_up_s, "spin-up time");
    require_positive(settings_.spin_down_s, "spin-down time");
    require_positive(settings_.resonance_hz, "resonance frequency");
    require_positive(settings_.q, "quality factor");
}

double ActuatorModel::lra_gain(double frequency_hz, double resonance_hz, double q) {
    const double r = frequency_hz / resonance_hz;
    const double detuning = 1.0 - r * r;
    const double damping = r / q;
    return (1.0 / q) / std::sqrt(detuning * detuning + damping * damping);
}

double ActuatorModel::lra_time_constant_s(double resonance_hz, double q) {
    return q / (std::numbers::pi * resonance_hz);
}

double ActuatorModel::steady_gain(double frequency_hz) const {
    if (settings_.kind == ActuatorKind::erm) {
        return 1.0;  // an ERM's frequency follows its speed; it cannot be driven off-tune
    }
    const double f = frequency_hz == 0.0 ? settings_.resonance_hz : frequency_hz;
    return lra_gain(f, settings_.resonance_hz, settings_.q);
}

void ActuatorModel::command(double t_s, double amplitude, double frequency_hz) {
    if (!std::isfinite(t_s)) {
        throw std::invalid_argument("actuator model: command time is not finite");
    }
    if (!(amplitude >= 0.0 && amplitude <= 1.0)) {
        throw std::invalid_argument("actuator model: amplitude " + number_text(amplitude) +
                                    " is outside 0..1");
    }
    if (!std::isfinite(frequency_hz) || frequency_hz < 0.0) {
        throw std::invalid_argument("actuator model: frequency " + number_text(frequency_hz) +
                                    " Hz is not a non-negative number");
    }
    // The strength is continuous: the new segment starts where the old one has got to.
    const double t = commanded_ ? std::max(t_s, t0_s_) : t_s;
    start_ = response_at(t);
    t0_s_ = t;
    commanded_ = true;
    target_ = amplitude * steady_gain(frequency_hz);
    if (settings_.kind == ActuatorKind::erm) {
        tau_s_ = target_ >= start_ ? settings_.spin_up_s : settings_.spin_down_s;
    } else {
        tau_s_ = lra_time_constant_s(settings_.resonance_hz, settings_.q);
    }
}

double ActuatorModel::response_at(double t_s) const {
    if (!commanded_) {
        return 0.0;
    }
    if (!(t_s > t0_s_)) {
        return start_;
    }
    return target_ + (start_ - target_) * std::exp(-(t_s - t0_s_) / tau_s_);
}

}  // namespace vibscore::drivers
