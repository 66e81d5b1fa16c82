#include "daemon/render/drive_planner.hpp"

#include <algorithm>
#include <cmath>

namespace vibscore::render {

namespace {

using actuator::Drive;
using actuator::Physics;
using actuator::State;
using Outcome = Physics::Reach::Outcome;

constexpr int kBisections = 60;

// Within this of the written strength counts as there: no overdrive or brake for a rounding.
double tolerance(double strength) {
    return 1e-6 * std::max(strength, 1e-3);
}

}  // namespace

DrivePlanner::DrivePlanner(const actuator::Declaration& declaration, const PlannerOptions& options,
                           const PlannerCarry& carry)
    : physics_(declaration),
      options_(options),
      state_(carry.state),
      drive_(carry.drive),
      last_frequency_hz_(carry.ringing_frequency_hz) {}

State DrivePlanner::follow(const std::vector<Step>& steps, double t) const {
    State state = state_;
    for (std::size_t i = 0; i < steps.size(); ++i) {
        const double from = steps[i].at;
        const double to = i + 1 < steps.size() ? std::min(steps[i + 1].at, t) : t;
        if (to <= from) {
            break;
        }
        state = physics_.advance(state, steps[i].drive, to - from);
    }
    return state;
}

std::vector<DrivePlanner::Step> DrivePlanner::approach(double at, double until, double strength,
                                                       double frequency_hz) const {
    // An open end (the silence after the last note) needs no more than the actuator can take to
    // settle from anywhere.
    const double longest =
        std::max({physics_.declaration().spin_up_s, physics_.declaration().spin_down_s,
                  physics_.time_constant_s({1.0, 0.0})});
    const double horizon = std::isfinite(until) ? until - at : 50.0 * longest;
    const double hold_amplitude =
        strength > 0.0 ? std::min(1.0, physics_.amplitude_for(strength, frequency_hz)) : 0.0;
    const Drive hold{hold_amplitude, hold_amplitude > 0.0 ? frequency_hz : 0.0};
    const double now = Physics::strength(state_);
    if (std::abs(now - strength) <= tolerance(strength)) {
        return {{at, hold}};
    }
    if (strength == 0.0 && options_.reverse && physics_.is_lra() && frequency_hz > 0.0) {
        // To rest off resonance: anti-phase at the frequency that leaves nothing ringing.
        const auto& d = physics_.declaration();
        if (const auto brake = physics_.brake_to_rest(state_, 3.0 * d.resonance_hz / d.q)) {
            const Drive push{-1.0, brake->frequency_hz};
            if (at + brake->after_s >= until) {
                return {{at, push}};
            }
            if (brake->after_s >= options_.min_pulse_s) {
                return {{at, push}, {at + brake->after_s, hold}};
            }
        }
    }
    Drive push;
    if (now < strength) {
        push = {1.0, frequency_hz};
    } else if (options_.reverse) {
        push = {-1.0, frequency_hz};
    } else {
        push = {0.0, 0.0};  // coast
        if (strength == 0.0) {
            return {{at, push}};
        }
    }
    const auto reach = physics_.time_to(state_, push, strength, horizon);
    if (reach.outcome == Outcome::horizon) {
        return {{at, push}};  // out of reach within the segment: push all the way
    }
    if (reach.after_s < options_.min_pulse_s || at + reach.after_s >= until) {
        // Too short to matter (or, stalled at once, of no use); the hold does the rest.
        return reach.after_s < options_.min_pulse_s ? std::vector<Step>{{at, hold}}
                                                    : std::vector<Step>{{at, push}};
    }
    return {{at, push}, {at + reach.after_s, hold}};
}

double DrivePlanner::early_end(const std::vector<Step>& steps, double until,
                               double strength) const {
    const double at = steps.front().at;
    const double felt_end = strength / 2.0;
    const auto at_end_if_cut = [&](double cut) {
        const State coasting = follow(steps, cut);
        return Physics::strength(physics_.advance(coasting, {0.0, 0.0}, until - cut));
    };
    if (at_end_if_cut(until) <= felt_end) {
        return until;  // the note never got strong enough to linger: keep all of it
    }
    if (at_end_if_cut(at) >= felt_end) {
        return at;  // already lingering at that strength: no drive at all
    }
    // The strength at the end grows with the cut (the drive only ever adds), so bisect.
    double lo = at, hi = until;
    for (int i = 0; i < kBisections; ++i) {
        const double mid = 0.5 * (lo + hi);
        (at_end_if_cut(mid) >= felt_end ? hi : lo) = mid;
    }
    return hi;
}

void DrivePlanner::emit(double at, const Drive& drive, std::vector<Cue>& out) {
    if (drive == drive_) {
        return;
    }
    drive_ = drive;
    out.push_back(drive_at(at, drive.amplitude, drive.frequency_hz));
    if (drive.amplitude != 0.0) {
        last_frequency_hz_ = drive.frequency_hz;
    }
}

void DrivePlanner::segment(double at, double until, double strength, double frequency_hz,
                           bool silence_follows, std::vector<Cue>& out) {
    if (!(until > at)) {
        return;  // of two drives at one instant only the later one is ever felt
    }
    const double written = std::max(0.0, strength * options_.scale);
    std::vector<Step> steps;
    if (!options_.compensation) {
        const double amplitude = std::min(1.0, written * physics_.declaration().rated_drive);
        steps.push_back({at, {amplitude, amplitude > 0.0 ? frequency_hz : 0.0}});
    } else {
        // Silence brakes the vibration that is ringing, at its own frequency.
        const double frequency = written > 0.0 ? frequency_hz : last_frequency_hz_;
        steps = approach(at, until, written, frequency);
        if (silence_follows && !options_.reverse && written > 0.0 && std::isfinite(until)) {
            const double cut = early_end(steps, until, written);
            if (cut < until) {
                std::erase_if(steps, [&](const Step& step) { return step.at >= cut; });
                steps.push_back({cut, {0.0, 0.0}});
            }
        }
    }
    for (const Step& step : steps) {
        emit(step.at, step.drive, out);
    }
    state_ = follow(steps, std::isfinite(until) ? until : steps.back().at);
}

}  // namespace vibscore::render
