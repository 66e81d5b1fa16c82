#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "actuator/declaration.hpp"
#include "score/clef.hpp"

namespace vibscore::render {

// What a clef asks that a declared actuator cannot give (`vibscore check CLEF --actuator`, and
// vibscored's log when it stores or fits a clef): warnings, not errors, one line each, naming the
// string or number and the figures.
//  - a sine string where full drive gives less than the clef's strongest number;
//  - neighbouring sine strings closer than kDistinctPitchRatio (an LRA), or any sine strings on
//    an ERM, which has no pitch;
//  - a number full drive cannot reach on some string;
//  - a shape string with a rise or fall faster than the actuator follows, or on/off pulses too
//    short for it to reach the strongest number.
std::vector<std::string> clef_warnings(const Clef& clef, const actuator::Declaration& declaration);

// The one rule of "out of reach", shared by the clef check above and the score check
// (render::actuator_warnings), so that a note playing number `number` on string `string` (both
// from 0) is named by the one exactly when the other names the number on that string: the
// strength full drive gives there when it is less than the number asks; nothing when full drive
// reaches it, or when the check does not judge it (sine strings on an ERM: no pitch, no reach).
std::optional<double> out_of_reach(const Clef& clef, std::size_t number, std::size_t string,
                                   const actuator::Declaration& declaration);

}  // namespace vibscore::render
