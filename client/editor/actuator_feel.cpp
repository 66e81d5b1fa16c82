#include "client/editor/actuator_feel.hpp"

#include <cmath>

#include "actuator/declaration.hpp"
#include "actuator/physics.hpp"

namespace vibscore::editor {

std::vector<std::string> actuator_feel(const Clef& clef,
                                       const std::map<std::string, std::string>& actuator) {
    if (actuator.empty()) {
        return {};
    }
    actuator::Declaration declared;
    try {
        // Read as the client's verbs read it (actuator::from_settings): one rule for what a
        // declaration is.
        declared = actuator::from_settings(actuator, "vibscored's Actuator property");
    } catch (const actuator::DeclarationError&) {
        return {};  // the window shows the clef as written rather than a feel it cannot know
    }
    if (declared.kind != actuator::Kind::lra) {
        return {};
    }
    std::vector<std::string> feel;
    for (const auto& string : clef.strings) {
        const double frequency = string.frequency > 0.0 ? string.frequency : declared.resonance_hz;
        const double gain =
            actuator::Physics::lra_gain(frequency, declared.resonance_hz, declared.q);
        feel.push_back("gives " + std::to_string(std::lround(gain * 100.0)) + "%");
    }
    return feel;
}

}  // namespace vibscore::editor
