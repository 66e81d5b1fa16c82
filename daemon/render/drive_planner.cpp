#include "daemon/render/drive_planner.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "common/number_text.hpp"

namespace vibscore::render {

namespace {

using actuator::Drive;
using actuator::Physics;
using actuator::State;
using Outcome = Physics::Reach::Outcome;

constexpr int kBisections = 60;
// An overdrive may take the declared actuator no more than this above the written strength, by
// the model (the resonator itself goes a little further: within 5 % on bench/feel's plant) ...
constexpr double kOvershoot = 0.03;
// ... and a hundredth of the strength more (of rated strength at most): the steps of a hairpin
// are that fine. Not a hundredth of rated strength whatever the note: a soft note's overdrive
// then went 5.5 % above it by the model (5.2 % on bench/feel's plant, a 0.4 note at 200 Hz).
constexpr double kOvershootFloor = 0.01;
// The declared LRA's whole motion (ResonatorMotion: what the model leaves out too) may go this
// far above, under an overdrive and the hold after it: issue 32's bound is 5 %, bench/feel's
// plant saw 6.5 % on a Q-8 LRA far off resonance judged by the model alone.
constexpr double kWholeOvershoot = 0.045;
// A held note's beat may top its strength by this, by the model: none, as the resonator itself
// beats a little higher than the model's envelope says.
constexpr double kBeatOvershoot = 0.0;
// (A thousandth of rated strength more: a hairpin's steps start each hold a hair off its phase.)
constexpr double kBeatFloor = 0.001;
// The other members may go this far above: a faster actuator than declared overshoots a little
// under any overdrive that gets the declared one there in time; this keeps it to a little.
constexpr double kMemberOvershoot = 0.30;
// A brake may push no member back up, after its lowest point, by more than this of its strength
// at the brake's start: past rest, a brake adds energy.
constexpr double kPushBack = 0.30;
// Where a brake has stopped an actuator: below this of its strength at the brake's start.
constexpr double kStopped = 0.10;
// How much sooner (a fraction of coasting's stop) a brake must stop the declared one than the
// best found so far to be preferred.
constexpr double kBetter = 1e-4;
// Issue 32: after a note's end the response never rises again above 10 % of the note. A brake's
// watch (actuator::ResonatorMotion, the declared LRA's whole motion) holds it to that around
// this level (from 0.8 to 1.2 of it, for what the declaration does not say). (Judged by the
// envelope alone, a brake far off a low-Q LRA's resonance at full scale left 20 % on bench/feel's
// plant.)
constexpr double kQuiet = 0.10;
// The brakes tried, strongest first: a weaker brake sets less ringing at each change, so where
// full scale far off resonance leaves too much, a weaker one nearer to it may not. Finely spaced:
// a brake's length moves with its strength, and whether what its start and its end set ringing
// cancels depends on its length to a fraction of a cycle.
constexpr double kBrakeAmplitudes[] = {1.0, 0.95, 0.9, 0.85, 0.8, 0.75, 0.7, 0.65,
                                       0.6, 0.55, 0.5, 0.45, 0.4, 0.35, 0.3, 0.25};
// Fewer where every member is simulated at each of them.
constexpr double kRobustBrakeAmplitudes[] = {1.0, 0.85, 0.7, 0.5, 0.35, 0.25};
// Points per brake, and per held time constant, at which the members are looked at.
constexpr int kLooks = 32;
// Brake frequencies tried on either side of the resonance.
constexpr int kFrequencies = 12;
// Where the resonance is uncertain by more than this many of its bandwidths (f0 / Q), the phase a
// brake meets is not known: an LRA built at the margin's edge rings up to ~60 degrees away from
// the model (more as it rings on at its own frequency), and a brake there pushes as much as it
// stops. Such an LRA is not braked: its drive ends early instead, as on a board that cannot brake,
// so that its own ring-down ends the note on time.
constexpr double kPhaseKnown = 0.5;

// An LRA's brake within a note of up to this many half cycles of its carrier is made a whole
// number of them (in_half_cycles). (Overdrives are not: their budget is judged against what may
// still ring at any phase, for the full-scale push alone.)
constexpr double kWholeHalfCycles = 4.0;

// Without braking, how far before a note's end its drive may be ended early, in time constants of
// the member that rings longest: from further, coasting brings any strength below a hundredth.
constexpr double kLookAheadTimeConstants = 8.0;
// At a note's end (without braking) a member may ring at no more than this share of what
// compensation off would leave it at (the model leaves a little out: bench/feel's plant rang 1 ms
// longer than off after a 25 ms note planned to off's level exactly) ...
constexpr double kOffShare = 0.9;
// ... but need not go below this of the note's strongest: where off leaves it lower, both have
// stopped (below kQuiet) by the note's end.
constexpr double kFeltFloor = kQuiet;

// Within this of the written strength counts as there: no overdrive or brake for a rounding.
double tolerance(double strength) {
    return 1e-6 * std::max(strength, 1e-3);
}

}  // namespace

Uncertainty uncertainty_of(const actuator::Declaration& declaration) {
    if (declaration.kind != actuator::Kind::lra) {
        return {};
    }
    return {declaration.resonance_tolerance, declaration.q_tolerance};
}

DrivePlanner::DrivePlanner(const actuator::Declaration& declaration, const PlannerOptions& options,
                           const PlannerCarry& carry)
    : physics_(declaration),
      options_(options),
      state_(carry.state),
      drive_(carry.drive),
      last_frequency_hz_(carry.ringing_frequency_hz),
      brakes_(options.reverse) {
    const Uncertainty& u = options.uncertainty;
    if (!(u.resonance >= 0.0 && u.resonance <= 0.5) || !(u.q >= 0.0 && u.q <= 0.9)) {
        throw std::invalid_argument("drive planner: uncertainty of resonance " +
                                    number_text(u.resonance) + " (0..0.5) or of q " +
                                    number_text(u.q) + " (0..0.9) out of range");
    }
    if (!physics_.is_lra() || !options.compensation || (u.resonance == 0.0 && u.q == 0.0)) {
        return;
    }
    brakes_ = options.reverse && u.resonance * declaration.q <= kPhaseKnown;
    for (const double f : {1.0 - u.resonance, 1.0, 1.0 + u.resonance}) {
        for (const double q : {1.0 - u.q, 1.0, 1.0 + u.q}) {
            if ((f == 1.0 && q == 1.0) || (u.resonance == 0.0 && f != 1.0) ||
                (u.q == 0.0 && q != 1.0)) {
                continue;
            }
            actuator::Declaration member = declaration;
            member.resonance_hz *= f;
            member.q *= q;
            members_.emplace_back(member);
        }
    }
    member_states_ = carry.members.size() == members_.size()
                         ? carry.members
                         : std::vector<State>(members_.size(), carry.state);
}

std::vector<std::pair<const Physics*, State>> DrivePlanner::ensemble() const {
    std::vector<std::pair<const Physics*, State>> all{{&physics_, state_}};
    for (std::size_t i = 0; i < members_.size(); ++i) {
        all.emplace_back(&members_[i], member_states_[i]);
    }
    return all;
}

double DrivePlanner::overdrive_budget(double at, const Drive& push, const Drive& hold,
                                      double needed, double span, double strength,
                                      bool note_ends) const {
    auto all = ensemble();
    if (drive_.amplitude == 0.0 && Physics::strength(state_) > 0.0) {
        // Starting again after a silence, the drive's phase is the backend's (gpio-lra starts
        // each waveform afresh; a force-feedback device has its own), not the model's: what
        // still rings may meet it in phase.
        all.emplace_back(&physics_, State{Physics::strength(state_), push.frequency_hz});
    }
    // Whether some member, overdriven for `t` and then held, goes above its limit while the
    // segment lasts (looked at over three of its time constants at most: by then it has settled).
    const auto overshoots = [&](double t) {
        // The declared one's whole motion (ResonatorMotion), at any phase the backend may have
        // started the vibration at, within the bound: for three time constants of the
        // hold, past the segment's end too unless the note ends there (a brake's watch takes
        // over), since a glide's and a hairpin's next steps go on much as this one (bench/feel's
        // ringtone glide on a 205 Hz Q-8 LRA crested 5.9 % above its strength a step after the
        // overdrive's).
        const double settle = 3.0 * physics_.time_constant_s(hold);
        const double whole = note_ends ? std::min(span - t, settle) : settle;
        if (physics_.is_lra() &&
            motion_.strongest(physics_, at, drive_, push, t, hold, whole, kLooks) >
                (1.0 + kWholeOvershoot) * std::max(strength, physics_.steady_strength(hold))) {
            return true;
        }
        for (const auto& [physics, state] : all) {
            const double allowance = physics == &physics_ ? kOvershoot : kMemberOvershoot;
            const double limit =
                (1.0 + allowance) * std::max(strength, physics->steady_strength(hold)) +
                kOvershootFloor * std::min(strength, 1.0);
            const State pushed = physics->advance(state, push, t);
            if (Physics::strength(pushed) > limit) {
                return true;
            }
            const double window = std::min(span - t, 3.0 * physics->time_constant_s(hold));
            for (int k = 1; k <= 3 * kLooks && window > 0.0; ++k) {
                const double after = window * k / (3.0 * kLooks);
                if (Physics::strength(physics->advance(pushed, hold, after)) > limit) {
                    return true;
                }
            }
        }
        return false;
    };
    if (!overshoots(needed)) {
        return needed;
    }
    double lo = 0.0, hi = needed;
    for (int i = 0; i < kBisections / 2; ++i) {
        const double mid = 0.5 * (lo + hi);
        (overshoots(mid) ? hi : lo) = mid;
    }
    return lo;
}

std::optional<DrivePlanner::Step> DrivePlanner::robust_brake(double at, double until,
                                                             double frequency_hz) const {
    const auto all = ensemble();
    const double level = kStopped * Physics::strength(state_);
    const double tau = physics_.time_constant_s({});
    const auto& d = physics_.declaration();
    // Where each member starts.
    std::vector<double> start;
    for (const auto& [physics, state] : all) {
        start.push_back(Physics::strength(state));
    }
    // The frequencies: around the resonance as far as the members' bands reach, and the note's.
    std::vector<double> frequencies{frequency_hz > 0.0 ? frequency_hz : d.resonance_hz};
    const double reach = (options_.uncertainty.resonance + 1.0 / d.q) * d.resonance_hz;
    for (int k = -kFrequencies; k <= kFrequencies; ++k) {
        frequencies.push_back(d.resonance_hz + reach * k / kFrequencies);
    }
    // When the declared one, `loudness` at `t`, is below `level` coasting on (a brake is measured
    // against coasting from its start).
    const auto stop_after = [&](double t, double loudness) {
        return loudness > level ? t + tau * std::log(loudness / level) : t;
    };
    double best = 1.0;  // coasting
    std::optional<Step> chosen;
    std::vector<double> lowest(all.size());
    for (const double amplitude : kRobustBrakeAmplitudes) {
        for (const double f : frequencies) {
            const Drive brake{-amplitude, f};
            auto watch = motion_.braking(physics_, at, drive_, brake, quiet_level());
            // An LRA's stop by its whole motion (ResonatorMotion), as loud as it typically is:
            // the envelope leaves out the part that turns at the LRA's own frequency, and that is
            // what is left where it says a brake has stopped it, so its quickest brake was often
            // not the actuator's (a 0.5 note at a 170 Hz Q-15 LRA's resonance, calibrate's
            // margins: the envelope's pick fell below a tenth 20.7 ms after the end on
            // bench/feel's plant, this one's 8.4 ms).
            const bool whole = physics_.is_lra() && watch.typical_at_start() > level;
            const double coasting = stop_after(0.0, whole ? watch.typical_at_start() : start[0]);
            lowest = start;
            for (int k = 1; k <= kLooks; ++k) {
                // (Longer than till `until` is that brake cut there: looked at once.)
                const double t = std::min(1.5 * tau * k / kLooks, until - at);
                watch.look(t);
                bool pushed_back = false;
                for (std::size_t i = 0; i < all.size(); ++i) {
                    const auto& [physics, state] = all[i];
                    const double left = Physics::strength(physics->advance(state, brake, t));
                    lowest[i] = std::min(lowest[i], left);
                    pushed_back = pushed_back || left > lowest[i] + kPushBack * start[i];
                }
                if (pushed_back) {
                    break;  // longer at this frequency only pushes further
                }
                // The declared one's stop, against its coasting.
                const double left = whole ? watch.typical_left()
                                          : Physics::strength(physics_.advance(state_, brake, t));
                const double nominal =
                    coasting > 1e-4 ? stop_after(t, left) / coasting : (left > level ? 2.0 : 1.0);
                // Once quiet it stays so by the whole motion at every phase (where it does not,
                // longer may yet: the brake's own ringing at its end can cancel). A brake must be
                // better by more than rounding: of two that stop it alike, the first found (the
                // strongest, the note's frequency first, the shorter first) is kept, whatever the
                // build's last bit.
                if (watch.rebound() <= 0.0 && nominal < best - kBetter &&
                    watch.rebound_left() <= 0.0 && !rebounds(at, brake, t)) {
                    best = nominal;
                    chosen = Step{t, brake};
                }
                if (t >= until - at) {
                    break;
                }
            }
        }
    }
    return chosen;
}

double DrivePlanner::quiet_level() const {
    // Of the note the brake ends, as written: where it was out of reach the LRA starts lower.
    return kQuiet * (note_peak_ > 0.0 ? note_peak_ : Physics::strength(state_));
}

bool DrivePlanner::rebounds(double at, const Drive& brake, double length) const {
    // Sixteen looks a period of the ripple the brake and the LRA's own ringing make together
    // (bench/feel's plant saw a 175 Hz Q-25 LRA braked at 168 Hz cross 10 % twice within
    // 1.5 ms, between two of a brake search's looks; with eight, a note on a 175 Hz Q-25 LRA
    // rose again to 10.05 % at a ripple's top between two), and never fewer than the search's.
    const double ripple_hz = physics_.frequency_of(brake) + physics_.declaration().resonance_hz;
    const int looks = std::max(kLooks, static_cast<int>(std::ceil(16.0 * ripple_hz * length)));
    auto watch = motion_.braking(physics_, at, drive_, brake, quiet_level());
    for (int k = 1; k <= looks && !watch.has_rebounded(); ++k) {
        watch.look(length * k / looks);
    }
    const double rebound = watch.has_rebounded() ? watch.rebound() : watch.rebound_left();
    // (A brake that drives the LRA on need never fall below the quiet level to be wrong: a 0.53
    // note at 163 Hz on a 150 Hz Q-25 LRA, braked at 161 Hz for 33 ms, was at 0.33 where
    // coasting leaves 0.28, and the next note went 93 % above.)
    return rebound > 0.0 || watch.louder_than_coasting();
}

std::optional<DrivePlanner::Step> DrivePlanner::rest_brake(double at, double until,
                                                           bool& any) const {
    const auto& d = physics_.declaration();
    const double search = 3.0 * d.resonance_hz / d.q;
    std::optional<Step> quickest;
    any = false;
    for (const double amplitude : kBrakeAmplitudes) {
        for (const auto& brake : physics_.brakes_to_rest(state_, search, amplitude)) {
            any = true;
            if (quickest && brake.after_s >= quickest->at) {
                break;  // quickest first: the rest at this amplitude are slower still
            }
            const Drive drive{-amplitude, brake.frequency_hz};
            // A brake that outlasts the silence is cut by the next note, and judged there (a
            // 0.53 note at 163 Hz on a 150 Hz Q-25 LRA was braked at 161 Hz for the 33 ms of
            // silence after it, judged by the 88 ms the envelope took to rest; at 33 ms it was
            // at 0.33, where coasting leaves 0.28, and the next note went 93 % above).
            if (!rebounds(at, drive, std::min(brake.after_s, until - at))) {
                quickest = Step{brake.after_s, drive};
                break;
            }
        }
    }
    return quickest;
}

double DrivePlanner::robust_hold(double strength, double frequency_hz) const {
    const auto& d = physics_.declaration();
    const Uncertainty& u = options_.uncertainty;
    if (members_.empty() || frequency_hz <= 0.0) {
        return INFINITY;
    }
    // The most responsive LRA within the margins at this frequency: one resonant at it where the
    // margin reaches it (a low Q peaks a little below its resonance, so a little above 1), else
    // near the nearest edge; looked for over the margin's resonances and Qs.
    const double nearest = std::clamp(frequency_hz, d.resonance_hz * (1.0 - u.resonance),
                                      d.resonance_hz * (1.0 + u.resonance));
    double most = 0.0;
    for (const double q : {d.q * (1.0 - u.q), d.q, d.q * (1.0 + u.q)}) {
        most = std::max(most, Physics::lra_gain(frequency_hz, nearest, q));
        for (int k = -kLooks; k <= kLooks; ++k) {
            const double f0 = d.resonance_hz * (1.0 + u.resonance * k / kLooks);
            most = std::max(most, Physics::lra_gain(frequency_hz, f0, q));
        }
    }
    // Off's hold leaves it at strength x most; the boost may take it no further from the written
    // strength than that on the other side, and where off would be that close (near its
    // resonance) no more than kOvershoot above: for no LRA within the margins is the held
    // strength further off than without compensation, or above the strength by more than an
    // overdrive may take the declared one.
    return strength * d.rated_drive * std::max(2.0 - most, 1.0 + kOvershoot) / most;
}

State DrivePlanner::follow(const std::vector<Step>& steps, double t) const {
    return follow(physics_, state_, steps, t);
}

State DrivePlanner::follow(const Physics& physics, State state, const std::vector<Step>& steps,
                           double t) {
    for (std::size_t i = 0; i < steps.size(); ++i) {
        const double from = steps[i].at;
        const double to = i + 1 < steps.size() ? std::min(steps[i + 1].at, t) : t;
        if (to <= from) {
            break;
        }
        state = physics.advance(state, steps[i].drive, to - from);
    }
    return state;
}

std::vector<DrivePlanner::Step> DrivePlanner::approach(double at, double until, double strength,
                                                       double frequency_hz,
                                                       bool silence_follows) const {
    // An open end (the silence after the last note) needs no more than the actuator can take to
    // settle from anywhere.
    const double longest =
        std::max({physics_.declaration().spin_up_s, physics_.declaration().spin_down_s,
                  physics_.time_constant_s({1.0, 0.0})});
    const double horizon = std::isfinite(until) ? until - at : 50.0 * longest;
    const double hold_amplitude =
        strength > 0.0 ? std::min({1.0, physics_.amplitude_for(strength, frequency_hz),
                                   robust_hold(strength, frequency_hz)})
                       : 0.0;
    const Drive hold{hold_amplitude, hold_amplitude > 0.0 ? frequency_hz : 0.0};
    const double now = Physics::strength(state_);
    if (std::abs(now - strength) <= tolerance(strength)) {
        return {{at, hold}};
    }
    if (strength == 0.0 && !brakes_ && !members_.empty()) {
        return {{at, hold}};  // coast: the brake's phase is not known (kPhaseKnown)
    }
    if (strength == 0.0 && options_.reverse && !members_.empty()) {
        // To rest, whatever the actuator within the uncertainty: the brake (frequency, length)
        // under which the worst of them stops soonest against coasting; none if none helps.
        const auto brake = robust_brake(at, until, frequency_hz);
        if (!brake || brake->at < options_.min_pulse_s) {
            return {{at, hold}};
        }
        if (at + brake->at >= until) {
            return {{at, brake->drive}};
        }
        return {{at, brake->drive}, {at + brake->at, hold}};
    }
    if (strength == 0.0 && options_.reverse && physics_.is_lra() && frequency_hz > 0.0) {
        // To rest off resonance: anti-phase at the frequency that leaves nothing ringing.
        bool any = false;
        if (const auto brake = rest_brake(at, until, any)) {
            if (at + brake->at >= until) {
                return {{at, brake->drive}};
            }
            if (brake->at >= options_.min_pulse_s) {
                return {{at, brake->drive}, {at + brake->at, hold}};
            }
        } else if (any) {
            return {{at, hold}};  // every brake would leave it ringing: coast
        }
    }
    Drive push;
    if (now < strength) {
        push = {1.0, frequency_hz};
    } else if (brakes_) {
        push = {-1.0, frequency_hz};
    } else {
        push = {0.0, 0.0};  // coast
        if (strength == 0.0) {
            return {{at, push}};
        }
    }
    auto reach = physics_.time_to(state_, push, strength, horizon);
    if (physics_.is_lra() && push.amplitude != 0.0 && std::isfinite(until)) {
        // Budgeted for every member (planned as exact too: the declared one alone, and what still
        // rings after a silence): an overdrive no faster actuator overshoots with. Ending early
        // is then a reach of its own.
        const double needed = reach.outcome == Outcome::horizon ? until - at : reach.after_s;
        const double budget = now < strength ? overdrive_budget(at, push, hold, needed, until - at,
                                                                strength, silence_follows)
                                             : needed;
        if (budget < needed) {
            reach = {Outcome::reached, budget};
        }
    }
    if (reach.outcome == Outcome::horizon) {
        return {{at, push}};  // out of reach within the segment: push all the way
    }
    if (reach.after_s >= options_.min_pulse_s) {
        if (auto steps = in_half_cycles(at, until, push, hold, reach.after_s)) {
            return *steps;
        }
    }
    if (reach.after_s < options_.min_pulse_s || at + reach.after_s >= until) {
        // Too short to matter (or, stalled at once, of no use); the hold does the rest.
        return reach.after_s < options_.min_pulse_s ? std::vector<Step>{{at, hold}}
                                                    : std::vector<Step>{{at, push}};
    }
    return {{at, push}, {at + reach.after_s, hold}};
}

std::optional<std::vector<DrivePlanner::Step>> DrivePlanner::in_half_cycles(double at, double until,
                                                                            const Drive& push,
                                                                            const Drive& hold,
                                                                            double length) const {
    // The envelope keeps the half of a drive that turns with the resonator and leaves out the
    // half that turns against it: over a whole number of half cycles that half adds up to
    // nothing, but in a pulse much shorter than a cycle to as much as the half kept, one way or
    // the other as the carrier's phase falls. A decrescendo's brakes of 0.5 ms every 10 ms on a
    // 150 Hz Q-25 LRA, each a thirteenth of a cycle, took it 20 % off its written strength, below
    // or above as they fell on one phase or another (bench/feel's notification-calendar).
    if (!physics_.is_lra() || push.amplitude >= 0.0 || push.frequency_hz != hold.frequency_hz) {
        return std::nullopt;
    }
    const double half = 0.5 / physics_.frequency_of(push);
    const double halves = std::ceil(length / half - 1e-9);
    const double whole = halves * half;
    if (halves > kWholeHalfCycles || whole <= length || at + whole >= until) {
        return std::nullopt;
    }
    const double target = Physics::strength(physics_.advance(state_, push, length));
    const auto landed = [&](double amplitude) {
        return Physics::strength(physics_.advance(state_, {amplitude, push.frequency_hz}, whole));
    };
    // Between the hold (which never gets it down there) and the brake (which does sooner).
    double lo = hold.amplitude, hi = push.amplitude;
    for (int i = 0; i < kBisections; ++i) {
        const double mid = 0.5 * (lo + hi);
        (landed(mid) > target ? lo : hi) = mid;
    }
    const double amplitude = 0.5 * (lo + hi);
    if (!(std::abs(landed(amplitude) - target) <= 1e-3 * std::max(target, 0.01))) {
        return std::nullopt;  // off resonance the beat may not land it there at all
    }
    return std::vector<Step>{{at, {amplitude, push.frequency_hz}}, {at + whole, hold}};
}

double DrivePlanner::early_end(const std::vector<Step>& steps, double until, double note_end,
                               const std::vector<double>& targets) const {
    const double at = steps.front().at;
    // Every actuator within the margins: the cut is the earliest any of them needs (one that
    // rings longer than declared needs it sooner).
    double cut = until;
    const auto all = ensemble();
    for (std::size_t m = 0; m < all.size(); ++m) {
        const Physics& physics = *all[m].first;
        const State& state = all[m].second;
        const auto at_end_if_cut = [&](double t) {
            const State coasting = follow(physics, state, steps, t);
            return Physics::strength(physics.advance(coasting, {0.0, 0.0}, note_end - t));
        };
        if (at_end_if_cut(cut) <= targets[m]) {
            continue;  // never strong enough to linger: its drive may go on to `cut`
        }
        if (at_end_if_cut(at) >= targets[m]) {
            return at;  // already lingering at that strength: no more drive
        }
        // The strength at the end grows with the cut (the drive only ever adds), so bisect.
        double lo = at, hi = cut;
        for (int i = 0; i < kBisections; ++i) {
            const double mid = 0.5 * (lo + hi);
            (at_end_if_cut(mid) >= targets[m] ? hi : lo) = mid;
        }
        cut = hi;
    }
    return cut;
}

std::vector<double> DrivePlanner::end_targets(double at, double until, double written,
                                              double frequency_hz,
                                              std::span<const Written> rest_of_note,
                                              bool silence_follows) const {
    // The declared actuator, for which the plan is made, ends on time when it is down to half
    // the written strength at the written end.
    const double felt_end = silence_follows ? written / 2.0 : INFINITY;
    std::vector<double> targets{felt_end};
    // The others within the margins, driven harder or softer than suits them, are held to what
    // compensation off leaves them at (their off-shadow, carried on to the note's end).
    for (std::size_t m = 0; m < members_.size(); ++m) {
        const Physics& physics = members_[m];
        State off =
            physics.advance(off_shadow_[m], uncompensated(written, frequency_hz), until - at);
        for (const Written& next : rest_of_note) {
            off = physics.advance(off,
                                  uncompensated(next.strength * options_.scale, next.frequency_hz),
                                  next.until - next.at);
        }
        const double off_end = std::max(Physics::strength(off), kFeltFloor * note_peak_);
        targets.push_back(std::min({note_peak_ / 2.0, kOffShare * off_end, felt_end}));
    }
    return targets;
}

Drive DrivePlanner::uncompensated(double written, double frequency_hz) const {
    const double amplitude = std::min(1.0, written * physics_.declaration().rated_drive);
    return {amplitude, amplitude > 0.0 ? frequency_hz : 0.0};
}

double DrivePlanner::look_ahead_s() const {
    if (!options_.compensation || brakes_ || members_.empty()) {
        return 0.0;  // a note's end is only ever looked at in the segment that silence follows
    }
    double longest = 0.0;
    for (const auto& member : ensemble()) {
        longest = std::max(longest, member.first->time_constant_s({}));
    }
    return kLookAheadTimeConstants * longest;
}

void DrivePlanner::tame(std::vector<Step>& steps, double until, double strength) const {
    Step& last = steps.back();
    if (!physics_.is_lra() || strength <= 0.0 || last.drive.amplitude <= 0.0 ||
        !std::isfinite(until) || until <= last.at) {
        return;
    }
    // Off resonance the resonator beats towards its steady strength (at |f - f0|): the drive
    // that settles it at the written strength, or full scale where that is out of reach, can
    // carry it above on the way. Where the model says it would, the drive is lowered until the
    // beat's top is the written strength.
    const State from = follow(steps, last.at);
    const double window = std::min(until - last.at, 3.0 * physics_.time_constant_s(last.drive));
    const double limit = (1.0 + kBeatOvershoot) * strength + kBeatFloor;
    if (Physics::strength(from) > limit) {
        return;  // falling to the hold: what rises above is not the hold's doing
    }
    const auto overshoots = [&](double amplitude) {
        const Drive drive{amplitude, last.drive.frequency_hz};
        // The whole motion (ResonatorMotion) beats a little higher than the model's envelope.
        const Step& first = steps.front();
        if (steps.size() <= 2 &&
            motion_.strongest(physics_, first.at, drive_, steps.size() == 1 ? drive : first.drive,
                              last.at - first.at, drive, window,
                              3 * kLooks) > (1.0 + kWholeOvershoot) * strength) {
            return true;
        }
        for (int k = 1; k <= 3 * kLooks; ++k) {
            if (Physics::strength(physics_.advance(from, drive, window * k / (3.0 * kLooks))) >
                limit) {
                return true;
            }
        }
        return false;
    };
    if (!overshoots(last.drive.amplitude)) {
        return;
    }
    // Never below what compensation off would hold: an LRA within the margins resonant at this
    // frequency would then fall short of where off leaves it.
    const double floor =
        std::min(last.drive.amplitude, strength * physics_.declaration().rated_drive);
    if (!overshoots(floor)) {
        double lo = floor, hi = last.drive.amplitude;
        for (int i = 0; i < kBisections / 2; ++i) {
            const double mid = 0.5 * (lo + hi);
            (overshoots(mid) ? hi : lo) = mid;
        }
        last.drive.amplitude = lo;
    } else {
        last.drive.amplitude = floor;
    }
}

void DrivePlanner::emit(double at, const Drive& drive, std::vector<Cue>& out) {
    if (drive == drive_) {
        return;
    }
    motion_.change(physics_, at, drive_, drive);
    drive_ = drive;
    out.push_back(drive_at(at, drive.amplitude, drive.frequency_hz));
    if (drive.amplitude != 0.0) {
        last_frequency_hz_ = drive.frequency_hz;
    }
}

void DrivePlanner::segment(double at, double until, double strength, double frequency_hz,
                           bool silence_follows, std::vector<Cue>& out,
                           std::span<const Written> rest_of_note) {
    if (!(until > at)) {
        return;  // of two drives at one instant only the later one is ever felt
    }
    const double written = std::max(0.0, strength * options_.scale);
    if (written > 0.0 && silent_) {
        // A note starts: where each member would be without compensation starts from where it
        // is.
        off_shadow_ = member_states_;
        note_cut_ = false;
    }
    if (written > 0.0) {
        // A note's strength is its strongest since it began (a decrescendo's end is judged
        // against where it started, a legato line's last note against itself).
        note_peak_ = silent_ || note_starts_ ? written : std::max(note_peak_, written);
    }
    note_starts_ = false;
    silent_ = written <= 0.0;
    std::vector<Step> steps;
    if (!options_.compensation) {
        steps.push_back({at, uncompensated(written, frequency_hz)});
    } else if (written > 0.0 && note_cut_) {
        steps.push_back({at, {0.0, 0.0}});  // ended early: it coasts to the note's end
    } else {
        // Silence brakes the vibration that is ringing, at its own frequency.
        const double frequency = written > 0.0 ? frequency_hz : last_frequency_hz_;
        steps = approach(at, until, written, frequency, silence_follows);
        tame(steps, until, written);
        const double note_end = silence_follows        ? until
                                : rest_of_note.empty() ? INFINITY
                                                       : rest_of_note.back().until;
        if (!brakes_ && written > 0.0 && std::isfinite(note_end)) {
            const double cut = early_end(
                steps, until, note_end,
                end_targets(at, until, written, frequency_hz, rest_of_note, silence_follows));
            if (cut < until) {
                std::erase_if(steps, [&](const Step& step) { return step.at >= cut; });
                steps.push_back({cut, {0.0, 0.0}});
                note_cut_ = true;
            }
        }
    }
    for (const Step& step : steps) {
        emit(step.at, step.drive, out);
    }
    const double end = std::isfinite(until) ? until : steps.back().at;
    for (std::size_t m = 0; m < members_.size(); ++m) {
        if (written > 0.0) {
            off_shadow_[m] =
                members_[m].advance(off_shadow_[m], uncompensated(written, frequency_hz), end - at);
        }
        for (std::size_t i = 0; i < steps.size(); ++i) {
            const double from = steps[i].at;
            const double to = i + 1 < steps.size() ? std::min(steps[i + 1].at, end) : end;
            if (to > from) {
                member_states_[m] =
                    members_[m].advance(member_states_[m], steps[i].drive, to - from);
            }
        }
    }
    state_ = follow(steps, end);
}

}  // namespace vibscore::render
