#include "actuator/resonator_motion.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <span>

namespace vibscore::actuator {

namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
// Looks a cycle of the drive, at the least, where the strongest is looked for: four a ripple,
// so that no ripple's top is missed by more than 1 - cos 45 degrees of it.
constexpr double kLooksPerCycle = 8.0;
const std::complex<double> kI(0.0, 1.0);

struct Constants {
    double g, w0, wd, force;
};

Constants constants(const Physics& physics) {
    const double g = 1.0 / physics.time_constant_s({});
    const double w0 = kTwoPi * physics.declaration().resonance_hz;
    // Rated drive at resonance holds amplitude 1: F rated / (2 g w0) = 1.
    return {g, w0, std::sqrt(std::max(0.0, w0 * w0 - g * g)),
            2.0 * g * w0 / physics.declaration().rated_drive};
}

}  // namespace

void ResonatorMotion::advance(const Physics& physics, std::span<Motion> motions, const Drive& drive,
                              double dt) {
    if (!physics.is_lra() || !(dt > 0.0)) {
        return;
    }
    const Constants c = constants(physics);
    const std::complex<double> l(-c.g, c.wd);
    const std::complex<double> decay = std::exp(l * dt);
    const double u = drive.amplitude;
    const double omega = kTwoPi * physics.frequency_of(drive);
    const std::complex<double> turn = std::polar(1.0, omega * dt);
    // cos = (e^(i theta) + e^(-i theta)) / 2, each half solved on its own.
    const std::complex<double> with = 0.5 * c.force * u * (turn - decay) / (kI * omega - l);
    const std::complex<double> against =
        0.5 * c.force * u * (std::conj(turn) - decay) / (-kI * omega - l);
    for (Motion& m : motions) {
        m.w = decay * m.w + with * m.carrier + against * std::conj(m.carrier);
        m.carrier *= turn;
    }
}

void ResonatorMotion::start(Now& now) {
    double loudest = 0.0;
    for (const Motion& m : now.own) {
        loudest = std::max(loudest, std::abs(m.w));
    }
    now.before += loudest;
    for (int k = 0; k < kPhases; ++k) {
        now.motions[k].carrier = std::polar(1.0, kTwoPi * k / kPhases);
        now.own[k] = {{}, now.motions[k].carrier};
    }
}

ResonatorMotion::Now ResonatorMotion::replaced_at(const Physics& physics, double t,
                                                  const Drive& from, const Drive& to) const {
    Now now = now_;
    if (physics.is_lra() && t > time_) {
        advance(physics, now.motions, from, t - time_);
        advance(physics, now.own, from, t - time_);
        now.before *= std::exp(-constants(physics).g * (t - time_));
    }
    if (from.amplitude == 0.0 && to.amplitude != 0.0) {
        start(now);
    }
    return now;
}

void ResonatorMotion::change(const Physics& physics, double t, const Drive& from, const Drive& to) {
    now_ = replaced_at(physics, t, from, to);
    for (Motions* motions : {&now_.motions, &now_.own}) {
        for (Motion& m : *motions) {
            m.carrier /= std::abs(m.carrier);  // over a long playback, rounding would creep in
        }
    }
    time_ = t;
}

double ResonatorMotion::strength(const Physics& physics, const Motion& motion,
                                 double frequency_hz) {
    const Constants c = constants(physics);
    const double x = motion.w.imag() / c.wd;
    const double v = (motion.w.real() - c.g * x) / (kTwoPi * frequency_hz);
    return std::sqrt(x * x + v * v);
}

double ResonatorMotion::strength_of_ringing(const Physics& physics, double ringing,
                                            double frequency_hz) {
    // (x, v / omega) is M (Re w, Im w), M = [[0, 1 / wd], [1 / omega, -g / (omega wd)]]: at the
    // worst phase, |w| times M's largest singular value.
    const Constants c = constants(physics);
    const double omega = kTwoPi * frequency_hz;
    const double sum = 1.0 / (c.wd * c.wd) + (1.0 + c.g * c.g / (c.wd * c.wd)) / (omega * omega);
    const double det = 1.0 / (c.wd * omega);
    return ringing * std::sqrt(0.5 * (sum + std::sqrt(std::max(0.0, sum * sum - 4.0 * det * det))));
}

