#include "bench/feel_plant.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace vibscore::bench {

namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

// The drive in force at each instant: the cues' amplitudes as a step function.
class DriveTrack {
  public:
    explicit DriveTrack(const std::vector<render::Cue>& drives) : drives_(drives) {}
    // Moves to `t` (never backwards) and returns the time of the next change after it.
    double next_change(double t) {
        while (next_ < drives_.size() && drives_[next_].at <= t) {
            if (drives_[next_].kind == render::Cue::Kind::drive) {
                amplitude_ = std::clamp(drives_[next_].amplitude, -1.0, 1.0);
                frequency_ = drives_[next_].frequency_hz;
            }
            ++next_;
        }
        return next_ < drives_.size() ? drives_[next_].at : INFINITY;
    }
    double amplitude() const { return amplitude_; }
    double frequency() const { return frequency_; }

  private:
    const std::vector<render::Cue>& drives_;
    std::size_t next_ = 0;
    double amplitude_ = 0.0;
    double frequency_ = 0.0;
};

}  // namespace

Plant::Plant(const actuator::Declaration& truth) : truth_(truth) {}

std::vector<double> Plant::respond(const std::vector<render::Cue>& drives, double rate_hz,
                                   std::size_t count) const {
    return truth_.kind == actuator::Kind::erm ? respond_erm(drives, rate_hz, count)
                                              : respond_lra(drives, rate_hz, count);
}

std::vector<double> Plant::respond_erm(const std::vector<render::Cue>& drives, double rate_hz,
                                       std::size_t count) const {
    DriveTrack track(drives);
    std::vector<double> out;
    out.reserve(count);
    const double max_step = std::min(truth_.spin_up_s, truth_.spin_down_s) / 200.0;
    double w = 0.0, t = 0.0;
    const auto slope = [&](double speed, double u) {
        return u != 0.0 ? (u / truth_.rated_drive - speed) / truth_.spin_up_s
                        : -speed / truth_.spin_down_s;
    };
    for (std::size_t k = 0; k < count; ++k) {
        const double sample_at = static_cast<double>(k) / rate_hz;
        while (t < sample_at) {
            const double change = track.next_change(t);
            const double h = std::min({max_step, sample_at - t, change - t});
            const double u = track.amplitude();
            const double k1 = slope(w, u);
            const double k2 = slope(w + 0.5 * h * k1, u);
            const double k3 = slope(w + 0.5 * h * k2, u);
            const double k4 = slope(w + h * k3, u);
            w += h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
            t += h;
        }
        track.next_change(t);
        out.push_back(std::abs(w));
    }
    return out;
}

std::vector<double> Plant::respond_lra(const std::vector<render::Cue>& drives, double rate_hz,
                                       std::size_t count) const {
    DriveTrack track(drives);
    std::vector<double> out;
    out.reserve(count);
    const double w0 = kTwoPi * truth_.resonance_hz;
    const double damping = w0 / truth_.q;  // 2 gamma
    // Rated drive at resonance settles at amplitude 1: F rated / (2 gamma w0) = 1.
    const double force = damping * w0 / truth_.rated_drive;
    double x = 0.0, v = 0.0, phase = 0.0, t = 0.0;
    double moving_hz = truth_.resonance_hz;  // the frequency it moves at, for its amplitude
    const auto acceleration = [&](double pos, double vel, double drive) {
        return drive - damping * vel - w0 * w0 * pos;
    };
    for (std::size_t k = 0; k < count; ++k) {
        const double sample_at = static_cast<double>(k) / rate_hz;
        while (t < sample_at) {
            const double change = track.next_change(t);
            const double u = track.amplitude();
            const double f = track.frequency() > 0.0 ? track.frequency() : truth_.resonance_hz;
            if (u != 0.0) {
                moving_hz = f;
            } else {
                moving_hz = truth_.resonance_hz;  // left alone it rings at its own frequency
            }
            const double h = std::min(
                {1.0 / (64.0 * std::max(f, truth_.resonance_hz)), sample_at - t, change - t});
            const double omega = kTwoPi * f;
            const auto drive_at = [&](double dt) {
                return force * u * std::cos(phase + omega * dt);
            };
            const double a1 = acceleration(x, v, drive_at(0.0));
            const double x2 = x + 0.5 * h * v, v2 = v + 0.5 * h * a1;
            const double a2 = acceleration(x2, v2, drive_at(0.5 * h));
            const double x3 = x + 0.5 * h * v2, v3 = v + 0.5 * h * a2;
            const double a3 = acceleration(x3, v3, drive_at(0.5 * h));
            const double x4 = x + h * v3, v4 = v + h * a3;
            const double a4 = acceleration(x4, v4, drive_at(h));
            x += h / 6.0 * (v + 2.0 * v2 + 2.0 * v3 + v4);
            v += h / 6.0 * (a1 + 2.0 * a2 + 2.0 * a3 + a4);
            phase = std::fmod(phase + omega * h, kTwoPi);
            t += h;
        }
        track.next_change(t);
        const double omega = kTwoPi * moving_hz;
        out.push_back(std::hypot(x, v / omega));
    }
    return out;
}

}  // namespace vibscore::bench
