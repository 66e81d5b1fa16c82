#pragma once

#include <map>
#include <string>
#include <vector>

#include "score/clef.hpp"

namespace vibscore::editor {

// What the daemon's declared actuator (Haptics1.Actuator: "kind", "resonance-hz", "q", ...)
// gives at each string of `clef`, string 1 first, for the clef window: an LRA's steady
// strength at the string's frequency relative to its resonance ("gives 62%"; a waveform string,
// played at the resonance, "gives 100%"). Empty for an ERM (its frequency follows its speed,
// not the string), and where no actuator, or no usable one (actuator::from_settings refuses it),
// is declared.
std::vector<std::string> actuator_feel(const Clef& clef,
                                       const std::map<std::string, std::string>& actuator);

}  // namespace vibscore::editor
