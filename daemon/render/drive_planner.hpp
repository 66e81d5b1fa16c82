#pragma once

#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "actuator/physics.hpp"
#include "actuator/resonator_motion.hpp"
#include "daemon/render/cue_stream.hpp"

namespace vibscore::render {

// How far the actual LRA may be from its declaration (issue 32: part to part, mounting,
// temperature), as fractions of the declared resonance and Q. With a margin the planner budgets
// an LRA's plans for every actuator within it, not only the declared one (its "members": the
// declared one and those at the margins' corners and edges, simulated alongside it), so that
// compensation is never further off than none for any of them: no overdrive takes the declared
// one more than 3 % or another more than 30 % above the written strength; no hold drives harder
// than leaves the most responsive LRA within the margins as close to the strength as off would
// (3 % above where one is resonant at the note); a brake to rest is the one that stops the
// declared one soonest without pushing any member back up, after its lowest point, by more than
// 30 % of where it started (past rest a brake adds energy: a shorter, weaker brake as the margins
// grow); and a held note whose beat (off resonance) would rise above its strength is driven
// lower, never below off's drive. Where the resonance is uncertain by more than half a bandwidth
// (resonance x Q > 0.5), nothing is braked: its phase is not known; falls coast, and before a
// silence the drive ends early instead, for the member that rings longest. Both zero: the
// declaration is taken as exact, issue 22's plans to the microsecond. An ERM's plans are not
// budgeted: its exact brake and overdrive stay better than none over +-30 % in both time
// constants (bench/feel, docs/performance.md), as coasting takes it twice as long as braking.
struct Uncertainty {
    double resonance = 0.0;  // 0..0.5
    double q = 0.0;          // 0..0.9
    bool operator==(const Uncertainty&) const = default;
};
// What issue 32 asks to be safe against: an LRA's resonance within 5 % and its Q within 40 %.
inline constexpr Uncertainty kPartToPart{0.05, 0.4};
// What a declaration says of itself ([actuator] resonance-tolerance-percent, q-tolerance-percent;
// by default kPartToPart): an LRA's tolerances; none for an ERM.
Uncertainty uncertainty_of(const actuator::Declaration& declaration);

struct PlannerOptions {
    // The written strength is multiplied by this (the playback's intensity, and the master
    // intensity unless the device applies it as a gain).
    double scale = 1.0;
    // Shape the drives to the actuator's physics (overdrive, braking or the early end, off-
    // resonance drive). Off: strength s is sent as s x rated-drive (at most full scale).
    bool compensation = true;
    // The backend can drive backwards and the board is declared to brake with it.
    bool reverse = false;
    // An overdrive or brake shorter than this is left out: no backend resolves it, and what it
    // would have added is that small.
    double min_pulse_s = 0.0005;
    Uncertainty uncertainty{};
};

// Where the actuator is, and the drive in force, when one pass of a playback hands over to the
// next: the next pass plans from there.
struct PlannerCarry {
    actuator::State state;
    actuator::Drive drive;            // as sent
    double ringing_frequency_hz = 0;  // of the last drive that vibrated, as sent
    // The same for each actuator within the uncertainty (DrivePlanner's members); empty: as
    // `state`.
    std::vector<actuator::State> members;
};

// A constant written strength from `at` to `until` (seconds) at one frequency, as
// DrivePlanner::segment() takes it.
struct Written {
    double at = 0.0;
    double until = 0.0;
    double strength = 0.0;
    double frequency_hz = 0.0;
};

// Turns a written strength envelope into the drives that make a declared actuator follow it as
// closely as it physically can (issue 22, docs/drivers.md "Compensation"). Pure: it simulates the
// actuator with actuator::Physics alongside the drives it chooses, and never reads a clock.
//
// The envelope comes as segments in time order, each a constant written strength (clef units:
// 1 = rated drive) at one frequency. For each one, from wherever the actuator is:
//  - below the strength: full scale (in phase) for exactly as long as the model takes to reach
//    it, then the drive that holds it (rated-drive x strength / the gain at that frequency);
//  - above it: with `reverse`, full scale backwards (anti-phase) for exactly as long as it takes
//    to fall to it, then the hold; without, no drive until it has coasted down to it;
//  - a strength out of reach (off resonance, or above full scale) is driven at full scale;
//  - without `reverse`, a segment followed by silence ends its drive early, when coasting from
//    there brings the actuator to half the written strength at the written end: the felt note
//    ends on time.
// No drive exceeds full scale, and no overdrive or brake lasts longer than the model needs.
class DrivePlanner {
  public:
    // Throws std::invalid_argument for impossible constants.
    DrivePlanner(const actuator::Declaration& declaration, const PlannerOptions& options,
                 const PlannerCarry& carry = {});

