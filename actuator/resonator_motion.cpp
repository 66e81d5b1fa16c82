#include "actuator/resonator_motion.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

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

ResonatorMotion::Motions ResonatorMotion::advanced(const Physics& physics, Motions motions,
                                                   const Drive& drive, double dt) {
    if (!physics.is_lra() || !(dt > 0.0)) {
        return motions;
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
    return motions;
}

ResonatorMotion::Motions ResonatorMotion::changed(Motions motions, const Drive& from,
                                                  const Drive& to, Start start) {
    if (from.amplitude == 0.0 && to.amplitude != 0.0) {
        // A vibration starts: at a phase of the backend's, against whatever still rings.
        for (int k = 0; k < kPhases; ++k) {
            const double ringing = start == Start::against_ringing && std::abs(motions[k].w) > 0.0
                                       ? std::arg(motions[k].w)
                                       : 0.0;
            motions[k].carrier = std::polar(1.0, ringing + kTwoPi * k / kPhases);
        }
    }
    return motions;
}

ResonatorMotion::Motions ResonatorMotion::replaced_at(const Physics& physics, double t,
                                                      const Drive& from, const Drive& to,
                                                      Start start) const {
    return changed(advanced(physics, motions_, from, t - time_), from, to, start);
}

void ResonatorMotion::change(const Physics& physics, double t, const Drive& from, const Drive& to) {
    motions_ = replaced_at(physics, t, from, to, Start::absolute);
    for (Motion& m : motions_) {
        m.carrier /= std::abs(m.carrier);  // over a long playback, rounding would creep in
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

double ResonatorMotion::strongest(const Physics& physics, double t, const Drive& from,
                                  const Drive& first, double first_s, const Drive& then,
                                  double then_s, int looks) const {
    if (!physics.is_lra()) {
        return 0.0;
    }
    double most = 0.0;
    Motions motions;
    const auto look = [&](const Drive& drive, double length) {
        // At least kLooksPerCycle a cycle: the half of the drive that turns against the
        // resonator ripples its strength at twice the drive's frequency, by up to 1 / 4Q.
        const int n = std::max(
            looks,
            static_cast<int>(std::ceil(kLooksPerCycle * physics.frequency_of(drive) * length)));
        for (int k = 1; k <= n && length > 0.0; ++k) {
            motions = advanced(physics, motions, drive, length / n);
            for (const Motion& m : motions) {
                most = std::max(most, strength(physics, m, physics.frequency_of(drive)));
            }
        }
    };
    // Where a vibration starts, each of the followed motions meets what still rings in it at
    // k / kPhases of a turn from its own phase (against_ringing), and starts at k / kPhases of a
    // turn of the carrier (absolute): what the start sets ringing depends on both. Where little
    // rings, each motion's ringing is at a phase its last start set, so against_ringing alone
    // can leave the carrier's worst phases untried (a 0.69 note at 199 Hz on a 175 Hz Q-8 LRA,
    // 33 ms after a brake, went 5.6 % above on bench/feel's plant where this said 1.3 %).
    const bool starts = (from.amplitude == 0.0 && first.amplitude != 0.0) ||
                        (first.amplitude == 0.0 && then.amplitude != 0.0);
    for (const Start start : {Start::against_ringing, Start::absolute}) {
        motions = replaced_at(physics, t, from, first, start);
        look(first, first_s);
        motions = changed(motions, first, then, start);
        look(then, then_s);
        if (!starts) {
            break;  // the drive goes on: the two are the same
        }
    }
    return most;
}

ResonatorMotion::Brake ResonatorMotion::braking(const Physics& physics, double t, const Drive& from,
                                                const Drive& brake, double quiet) const {
    return Brake(physics, replaced_at(physics, t, from, brake, Start::absolute), brake, quiet);
}

ResonatorMotion::Brake::Brake(const Physics& physics, Motions motions, const Drive& drive,
                              double quiet)
    : physics_(&physics), motions_(motions), drive_(drive) {
    for (int l = 0; l < kLevels; ++l) {
        levels_[l] = quiet * (0.8 + 0.4 * l / (kLevels - 1));
    }
    // Off resonance a brake's anti-phase holds only for a while: past it the brake drives the
    // resonator on (a 0.37 note at 171 Hz on a 150 Hz Q-25 LRA, braked at 168 Hz, was at 0.43
    // when the next note started, and the planner's envelope said it was at rest).
    const double driven_hz = physics.frequency_of(drive);
    for (int k = 0; k < kPhases; ++k) {
        ceiling_[k] =
            std::max((1.0 + kPushUp) * strength(physics, motions_[k], driven_hz), levels_.back());
    }
}

double ResonatorMotion::Brake::rebound_until(double length) {
    if (!physics_->is_lra()) {
        return -INFINITY;
    }
    motions_ = advanced(*physics_, motions_, drive_, length - length_);
    length_ = std::max(length_, length);
    const double driven_hz = physics_->frequency_of(drive_);
    const double own_hz = physics_->declaration().resonance_hz;
    double ending = -INFINITY;
    for (int k = 0; k < kPhases; ++k) {
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

}  // namespace vibscore::actuator
