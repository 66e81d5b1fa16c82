#pragma once

#include <vector>

#include "daemon/actuator/physics.hpp"
#include "daemon/render/cue_stream.hpp"

namespace vibscore::render {

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
};

// Where the actuator is, and the drive in force, when one pass of a playback hands over to the
// next: the next pass plans from there.
struct PlannerCarry {
    actuator::State state;
    actuator::Drive drive;            // as sent
    double ringing_frequency_hz = 0;  // of the last drive that vibrated, as sent
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
    void segment(double at, double until, double strength, double frequency_hz,
                 bool silence_follows, std::vector<Cue>& out);

    // The actuator's state and the drive in force at the end of the last segment.
    PlannerCarry carry() const { return {state_, drive_, last_frequency_hz_}; }
    const actuator::Physics& physics() const { return physics_; }

  private:
    struct Step {
        double at;
        actuator::Drive drive;
    };
    // The drives that take the actuator from its state at `at` to `strength` and hold it there,
    // without regard to what follows (at most two).
    std::vector<Step> approach(double at, double until, double strength, double frequency_hz) const;
    // The state at `t` following `steps` from the current state at steps.front().at.
    actuator::State follow(const std::vector<Step>& steps, double t) const;
    // For a segment that silence follows: where the drive should stop so that coasting from there
    // brings the strength to half of `strength` at `until`; `until` itself when it need not.
    double early_end(const std::vector<Step>& steps, double until, double strength) const;
    void emit(double at, const actuator::Drive& drive, std::vector<Cue>& out);

    actuator::Physics physics_;
    PlannerOptions options_;
    actuator::State state_;
    actuator::Drive drive_;
    double last_frequency_hz_ = 0.0;  // of the last drive that vibrated: braking continues it
};

}  // namespace vibscore::render
