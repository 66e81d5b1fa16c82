#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "actuator/declaration.hpp"
#include "bench/feel_metrics.hpp"
#include "daemon/render/cue_stream.hpp"
#include "daemon/render/drive_planner.hpp"
#include "score/bundle.hpp"

// What bench/feel plays and how it judges it (docs/performance.md, "What people feel"): the
// pieces, each planned for a declared actuator and felt on a true one through bench/feel_plant.
// Shared with bench/calibrated_feel, so its figures are bench/feel's figures, not a copy of them.
namespace vibscore::bench {

inline constexpr double kRate = 2000.0;  // samples per second of every strength compared
inline constexpr double kTail = 0.5;     // seconds after a score's end, for the ringing

// The nine shipped notification tactons (bench/press_targets.hpp names the same set).
extern const std::vector<std::string> kTactons;

struct Piece {
    std::string name;
    ScoreBundle bundle;
};

// The nine tactons from `clefs` (the shipped clefs folder), then ten 50 ms taps a second and
// typing through its lra-phone clef.
std::vector<Piece> pieces(const std::filesystem::path& clefs);

// The piece as the declared LRA plays it: every sine clef moved into its band.
ScoreBundle for_actuator(ScoreBundle bundle, const actuator::Declaration& declared);

// Drives felt on `truth`, measured against the written strength (`written` sampled at kRate).
ScoreFeel judge(const std::string& name, const std::vector<NoteSpan>& notes,
                const std::vector<double>& written, const std::vector<render::Cue>& drives,
                const actuator::Declaration& truth);

// One piece on one actuator: planned for `declared` (compensation as asked, within
// `uncertainty`), felt on `truth`.
ScoreFeel feel(const Piece& piece, const actuator::Declaration& declared,
               const actuator::Declaration& truth, bool compensation,
               const render::Uncertainty& uncertainty);

}  // namespace vibscore::bench