    // The written `strength` at `frequency_hz` from `at` to `until` (seconds; `until` may be
    // infinite for the silence after the last note): appends its drives to `out` (drive cues,
    // signed amplitude -1..1, in time order) and moves the simulated actuator to `until`.
    // `silence_follows`: the written strength drops to 0 at `until`.
    // `rest_of_note`: where silence does not follow at `until` but ends the note within
    // look_ahead_s(), the note's segments after this one up to that silence; else empty. Without
    // braking, a note's drive then ends early enough (in this segment, if coasting from its end
    // would not do) that no actuator within the margins rings on at the note's end more than
    // compensation off would leave it: a decrescendo's last steps cannot undo its first.
    void segment(double at, double until, double strength, double frequency_hz,
                 bool silence_follows, std::vector<Cue>& out,
                 std::span<const Written> rest_of_note = {});
    // The next segment is the first of a written note, tied to the one before or after a
    // silence: the note's strength, which its end and any rebound after it are judged against,
    // is counted from there (a glide's last note is felt as itself).
    void note_starts() { note_starts_ = true; }
    // How far ahead of a segment segment() wants to be shown the note's end: 0 when it brakes
    // (the end is then the brake's), plans as exact (only the last segment ends early) or does
    // not compensate.
    double look_ahead_s() const;

    // The actuator's state and the drive in force at the end of the last segment.
    PlannerCarry carry() const { return {state_, drive_, last_frequency_hz_, member_states_}; }
    const actuator::Physics& physics() const { return physics_; }

  private:
    struct Step {
        double at;
        actuator::Drive drive;
    };
    // The drives that take the actuator from its state at `at` to `strength` and hold it there,
    // without regard to what follows (at most two).
    // `silence_follows`: the note ends at `until` (what comes after is the brake's or the coast's).
    std::vector<Step> approach(double at, double until, double strength, double frequency_hz,
                               bool silence_follows) const;
    // A brake of `length` (from `at`, to `hold` after it) of up to kWholeHalfCycles half cycles
    // of its carrier, made a whole number of them long and as much weaker as lands the LRA, by
    // the model, where the brake would have; nothing where it need not or cannot be.
    std::optional<std::vector<Step>> in_half_cycles(double at, double until,
                                                    const actuator::Drive& push,
                                                    const actuator::Drive& hold,
                                                    double length) const;
    // The state at `t` following `steps` from the current state at steps.front().at.
    actuator::State follow(const std::vector<Step>& steps, double t) const;
    // The same for any actuator from any state.
    static actuator::State follow(const actuator::Physics& physics, actuator::State state,
                                  const std::vector<Step>& steps, double t);
    // For a segment of a note that silence ends at `note_end`: where its drive (up to `until`)
    // should stop so that coasting from there brings each member of the ensemble no higher than
    // its `targets` entry at `note_end`; `until` itself when it need not.
    double early_end(const std::vector<Step>& steps, double until, double note_end,
                     const std::vector<double>& targets) const;
    // How strong each member of the ensemble may still be at `note_end`. The declared one: half
    // the written strength in the segment that silence follows (the felt end on time), anything
    // before it. Each other one: that too, half the note's strongest, and nine tenths of what
    // compensation off would leave it at (its off-shadow, driven on through `rest_of_note`) or of
    // a tenth of the note, whichever is more.
    std::vector<double> end_targets(double at, double until, double written, double frequency_hz,
                                    std::span<const Written> rest_of_note,
                                    bool silence_follows) const;
    // The drive that compensation off sends for `written` at `frequency_hz`.
    actuator::Drive uncompensated(double written, double frequency_hz) const;
    void emit(double at, const actuator::Drive& drive, std::vector<Cue>& out);
    // Lowers the last of `steps` (the hold, or a push all the way) where an LRA would beat above
    // `strength` under it before `until` (by the model; with a margin only).
    void tame(std::vector<Step>& steps, double until, double strength) const;

