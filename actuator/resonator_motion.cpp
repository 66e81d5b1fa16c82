#include "actuator/resonator_motion.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <tuple>

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

// e^(i phi) at each phase a brake is judged at.
const std::array<std::complex<double>, ResonatorMotion::kPhases>& phases() {
    static const auto table = [] {
        std::array<std::complex<double>, ResonatorMotion::kPhases> t{};
        for (int k = 0; k < ResonatorMotion::kPhases; ++k) {
            t[k] = std::polar(1.0, kTwoPi * k / ResonatorMotion::kPhases);
        }
        return t;
    }();
    return table;
}

void ResonatorMotion::advance(const Physics& physics, Phased& motion, const Drive& drive,
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
    motion.with = decay * motion.with + with * motion.carrier;
    motion.against = decay * motion.against + against * std::conj(motion.carrier);
    motion.carrier *= turn;
}

void ResonatorMotion::start(Now& now) {
    // At its loudest phase, |w| is |with| + |against|.
    now.before += std::abs(now.own.with) + std::abs(now.own.against);
    now.motion.carrier = 1.0;
    now.own = {};
}

ResonatorMotion::Now ResonatorMotion::replaced_at(const Physics& physics, double t,
                                                  const Drive& from, const Drive& to) const {
    Now now = now_;
    if (physics.is_lra() && t > time_) {
        advance(physics, now.motion, from, t - time_);
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
    for (Phased* motion : {&now_.motion, &now_.own}) {
        // Over a long playback, rounding would creep in.
        motion->carrier /= std::abs(motion->carrier);
    }
    time_ = t;
}

ResonatorMotion::Measure ResonatorMotion::measure(const Physics& physics, double frequency_hz) {
    const Constants c = constants(physics);
    const double omega = kTwoPi * frequency_hz;
    const auto z = [&](std::complex<double> w) {
        const double x = w.imag() / c.wd;
        return std::complex<double>(x, (w.real() - c.g * x) / omega);
    };
    // z is real-linear in w: a w + b conj(w), read off at w = 1 and w = i.
    return {0.5 * (z(1.0) - kI * z(kI)), 0.5 * (z(1.0) + kI * z(kI))};
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
    // alone moves its strength by 7 % of a note off resonance; at its loudest phase it measures
    // |first| + |second|), and what rang before it, ringing down as if alone (the resonator is
    // linear), met where the two add up: each earlier vibration started at a phase of its own.
    // (The whole motion, every start at one phase, said 4.6 % for a 0.38 note at 178 Hz on a
    // 175 Hz Q-8 LRA started where 4 % of it still rang, and 4.5 % for a 0.38 note on a 175 Hz
    // Q-25 LRA overdriven out of the brake of the note before; on bench/feel's plant they went
    // 5.7 % and 10.7 % above.)
    const auto look = [&](const Drive& drive, double length) {
        // At least kLooksPerCycle a cycle: the half of the drive that turns against the
        // resonator ripples its strength at twice the drive's frequency, by up to 1 / 4Q.
        const double hz = physics.frequency_of(drive);
        const Measure at_hz = measure(physics, hz);
        const int n = std::max(looks, static_cast<int>(std::ceil(kLooksPerCycle * hz * length)));
        for (int k = 1; k <= n && length > 0.0; ++k) {
            advance(physics, now.own, drive, length / n);
            now.before *= std::exp(-g * length / n);
            const auto [first_part, second_part] = at_hz.of(now.own);
            most = std::max(
                most, std::abs(first_part) + std::abs(second_part) + at_hz.loudest(now.before));
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

struct ResonatorMotion::Brake::Seen {
    Seen(const Measure& measure, const Phased& motion, std::complex<double> rang)
        : ringing(measure.of(rang)) {
        std::tie(first, second) = measure.of(motion);
    }
    double at(std::complex<double> e) const {
        return std::abs(first * e + second * std::conj(e) + ringing);
    }
    // The least and the most over every phase.
    double least() const {
        return std::abs(std::abs(first) - std::abs(second)) - std::abs(ringing);
    }
    double most() const { return std::abs(first) + std::abs(second) + std::abs(ringing); }
    // The root mean square over every phase (the three turn apart, so their cross terms average
    // out).
    double typical() const {
        return std::sqrt(std::norm(first) + std::norm(second) + std::norm(ringing));
    }
    std::complex<double> first, second, ringing;
};

template <class Judge>
void ResonatorMotion::Brake::each(Judge judge) const {
    for (int group = 0; group <= ringings_; ++group) {
        const Phased& motion = group == 0 ? whole_ : own_;
        const std::complex<double> ringing = group == 0 ? 0.0 : ringing_[group - 1];
        judge(group, Seen(driven_, motion, ringing), Seen(resting_, motion, ringing));
    }
}

ResonatorMotion::Brake::Brake(const Physics& physics, const Now& now, const Drive& drive,
                              double quiet)
    : physics_(&physics),
      whole_(now.motion),
      own_(now.own),
      drive_(drive),
      driven_(measure(physics, physics.frequency_of(drive))),
      resting_(measure(physics, physics.declaration().resonance_hz)),
      start_(now.motion) {
    for (int l = 0; l < kLevels; ++l) {
        levels_[l] = quiet * (0.8 + 0.4 * l / (kLevels - 1));
    }
    if (now.before > 0.01 * quiet) {
        for (int level = 1; level <= kRingingLevels; ++level) {
            for (int r = 0; r < kRingingPhases; ++r) {
                ringing_[ringings_++] =
                    std::polar(now.before * level / kRingingLevels, kTwoPi * r / kRingingPhases);
            }
        }
    }
    // Off resonance a brake's anti-phase holds only for a while: past it the brake drives the
    // resonator on (a 0.37 note at 171 Hz on a 150 Hz Q-25 LRA, braked at 168 Hz, was at 0.43
    // when the next note started, and the planner's envelope said it was at rest).
    const auto& e = phases();
    each([&](int group, const Seen& driven, const Seen&) {
        lowest_ceiling_[group] = INFINITY;
        for (int k = 0; k < kPhases; ++k) {
            double& ceiling = ceiling_[group * kPhases + k];
            ceiling = std::max((1.0 + kPushUp) * driven.at(e[k]), levels_.back());
            lowest_[group * kPhases + k] = INFINITY;  // judged from the first look on
            lowest_ceiling_[group] = std::min(lowest_ceiling_[group], ceiling);
        }
    });
}

void ResonatorMotion::Brake::look(double length) {
    if (!physics_->is_lra()) {
        return;
    }
    const double dt = length - length_;
    if (dt > 0.0) {
        advance(*physics_, whole_, drive_, dt);
        advance(*physics_, own_, drive_, dt);
        // What rang before rings down alone: the drive's part is in own_.
        const Constants c = constants(*physics_);
        const std::complex<double> decay = std::exp(std::complex<double>(-c.g, c.wd) * dt);
        for (int r = 0; r < ringings_; ++r) {
            ringing_[r] *= decay;
        }
    }
    length_ = std::max(length_, length);
    const auto& e = phases();
    each([&](int group, const Seen& driven, const Seen&) {
        if (!any_below_[group] && driven.least() >= levels_.back() &&
            driven.most() < lowest_ceiling_[group]) {
            return;  // no phase has been or is below a level, nor reaches its ceiling
        }
        std::array<double, kPhases> now;
        double* lowest = &lowest_[group * kPhases];
        for (int k = 0; k < kPhases; ++k) {
            now[k] = driven.at(e[k]);
            rebound_ = std::max(rebound_, now[k] - ceiling_[group * kPhases + k]);
            lowest[k] = std::min(lowest[k], now[k]);
            any_below_[group] = any_below_[group] || lowest[k] < levels_.back();
        }
        if (any_below_[group]) {
            rebound_ = std::max(rebound_, rise(group, [&](int k) { return now[k]; }));
        }
    });
}

template <class Loudness>
double ResonatorMotion::Brake::rise(int group, Loudness loudness) const {
    const double* lowest = &lowest_[group * kPhases];
    double most = -INFINITY;
    for (int k = 0; k < kPhases; ++k) {
        const int next = (k + 1) % kPhases;
        for (int l = 0; l < kLevels; ++l) {
            const double level = levels_[l];
            const bool here = lowest[k] < level, there = lowest[next] < level;
            const double above = level * (1.0 + kRiseSlack);
            if (here) {
                most = std::max(most, loudness(k) - above);
            }
            if (here != there) {
                // Between this phase and the next, one that went just down to the level: as
                // loud as where it lies between them (a brake at 185 Hz on a 175 Hz Q-8 LRA left
                // the phase bench/feel's plant started it at 10.2 % after dipping, where the
                // nearest of 96 phases that dipped stayed under 10 %).
                const double x = (lowest[k] - level) / (lowest[k] - lowest[next]);
                most = std::max(most, loudness(k) + x * (loudness(next) - loudness(k)) - above);
            }
        }
    }
    return most;
}

double ResonatorMotion::Brake::rebound_left() const {
    if (!physics_->is_lra()) {
        return -INFINITY;
    }
    const auto& e = phases();
    double most = -INFINITY;
    each([&](int group, const Seen&, const Seen& resting) {
        if (any_below_[group]) {
            most = std::max(most, rise(group, [&](int k) { return resting.at(e[k]); }));
        }
    });
    return most;
}

double ResonatorMotion::Brake::rebound_until(double length) {
    look(length);
    return std::max(rebound_, rebound_left());
}

double ResonatorMotion::Brake::typical_left() const {
    return Seen(resting_, whole_, 0.0).typical();
}

double ResonatorMotion::Brake::typical_at_start() const {
    return Seen(resting_, start_, 0.0).typical();
}

bool ResonatorMotion::Brake::louder_than_coasting() const {
    if (!physics_->is_lra()) {
        return false;
    }
    const Constants c = constants(*physics_);
    const std::complex<double> coasted = std::exp(std::complex<double>(-c.g, c.wd) * length_);
    const Seen left(resting_, whole_, 0.0);
    const Seen coasting(resting_, Phased{start_.with * coasted, start_.against * coasted}, 0.0);
    for (const std::complex<double> e : phases()) {
        const double loudness = left.at(e);
        if (loudness > coasting.at(e) && loudness > levels_.back()) {
            return true;
        }
    }
    return false;
}

}  // namespace vibscore::actuator
