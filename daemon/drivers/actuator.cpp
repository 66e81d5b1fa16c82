#include "daemon/drivers/actuator.hpp"

namespace vibscore::drivers {

std::vector<std::string> Capabilities::names() const {
    std::vector<std::string> names;
    if (amplitude_control)
        names.emplace_back("amplitude-control");
    if (frequency_control)
        names.emplace_back("frequency-control");
    if (effect_memory)
        names.emplace_back("effect-memory");
    if (envelopes)
        names.emplace_back("envelopes");
    if (gain_control)
        names.emplace_back("gain-control");
    if (reverse)
        names.emplace_back("reverse-drive");
    if (max_on_time_s > 0.0)
        names.emplace_back("max-on-time");
    return names;
}

}  // namespace vibscore::drivers
