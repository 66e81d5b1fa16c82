#include "actuator/physics.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "common/number_text.hpp"

namespace vibscore::actuator {

namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
// Steps per time constant (or per radian of beating) when a crossing has to be searched for: fine
// enough that no crossing and no turn of |z| hides between two steps.
constexpr double kStepsPerConstant = 64.0;
constexpr int kBisections = 80;

void require_positive(double value, const char* name) {
    if (!std::isfinite(value) || value <= 0.0) {
        throw std::invalid_argument(std::string("actuator: ") + name + " must be positive, not " +
                                    number_text(value));
    }
}

}  // namespace

Physics::Physics(const Declaration& declaration) : declaration_(declaration) {
    require_positive(declaration_.rated_drive, "rated-drive");
    require_positive(declaration_.spin_up_s, "spin-up time");
    require_positive(declaration_.spin_down_s, "spin-down time");
    require_positive(declaration_.resonance_hz, "resonance frequency");
    require_positive(declaration_.q, "quality factor");
    lra_tau_s_ = lra_time_constant_s(declaration_.resonance_hz, declaration_.q);
}

double Physics::lra_gain(double frequency_hz, double resonance_hz, double q) {
    const double r = frequency_hz / resonance_hz;
    const double detuning = 1.0 - r * r;
    const double damping = r / q;
    return (1.0 / q) / std::sqrt(detuning * detuning + damping * damping);
}

std::optional<Physics::GainBand> Physics::lra_band(double gain, double resonance_hz, double q) {
    // lra_gain(f) >= gain with y = (f/f0)^2:  y^2 + (1/Q^2 - 2) y + 1 - 1/(Q gain)^2 <= 0.
    const double inv_q2 = 1.0 / (q * q);
    const double b = inv_q2 - 2.0;
    const double c = 1.0 - inv_q2 / (gain * gain);
    const double discriminant = b * b - 4.0 * c;
    if (discriminant < 0.0) {
        return std::nullopt;
    }
    const double y_high = (-b + std::sqrt(discriminant)) / 2.0;
    const double y_low = (-b - std::sqrt(discriminant)) / 2.0;
    if (y_high <= 0.0) {
        return std::nullopt;
    }
    return GainBand{resonance_hz * std::sqrt(std::max(0.0, y_low)),
                    resonance_hz * std::sqrt(y_high)};
}

double Physics::frequency_of(const Drive& drive) const {
    if (!is_lra()) {
        return 0.0;
    }
    return drive.frequency_hz > 0.0 ? drive.frequency_hz : declaration_.resonance_hz;
}

double Physics::gain(double frequency_hz) const {
    if (!is_lra()) {
        return 1.0;  // an ERM's frequency follows its speed; it cannot be driven off-tune
    }
    const double f = frequency_hz > 0.0 ? frequency_hz : declaration_.resonance_hz;
    return lra_gain(f, declaration_.resonance_hz, declaration_.q);
}

double Physics::steady_strength(const Drive& drive) const {
    return std::abs(drive.amplitude) / declaration_.rated_drive * gain(drive.frequency_hz);
}

double Physics::amplitude_for(double strength, double frequency_hz) const {
    return strength * declaration_.rated_drive / gain(frequency_hz);
}

double Physics::time_constant_s(const Drive& drive) const {
    if (is_lra()) {
        return lra_tau_s_;
    }
    return drive.amplitude != 0.0 ? declaration_.spin_up_s : declaration_.spin_down_s;
}

Physics::Motion Physics::motion(const State& state, const Drive& drive) const {
    const double u = drive.amplitude;
    if (!is_lra()) {
        const double tau = time_constant_s(drive);
        return {{-1.0 / tau, 0.0}, {u != 0.0 ? u / declaration_.rated_drive : 0.0, 0.0}};
    }
    const double f = u != 0.0 ? frequency_of(drive)
                              : (state.frame_hz > 0.0 ? state.frame_hz : declaration_.resonance_hz);
    const double gamma = 1.0 / lra_tau_s_;
    const double delta = kTwoPi * (f - declaration_.resonance_hz);
    const std::complex<double> rate(-gamma, -delta);
    if (u == 0.0) {
        return {rate, {0.0, 0.0}};
    }
    // k(f): the forcing that makes the steady |z| exactly u / rated x G(f).
    const double k = gain(f) / declaration_.rated_drive * std::hypot(1.0, delta / gamma);
    return {rate, gamma * k * u / std::complex<double>(gamma, delta)};
}

