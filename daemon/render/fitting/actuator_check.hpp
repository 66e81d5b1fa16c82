#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "actuator/declaration.hpp"
#include "daemon/render/performance.hpp"
#include "score/bundle.hpp"

namespace vibscore::render {

// What a score asks that a declared actuator cannot give (`vibscore check --actuator`): warnings,
// not errors. Each names the note (bar and note, counted from 1 within the bar, rests left out)
// and the numbers.
struct ActuatorWarning {
    std::size_t bar = 0;   // 1-based
    std::size_t note = 0;  // 1-based, among the bar's notes
    std::string text;
};

// - a note that, played with compensation (overdrive, braking as declared), never reaches 90 %
//   of its written strength while it sounds: too short for the actuator;
// - an LRA string where full drive gives less than half the strength the score asks on it (named
//   at its first note);
// - every note whose number is out of reach on its string, by the clef check's own rule
//   (render::out_of_reach: what `check CLEF --actuator` names for that clef).
// In score order.
std::vector<ActuatorWarning> actuator_warnings(const ScoreBundle& bundle,
                                               const Performance& performance,
                                               const actuator::Declaration& declaration);

// "bar 2, note 3: ..." for messages.
std::string describe(const ActuatorWarning& warning);

}  // namespace vibscore::render
