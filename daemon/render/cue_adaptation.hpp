#pragma once

#include <deque>
#include <memory>
#include <optional>
#include <vector>

#include "actuator/declaration.hpp"
#include "daemon/render/cue_schedule.hpp"
#include "daemon/render/drive_planner.hpp"

namespace vibscore::render {

// What an actuator can take, and how to express what it cannot.
struct CueAdaptation {
    // The actuator can choose its frequency; otherwise every drive says 0 (its own).
    bool frequency = true;
    // The actuator can vary its strength. Otherwise strength becomes pulse modulation: in each
    // pulse period from the start of a vibrating stretch the actuator is on for strength x
    // period and off for the rest, the strength being the one at the period's start (scaled by
    // `scale` and clamped to 0..1). Strength >= 1 - 1e-9 is continuous on; an on-pulse shorter
    // than min_pulse_s is left out, since a motor cannot spin up in it.
    bool amplitude = true;
    // The actuator takes a linear ramp whole (an FF envelope): runs of update steps that lie
    // on one line become one drive with ramp_to/ramp_s.
    bool envelopes = false;
    // The strength scale the playback asked for: applied by pulse modulation, or, with a declared
    // actuator, by the drives made for it.
    double scale = 1.0;
    double pulse_period_s = 0.040;
    double min_pulse_s = 0.004;
    double update_interval_s = CueOptions{}.update_interval_s;
    // The actuator [actuator] declares. With it, strengths leave as drives of the backend's full
    // scale, -1..1: strength x scale x rated-drive, or with its compensation the drives a
    // DrivePlanner shapes to its physics; pulse modulation and envelopes then work on those
    // drives. Without it, strengths leave as written (the player scales them).
    std::optional<actuator::Declaration> actuator;
    // The backend can drive backwards (Capabilities::reverse): with brake = reverse declared,
    // the planner brakes with it.
    bool reverse = false;
    double min_drive_pulse_s = PlannerOptions{}.min_pulse_s;
    // How far the actual actuator may be from the declaration (DrivePlanner's Uncertainty);
    // nothing: what the declaration says of itself (uncertainty_of: its tolerances).
    std::optional<Uncertainty> uncertainty;
};

// How the passes of one playback continue each other: the actuator's state where one pass ends
// is where the next one plans from, and only the last pass may drive beyond its end (a brake
// after its last note).
struct PassLink {
    std::shared_ptr<PlannerCarry> carry;  // read at the pass's start, written at its end
    bool last = true;
};

// The cues of one pass (duration_s long) rewritten for an actuator, as they are asked for.
// Position cues are kept; the result is in time order, drives before positions at the same
// instant, as a schedule stream. It reads its input only as far ahead as the cue it makes needs
// (a pulse period, the run of steps that one ramp replaces, or, while a note goes on, as far as
// the planner looks ahead for its end: DrivePlanner::look_ahead_s).
class AdaptedCueStream final : public CueStream {
  public:
    AdaptedCueStream(std::unique_ptr<CueStream> input, double duration_s,
                     const CueAdaptation& adaptation, const PassLink& link = {});
    ~AdaptedCueStream() override;
    std::optional<Cue> next() override;

    // One step of the drive pipeline: drives in, drives out.
    class Stage {
      public:
        virtual ~Stage() = default;
        virtual std::optional<Cue> next() = 0;
    };

  private:
    class InputDrives;

    std::deque<Cue> positions_;  // read from the input, waiting for their turn
    std::unique_ptr<InputDrives> input_;
    std::vector<std::unique_ptr<Stage>> stages_;  // each reads the one before it
    std::optional<Cue> waiting_drive_;
    bool drives_done_ = false;
};

// The whole adapted list (tests, tools and the hil expectations).
std::vector<Cue> adapt_cues(const std::vector<Cue>& cues, double duration_s,
                            const CueAdaptation& adaptation);

}  // namespace vibscore::render
