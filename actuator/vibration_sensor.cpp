#include "actuator/vibration_sensor.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "common/number_text.hpp"

namespace vibscore::actuator {

namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
// Integration steps per period of the fastest motion: RK4 at 64 steps a cycle keeps the LRA's
// phase and amplitude far below the sensor's own noise over a whole probe.
constexpr double kStepsPerCycle = 64.0;

void random_unit(std::mt19937_64& random, double out[3]) {
    std::normal_distribution<double> normal;
    double n = 0.0;
    while (n < 1e-6) {
        for (int i = 0; i < 3; ++i) {
            out[i] = normal(random);
        }
        n = std::sqrt(out[0] * out[0] + out[1] * out[1] + out[2] * out[2]);
    }
    for (int i = 0; i < 3; ++i) {
        out[i] /= n;
    }
}

}  // namespace

VibrationSensor::VibrationSensor(const Declaration& truth, const SensorOptions& options)
    : truth_(Physics(truth).declaration()), options_(options), random_(options.seed) {
    if (!(options_.rate_hz > 0.0) || !std::isfinite(options_.rate_hz)) {
        throw std::invalid_argument("vibration sensor: the rate must be positive, not " +
                                    number_text(options_.rate_hz));
    }
    if (options_.low_pass_hz < 0.0 || !std::isfinite(options_.low_pass_hz) ||
        (options_.low_pass_order != 1 && options_.low_pass_order != 2)) {
        throw std::invalid_argument(
            "vibration sensor: the low-pass must be 0 or a frequency of "
            "order 1 or 2, not " +
            number_text(options_.low_pass_hz) + " Hz order " +
            std::to_string(options_.low_pass_order));
    }
    random_unit(random_, gravity_);
    random_unit(random_, axis_);
    // A second axis at right angles to the first, for a rotating ERM force.
    double other[3];
    random_unit(random_, other);
    const double dot = other[0] * axis_[0] + other[1] * axis_[1] + other[2] * axis_[2];
    double n = 0.0;
    for (int i = 0; i < 3; ++i) {
        axis2_[i] = other[i] - dot * axis_[i];
        n += axis2_[i] * axis2_[i];
    }
    n = std::sqrt(n);
    for (int i = 0; i < 3; ++i) {
        axis2_[i] /= n;
    }
    phase_ = std::uniform_real_distribution<double>(0.0, kTwoPi)(random_);
    angle_ = std::uniform_real_distribution<double>(0.0, kTwoPi)(random_);
    t_ = options_.first_sample_s;
    next_sample_time();
}

double VibrationSensor::next_sample_time() {
    std::uniform_real_distribution<double> jitter(-options_.jitter_s, options_.jitter_s);
    const double nominal = options_.first_sample_s + static_cast<double>(index_) / options_.rate_hz;
    const double error = options_.jitter_s > 0.0 ? jitter(random_) : 0.0;
    if (options_.jittered_sampling) {
        // The reading is taken at the jittered instant and reported exactly; never before the
        // previous one.
        due_ = std::max(t_, nominal + error);
        due_reported_ = due_;
    } else {
        due_ = nominal;
        due_reported_ = nominal + error;
    }
    ++index_;
    return due_;
}

void VibrationSensor::command(double t_s, const Drive& drive) {
    if (t_s <= t_) {
        drive_ = drive;
        return;
    }
    pending_.push_back({t_s, drive});
    std::stable_sort(pending_.begin(), pending_.end(),
                     [](const Command& a, const Command& b) { return a.t_s < b.t_s; });
}

void VibrationSensor::step(double h) {
    if (truth_.kind == Kind::erm) {
        const double u = drive_.amplitude;
        const double target = u;
        const double tau = u != 0.0 ? truth_.spin_up_s : truth_.spin_down_s;
        const double decay = std::exp(-h / tau);
        // Exact over the step: the speed's exponential and the angle its integral.
        const double start = speed_;
        speed_ = target + (start - target) * decay;
        angle_ += kTwoPi * options_.erm_full_speed_hz *
                  (target * h + (start - target) * tau * (1.0 - decay));
        angle_ = std::fmod(angle_, kTwoPi);
        return;
    }
    const double w0 = kTwoPi * truth_.resonance_hz;
    const double damping = w0 / truth_.q;
    // Full-scale drive at resonance settles where |x''| = w0^2 F / (damping w0) = F Q: so
    // F = peak / Q.
    const double force = options_.peak_accel / truth_.q;
    const double f = drive_.frequency_hz > 0.0 ? drive_.frequency_hz : truth_.resonance_hz;
    const double omega = kTwoPi * f;
    const double u = drive_.amplitude;
    const auto accel = [&](double pos, double vel, double dt) {
        return force * u * std::cos(phase_ + omega * dt) - damping * vel - w0 * w0 * pos;
    };
    const double a1 = accel(x_, v_, 0.0);
    const double x2 = x_ + 0.5 * h * v_, v2 = v_ + 0.5 * h * a1;
    const double a2 = accel(x2, v2, 0.5 * h);
    const double x3 = x_ + 0.5 * h * v2, v3 = v_ + 0.5 * h * a2;
    const double a3 = accel(x3, v3, 0.5 * h);
    const double x4 = x_ + h * v3, v4 = v_ + h * a3;
    const double a4 = accel(x4, v4, h);
    x_ += h / 6.0 * (v_ + 2.0 * v2 + 2.0 * v3 + v4);
    v_ += h / 6.0 * (a1 + 2.0 * a2 + 2.0 * a3 + a4);
    phase_ = std::fmod(phase_ + omega * h, kTwoPi);
}

