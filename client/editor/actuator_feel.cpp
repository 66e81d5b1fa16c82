#include "client/editor/actuator_feel.hpp"

#include <cmath>
#include <optional>
#include <stdexcept>

#include "actuator/physics.hpp"

namespace vibscore::editor {

namespace {

std::optional<double> positive(const std::map<std::string, std::string>& actuator,
                               const std::string& key) {
    const auto found = actuator.find(key);
    if (found == actuator.end()) {
        return std::nullopt;
    }
    try {
        std::size_t used = 0;
        const double value = std::stod(found->second, &used);
        if (used != found->second.size() || !std::isfinite(value) || value <= 0.0) {
            return std::nullopt;
        }
        return value;
    } catch (const std::logic_error&) {
        return std::nullopt;
    }
}

}  // namespace

std::vector<std::string> actuator_feel(const Clef& clef,
                                       const std::map<std::string, std::string>& actuator) {
    const auto kind = actuator.find("kind");
    const auto resonance = positive(actuator, "resonance-hz");
    const auto q = positive(actuator, "q");
    if (kind == actuator.end() || kind->second != "lra" || !resonance || !q) {
        return {};
    }
    std::vector<std::string> feel;
    for (const auto& string : clef.strings) {
        const double frequency = string.frequency > 0.0 ? string.frequency : *resonance;
        const double gain = actuator::Physics::lra_gain(frequency, *resonance, *q);
        feel.push_back("gives " + std::to_string(std::lround(gain * 100.0)) + "%");
    }
    return feel;
}

}  // namespace vibscore::editor