State Physics::advance(const State& state, const Drive& drive, double dt_s) const {
    const Motion m = motion(state, drive);
    State next;
    next.envelope = m.steady + (state.envelope - m.steady) * std::exp(m.rate * dt_s);
    if (is_lra()) {
        next.frame_hz = drive.amplitude != 0.0
                            ? frequency_of(drive)
                            : (state.frame_hz > 0.0 ? state.frame_hz : declaration_.resonance_hz);
    }
    return next;
}

Physics::Reach Physics::time_to(const State& state, const Drive& drive, double level,
                                double horizon_s) const {
    using Outcome = Reach::Outcome;
    const double start = strength(state);
    if (std::abs(start - level) <= 1e-12) {
        return {Outcome::reached, 0.0};
    }
    const Motion m = motion(state, drive);
    const bool real_path = m.rate.imag() == 0.0 && m.steady.imag() == 0.0 &&
                           std::abs(state.envelope.imag()) <= 1e-12 * (1.0 + start);
    if (!real_path) {
        return time_to_numeric(state, drive, level, horizon_s);
    }
    // z(t) = a + (z0 - a) e^(-t/tau) moves monotonically towards a: |z| reaches the level where z
    // meets +level or -level, whichever comes first.
    const double tau = -1.0 / m.rate.real();
    const double a = m.steady.real();
    const double z0 = state.envelope.real();
    double first = INFINITY;
    for (const double c : {level, -level}) {
        if (z0 == a) {
            break;
        }
        const double ratio = (c - a) / (z0 - a);
        if (ratio > 0.0 && ratio <= 1.0) {
            first = std::min(first, -tau * std::log(ratio));
        }
    }
    if (std::isfinite(first)) {
        return first <= horizon_s ? Reach{Outcome::reached, first}
                                  : Reach{Outcome::horizon, horizon_s};
    }
    // Never reached: it either creeps towards the level for ever (keep driving) or moves away.
    const bool rising = start < level;
    const bool moves_up = std::abs(a) > start && (a * z0 >= 0.0);
    return rising == moves_up ? Reach{Outcome::horizon, horizon_s} : Reach{Outcome::stalled, 0.0};
}

std::vector<Physics::RestBrake> Physics::brakes_to_rest(const State& state, double search_hz,
                                                        double amplitude) const {
    std::vector<RestBrake> found;
    if (!is_lra() || std::abs(state.envelope) < 1e-12 || !(amplitude > 0.0)) {
        return found;
    }
    // Under anti-phase drive at f the envelope (in f's frame) is z(t) = s + (z0 - s) e^(-rate t);
    // it is 0 at t where e^(-rate t) = R = -s / (z0 - s): |R| = e^(-t/tau) fixes t, and the
    // frequency must make the phase of R agree, arg R = -delta t (mod 2 pi).
    struct Candidate {
        bool valid;
        double mismatch;  // arg R + delta t, wrapped into (-pi, pi]
        double after_s;
    };
    const auto candidate = [&](double f) {
        const Motion m = motion(state, {-amplitude, f});
        const std::complex<double> r = -m.steady / (state.envelope - m.steady);
        const double magnitude = std::abs(r);
        if (!(magnitude < 1.0) || magnitude == 0.0) {
            return Candidate{false, 0.0, 0.0};
        }
        const double t = std::log(magnitude) / m.rate.real();
        return Candidate{
            true, std::remainder(std::arg(r) - m.rate.imag() * t, 2.0 * std::numbers::pi), t};
    };
    const double f0 = declaration_.resonance_hz;
    const double low = std::max(1.0, f0 - search_hz), high = f0 + search_hz;
    constexpr int kSteps = 400;
    double previous_f = low;
    Candidate previous = candidate(low);
    for (int i = 1; i <= kSteps; ++i) {
        const double f = low + (high - low) * i / kSteps;
        const Candidate here = candidate(f);
        // A root, not the jump where the wrapped phase goes round.
        if (previous.valid && here.valid && (previous.mismatch <= 0.0) != (here.mismatch <= 0.0) &&
            std::abs(previous.mismatch - here.mismatch) < std::numbers::pi) {
            double lo = previous_f, hi = f;
            const bool rising = previous.mismatch <= 0.0;
            for (int k = 0; k < kBisections; ++k) {
                const double mid = 0.5 * (lo + hi);
                const Candidate at = candidate(mid);
                ((at.valid && (at.mismatch <= 0.0) == rising) ? lo : hi) = mid;
            }
            const Candidate root = candidate(0.5 * (lo + hi));
            if (root.valid) {
                found.push_back({0.5 * (lo + hi), root.after_s});
            }
        }
        previous = here;
        previous_f = f;
    }
    std::stable_sort(found.begin(), found.end(),
                     [](const RestBrake& a, const RestBrake& b) { return a.after_s < b.after_s; });
    return found;
}