double ResonatorMotion::strongest(const Physics& physics, double t, const Drive& from,
                                  const Drive& first, double first_s, const Drive& then,
                                  double then_s, int looks) const {
    if (!physics.is_lra()) {
        return 0.0;
    }
    const double g = constants(physics).g;
    double most = 0.0;
    Now now = replaced_at(physics, t, from, first);
    // The vibration going on, from rest at every phase of the carrier where it started (which
    // alone moves its strength by 7 % of a note off resonance), and what rang before it, ringing
    // down as if alone (the resonator is linear), met where the two add up: each earlier
    // vibration started at a phase of its own. (The whole motion, every start at one phase,
    // said 4.6 % for a 0.38 note at 178 Hz on a 175 Hz Q-8 LRA started where 4 % of it still
    // rang, and 4.5 % for a 0.38 note on a 175 Hz Q-25 LRA overdriven out of the brake of the
    // note before; on bench/feel's plant they went 5.7 % and 10.7 % above.)
    const auto look = [&](const Drive& drive, double length) {
        // At least kLooksPerCycle a cycle: the half of the drive that turns against the
        // resonator ripples its strength at twice the drive's frequency, by up to 1 / 4Q.
        const double hz = physics.frequency_of(drive);
        const int n = std::max(looks, static_cast<int>(std::ceil(kLooksPerCycle * hz * length)));
        for (int k = 1; k <= n && length > 0.0; ++k) {
            advance(physics, now.own, drive, length / n);
            now.before *= std::exp(-g * length / n);
            const double rings = strength_of_ringing(physics, now.before, hz);
            for (const Motion& m : now.own) {
                most = std::max(most, strength(physics, m, hz) + rings);
            }
        }
    };
    look(first, first_s);
    if (first.amplitude == 0.0 && then.amplitude != 0.0) {
        start(now);
    }
    look(then, then_s);
    return most;
}

ResonatorMotion::Brake ResonatorMotion::braking(const Physics& physics, double t, const Drive& from,
                                                const Drive& brake, double quiet) const {
    return Brake(physics, replaced_at(physics, t, from, brake), brake, quiet);
}

ResonatorMotion::Brake::Brake(const Physics& physics, const Now& now, const Drive& drive,
                              double quiet)
    : physics_(&physics), drive_(drive) {
    for (int l = 0; l < kLevels; ++l) {
        levels_[l] = quiet * (0.8 + 0.4 * l / (kLevels - 1));
    }
    std::copy(now.motions.begin(), now.motions.end(), motions_.begin());
    start_ = now.motions;
    if (now.before > 0.01 * quiet) {
        for (int level = 1; level <= kRingingLevels; ++level) {
            for (int r = 0; r < kRingingPhases; ++r) {
                const auto ringing =
                    std::polar(now.before * level / kRingingLevels, kTwoPi * r / kRingingPhases);
                for (const Motion& m : now.own) {
                    motions_[count_++] = {m.w + ringing, m.carrier};
                }
            }
        }
    }
    // Off resonance a brake's anti-phase holds only for a while: past it the brake drives the
    // resonator on (a 0.37 note at 171 Hz on a 150 Hz Q-25 LRA, braked at 168 Hz, was at 0.43
    // when the next note started, and the planner's envelope said it was at rest).
    const double driven_hz = physics.frequency_of(drive);
    for (int k = 0; k < count_; ++k) {
        ceiling_[k] =
            std::max((1.0 + kPushUp) * strength(physics, motions_[k], driven_hz), levels_.back());
    }
}

double ResonatorMotion::Brake::rebound_until(double length) {
    if (!physics_->is_lra()) {
        return -INFINITY;
    }
    advance(*physics_, std::span(motions_.data(), static_cast<std::size_t>(count_)), drive_,
            length - length_);
    length_ = std::max(length_, length);
    const double driven_hz = physics_->frequency_of(drive_);
    const double own_hz = physics_->declaration().resonance_hz;
    double ending = -INFINITY;
    for (int k = 0; k < count_; ++k) {
        const double now = strength(*physics_, motions_[k], driven_hz);
        const double left = strength(*physics_, motions_[k], own_hz);
        rebound_ = std::max(rebound_, now - ceiling_[k]);
        for (int l = 0; l < kLevels; ++l) {
            below_[k][l] = below_[k][l] || now < levels_[l];
            if (below_[k][l]) {
                rebound_ = std::max(rebound_, now - levels_[l]);
                ending = std::max(ending, left - levels_[l]);
            }
        }
    }
    return std::max(rebound_, ending);
}

bool ResonatorMotion::Brake::louder_than_coasting() const {
    if (!physics_->is_lra()) {
        return false;
    }
    const Constants c = constants(*physics_);
    const std::complex<double> coasted = std::exp(std::complex<double>(-c.g, c.wd) * length_);
    const double own_hz = physics_->declaration().resonance_hz;
    for (int k = 0; k < kPhases; ++k) {
        const double left = strength(*physics_, motions_[k], own_hz);
        const double coasting = strength(*physics_, Motion{start_[k].w * coasted}, own_hz);
        if (left > coasting && left > levels_.back()) {
            return true;
        }
    }
    return false;
}

}  // namespace vibscore::actuator