    // The actuators within the uncertainty, the declared one first, and where each one is.
    std::vector<std::pair<const actuator::Physics*, actuator::State>> ensemble() const;
    // How long an overdrive `push` of `needed` seconds (within `span`) may last so that, once held,
    // the declared actuator goes no more than 3 % above `strength` (or above what `hold` settles
    // it at, if more) by the model and 4.5 % by its whole motion, and no other member more than
    // 30 %. Its whole motion is looked at past `span` too unless `note_ends` there.
    double overdrive_budget(double at, const actuator::Drive& push, const actuator::Drive& hold,
                            double needed, double span, double strength, bool note_ends) const;
    // The brake to rest when the actuator is uncertain: the anti-phase drive (strength,
    // frequency, and its length in `at`) under which the declared actuator stops soonest, as long
    // as no member is pushed back up, after its lowest point, by more than 30 % of its strength
    // at the brake's start (past rest a brake adds energy), nor the declared one, by its whole
    // motion, back above quiet_level() once below; nothing when coasting does as well. Each is
    // judged as long as it is used: no longer than till `until`, where the next note cuts it.
    std::optional<Step> robust_brake(double at, double until, double frequency_hz) const;
    // The quickest brake to rest of the exact ones (the envelope passes through zero) under
    // which the LRA, by its whole motion, once below quiet_level(), stays there;
    // `any` says whether there was an exact brake at all, safe or not. Judged to `until` where
    // it lasts longer.
    std::optional<Step> rest_brake(double at, double until, bool& any) const;
    // Below which a brake's watch keeps the LRA once it is there: kQuiet of the note it ends.
    double quiet_level() const;
    // Whether `brake` from `at` for `length` leaves the LRA, by its whole motion, back above
    // quiet_level() once below it, looked at finely enough to see the ripple the brake's drive
    // and the LRA's own ringing make together (at their frequencies' sum), or louder at its end
    // than coasting would.
    bool rebounds(double at, const actuator::Drive& brake, double length) const;

    // The most a hold at `frequency_hz` may drive so that no LRA within the margins settles
    // further from `strength` than without compensation (infinite without margins).
    double robust_hold(double strength, double frequency_hz) const;

    actuator::Physics physics_;
    PlannerOptions options_;
    actuator::State state_;
    actuator::Drive drive_;
    double last_frequency_hz_ = 0.0;  // of the last drive that vibrated: braking continues it
    double note_peak_ = 0.0;          // the last note's strongest, as written (and scaled)
    bool note_starts_ = false;        // note_starts(): the next segment begins a written note
    bool silent_ = true;              // the last segment was a silence
    bool note_cut_ = false;           // the note's drive has ended early: it coasts to its end
    // Where each of members_ would be had the note been sent uncompensated (from where it was
    // at the note's start).
    std::vector<actuator::State> off_shadow_;
    // The declared LRA's whole motion under the drives emitted, to judge brakes by (a pass
    // starts from rest: what the last one left is not carried).
    actuator::ResonatorMotion motion_;
    std::vector<actuator::Physics> members_;  // an LRA's neighbours within the uncertainty
    std::vector<actuator::State> member_states_;
    // Whether it brakes: `reverse`, and (with members) the resonance known to within a
    // bandwidth's fraction (kPhaseKnown).
    bool brakes_ = false;
};

}  // namespace vibscore::render