Physics::Reach Physics::time_to_numeric(const State& state, const Drive& drive, double level,
                                        double horizon_s) const {
    using Outcome = Reach::Outcome;
    const Motion m = motion(state, drive);
    const auto z_at = [&](double t) {
        return m.steady + (state.envelope - m.steady) * std::exp(m.rate * t);
    };
    // d|z|^2/dt = 2 Re(conj(z) z'), z' = rate (z - steady): its sign says where |z| is heading.
    const auto heading = [&](double t) {
        const auto z = z_at(t);
        return std::real(std::conj(z) * m.rate * (z - m.steady));
    };
    const bool rising = strength(state) < level;
    const auto beyond = [&](double t) {
        const double s = std::abs(z_at(t));
        return rising ? s >= level : s <= level;
    };
    const auto wrong_way = [&](double t) {
        if (std::abs(z_at(t)) < 1e-12) {
            return false;  // at rest there is no direction yet
        }
        return rising ? heading(t) <= 0.0 : heading(t) >= 0.0;
    };
    const auto bisect = [&](double lo, double hi, const auto& past) {
        for (int i = 0; i < kBisections; ++i) {
            const double mid = 0.5 * (lo + hi);
            (past(mid) ? hi : lo) = mid;
        }
        return hi;
    };
    const double scale = std::min(1.0 / std::abs(m.rate.real()),
                                  m.rate.imag() != 0.0 ? 1.0 / std::abs(m.rate.imag()) : INFINITY);
    const double step = std::max(scale / kStepsPerConstant, horizon_s / 1e6);
    double before = 0.0;
    if (wrong_way(0.0)) {
        if (!rising) {
            return {Outcome::stalled, 0.0};  // it would first get louder
        }
        // What rings against the drive (a brake's residue in anti-phase) takes it down first,
        // through its least, and only then up: driving on is what gets it there (a 50 ms tap at
        // 248 Hz on a 235 Hz Q-8 LRA, started where the last tap's brake left 0.08 % of it in
        // anti-phase, was held without its push and reached 78 % of its strength).
        while (before < horizon_s && wrong_way(before)) {
            before = std::min(before + step, horizon_s);
        }
        if (wrong_way(before)) {
            return {Outcome::horizon, horizon_s};
        }
    }
    while (before < horizon_s) {
        const double t = std::min(before + step, horizon_s);
        if (beyond(t)) {
            return {Outcome::reached, bisect(before, t, beyond)};
        }
        if (wrong_way(t)) {
            return {Outcome::stalled, bisect(before, t, wrong_way)};
        }
        before = t;
    }
    return {Outcome::horizon, horizon_s};
}

}  // namespace vibscore::actuator
