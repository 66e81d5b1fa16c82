#pragma once

#include <utility>
#include <vector>

#include "actuator/declaration.hpp"
#include "daemon/render/cue_stream.hpp"
#include "daemon/render/drive_planner.hpp"

namespace vibscore::bench {

// A phrase of notes (strength, frequency), each `length` seconds and followed by as long a
// silence, planned by DrivePlanner for the declared actuator and played on bench/feel's plant
// of the true one: what the drive planner's tests and bench/planner_search judge it by.
inline constexpr double kPhraseRate = 10000.0;  // the plant's samples a second

using Notes = std::vector<std::pair<double, double>>;

struct Played {
    std::vector<render::Cue> drives;
    std::vector<double> strength;  // at kPhraseRate, from the first note to 0.2 s after the last
};
Played play_notes(const actuator::Declaration& declared, const actuator::Declaration& truth,
                  const render::PlannerOptions& options, const Notes& notes, double length);

// Over the notes: the most one goes above its strength while it sounds (a fraction of it), and
// the most one is again, after its end and before the next, once it has fallen below 10 % of its
// strength (a fraction of it; 0 where none falls below).
struct Artefacts {
    double overshoot = 0.0, rebound = 0.0;
};
Artefacts artefacts(const Played& played, const Notes& notes, double length);

}  // namespace vibscore::bench