void VibrationSensor::advance_to(double t_s) {
    while (t_ < t_s) {
        while (!pending_.empty() && pending_.front().t_s <= t_) {
            drive_ = pending_.front().drive;
            pending_.pop_front();
        }
        const double change = pending_.empty() ? t_s : std::min(t_s, pending_.front().t_s);
        double fastest = 1.0;
        if (truth_.kind == Kind::lra) {
            fastest = std::max(truth_.resonance_hz, drive_.frequency_hz);
        } else {
            fastest = 4.0 * options_.erm_full_speed_hz;  // the exact step only needs to be short
        }
        const double h = std::min(change - t_, 1.0 / (kStepsPerCycle * fastest));
        step(h);
        filter(h);
        t_ += h;
        if (change - t_ < 1e-12) {
            t_ = change;
        }
    }
    while (!pending_.empty() && pending_.front().t_s <= t_) {
        drive_ = pending_.front().drive;
        pending_.pop_front();
    }
}

double VibrationSensor::vibration() const {
    if (truth_.kind == Kind::erm) {
        return options_.peak_accel * speed_ * std::abs(speed_) * std::cos(angle_);
    }
    // The mass's acceleration x'' (the phone feels its reaction; the sign is the axis's).
    const double w0 = kTwoPi * truth_.resonance_hz;
    if (options_.lra_spring) {
        return -w0 * w0 * x_;  // at resonance as strong as x'' (both F Q)
    }
    const double force = options_.peak_accel / truth_.q;
    return force * drive_.amplitude * std::cos(phase_) - (w0 / truth_.q) * v_ - w0 * w0 * x_;
}

double VibrationSensor::second_component() const {
    if (truth_.kind == Kind::erm && options_.erm_rotating) {
        return options_.peak_accel * speed_ * std::abs(speed_) * std::sin(angle_);
    }
    return 0.0;
}

void VibrationSensor::filter(double h) {
    if (options_.low_pass_hz <= 0.0) {
        return;
    }
    // Each stage exact for an input held over the step (the step is 1/64 of a cycle or less).
    const double keep = std::exp(-kTwoPi * options_.low_pass_hz * h);
    double a = vibration(), b = second_component();
    for (int stage = 0; stage < options_.low_pass_order; ++stage) {
        filtered_a_[stage] = a + (filtered_a_[stage] - a) * keep;
        filtered_b_[stage] = b + (filtered_b_[stage] - b) * keep;
        a = filtered_a_[stage];
        b = filtered_b_[stage];
    }
}

std::vector<calibration::Sample> VibrationSensor::sample_until(double t_s) {
    std::vector<calibration::Sample> out;
    std::normal_distribution<double> noise(0.0, options_.noise_rms);
    const double lsb =
        options_.bits > 0 ? 2.0 * options_.range / std::ldexp(1.0, options_.bits) : 0.0;
    while (due_ <= t_s) {
        advance_to(due_);
        const bool filtered = options_.low_pass_hz > 0.0;
        const int last = options_.low_pass_order - 1;
        const double a = filtered ? filtered_a_[last] : vibration();
        const double b = filtered ? filtered_b_[last] : second_component();
        double value[3];
        for (int i = 0; i < 3; ++i) {
            double v = options_.gravity * gravity_[i] + a * axis_[i] + b * axis2_[i];
            if (options_.noise_rms > 0.0) {
                v += noise(random_);
            }
            if (lsb > 0.0) {
                v = std::clamp(std::round(v / lsb) * lsb, -options_.range, options_.range - lsb);
            }
            value[i] = v;
        }
        out.push_back({due_reported_, value[0], value[1], value[2]});
        next_sample_time();
    }
    advance_to(t_s);
    return out;
}

std::vector<calibration::Sample> record(const calibration::Plan& plan, const Declaration& truth,
                                        const SensorOptions& options, double delay_s,
                                        double tail_s) {
    VibrationSensor sensor(truth, options);
    for (const calibration::PlanRow& row : plan.rows) {
        sensor.command(row.t_s + delay_s, {row.amplitude, row.frequency_hz});
    }
    return sensor.sample_until(plan.duration_s() + tail_s);
}

}  // namespace vibscore::actuator
